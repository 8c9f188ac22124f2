"""The project is described in pyproject.toml; this file only adds the
optional C accelerator of the front end (epuckc/syntax/_front.c), which
pyproject.toml cannot declare with the setuptools this project supports.
Without a C compiler the build goes on and epuckc runs its Python front
end, which gives the same results more slowly."""
from setuptools import Extension, setup

setup(ext_modules=[Extension("epuckc.syntax._front", ["epuckc/syntax/_front.c"], optional=True)])
