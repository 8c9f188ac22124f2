"""`epuckc run` of a rule file built before goes straight to its executable
(epuckc/build/runcache.py): the same output as the first run, without importing
the front end or Jinja2, and never a stale build."""
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import require_tool

from tests.support.programs import EXAMPLES, REPO, epuckc


def imported(*args, cwd=None):
    """Run the CLI under `-X importtime`: (result, names of the modules it imported)."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    result = subprocess.run([sys.executable, "-X", "importtime", "-m", "epuckc", *map(str, args)],
                            cwd=cwd, env=env, capture_output=True, text=True)
    modules = {line.split("|")[-1].strip() for line in result.stderr.splitlines()
               if line.startswith("import time:")}
    stderr = "\n".join(line for line in result.stderr.splitlines()
                       if not line.startswith("import time:"))
    return result, modules, stderr


@pytest.fixture
def program(tmp_path):
    """A rule file with a warning and an extern C file, in a folder of its own."""
    require_tool("cc")
    shutil.copy(EXAMPLES / "extern_spin.epk", tmp_path / "spin_rules.epk")
    # the extern C includes the header named after the rule file
    (tmp_path / "spin.c").write_text((EXAMPLES / "spin.c").read_text().replace(
        "extern_spin_externs.h", "spin_rules_externs.h"))
    with open(tmp_path / "spin_rules.epk", "a", encoding="utf-8") as f:
        f.write("\nconst UNUSED = 5 mm\n")
    return tmp_path / "spin_rules.epk"


def test_second_run_prints_the_same_and_skips_the_front_end(program):
    first, first_modules, first_err = imported("run", program.name, cwd=program.parent)
    assert first.returncode == 0, first_err
    assert "W007" in first_err and "epuckc.check.checker" in first_modules
    second, modules, second_err = imported("run", program.name, cwd=program.parent)
    assert second.returncode == 0, second_err
    assert second.stdout == first.stdout
    assert second_err == first_err                  # the warning is shown again
    for name in ("jinja2", "epuckc.check.checker", "epuckc.syntax.parser", "epuckc.lower.program", "epuckc.emit.program",
                 "epuckc.check.frontend"):
        assert name not in modules, name


def test_werror_fails_on_cached_warnings(program):
    assert epuckc("run", program.name, cwd=program.parent).returncode == 0
    result = epuckc("run", program.name, "--werror", cwd=program.parent)
    assert result.returncode == 1 and "W007" in result.stderr


def _run(program):
    result, modules, err = imported("run", program.name, cwd=program.parent)
    assert result.returncode == 0, err
    return result.stdout, "epuckc.check.checker" in modules


def test_an_edited_rule_file_is_built_again(program):
    _run(program)
    text = program.read_text(encoding="utf-8")
    program.write_text(text.replace("const UNUSED = 5 mm", "const UNUSED = 6 mm"), encoding="utf-8")
    _, checked = _run(program)
    assert checked


def test_an_edited_extern_file_is_built_again(program):
    first, _ = _run(program)
    spin = program.parent / "spin.c"
    spin.write_text(spin.read_text(encoding="utf-8") + "\n/* edited */\n", encoding="utf-8")
    _, checked = _run(program)
    assert checked
    again, checked = _run(program)
    assert not checked and again == first


def test_a_deleted_executable_is_built_again(program):
    first, _ = _run(program)
    cache = Path(os.environ["EPUCKC_CACHE_DIR"])
    for exe in (cache / "host").glob(f"*/{program.stem}"):
        exe.unlink()
    second, checked = _run(program)
    assert checked and second == first


def test_capacity_options_are_part_of_the_key(program):
    _run(program)
    result, modules, err = imported("run", program.name, "--max-events", "1", cwd=program.parent)
    assert result.returncode == 0, err      # the rules are tables: no capacity to exceed
    assert "epuckc.check.checker" in modules      # another key: checked and built, not the cached run


def test_the_key_follows_the_runtime_and_the_compiler(program, tmp_path, monkeypatch):
    from epuckc.build import runcache
    runtime = tmp_path / "rt"
    shutil.copytree(REPO / "runtime_c", runtime, ignore=shutil.ignore_patterns("build"))
    monkeypatch.setattr(runcache, "runtime_dir", lambda: runtime)
    data = program.read_bytes()

    def key():
        return runcache.input_key(program, data, program.name, None, None)

    before = key()
    assert key() == before
    header = runtime / "epuckrt.h"
    os.utime(header, ns=(time.time_ns(), header.stat().st_mtime_ns + 1_000_000))
    assert key() != before
    before = key()
    monkeypatch.setenv("CC", "clang")
    assert key() != before
    assert runcache.input_key(program, data + b"\n", program.name, None, None) != before


def test_check_imports_neither_lark_nor_jinja2_nor_lowering():
    """`check` loads the parse tables from the cache and, for a program
    within the runtime's capacity, never lowers it (checker._capacity).
    Nor does it import `dataclasses` (with `inspect`, ~10 ms): the modules
    it imports declare their classes with epuckc.records.record."""
    example = EXAMPLES / "obstacle_avoidance.epk"
    imported("check", example)                  # the tables are in the cache now
    result, modules, err = imported("check", example)
    assert result.returncode == 0, err
    for name in ("lark", "jinja2", "epuckc.lower.program", "epuckc.emit.program", "json", "difflib", "hashlib"):
        assert name not in modules, f"`epuckc check` imports {name}: import it where it is used"
    for name in ("dataclasses", "inspect"):
        assert name not in modules, (
            f"`epuckc check` imports {name}: declare the classes of the modules check imports "
            "with epuckc.records.record (same syntax as @dataclass), see docs/performance.md")


WORLD = "arena 60 cm x 60 cm\nrobot at 20 cm, 20 cm heading 30 deg\nrobot at 40 cm, 35 cm\n"


def test_a_world_run_skips_the_front_end_the_second_time(program):
    """`run --world` of a rule file built before goes straight to its
    robot: the same output and trace, the warning shown again, no front
    end, no Jinja2, no dataclasses; an edited rule file is checked again."""
    from tests.conftest import require_enki
    require_enki()
    world = program.parent / "w.world"
    world.write_text(WORLD, encoding="utf-8")
    args = ("run", program.name, "--world", "w.world", "--time-limit", "2s", "--trace", "t.jsonl")
    first, first_modules, first_err = imported(*args, cwd=program.parent)
    assert first.returncode == 3, first_err
    assert "W007" in first_err and "epuckc.check.checker" in first_modules
    first_trace = (program.parent / "t.jsonl").read_bytes()
    second, modules, second_err = imported(*args, cwd=program.parent)
    assert second.returncode == 3, second_err
    assert (second.stdout, second_err) == (first.stdout, first_err)
    assert (program.parent / "t.jsonl").read_bytes() == first_trace
    for name in ("jinja2", "epuckc.check.checker", "epuckc.syntax.parser", "epuckc.lower.program",
                 "epuckc.emit.program", "epuckc.check.frontend", "epuckc.build.host",
                 "dataclasses"):
        assert name not in modules, name
    # the plain run of the same file is another entry
    plain, plain_modules, _ = imported("run", program.name, cwd=program.parent)
    assert plain.returncode == 0 and "epuckc.check.checker" in plain_modules
    text = program.read_text(encoding="utf-8")
    program.write_text(text.replace("const UNUSED = 5 mm", "const UNUSED = 7 mm"), encoding="utf-8")
    third, modules, _ = imported(*args, cwd=program.parent)
    assert third.returncode == 3 and "epuckc.check.checker" in modules
