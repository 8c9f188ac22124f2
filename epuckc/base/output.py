"""Every file epuckc writes goes through here: one mechanism, one set of rules.

- The whole file or nothing: a regular file is written to a temporary file
  next to it and renamed over it, so a killed run or a full disk never
  leaves half a file, and a reader never sees one.
- `-` (for `compile -o -`) is standard output; see `is_stdout`.
- A symbolic link is followed: its target is replaced atomically and the
  link stays a link (as `cp` and the shell's `>` do). A dangling link gets
  its target created.
- A file that exists and is not a regular file (`/dev/null`, `/dev/stdout`,
  a FIFO, a terminal) is written to in place, never replaced: replacing a
  device node with a regular file would break the machine. So is anything
  under /dev and /proc (`/dev/stdout` redirected to a file is the shell's
  open file, not a path to replace).
- A replaced regular file keeps its permission bits (plus the execute bits
  when an executable is written).
- Every failure is an OutputError whose message names the path and says
  what to do (a full disk, a read-only folder, a directory in the way).
"""
from __future__ import annotations

import errno
import os
import stat
import sys
import tempfile
from pathlib import Path
from typing import Optional, Union

STDOUT = "-"
TEMP_PREFIX = ".epuckc-tmp-"     # temporary files and folders; stale ones are swept


class OutputError(OSError):
    """A file could not be written; the message names it and says why. An
    OSError, so that code catching those still catches it."""


def is_stdout(path) -> bool:
    return str(path) == STDOUT


def describe_os_error(exc: OSError, path, doing: str = "write") -> str:
    """`cannot write PATH: REASON; HOW TO FIX` for an OSError."""
    shown = os.fsdecode(path) if path is not None else "?"
    shown = shown.encode("utf-8", "surrogateescape").decode("utf-8", "replace")
    reason = exc.strerror or str(exc)
    hint = {
        errno.ENOSPC: "the disk is full: free some space or write somewhere else",
        errno.EDQUOT: "the disk quota is exhausted: free some space or write somewhere else",
        errno.EROFS: "the file system is read-only: write somewhere else",
        errno.EACCES: "you may not write there: check the permissions or write somewhere else",
        errno.EPERM: "you may not write there: check the permissions or write somewhere else",
        errno.EISDIR: "it is a directory: give a file name",
        errno.ENOTDIR: "a part of the path is a file, not a directory",
        errno.ENAMETOOLONG: "the name is too long for the file system",
    }.get(exc.errno)
    return f"cannot {doing} {shown}: {reason}" + (f"; {hint}" if hint else "")


def _target(path: Path) -> Path:
    """The path to write: a symbolic link's final target."""
    if path.is_symlink():
        return Path(os.path.realpath(path))
    return path


def _is_regular(path: Path) -> bool:
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except OSError:
        return False


def _existing_mode(path: Path) -> Optional[os.stat_result]:
    try:
        return os.stat(path)
    except FileNotFoundError:
        return None


def write_file(path: Union[str, Path], data: Union[str, bytes], mode: int = 0o644) -> None:
    """Write `data` to `path` by the rules above; raises OutputError."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    if is_stdout(path):
        try:
            sys.stdout.flush()
            out = getattr(sys.stdout, "buffer", None)
            if out is not None:
                out.write(data)
                out.flush()
            else:
                sys.stdout.write(data.decode("utf-8"))
                sys.stdout.flush()
        except BrokenPipeError:
            raise               # the reader went away: cli.main stops quietly
        except OSError as exc:
            raise OutputError(describe_os_error(exc, "standard output")) from None
        return
    path = Path(path)
    try:
        st = _existing_mode(path)       # follows links
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path)) from None
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise OutputError(f"cannot write {path}: it is a directory; give a file name, "
                          "or remove the directory")
    if st is not None and (not stat.S_ISREG(st.st_mode) or _special_tree(path)):
        _write_in_place(path, data)
        return
    try:
        target = _target(path)
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path)) from None
    if st is not None:      # its permissions stay; an executable stays executable
        mode = stat.S_IMODE(st.st_mode) | (mode & 0o111)
    _replace_atomically(path, target, data, mode)


def _special_tree(path: Path) -> bool:
    absolute = os.path.abspath(path)
    return absolute.startswith(("/dev/", "/proc/"))


def _write_in_place(path: Path, data: bytes) -> None:
    """A device, FIFO or terminal: open it and write, never replace it."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_NOCTTY | (os.O_TRUNC if _is_regular(path) else 0))
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path)) from None
    try:
        view = memoryview(data)
        while view:
            written = os.write(fd, view)
            view = view[written:]
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path)) from None
    finally:
        os.close(fd)


def _replace_atomically(path: Path, target: Path, data: bytes, mode: int) -> None:
    folder = target.parent
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise OutputError(f"cannot write {path}: {folder} is a file, not a directory") from None
    except OSError as exc:
        raise OutputError(describe_os_error(exc, folder, "create the folder")) from None
    try:
        # The pid in the name tells a sweep (build.sweep_stale) whether the
        # writer is still alive.
        fd, tmp = tempfile.mkstemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-{target.name[:64]}.",
                                   dir=folder)
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path)) from None
    try:
        try:
            view = memoryview(data)
            while view:
                written = os.write(fd, view)
                view = view[written:]
        finally:
            os.close(fd)
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise OutputError(describe_os_error(exc, path)) from None
        raise


def prepare_directory(path: Union[str, Path], option: str = "-o") -> Path:
    """An output folder: created when missing; a clear OutputError when a
    file (or anything else) is in the way."""
    path = Path(path)
    if is_stdout(path):
        raise OutputError(f"`{option} -` is for `epuckc compile`: this command writes a folder; "
                          f"give its name with {option} DIR")
    try:
        st = os.stat(path)
    except FileNotFoundError:
        st = None
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path, "use the folder")) from None
    if st is not None and not stat.S_ISDIR(st.st_mode):
        raise OutputError(f"cannot use {path} as the output folder: it is a file, not a folder; "
                          f"remove it or give another folder with {option} DIR")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise OutputError(f"cannot create the output folder {path}: a part of the path is a "
                          f"file; give another folder with {option} DIR") from None
    except OSError as exc:
        raise OutputError(describe_os_error(exc, path, "create the folder")) from None
    return path


def write_atomic(path: Path, data, mode: int = 0o644, only_if_changed: bool = False):
    """Write the whole file or nothing (see output.py, which every write
    uses). With only_if_changed, an identical file is left alone (its time
    stamp too, so that make rebuilds nothing)."""
    if only_if_changed and not is_stdout(path):
        payload = data.encode("utf-8") if isinstance(data, str) else data
        try:
            if Path(path).is_file() and Path(path).read_bytes() == payload:
                return
        except OSError:
            pass
    write_file(path, data, mode)
