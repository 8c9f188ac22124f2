"""The user's C is its own translation unit: compiled on its own against the
generated externs header, linked, copied into the dspic project under
collision-free names, and never written over. No command writes over one of
its inputs, and the dspic project never writes outside -o DIR."""
import os
import stat
import subprocess
from pathlib import Path

import pytest

from tests.conftest import require_tool

from tests.support.programs import epuckc, run_program

SPIN_RULES = """extern action spin(turns: int, speed: speed) from "{path}"
on immediate  do spin(turns: 1, speed: 500 steps/s)
on stop_motor do exit_main
"""

SPIN_C = """#include "{header}"
static param_start_curve spin_curve;
void spin(void *param)
{{
    const param_spin *p = (const param_spin *)param;
    spin_curve.radius = 0;
    spin_curve.degrees = 360 * p->turns;
    spin_curve.speed = p->speed;
    start_curve(&spin_curve);
}}
"""


def make_program(folder: Path, name: str, c_path: str, c_file: Path = None, mode=0o600):
    """A rule file NAME.epk whose extern spin is in c_path (relative to it,
    or absolute); returns (rule file, C file, the C file's state)."""
    folder.mkdir(parents=True, exist_ok=True)
    rules = folder / f"{name}.epk"
    rules.write_text(SPIN_RULES.format(path=c_path))
    c_file = c_file or folder / c_path
    c_file.parent.mkdir(parents=True, exist_ok=True)
    c_file.write_text(SPIN_C.format(header=f"{name}_externs.h"))
    os.chmod(c_file, mode)
    return rules, c_file, snapshot(c_file)


def snapshot(path: Path):
    st = path.stat()
    return path.read_bytes(), stat.S_IMODE(st.st_mode), st.st_mtime_ns


def tree(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): snapshot(p) for p in sorted(folder.rglob("*"))
            if p.is_file()}


def test_extern_file_named_like_the_program(tmp_path):
    """robot.epk with robot.c: compile's default output would be robot.c."""
    rules, c_file, before = make_program(tmp_path, "robot", "robot.c")
    result = epuckc("compile", rules)
    assert result.returncode == 2, result.stderr
    assert "robot.c" in result.stderr and "-o" in result.stderr
    assert snapshot(c_file) == before
    # run builds it as its own translation unit, and it works
    records, _ = run_program(rules, tmp_path)
    assert records[-1]["kind"] == "exit"
    assert snapshot(c_file) == before
    # build -o into the rule file's own folder would write robot.c: refused
    result = epuckc("build", rules, "-o", tmp_path)
    assert result.returncode == 2 and "robot.c" in result.stderr
    assert snapshot(c_file) == before
    # elsewhere: the program, its header and the executable
    out = tmp_path / "out"
    epuckc("build", rules, "-o", out, check=True)
    assert {p.name for p in out.iterdir()} == {"robot.c", "robot_externs.h", "robot"}
    assert snapshot(c_file) == before


def test_compile_writes_the_header_beside_the_c_file(tmp_path):
    rules, c_file, before = make_program(tmp_path, "robot", "robot.c")
    out = tmp_path / "gen" / "prog.c"
    out.parent.mkdir()
    epuckc("compile", rules, "-o", out, check=True)
    header = out.parent / "robot_externs.h"
    assert '#include "robot_externs.h"' in out.read_text()
    text = header.read_text()
    assert "typedef struct {\n    int turns;\n    int speed;\n} param_spin;" in text
    assert "void spin(void *);" in text
    # the user's C compiles on its own against it, strictly
    cc = require_tool("cc")
    runtime = Path(__file__).resolve().parents[2] / "runtime_c"
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic",
                    f"-I{out.parent}", f"-I{runtime}", "-c", str(c_file), "-o",
                    str(tmp_path / "spin.o")], check=True)
    assert snapshot(c_file) == before


def test_compile_onto_an_input_is_refused(tmp_path):
    rules, c_file, before = make_program(tmp_path, "robot", "spin.c")
    rule_text = rules.read_bytes()
    for target in (rules, c_file):
        result = epuckc("compile", rules, "-o", target)
        assert result.returncode == 2, result.stderr
    assert rules.read_bytes() == rule_text and snapshot(c_file) == before
    # the header would land on an input: nothing at all is written
    rules, c_file, before = make_program(tmp_path, "robot", "robot_externs.h")
    result = epuckc("compile", rules, "-o", tmp_path / "x.c")
    assert result.returncode == 2 and "robot_externs.h" in result.stderr
    assert not (tmp_path / "x.c").exists()
    assert snapshot(c_file) == before


