"""Builds and the command line: the dspic project, hand-written C, atomic
output, determinism, caching, the wheel."""
import os
import shutil
import stat
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from epuckc.base.resources import RUNTIME_CORE, RUNTIME_DSPIC_DEVICES
from tests.conftest import require_tool

from tests.support.programs import EXAMPLES, REPO, epuckc

RUNTIME = REPO / "runtime_c"
EPUCK_API = RUNTIME / "epuck_api"
WARN = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def dspic_project(tmp_path, example="extern_spin.epk", env=None):
    out = tmp_path / "proj"
    result = epuckc("build", EXAMPLES / example, "--target", "dspic", "-o", out,
                    env={"PATH": os.environ["PATH"], "XC16_DIR": "", **(env or {})})
    return out, result


def test_dspic_without_xc16_writes_the_project_and_says_what_is_missing(tmp_path):
    out, result = dspic_project(tmp_path, env={"PATH": "/usr/bin:/bin"})
    assert result.returncode == 3, result.stderr
    assert "xc16-gcc" in result.stderr and str(out) in result.stderr
    assert "Traceback" not in result.stderr
    for name in ("extern_spin.c", "extern_spin_externs.h", "runtime/epuckrt.c",
                 "runtime/platform_robot.c", "runtime/epuckrt.h", "runtime/utility.h",
                 "runtime/rt_platform.h", "user/1_spin.c", "Makefile"):
        assert (out / name).is_file(), name


def test_dspic_project_compiles_on_the_host_against_the_library_declarations(tmp_path):
    out, _ = dspic_project(tmp_path)
    cc = require_tool("cc")
    for source in ("extern_spin.c", "runtime/epuckrt.c", "runtime/platform_robot.c",
                   "user/1_spin.c"):
        subprocess.run([cc, *WARN, f"-I{out}", f"-I{out / 'runtime'}", f"-I{EPUCK_API}", "-c",
                        str(out / source), "-o", str(tmp_path / "x.o")], check=True)


@pytest.mark.parametrize("example", ["square.epk", "explorer.epk", "two_phase.epk",
                                     "selector_menu.epk"])
def test_dspic_project_compiles_with_16_bit_int(tmp_path, example):
    out, _ = dspic_project(tmp_path, example=example)
    avr = require_tool("avr-gcc")
    for source in (example.replace(".epk", ".c"), "runtime/epuckrt.c", "runtime/platform_robot.c"):
        subprocess.run([avr, "-mmcu=atmega128", *WARN, "-Os", f"-I{out}", f"-I{out / 'runtime'}",
                        f"-I{EPUCK_API}", "-c", str(out / source), "-o", str(tmp_path / "x.o")],
                       check=True)


def _fake_xc16(bin_dir: Path, log: Path):
    """xc16-gcc and xc16-bin2hex that record their arguments and make the
    files a real toolchain would."""
    bin_dir.mkdir(parents=True)
    gcc = bin_dir / "xc16-gcc"
    gcc.write_text(f"""#!/bin/sh
echo "xc16-gcc $*" >> {log}
out=""
while [ $# -gt 0 ]; do [ "$1" = "-o" ] && out="$2"; shift; done
[ -n "$out" ] && : > "$out"
exit 0
""")
    hexer = bin_dir / "xc16-bin2hex"
    hexer.write_text(f"""#!/bin/sh
echo "xc16-bin2hex $*" >> {log}
: > "${{1%.elf}}.hex"
""")
    for tool in (gcc, hexer):
        tool.chmod(tool.stat().st_mode | stat.S_IXUSR)


def _library_sources() -> list:
    """The paths of GCtronic's library that the generated Makefile compiles
    (templates/dspic.mk.j2's `$(LIB)/...`)."""
    template = (REPO / "templates" / "dspic.mk.j2").read_text()
    template = re.sub(r"\{% if trace %\}.*?\{% endif %\}", "", template, flags=re.S)
    return sorted(set(re.findall(r"\$\(LIB\)/([\w/.]+\.[cs])\b", template)))


def _fake_library(root: Path) -> Path:
    """A stand-in of GCtronic's library: an empty file at each of its paths
    that the generated Makefile names."""
    lib = root / "e-puck-library"
    for rel in _library_sources():
        (lib / "library" / rel).parent.mkdir(parents=True, exist_ok=True)
        (lib / "library" / rel).write_text("/* stand-in */\n")
    return lib


def test_dspic_makefile_dry_run_names_the_xc16_steps(tmp_path):
    out, _ = dspic_project(tmp_path)
    lib = _fake_library(tmp_path)
    make = require_tool("make")
    dry = subprocess.run([make, "-n", "-C", str(out), f"EPUCK_LIB={lib}"],
                         capture_output=True, text=True, check=True).stdout
    assert "xc16-gcc -mcpu=30F6014A -omf=elf" in dry
    assert "-DEPUCKRT_NO_NAMES" in dry      # the robot stores no name labels
    assert f"-I{lib}/library" in dry
    assert "-Tp30F6014A.gld" in dry and "xc16-bin2hex extern_spin.elf" in dry
    for source in ("extern_spin.c", "epuckrt.c", "platform_robot.c", "e_agenda.c", "e_prox.c"):
        assert source in dry


