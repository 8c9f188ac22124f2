"""`epuckc check` of many files with its cache (check/cache.py): after
every change (a file edited, an extern C file added, removed or made a
folder, another target, another name, epuckc itself changed) what it
prints and its exit status are byte for byte those of a check without the
cache, and a file that did not change is not parsed again."""
from __future__ import annotations

import random
import shutil
from pathlib import Path

import pytest

from epuckc.check import cache, frontend

from tests.support.cli import run_cli

REPO = Path(__file__).resolve().parents[2]
FORMATS = ("human", "json", "sarif", "gcc", "short")
SOURCES = sorted((REPO / "examples").glob("*.epk"))[:8] + [
    REPO / "tests" / "check" / "cases" / name for name in (
        "E040_extern_file_missing.epk", "E027_reserved_c_name.epk", "E003_unterminated_string.epk")]
PIECES = ["on ", "do ", ", ", "stop_motor", "start_straight(300, 2 m)", "\n", "#", "é", "@",
          "const K = 5 cm\n", "extern action spin() from \"spin.c\"\n", "var v = 1\n",
          "every 10 ms do v = v + 1\n", "K", "(", ")", "\0", "\xff"]


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("EPUCKC_NO_CACHE", raising=False)
    for i, src in enumerate(SOURCES):
        shutil.copy(src, tmp_path / f"p{i}.epk")
    (tmp_path / "spin.c").write_text("void spin(void) {}\n")
    return tmp_path


def _parses(monkeypatch) -> list:
    """The files check_file is asked to check, from now on."""
    seen, real = [], frontend.check_file
    monkeypatch.setattr(frontend, "check_file",
                        lambda path, *a, **k: seen.append(path.name) or real(path, *a, **k))
    return seen


def _both(capsys, argv) -> tuple:
    """`check ARGV` with the cache, and without it: both results."""
    cached = run_cli(["check", *argv], capsys)
    fresh = run_cli(["check", "--no-cache", *argv], capsys)
    return cached, fresh


def _change(rng: random.Random, work: Path) -> str:
    """One change of what a check reads: a file's text (or bytes), an
    extern C file."""
    kind = rng.random()
    if kind < 0.15:
        c_file = work / "spin.c"
        if c_file.is_dir():
            c_file.rmdir()
        elif c_file.exists():
            c_file.unlink()
            if rng.random() < 0.5:
                c_file.mkdir()
        else:
            c_file.write_text("void spin(void) {}\n")
        return "spin.c"
    path = work / f"p{rng.randrange(len(SOURCES))}.epk"
    data = path.read_bytes()
    at = rng.randint(0, len(data))
    new = "".join(rng.choice(PIECES) for _ in range(rng.choice([1, 1, 2])))
    raw = new.encode("latin-1") if "\xff" in new else new.encode("utf-8")
    path.write_bytes(data[:at] + raw + data[at + rng.choice([0, 0, 1, 5]):])
    return path.name


def test_every_change_gives_what_a_check_without_the_cache_prints(work, capsys):
    rng = random.Random(31)
    files = [f"p{i}.epk" for i in range(len(SOURCES))]
    for step in range(40):
        fmt = FORMATS[step % len(FORMATS)]
        argv = ["--format", fmt, *files]
        if step % 7 == 3:
            argv += ["--target", "dspic"]
        cached, fresh = _both(capsys, argv)
        assert cached == fresh, (step, fmt)
        again, _ = _both(capsys, argv)          # a hit, the same again
        assert again == fresh, (step, fmt)
        _change(rng, work)


def test_an_unchanged_file_is_not_checked_again(work, capsys, monkeypatch):
    files = [f"p{i}.epk" for i in range(len(SOURCES))]
    first = run_cli(["check", *files], capsys)
    parsed = _parses(monkeypatch)
    assert run_cli(["check", *files], capsys) == first
    assert parsed == []
    # one file edited: that one only
    (work / "p2.epk").write_text((work / "p2.epk").read_text() + "\non immediate do stop_motr\n")
    changed = run_cli(["check", *files], capsys)
    assert parsed == ["p2.epk"]
    assert changed[0] == 1 and "stop_motr" in changed[2]
    # the same file under another name is another entry: its name is in the output
    parsed.clear()
    assert run_cli(["check", "./p2.epk"], capsys)[2].count("./p2.epk") >= 1
    assert parsed == ["p2.epk"]


def test_an_extern_c_file_that_appears_is_seen(work, capsys, monkeypatch):
    (work / "ext.epk").write_text('extern action spin() from "spin.c"\non immediate do spin\n')
    assert run_cli(["check", "ext.epk"], capsys)[0] == 0
    (work / "spin.c").unlink()
    status, _, err = run_cli(["check", "ext.epk"], capsys)
    assert status == 1 and "E040" in err
    (work / "spin.c").write_text("void spin(void) {}\n")
    parsed = _parses(monkeypatch)
    assert run_cli(["check", "ext.epk"], capsys)[0] == 0
    assert parsed == ["ext.epk"]        # (the entry said E040: checked again)


def test_another_epuckc_checks_again(work, capsys, monkeypatch):
    run_cli(["check", "p0.epk"], capsys)
    parsed = _parses(monkeypatch)
    monkeypatch.setattr(cache, "front_end_fingerprint", lambda: "epuckc, edited")
    run_cli(["check", "p0.epk"], capsys)
    assert parsed == ["p0.epk"]


def test_a_cache_that_cannot_be_written_or_read_is_no_error(work, capsys, monkeypatch):
    expected = run_cli(["check", "--no-cache", "p1.epk"], capsys)
    (work / "blocked").write_text("a file where the cache folder should be")
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(work / "blocked"))
    assert run_cli(["check", "p1.epk"], capsys) == expected
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(work / "cache"))
    run_cli(["check", "p1.epk"], capsys)
    for entry in (work / "cache" / "check").iterdir():
        entry.write_bytes(b"\x00garbage")
    assert run_cli(["check", "p1.epk"], capsys) == expected


def test_no_cache_from_the_environment(work, capsys, monkeypatch):
    monkeypatch.setenv("EPUCKC_NO_CACHE", "1")
    run_cli(["check", "p0.epk"], capsys)
    assert not (work / "cache" / "check").exists()