def test_extern_file_named_like_the_runtime(tmp_path):
    rules, c_file, before = make_program(tmp_path, "prog", "epuckrt.c")
    records, _ = run_program(rules, tmp_path)
    assert records[-1]["kind"] == "exit"
    out = tmp_path / "proj"
    epuckc("build", rules, "--target", "dspic", "-o", out,
           env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    runtime = Path(__file__).resolve().parents[2] / "runtime_c" / "epuckrt.c"
    assert (out / "runtime" / "epuckrt.c").read_bytes() == runtime.read_bytes()
    assert (out / "user" / "1_epuckrt.c").read_bytes() == before[0]
    assert snapshot(c_file) == before


def test_dspic_copy_of_a_file_outside_the_rule_folder_stays_inside_dir(tmp_path):
    rules, c_file, before = make_program(tmp_path / "app", "prog", "../lib/spin.c")
    outside = tree(tmp_path / "lib")
    out = tmp_path / "app" / "proj"
    result = epuckc("build", rules, "--target", "dspic", "-o", out,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 3, result.stderr        # no XC16 here
    assert tree(tmp_path / "lib") == outside
    assert (out / "user" / "1_spin.c").read_bytes() == before[0]
    written = {p for p in tmp_path.rglob("*") if p.is_file()} - {rules, c_file.resolve()}
    assert all(out in p.parents for p in written), written


def test_dspic_absolute_path_is_copied_with_its_mode_and_left_alone(tmp_path):
    elsewhere = tmp_path / "elsewhere" / "spin.c"
    rules, c_file, before = make_program(tmp_path / "app", "prog", str(elsewhere), elsewhere,
                                         mode=0o600)
    out = tmp_path / "proj"
    epuckc("build", rules, "--target", "dspic", "-o", out,
           env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert snapshot(c_file) == before                    # content, 0600 and time
    copy = out / "user" / "1_spin.c"
    assert copy.read_bytes() == before[0]
    assert stat.S_IMODE(copy.stat().st_mode) == 0o600
    # built again: nothing changes, the copy is not even rewritten
    first = tree(out)
    epuckc("build", rules, "--target", "dspic", "-o", out,
           env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert tree(out) == first and snapshot(c_file) == before


def test_dspic_into_the_rule_folder_would_overwrite_an_input(tmp_path):
    rules, c_file, before = make_program(tmp_path, "robot", "robot.c")
    result = epuckc("build", rules, "--target", "dspic", "-o", tmp_path,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 2 and "robot.c" in result.stderr
    assert snapshot(c_file) == before
    assert {p.name for p in tmp_path.iterdir()} == {"robot.epk", "robot.c"}


def test_dspic_project_never_writes_through_a_link_out_of_dir(tmp_path):
    rules, c_file, before = make_program(tmp_path / "app", "prog", "spin.c")
    out = tmp_path / "proj"
    out.mkdir()
    (tmp_path / "victim").mkdir()
    (out / "user").symlink_to(tmp_path / "victim")
    result = epuckc("build", rules, "--target", "dspic", "-o", out,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 2 and "outside" in result.stderr
    assert list((tmp_path / "victim").iterdir()) == []


def test_trace_onto_an_input_is_refused(tmp_path):
    rules, c_file, before = make_program(tmp_path, "prog", "spin.c")
    result = epuckc("run", rules, "--trace", c_file)
    assert result.returncode == 2, result.stderr
    assert snapshot(c_file) == before


def test_warnings_in_user_c_name_the_users_file_and_are_not_fatal(tmp_path):
    rules, c_file, _ = make_program(tmp_path, "prog", "spin.c")
    c_file.write_text(c_file.read_text().replace(
        "    spin_curve.radius = 0;", "    int unused_here;\n    spin_curve.radius = 0;"))
    result = epuckc("run", "prog.epk", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "spin.c:6:9: warning: unused variable" in result.stderr
    assert ".cache" not in result.stderr and "/tmp/" not in result.stderr.split("warning")[0]


def test_warnings_in_hand_written_c_name_the_users_file(tmp_path):
    prog = tmp_path / "fig.c"
    prog.write_text('#include "utility.h"\nint main(void)\n{\n    int e1;\n'
                    '    e1 = register_action(exit_main, NULL);\n'
                    '    register_event(immediate, NULL, e1);\n    mainloop();\n    return 0;\n}\n'
                    .replace("int e1;", "int e1, unused;"))
    result = epuckc("run", "fig.c", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stderr.startswith("fig.c:") and "unused" in result.stderr


def test_one_c_file_for_several_externs_is_compiled_once(tmp_path):
    (tmp_path / "two.c").write_text('#include "prog_externs.h"\n'
                                    "void a(void *p) { (void)p; }\n"
                                    "void b(void *p) { (void)p; exit_main(NULL); }\n")
    (tmp_path / "prog.epk").write_text('extern action a() from "two.c"\n'
                                       'extern action b() from "./two.c"\n'
                                       "on immediate do a, b\n")
    records, _ = run_program(tmp_path / "prog.epk", tmp_path)
    assert records[-1]["kind"] == "exit"


@pytest.fixture
def fake_toolchain(tmp_path):
    from .test_build import _fake_library, _fake_xc16
    log = tmp_path / "xc16.log"
    _fake_xc16(tmp_path / "xc16" / "bin", log)
    return {"XC16_DIR": str(tmp_path / "xc16"), "EPUCK_LIB": str(_fake_library(tmp_path))}, log


def test_dspic_make_rebuilds_only_what_changed(tmp_path, fake_toolchain):
    env, log = fake_toolchain
    make = require_tool("make")
    rules, c_file, _ = make_program(tmp_path / "app", "prog", "spin.c")
    out = tmp_path / "proj"
    epuckc("build", rules, "--target", "dspic", "-o", out, env=env, check=True)
    args = [make, "-C", str(out), f"EPUCK_LIB={env['EPUCK_LIB']}", f"XC16_DIR={env['XC16_DIR']}"]
    # up to date: `make -q` says so, and a second make compiles nothing
    assert subprocess.run(args + ["-q", "prog.hex"]).returncode == 0
    log.write_text("")
    subprocess.run(args, check=True, capture_output=True)
    assert log.read_text() == ""
    # epuckc build again with nothing changed: still nothing to do
    epuckc("build", rules, "--target", "dspic", "-o", out, env=env, check=True)
    assert log.read_text() == ""
    # the user's file changed: only its copy is compiled, then the link
    c_file.write_text(c_file.read_text() + "\n/* edited */\n")
    epuckc("build", rules, "--target", "dspic", "-o", out, env=env, check=True)
    compiles = [c for c in log.read_text().splitlines() if " -c " in c]
    assert len(compiles) == 1 and "user/1_spin.c" in compiles[0]


def test_extern_path_with_a_quote_and_a_backslash(tmp_path):
    """The path never reaches C: no `#include "we"ird.c"` any more."""
    rules, c_file, before = make_program(tmp_path, "prog", 'we"ird\\x.c')
    rules.write_text(SPIN_RULES.format(path='we\\"ird\\\\x.c'))
    records, _ = run_program(rules, tmp_path)
    assert records[-1]["kind"] == "exit"
    out = tmp_path / "proj"
    epuckc("build", rules, "--target", "dspic", "-o", out,
           env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert (out / "user" / "1_we_ird_x.c").read_bytes() == before[0]
    assert '"' not in (out / "Makefile").read_text().split("USER_SOURCES =")[1].splitlines()[0]


def test_compile_to_standard_output_says_where_the_header_is(tmp_path):
    rules, c_file, before = make_program(tmp_path, "prog", "spin.c")
    result = epuckc("compile", rules, "-o", "-", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert '#include "prog_externs.h"' in result.stdout
    assert "prog_externs.h" in result.stderr and "note" in result.stderr
    assert not (tmp_path / "prog_externs.h").exists()


def _with_headers(folder: Path, name="prog", stale=False):
    """spin.c including a header beside it, which includes one below it;
    with `stale`, an old copy of the generated externs header beside it."""
    rules, c_file, _ = make_program(folder, name, "spin.c")
    c_file.write_text('#include "spin_util.h"\n' + c_file.read_text()
                      .replace("360 * p->turns", "SPIN_DEGREES(p->turns)"))
    (folder / "spin_util.h").write_text('#include "sub/deep.h"\n'
                                        "#define SPIN_DEGREES(t) (DEGREES_PER_TURN * (t))\n")
    (folder / "sub").mkdir()
    (folder / "sub" / "deep.h").write_text("#define DEGREES_PER_TURN 360\n")
    if stale:
        (folder / f"{name}_externs.h").write_text("#error a stale header, not this program's\n")
    return rules, c_file


def test_dspic_project_carries_the_headers_the_users_c_includes(tmp_path):
    """The C is copied into user/: the headers it includes from beside it
    come along at the same place relative to it, and the project compiles
    as the host build does (which runs the program)."""
    rules, c_file = _with_headers(tmp_path / "app")
    records, _ = run_program(rules, tmp_path / "app")
    assert records[-1]["kind"] == "exit"
    out = tmp_path / "proj"
    result = epuckc("build", rules, "--target", "dspic", "-o", out,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 3, result.stderr                # no XC16 here
    app = tmp_path / "app"
    assert (out / "user" / "spin_util.h").read_bytes() == (app / "spin_util.h").read_bytes()
    assert (out / "user" / "sub" / "deep.h").read_bytes() == (app / "sub" / "deep.h").read_bytes()
    makefile = (out / "Makefile").read_text()
    assert "USER_HEADERS = user/spin_util.h user/sub/deep.h" in makefile
    cc = require_tool("cc")
    api = Path(__file__).resolve().parents[2] / "runtime_c" / "epuck_api"
    subprocess.run([cc, "-std=c99", "-Wall", "-c", str(out / "user" / "1_spin.c"), f"-I{out}",
                    f"-I{out / 'runtime'}", f"-I{api}", "-o", str(tmp_path / "spin.o")],
                   check=True)


def test_dspic_project_with_an_edited_header_rebuilds_the_users_c(tmp_path, fake_toolchain):
    env, log = fake_toolchain
    make = require_tool("make")
    rules, c_file = _with_headers(tmp_path / "app")
    out = tmp_path / "proj"
    epuckc("build", rules, "--target", "dspic", "-o", out, env=env, check=True)
    log.write_text("")
    deep = tmp_path / "app" / "sub" / "deep.h"
    deep.write_text(deep.read_text() + "/* edited */\n")
    epuckc("build", rules, "--target", "dspic", "-o", out, env=env, check=True)
    compiles = [c for c in log.read_text().splitlines() if " -c " in c]
    assert len(compiles) == 1 and "user/1_spin.c" in compiles[0]
    assert make


@pytest.mark.parametrize("layout", ["climbs", "clash"])
def test_dspic_project_refuses_headers_it_cannot_lay_out(tmp_path, layout):
    """A header above the C's folder, or two different headers that would
    be the same copy: a clear message, exit 2, and no project."""
    app = tmp_path / "app"
    rules, c_file, _ = make_program(app, "prog", "spin.c")
    if layout == "climbs":
        (tmp_path / "common.h").write_text("#define X 1\n")
        c_file.write_text('#include "../common.h"\n' + c_file.read_text())
        expected = "a header outside its folder"
    else:
        rules.write_text(rules.read_text() + 'extern action wave() from "other/wave.c"\n'
                         "on stop_motor do wave\n")
        (app / "other").mkdir()
        (app / "other" / "wave.c").write_text('#include "util.h"\nvoid wave(void *p) { (void)p; }\n')
        (app / "other" / "util.h").write_text("#define U 2\n")
        (app / "util.h").write_text("#define U 1\n")
        c_file.write_text('#include "util.h"\n' + c_file.read_text())
        expected = "two different headers"
    out = tmp_path / "proj"
    result = epuckc("build", rules, "--target", "dspic", "-o", out,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 2, result.stdout + result.stderr
    assert expected in result.stderr and "Traceback" not in result.stderr
    assert not out.exists()


def test_a_stale_externs_header_beside_the_c_is_named_not_compiled(tmp_path):
    """An externs header an earlier `epuckc compile` left beside the C
    would be read instead of the current one: the host build says so; the
    dspic project does not copy it (its own is at the top)."""
    rules, c_file = _with_headers(tmp_path / "app", stale=True)
    result = epuckc("run", rules, cwd=tmp_path)
    assert result.returncode == 1, result.stdout + result.stderr
    assert "is not the externs header of this program" in result.stderr
    assert "prog_externs.h" in result.stderr and "Traceback" not in result.stderr
    out = tmp_path / "proj"
    result = epuckc("build", rules, "--target", "dspic", "-o", out,
                    env={"PATH": "/usr/bin:/bin", "XC16_DIR": ""})
    assert result.returncode == 3, result.stderr
    assert not (out / "user" / "prog_externs.h").exists()
    assert (out / "user" / "spin_util.h").exists()
    # rewritten by compile: the host build takes it
    epuckc("compile", rules, "-o", tmp_path / "app" / "prog.c", check=True)
    records, _ = run_program(rules, tmp_path / "app")
    assert records[-1]["kind"] == "exit"


def test_an_edited_header_of_the_users_c_is_built_again(tmp_path):
    """The host build and the run cache depend on the headers the user's
    C includes, not only on the C: the edit is seen."""
    rules, c_file = _with_headers(tmp_path / "app")
    first, _ = run_program(rules, tmp_path / "app")
    deep = tmp_path / "app" / "sub" / "deep.h"
    deep.write_text("#define DEGREES_PER_TURN 720\n")
    second, _ = run_program(rules, tmp_path / "app")
    assert first[-1]["kind"] == second[-1]["kind"] == "exit"
    assert second[-1]["t_ms"] > first[-1]["t_ms"]   # twice the turning takes longer
