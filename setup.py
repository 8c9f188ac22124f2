"""The project is described in pyproject.toml; this file only adds the
optional C accelerator of the front end (epuckc/syntax/_front*.c), which
pyproject.toml cannot declare with the setuptools this project supports.
Without a C compiler the build goes on and epuckc runs its Python front
end, which gives the same results more slowly."""
from setuptools import Extension, setup

FRONT = "epuckc/syntax/"
# epuckc/syntax/accel.py lists the same files (SOURCES, HEADERS); a test keeps them equal.
SOURCES = ["_front.c", "_front_lex.c", "_front_make.c"]
HEADERS = ["_front.h"]

setup(ext_modules=[Extension("epuckc.syntax._front", [FRONT + s for s in SOURCES],
                             depends=[FRONT + h for h in HEADERS], optional=True)])
