"""The link to real robots: what passes between epuckc and a robot over its
serial ports, both ways (issue 39).

Flashing: the serial ports the robots are on, told apart in the system's
list, and opening one with a message that says what to do when it cannot
be opened (`ports.py`); the e-puck2 through its on-board programmer, a
Black Magic Probe firmware that GDB drives (`gdbflash.py`, over GDB's
machine interface, `gdbmi.py`); the e-puck through its Bluetooth
bootloader, tinybld, whose program memory image is made from the XC16 hex
file (`dspic_image.py`) and sent packet by packet (`tinybld.py`); several
robots at once, each in its thread, with a progress bar on a terminal or
one line each (`flash.py`, `progress.py`).

Watching: the frames of the robot's tracer (runtime_c/rt_trace.c) and
their reader, which resynchronises after lost bytes (`frames.py`), the
records in them decoded with the program's table into the host trace's
JSON records (`stream.py`), the wheels' odometry of a decoded trace
(`odometry.py`), and `epuckc monitor` on a serial port or on the 16-bit
simulator's UART (`monitor.py`).

It starts from programs already built (the cli builds them through
build/ first) and reaches ports, processes and files through pyserial,
intelhex, pyelftools and the debugger's process.

May import: base, build (what a build leaves: the trace table beside the
program), sim (the readable trace and the replay page of a run, so that a
robot's run reads as a simulated one).
"""
