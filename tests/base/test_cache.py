"""The cache folder's rules (epuckc/base/cache.py): entries written whole,
marked when used, the least recently used evicted down to the bound, never
one used within the grace period, a folder renamed aside before it goes;
an unusable folder is a miss, never an error."""
from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from epuckc.base import cache
from epuckc.base.output import TEMP_PREFIX


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("EPUCKC_CACHE_MAX", raising=False)
    monkeypatch.delenv("EPUCKC_CACHE_GRACE", raising=False)
    monkeypatch.delenv("EPUCKC_CACHE_TRIM_EVERY", raising=False)
    return tmp_path / "cache"


def _age(path: Path, seconds: float) -> None:
    then = time.time() - seconds
    os.utime(path, (then, then))


def test_sizes_are_parsed_as_people_write_them():
    assert cache.parse_size("1024") == 1024
    assert cache.parse_size("500K") == 500 << 10
    assert cache.parse_size("500M") == cache.parse_size("500MiB") == cache.parse_size("500mb") \
        == 500 << 20
    assert cache.parse_size(" 2G ") == 2 << 30
    assert cache.parse_size("1.5G") == 3 << 29
    assert cache.parse_size("0") == 0
    for bad in ("", "G", "-1M", "lots", "1X", "nan"):
        with pytest.raises(ValueError, match="is not a size"):
            cache.parse_size(bad)


def test_the_bound_comes_from_the_environment(monkeypatch):
    monkeypatch.delenv("EPUCKC_CACHE_MAX", raising=False)
    assert cache.bound() == (cache.DEFAULT_BOUND, "the default")
    monkeypatch.setenv("EPUCKC_CACHE_MAX", "20M")
    assert cache.bound() == (20 << 20, "EPUCKC_CACHE_MAX=20M")
    monkeypatch.setenv("EPUCKC_CACHE_MAX", "plenty")
    limit, why = cache.bound()
    assert limit == cache.DEFAULT_BOUND and "`plenty` is not a size" in why


def test_key_names_differ_with_the_key():
    names = {cache.key_name(bytes([i]) * n) for i in range(20) for n in range(1, 20)}
    assert len(names) == 20 * 19
    assert cache.key_name(b"abc") == cache.key_name(b"abc")


def test_a_stored_entry_is_loaded_and_marked_used(folder):
    entry = cache.area("check") / "one.marshal"
    cache.store(entry, (1, "two", b"three"))
    assert cache.load(entry) == (1, "two", b"three")
    assert [p.name for p in entry.parent.iterdir()] == ["one.marshal"]   # no temporary left
    _age(entry, 3600)
    assert cache.load(entry) is not None
    assert time.time() - entry.stat().st_mtime < 60
    assert cache.load(cache.area("check") / "missing.marshal") is None
    entry.write_bytes(b"not marshal")
    assert cache.load(entry) is None


def test_a_folder_entry_is_committed_whole(folder):
    host = cache.area("host")
    tmp = cache.temporary_folder(host)
    assert tmp.name.startswith(f"{TEMP_PREFIX}{os.getpid()}-")
    (tmp / "prog").write_bytes(b"x" * 10)
    final = host / "key"
    cache.commit_folder(tmp, final, lambda f: (f / "prog").is_file())
    assert (final / "prog").read_bytes() == b"x" * 10 and not tmp.exists()
    # a parallel build got there first: its whole entry stays, ours goes
    again = cache.temporary_folder(host)
    (again / "prog").write_bytes(b"y")
    cache.commit_folder(again, final, lambda f: (f / "prog").is_file())
    assert (final / "prog").read_bytes() == b"x" * 10 and not again.exists()
    # a broken one is replaced
    (final / "prog").unlink()
    third = cache.temporary_folder(host)
    (third / "prog").write_bytes(b"z")
    cache.commit_folder(third, final, lambda f: (f / "prog").is_file())
    assert (final / "prog").read_bytes() == b"z"