def test_dspic_arrays_shrink_unless_user_c_can_register(tmp_path):
    """A rule file's rules are tables: without user C nothing registers, so
    the dynamic arrays get one entry each; with user C the runtime's default."""
    out, _ = dspic_project(tmp_path / "a", example="square.epk")
    makefile = (out / "Makefile").read_text()
    assert "-DMAX_ACTIONS=1 -DMAX_EVENTS=1 -DEPUCKRT_NO_NAMES" in makefile
    out, _ = dspic_project(tmp_path / "b")
    makefile = (out / "Makefile").read_text()
    assert "MAX_ACTIONS" not in makefile and "-DEPUCKRT_NO_NAMES" in makefile


def test_dspic_build_runs_make_with_xc16_from_xc16_dir(tmp_path):
    log = tmp_path / "xc16.log"
    _fake_xc16(tmp_path / "xc16" / "bin", log)
    lib = _fake_library(tmp_path)
    out, result = dspic_project(tmp_path, env={"XC16_DIR": str(tmp_path / "xc16"),
                                               "EPUCK_LIB": str(lib)})
    assert result.returncode == 0, result.stdout + result.stderr
    assert (out / "extern_spin.hex").is_file()
    calls = log.read_text().splitlines()
    compiles = [c for c in calls if " -c " in c]
    # program, the runtime's files (its core and the e-puck's devices), robot
    # layer, spin.c + the library's C and assembly files
    assert len(compiles) == 1 + len(RUNTIME_CORE) + len(RUNTIME_DSPIC_DEVICES) + 1 + 1 \
        + len(_library_sources())
    # generated C is -Werror, the user's not
    [program] = [c for c in compiles if c.endswith("-c extern_spin.c -o extern_spin.o")]
    [user] = [c for c in compiles if "user/1_spin.c" in c]
    assert "-Werror" in program and "-Werror" not in user
    assert all("-mcpu=30F6014A" in c for c in calls if c.startswith("xc16-gcc"))
    assert calls[-1] == "xc16-bin2hex extern_spin.elf"


def test_dspic_build_without_epuck_lib_exits_3(tmp_path, monkeypatch):
    log = tmp_path / "xc16.log"
    _fake_xc16(tmp_path / "xc16" / "bin", log)
    env = {"XC16_DIR": str(tmp_path / "xc16")}
    # (for this test only: CI points EPUCK_LIB at the library for the others)
    monkeypatch.delenv("EPUCK_LIB", raising=False)
    out, result = dspic_project(tmp_path, env=env)
    assert result.returncode == 3 and "EPUCK_LIB" in result.stderr


def test_hand_written_paper_figure_2_builds_and_runs(tmp_path):
    fig2 = tmp_path / "fig2.c"
    fig2.write_text((REPO / "tests" / "runtime" / "paper_fig2.c").read_text())
    result = epuckc("run", fig2)
    assert result.returncode == 0, result.stderr
    assert "exit at" in result.stdout
    built = epuckc("build", fig2, "-o", tmp_path / "out")
    assert built.returncode == 0 and (tmp_path / "out" / "fig2").is_file()


def test_c_compiler_errors_are_shown(tmp_path):
    bad = tmp_path / "bad.c"
    bad.write_text("#include \"utility.h\"\nint main(void) { return undefined_thing; }\n")
    result = epuckc("run", bad)
    assert result.returncode == 1
    assert "undefined_thing" in result.stderr and "Traceback" not in result.stderr


def test_compile_is_deterministic_and_has_no_absolute_paths(tmp_path):
    a, b = tmp_path / "a.c", tmp_path / "b.c"
    epuckc("compile", EXAMPLES / "obstacle_avoidance.epk", "-o", a, check=True)
    epuckc("compile", "obstacle_avoidance.epk", "-o", b, cwd=EXAMPLES, check=True)
    assert a.read_bytes() == b.read_bytes()
    assert str(REPO) not in a.read_text() and "/tmp" not in a.read_text()


def test_failed_compile_leaves_an_existing_output_untouched(tmp_path):
    bad = tmp_path / "bad.epk"
    bad.write_text("on immediate do nothing_such\n")
    out = tmp_path / "out.c"
    out.write_text("previous\n")
    result = epuckc("compile", bad, "-o", out)
    assert result.returncode == 1 and "E011" in result.stderr
    assert out.read_text() == "previous\n"
    assert list(tmp_path.iterdir()) == sorted([bad, out]) or set(tmp_path.iterdir()) == {bad, out}


