"""The generated C's names and text: every name epuckc makes up is under its
reserved prefix, the names the checker refuses come from the headers, every
string that reaches C is escaped for C, and the C grows linearly with the
rule file."""
import re
import subprocess

from epuckc.base.resources import RUNTIME_CORE, RUNTIME_DEVICES, RUNTIME_SIMULATED
from epuckc.build.common import HOST_SOURCES
from epuckc.check.cnames import KEYWORDS, is_reserved, visible_names
from epuckc.lower.program import PREFIX, c_comment, c_string
from tests.conftest import require_tool

from tests.support.programs import EXAMPLES, REPO, epuckc

GOLDEN = REPO / "tests" / "golden"
RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def identifiers(c_text: str) -> set:
    text = re.sub(r"/\*.*?\*/", " ", c_text, flags=re.S)
    text = re.sub(r'"(?:[^"\\]|\\.)*"', " ", text)
    text = re.sub(r"^#.*$", " ", text, flags=re.M)
    return set(re.findall(r"\b[A-Za-z_][A-Za-z0-9_]*\b", text)) - set(re.findall(
        r"\b[0-9][A-Za-z0-9_]*\b", text))


def test_every_generated_name_is_under_the_prefix_or_declared_by_a_header(tmp_path):
    names = visible_names()
    for case in ["names", "extern", "sequences", "cancel", "events", "units"]:
        out = tmp_path / f"{case}.c"
        epuckc("compile", GOLDEN / f"{case}.epk", "-o", out, check=True)
        externs = set(re.findall(r"extern (?:action|event) (\w+)",
                                 (GOLDEN / f"{case}.epk").read_text()))
        for name in identifiers(out.read_text()):
            made_up = name.startswith(PREFIX)
            known = name in KEYWORDS or names.declared(name) or name == "main"
            user = name in externs or name.removeprefix("param_") in externs
            assert made_up or known or user, f"{case}.c: `{name}` could clash with a user name"


def test_runtime_symbols_are_all_known_to_the_checker(tmp_path):
    """Every external symbol of the runtime (its device files too) and of
    the host harness (every file a host build links) is a name the checker
    refuses to an extern (taken from the headers), so no extern can clash
    at link time."""
    cc, nm = require_tool("cc"), require_tool("nm")
    names = visible_names()
    sources = list(dict.fromkeys([*HOST_SOURCES, *RUNTIME_DEVICES, "platform/platform_robot.c"]))
    assert set(RUNTIME_CORE) | set(RUNTIME_SIMULATED) | set(RUNTIME_DEVICES) <= set(sources)
    for src in sources:
        obj = tmp_path / "x.o"
        subprocess.run([cc, *STRICT, f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}",
                        f"-I{RUNTIME / 'host'}", f"-I{RUNTIME / 'epuck_api_unsimulated'}",
                        "-c", str(RUNTIME / src), "-o", str(obj)], check=True)
        listing = subprocess.run([nm, "-g", "--defined-only", str(obj)], capture_output=True,
                                 text=True, check=True).stdout
        for symbol in (line.split()[-1] for line in listing.splitlines() if line.strip()):
            # (a reserved name, `__x`, is refused to an extern as such)
            assert names.declared(symbol) or is_reserved(symbol, file_scope=True), \
                f"{src} defines `{symbol}`, unknown to the checker"


def test_c_strings_and_comments_are_escaped():
    assert c_string('a"b\\c??=d\u00e9') == '"a\\"b\\\\c\\?\\?=d\\303\\251"'
    comment = c_comment("x */ y /* z ??= ??/ \u00e9\n w")
    assert "*/" not in comment and "/*" not in comment and "??" not in comment
    assert comment.isascii() and "\n" not in comment and "\\u00E9" in comment


def test_hostile_file_name_compiles_with_trigraphs_enabled(tmp_path):
    cc = require_tool("cc")
    hostile = tmp_path / "x??=\u00e9*\\ *.epk"
    hostile.write_text((EXAMPLES / "paper_fig2.epk").read_text())
    out = tmp_path / "out.c"
    epuckc("compile", hostile, "-o", out, check=True)
    text = out.read_text()
    assert text.isascii() and "??" not in text
    subprocess.run([cc, *STRICT, "-trigraphs", f"-I{RUNTIME}", "-c", str(out), "-o",
                    str(tmp_path / "out.o")], check=True)


def test_c_grows_linearly_with_a_long_sequence(tmp_path):
    sizes = []
    for steps in (200, 400):
        rules = tmp_path / f"s{steps}.epk"
        body = " then ".join(f"start_straight(300, {1 + i % 9} cm), set_timer" for i in range(steps))
        rules.write_text(f"on immediate do {body}\non stop_motor do exit_main\n")
        out = tmp_path / f"s{steps}.c"
        epuckc("compile", rules, "-o", out, check=True)
        sizes.append(out.stat().st_size)
    # each step's function says its own step, not the whole rule again
    assert sizes[1] < 2.1 * sizes[0], sizes