def _entry(area: str, name: str, size: int, age: float, folder: bool = False) -> Path:
    path = cache.area(area) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    if folder:
        path.mkdir()
        (path / "a").write_bytes(b"a" * (size // 2))
        (path / "sub").mkdir()
        (path / "sub" / "b").write_bytes(b"b" * (size - size // 2))
    else:
        path.write_bytes(b"e" * size)
    _age(path, age)
    return path


def test_trim_evicts_the_least_recently_used_first(folder):
    oldest = _entry("host", "h1", 1000, 9000, folder=True)
    old = _entry("run", "r1", 1000, 8000)
    newer = _entry("runtime", "o1", 1000, 7000, folder=True)
    recent = _entry("check", "c1", 1000, 1)
    assert sum(e.size for n in cache.AREAS for e in cache.entries(n)) == 4000
    assert cache.trim(2500) == (2, 2000)
    assert not oldest.exists() and not old.exists()
    assert newer.exists() and recent.exists()
    # the entry used just now is kept even when the bound is smaller
    assert cache.trim(0) == (1, 1000)
    assert recent.exists() and not newer.exists()
    assert not any(p.name.startswith(TEMP_PREFIX) for p in cache.area("runtime").iterdir())


def test_an_entry_marked_used_is_not_evicted(folder):
    first = _entry("host", "h1", 1000, 9000, folder=True)
    second = _entry("host", "h2", 1000, 8000, folder=True)
    assert cache.used(first)
    cache.trim(1000)
    assert first.exists() and not second.exists()
    assert not cache.used(second)       # gone: a miss


def test_what_the_areas_do_not_hold_goes_first(folder):
    _entry("host", "h1", 100, 9000)
    folder.mkdir(exist_ok=True)
    stray = folder / "tables-0badc0de.marshal"      # an older epuckc's file
    stray.write_bytes(b"t" * 100)
    _age(stray, 9000)
    assert [e.path for e in cache.others()] == [stray]
    cache.trim(100)
    assert not stray.exists() and (cache.area("host") / "h1").exists()


def test_temporary_folders_count_but_are_not_evicted(folder):
    tmp = cache.temporary_folder(cache.area("host"))
    (tmp / "big").write_bytes(b"x" * 5000)
    _age(tmp, 9000)
    entry = _entry("host", "h1", 100, 9000)
    assert cache.trim(1000) == (1, 100)
    assert tmp.exists() and not entry.exists()


def test_added_trims_at_most_once_in_a_while(folder, monkeypatch):
    monkeypatch.setenv("EPUCKC_CACHE_MAX", "1500")
    old = _entry("host", "h1", 1000, 9000)
    cache.write_entry(cache.area("check") / "c1", b"c" * 1000)     # the first write trims
    assert not old.exists()
    again = _entry("host", "h2", 1000, 9000)
    cache.write_entry(cache.area("check") / "c2", b"c" * 10)       # trimmed a moment ago
    assert again.exists()
    _age(folder / cache.STAMP, cache.TRIM_EVERY_S + 1)
    cache.write_entry(cache.area("check") / "c3", b"c" * 10)
    assert not again.exists()


def test_clear_removes_every_entry(folder):
    _entry("host", "h1", 100, 1, folder=True)
    _entry("check", "c1", 50, 1)
    tmp = cache.temporary_folder(cache.area("host"))       # a build under way
    assert cache.clear() == (2, 150)
    assert tmp.exists()
    assert [e for n in cache.AREAS for e in cache.entries(n)] == []


def test_an_unusable_folder_is_a_miss_not_an_error(tmp_path, monkeypatch):
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(blocker / "cache"))
    entry = cache.area("check") / "c1"
    cache.store(entry, (1, 2))
    assert cache.load(entry) is None
    assert cache.write_entry(entry, b"x") is False
    assert cache.used(entry) is False
    assert cache.trim(0) == (0, 0) and cache.clear() == (0, 0)
    with pytest.raises(OSError):
        cache.temporary_folder(cache.area("host"))      # the builds fall back on their own


def test_files_that_are_not_epuckc_s_are_never_removed(folder):
    """EPUCKC_CACHE_DIR may name a folder that holds other files."""
    folder.mkdir(exist_ok=True)
    mine = folder / "notes.txt"
    mine.write_text("keep me")
    (folder / "photos").mkdir()
    (folder / "photos" / "a.jpg").write_bytes(b"j" * 5000)
    _age(mine, 9000)
    _age(folder / "photos", 9000)
    assert cache.others() == []
    assert cache.trim(0) == (0, 0) and cache.clear() == (0, 0)
    assert mine.read_text() == "keep me" and (folder / "photos" / "a.jpg").is_file()
