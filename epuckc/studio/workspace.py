"""The folder the studio opened (DIR): every path the page names is a path
inside it, or refused.

A path is relative, made of plain names (no `..`, no `.` part, no empty
part, no backslash, no part starting with `.`: hidden files and the
editors' temporary files stay out), and what it names, once symbolic links
are followed, is still inside DIR: a link that points out is refused as if
the file did not exist. Saving writes the whole file or nothing
(base/output.write_atomic) and only over the version the page read: each
read gives the file's version (a hash of its bytes), and a save that names
another version than the file's on disk is a conflict, not an overwrite.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path
from typing import Optional

from ..base.output import OutputError, write_atomic

# what the page lists and opens; anything else in DIR is not the studio's
EDITABLE = (".epk", ".world", ".scn", ".toml", ".c", ".h")
MAX_FILE_BYTES = 2_000_000
MAX_FILES = 5_000
NEW_WORLD = """# A new world (docs/world.md): the arena, obstacles and robots of a run.
arena 100 cm x 80 cm
box at 60 cm, 40 cm size 10 cm x 30 cm angle 0 deg
cylinder at 30 cm, 60 cm radius 5 cm
robot at 20 cm, 20 cm heading 45 deg
"""


class PathRefused(Exception):
    """A path the page may not use; the message says why (for a 403/404)."""

    def __init__(self, message: str, missing: bool = False):
        super().__init__(message)
        self.missing = missing


class Conflict(Exception):
    """The file changed on disk since the page read it."""

    def __init__(self, version: Optional[str]):
        super().__init__("the file changed on disk since it was opened")
        self.version = version


def version_of(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()[:20]


class Workspace:
    def __init__(self, root: Path):
        self.root = Path(os.path.realpath(root))

    def resolve(self, rel: str, must_exist: bool = True) -> Path:
        """The real path of `rel` inside the folder, or PathRefused."""
        if not isinstance(rel, str) or not rel or len(rel) > 1000:
            raise PathRefused("no path given")
        if "\\" in rel or "\0" in rel or rel.startswith("/"):
            raise PathRefused(f"{rel!r}: a path inside the folder, with / between its parts")
        parts = rel.split("/")
        if any(p in ("", ".", "..") or p.startswith(".") for p in parts):
            raise PathRefused(f"{rel!r}: no '..', '.', empty or hidden parts")
        path = self.root.joinpath(*parts)
        real = Path(os.path.realpath(path))
        if real != self.root and self.root not in real.parents:
            raise PathRefused(f"{rel!r} is outside the folder", missing=True)
        if must_exist and not real.exists():
            raise PathRefused(f"{rel!r}: no such file", missing=True)
        return real

    def relative(self, path: Path) -> str:
        return Path(os.path.realpath(path)).relative_to(self.root).as_posix()

    def files(self) -> list:
        """The editable files under the folder (relative, sorted), links
        out of it and hidden folders left out."""
        found = []
        for folder, dirs, names in os.walk(self.root, followlinks=False):
            dirs[:] = sorted(d for d in dirs if not d.startswith(".")
                             and d not in ("node_modules", "__pycache__", "build"))
            for name in sorted(names):
                if name.startswith(".") or not name.endswith(EDITABLE):
                    continue
                rel = Path(folder, name).relative_to(self.root).as_posix()
                try:
                    self.resolve(rel)
                except PathRefused:
                    continue
                found.append(rel)
                if len(found) >= MAX_FILES:
                    return found
        return found

    def read(self, rel: str) -> tuple:
        """(text, version) of a file."""
        path = self.resolve(rel)
        if not path.is_file():
            raise PathRefused(f"{rel!r} is not a file")
        data = path.read_bytes()
        if len(data) > MAX_FILE_BYTES:
            raise PathRefused(f"{rel!r} is larger than {MAX_FILE_BYTES} bytes")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise PathRefused(f"{rel!r} is not UTF-8 text") from None
        return text, version_of(data)

    def current_version(self, rel: str) -> Optional[str]:
        try:
            return version_of(self.resolve(rel).read_bytes())
        except (PathRefused, OSError):
            return None

    def save(self, rel: str, text: str, base: Optional[str]) -> str:
        """Write `text` over the version `base` the page read (None: a new
        file, which must not exist). The new version; Conflict when the
        file on disk is another version."""
        if not rel.endswith(EDITABLE):
            raise PathRefused(f"{rel!r}: the studio writes only {', '.join(EDITABLE)} files")
        path = self.resolve(rel, must_exist=False)
        current = version_of(path.read_bytes()) if path.is_file() else None
        if path.exists() and not path.is_file():
            raise PathRefused(f"{rel!r} is not a file")
        if current != base:
            raise Conflict(current)
        data = text.encode("utf-8")
        if len(data) > MAX_FILE_BYTES:
            raise PathRefused(f"the text is larger than {MAX_FILE_BYTES} bytes")
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            write_atomic(path, text)
        except OutputError:
            raise
        return version_of(path.read_bytes())

    def new_world(self, rel: str) -> str:
        """A new world file from the template; its version."""
        if not rel.endswith(".world"):
            raise PathRefused(f"{rel!r}: a world file's name ends in .world")
        return self.save(rel, NEW_WORLD, None)
