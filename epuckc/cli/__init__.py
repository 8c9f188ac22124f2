"""The epuckc command line: `main` (signals, a closed stdout, internal errors
as one line); the arguments are args.py, the commands commands.py, the
commands on worlds and pictures world.py, `epuckc fmt` fmt.py, and the
way from a file to a built or running program driver.py."""
from __future__ import annotations

import gc
import os
import sys


from .args import _COMMANDS, build_parser
from .commands import EXIT_INTERNAL, EXIT_USAGE, _error


def _signal_module():
    # `signal` is `_signal` with its numbers made enums, which costs ~1 ms
    # of every command to import; these two calls need only the numbers.
    try:
        import _signal as signal
    except ImportError:         # an interpreter without it
        import signal
    return signal


def _terminate_cleanly():
    """SIGTERM (a `kill`, a CI timeout) unwinds like Ctrl-C, so temporary
    files and folders are removed on the way out."""
    signal = _signal_module()

    def handler(signum, frame):
        raise SystemExit(128 + signum)
    try:
        return signal.signal(signal.SIGTERM, handler)
    except ValueError:          # not the main thread (an embedding tool)
        return None


def _restore_sigterm(previous):
    signal = _signal_module()
    if previous is not None:
        signal.signal(signal.SIGTERM, previous)


EXIT_BROKEN_PIPE = 128 + 13     # what a shell reports for a process killed by SIGPIPE


def _silence_stdout():
    """Point stdout at /dev/null, so that flushing it at exit cannot raise
    BrokenPipeError again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


def main(argv=None) -> int:
    # A command is short-lived, and what it builds (tokens, the AST, the
    # checked program) holds no reference cycles: the cyclic garbage
    # collector would only walk it again and again (~4 ms of a 1,000-rule
    # check), so it is off until the command ends. `lsp` runs for hours and
    # turns it back on.
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _main(argv)
    finally:
        if argv is None:
            # Run as a program (not called from Python): the process ends
            # now, and the collector's last pass over every object at exit
            # would free nothing.
            gc.freeze()
        elif collecting:
            gc.enable()


def _main(argv) -> int:
    words = sys.argv[1:] if argv is None else list(argv)
    # `epuckc COMMAND ...`: only COMMAND's arguments are needed (the
    # top-level options take no value, so the first word is the command);
    # anything else (`--help`, a misspelt command) gets every command.
    command = words[0] if words and words[0] in _COMMANDS else None
    parser = build_parser(command)
    args = parser.parse_args(words)
    if getattr(args, "command", None) is None:
        parser.print_help(sys.stderr)
        return EXIT_USAGE
    previous = _terminate_cleanly()
    try:
        return args.run(args)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader went away (`epuckc compile f.epk -o - | head`): stop
        # quietly, as a Unix filter does, with SIGPIPE's status.
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except Exception as exc:  # a bug in epuckc: say so plainly, no traceback
        if os.environ.get("EPUCKC_DEBUG"):
            raise
        _error(f"internal error ({type(exc).__name__}: {exc}); this is a bug in epuckc, "
               "please report it with the input (EPUCKC_DEBUG=1 shows the traceback)")
        return EXIT_INTERNAL
    finally:
        _restore_sigterm(previous)