def test_run_of_a_broken_rule_file_reports_and_builds_nothing(tmp_path):
    bad = tmp_path / "bad.epk"
    bad.write_text("on immediate do\n")
    result = epuckc("run", bad)
    assert result.returncode == 1 and "E001" in result.stderr and "Traceback" not in result.stderr


def test_second_run_uses_the_cache(tmp_path):
    epuckc("run", EXAMPLES / "paper_fig2.epk", check=True)
    cache = Path(os.environ["EPUCKC_CACHE_DIR"]) / "host"
    before = {p: p.stat().st_mtime_ns for p in cache.rglob("paper_fig2")}
    epuckc("run", EXAMPLES / "paper_fig2.epk", check=True)
    after = {p: p.stat().st_mtime_ns for p in cache.rglob("paper_fig2")}
    assert before and before == after


@pytest.mark.parametrize("command", ["check", "explain", "compile", "build", "run"])
def test_every_command_has_help(command):
    result = epuckc(command, "-h")
    assert result.returncode == 0 and "usage: epuckc" in result.stdout


def test_missing_file_is_a_usage_error(tmp_path):
    result = epuckc("run", tmp_path / "nope.epk")
    assert result.returncode == 2 and "nope.epk" in result.stderr
    assert "Traceback" not in result.stderr


def test_wheel_in_a_fresh_virtual_environment_runs_an_example(tmp_path):
    """The wheel carries grammar, templates and runtime: no checkout needed."""
    require_tool("cc")
    dist = tmp_path / "dist"
    subprocess.run([sys.executable, "-m", "build", "--wheel", "--outdir", str(dist), str(REPO)],
                   check=True, capture_output=True)
    [wheel] = dist.glob("epuckc-*.whl")
    with zipfile.ZipFile(wheel) as archive:     # the C front end is built into it
        assert any(n.startswith("epuckc/syntax/_front.") and n.endswith(".so") for n in archive.namelist())
        # and the studio's page, built (docs/studio.md): no node needed
        assert {"epuckc/studio/static/index.html", "epuckc/studio/static/studio.js",
                "epuckc/studio/static/studio.css"} <= set(archive.namelist())
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip = venv / "bin" / "pip"
    # Without PYTHONPATH: a checkout on it (with the epuckc.egg-info the build
    # leaves there) would make pip think epuckc is installed already.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    subprocess.run([str(pip), "install", "--quiet", str(wheel)], check=True, env=env)
    work = tmp_path / "elsewhere"
    work.mkdir()
    shutil.copy(EXAMPLES / "square.epk", work)
    result = subprocess.run([str(venv / "bin" / "epuckc"), "run", "square.epk"], cwd=work,
                            env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "exit at" in result.stdout
    probe = "from epuckc.syntax import parser; print(parser._c_driver() is not None)"
    used = subprocess.run([str(venv / "bin" / "python"), "-c", probe], cwd=work, env=env,
                          capture_output=True, text=True)
    assert used.stdout.strip() == "True", used.stderr


def test_one_name_for_the_xc16_folder():
    """epuckc, the generated Makefile and the docs name XC16's install
    folder the same way: XC16_DIR (a user who exports it for epuckc can run
    `make` in the project with nothing else)."""
    texts = {p: p.read_text(encoding="utf-8") for p in
             [REPO / "templates" / "dspic.mk.j2", REPO / "README.md", REPO / "epuckc" / "build" / "dspic.py",
              *sorted((REPO / "docs").glob("*.md"))]}
    assert all("XC16_BIN" not in text for text in texts.values())
    assert "XC16_DIR ?=" in texts[REPO / "templates" / "dspic.mk.j2"]


def test_dspic_project_of_a_camera_program_has_the_camera_and_compiles_with_16_bit_int(tmp_path):
    """Issue 27: the e-puck has the camera; its project takes the runtime's
    camera file and the library's camera driver (docs/runtime.md)."""
    out, result = dspic_project(tmp_path, example="colour_seeker.epk")
    assert result.returncode == 3, result.stderr
    makefile = (out / "Makefile").read_text()
    assert "runtime/rt_camera.c" in makefile and "$(LIB)/camera/fast_2_timer/e_common.c" in makefile
    avr = require_tool("avr-gcc")
    for source in ("colour_seeker.c", "runtime/rt_camera.c"):
        subprocess.run([avr, "-mmcu=atmega128", *WARN, "-Os", f"-I{out}", f"-I{out / 'runtime'}",
                        f"-I{EPUCK_API}", "-c", str(out / source), "-o", str(tmp_path / "x.o")],
                       check=True)


def test_dspic_build_of_a_program_with_messages_is_a_checker_error_naming_the_target(tmp_path):
    out, result = dspic_project(tmp_path, example="follower.epk")
    assert result.returncode == 1
    assert "error[E070]" in result.stderr and "the e-puck (dspic) does not have" in result.stderr
    assert "Traceback" not in result.stderr and not out.exists()
