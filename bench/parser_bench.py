#!/usr/bin/env python3
"""epuckc's LALR driver against Lark's own LALR parser, in the two ways
Lark can avoid rebuilding its tables at each run: `Lark(..., cache=FILE)`
and a module from its standalone generator (`python -m lark.tools.standalone`).

All three parse the same statements (tokens from epuckc's lexer) into the
same AST (tests/support/lark_reference.py turns Lark's tree into it with
the parser's own callbacks; tests/syntax/test_lalr_vs_lark.py holds
them equal). Two figures each, medians of --runs:

  load    a fresh process: import the parser and get its tables ready
          (epuckc: the marshal cache; Lark: its cache file; standalone:
          import the generated module), minus `python -c pass`
  parse   in one process, CPU time to parse a 1,000-rule file's
          statements to the AST, the tokens made beforehand

    python3 bench/parser_bench.py [--runs 9] [--rules 1000]
"""
from __future__ import annotations

import argparse
import gc
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402

LOAD = {
    "epuckc driver": "from epuckc.syntax.parser import _tables; _tables()",
    "Lark, cache=FILE": ("import sys; sys.path.insert(0, {repo!r}); "
                         "from tests.support.lark_reference import lark_parser; "
                         "lark_parser(cache={cache!r})"),
    "Lark standalone": ("import sys; sys.path.insert(0, {work!r}); import epuck_standalone; "
                        "epuck_standalone.Lark_StandAlone()"),
    "Lark itself": "import lark",
}


def cpu_of(cmd, env) -> float:
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, env=env, check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime) * 1000


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=9)
    ap.add_argument("--rules", type=int, default=1000)
    args = ap.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="epuckc-parser-bench-"))
    cache = work / "lark.cache"
    subprocess.run([sys.executable, "-m", "lark.tools.standalone", "-s", "statement", "-l", "basic",
                    "--propagate_positions", "--maybe_placeholders",
                    str(REPO / "grammar" / "epuck.lark"), "-o", str(work / "epuck_standalone.py")],
                   check=True)
    env = dict(os.environ, PYTHONPATH=str(REPO), EPUCKC_CACHE_DIR=str(work / "epuckc-cache"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)

    # ---- load: fresh processes, interleaved --------------------------------
    codes = {name: code.format(repo=str(REPO), cache=str(cache), work=str(work))
             for name, code in LOAD.items()}
    floor, loads = [], {name: [] for name in codes}
    for name, code in codes.items():                 # warm up: caches, bytecode
        subprocess.run([sys.executable, "-c", code], env=env, check=True)
    for _ in range(args.runs):
        floor.append(cpu_of([sys.executable, "-c", "pass"], env))
        for name, code in codes.items():
            loads[name].append(cpu_of([sys.executable, "-c", code], env))

    # ---- parse: one process ----------------------------------------------------
    from epuckc.syntax import lalr
    from epuckc.diagnostics import Collector
    from epuckc.syntax.lexer import iter_statements, iter_tokens
    from epuckc.syntax.parser import _CALLBACKS, _tables
    from epuckc.base.source import SourceFile, Span
    from tests.support.lark_reference import (TO_AST, lark_parser, lark_tokens,
                                               standalone_parser, to_ast_transformer)

    sys.path.insert(0, str(work))
    import epuck_standalone

    source = SourceFile("bench.epk", generate(args.rules))
    chunks = list(iter_statements(iter_tokens(source, Collector(source))))
    lark_chunks = [lark_tokens(c) for c in chunks]
    tables = _tables()
    lark = lark_parser(cache=str(cache))
    standalone = standalone_parser(epuck_standalone)

    def ours():
        return [lalr.parse(tables, c, _CALLBACKS, meta=Span) for c in chunks]

    standalone_chunks = [lark_tokens(c, epuck_standalone.Token) for c in chunks]

    def with_lark(parser, to_ast, lark_chunks):
        def run():
            return [to_ast.transform(parser.parse(c)) for c in lark_chunks]
        return run

    parsers = {"epuckc driver": ours, "Lark, cache=FILE": with_lark(lark, TO_AST, lark_chunks),
               "Lark standalone": with_lark(standalone, to_ast_transformer(
                   epuck_standalone.Transformer), standalone_chunks)}
    reference = ours()
    parse_times = {name: [] for name in parsers}
    gc.disable()
    for name, run in parsers.items():
        assert run() == reference, f"{name} gives another AST"
    for _ in range(args.runs):
        for name, run in parsers.items():
            start = time.process_time()
            run()
            parse_times[name].append((time.process_time() - start) * 1000)
    gc.enable()

    tokens = sum(len(c) for c in chunks)
    print(f"python {sys.version.split()[0]}; {args.rules} rules, {len(chunks)} statements, "
          f"{tokens} tokens; medians of {args.runs}; `python -c pass` "
          f"{statistics.median(floor):.0f} ms CPU")
    print(f"  {'':<20} {'load ms':>8} {'parse ms':>9} {'x driver':>9}")
    base = statistics.median(parse_times["epuckc driver"])
    for name in loads:
        if name not in parsers:
            load = statistics.median(loads[name]) - statistics.median(floor)
            print(f"  {name + ' (import)':<20} {load:>8.0f}")
            continue
        load = statistics.median(loads[name]) - statistics.median(floor)
        parse = statistics.median(parse_times[name])
        print(f"  {name:<20} {load:>8.0f} {parse:>9.0f} {parse / base:>9.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
