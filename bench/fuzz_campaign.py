#!/usr/bin/env python3
"""A long campaign of the fuzz properties of tests/emit/test_property.py
(programs with hostile names) and tests/emit/test_language_fuzz.py (the
whole language: variables, expressions, `when`, guards, every/after/wait,
modes, deep and long expressions).

    python3 bench/fuzz_campaign.py [--generator language|hostile] [--count N]
        [--seed S] [--jobs J] [--run-every K] [--messages] [--max-seconds T]

The language generator draws nested indexes, long `else if` chains and
the extreme sizes of each construct too (tests/support/language.py);
--messages makes every program send and receive IR messages (their world
runs under the sanitizers are tests/sim/test_world_sanitizers.py's).

For every input: `check`, `compile` and the language server's analysis run
in process (an exception is an internal error). Every accepted program is
compiled with gcc and 16-bit avr-gcc under -std=c99 -Wall -Wextra -Werror
-pedantic; one accepted program in K (default 1: all) is also linked with
ASan/UBSan and run on the host harness. J processes share the inputs (each
its own seed, S + j). The front end's CPU time of each input is measured:
one over 5 s is a hang (counted, and the slowest input is named by its seed
and number). --max-seconds stops each process after T seconds with the
count it reached (a budget on a shared machine). Prints the counts; stops
at the first failure and prints it (exit status 1). An interrupt (Ctrl-C, or `kill PID`) ends the
campaign with the counts so far. The last count goes in
docs/performance.md."""
from __future__ import annotations

import argparse
import multiprocessing
import random
import shutil
import signal
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from hypothesis import HealthCheck, given, seed, settings  # noqa: E402

from tests.support.hostile import Outcome, check_one, programs, runtime_objects  # noqa: E402
from tests.support.language import RandomChoices, language_program, language_programs  # noqa: E402

GENERATORS = {"hostile": programs, "language": language_programs}


def front_end(text: str):
    """check + compile + the language server's analysis; an exception is
    an internal error."""
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report
    from epuckc.emit.program import emit_program
    from epuckc.ide.incremental import Analyzer
    report = Report()
    result = check_file(Path("fuzz.epk"), report, shown_name="fuzz.epk", text=text)
    if result.checked is not None:
        emit_program(result.checked, result.source.text, "fuzz")
    Analyzer("fuzz.epk").analyse(text)
    return result.checked is not None


def worker(job: tuple) -> tuple:
    """One process's share: (counts, failure text or None)."""
    generator, count, worker_seed, run_every, messages, max_seconds = job
    deadline = time.monotonic() + max_seconds if max_seconds else None
    cc, avr = shutil.which("cc"), shutil.which("avr-gcc")
    counts: Counter = Counter()
    failure = None
    slowest = [0.0, ""]         # (the front end's CPU seconds, which input)

    def interrupted(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, interrupted)
    with tempfile.TemporaryDirectory(prefix="epuckc-fuzz-") as tmp:
        tmp = Path(tmp)
        runtime = runtime_objects(tmp, cc)

        def one(program):
            if deadline is not None and time.monotonic() > deadline:
                raise _OutOfTime
            counts["inputs"] += 1
            started = time.process_time()
            try:
                accepted = front_end(program.text)
            except Exception as exc:        # noqa: BLE001 - that is the finding
                counts["internal errors"] += 1
                raise AssertionError(f"internal error {type(exc).__name__}: {exc}\n"
                                     f"--- input ---\n{program.text}") from exc
            spent = time.process_time() - started
            if spent > HANG:
                counts["hangs"] += 1
            if spent > slowest[0]:
                slowest[:] = [spent, f"seed {worker_seed} input {counts['inputs'] - 1}"]
            if not accepted:
                counts[Outcome.REJECTED] += 1
                return
            work = tmp / str(counts["inputs"])
            run = counts["accepted"] % run_every == 0
            counts["accepted"] += 1
            counts[check_one(program, work, cc, avr, runtime, run=run)] += 1
            shutil.rmtree(work, ignore_errors=True)

        if generator == "language":
            # plain random choices (a fraction of Hypothesis's cost per
            # input); input k of seed S is random.Random(S * 1000003 + k)
            def campaign():
                for k in range(count):
                    one(language_program(RandomChoices(random.Random(worker_seed * 1000003 + k)),
                                         messages=messages))
        else:
            campaign = seed(worker_seed)(settings(
                max_examples=count, deadline=None, database=None,
                suppress_health_check=list(HealthCheck))(given(GENERATORS[generator]())(one)))
        try:
            campaign()
        except AssertionError as exc:
            failure = str(exc)
        except (KeyboardInterrupt, _OutOfTime):
            failure = None
    return counts, failure, tuple(slowest)


HANG = 5.0          # the front end's CPU seconds for one input beyond which it is a hang


class _OutOfTime(Exception):
    """--max-seconds is spent."""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--generator", choices=sorted(GENERATORS), default="language")
    parser.add_argument("--count", type=int, default=3000, help="inputs to generate")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--run-every", type=int, default=1,
                        help="link with ASan/UBSan and run one accepted program in K")
    parser.add_argument("--messages", action="store_true",
                        help="every program sends and receives IR messages")
    parser.add_argument("--max-seconds", type=float, default=0,
                        help="stop each process after this many seconds (0: no limit)")
    args = parser.parse_args()
    if not shutil.which("cc") or not shutil.which("avr-gcc"):
        print("needs cc and avr-gcc", file=sys.stderr)
        return 2
    started = time.monotonic()
    share = [args.count // args.jobs + (j < args.count % args.jobs) for j in range(args.jobs)]
    jobs = [(args.generator, n, args.seed + j, args.run_every, args.messages, args.max_seconds)
            for j, n in enumerate(share)]
    try:
        with multiprocessing.Pool(args.jobs) as pool:
            results = pool.map(worker, jobs)
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    total: Counter = Counter()
    for counts, _, _ in results:
        total.update(counts)
    failures = [f for _, f, _ in results if f]
    slowest = max(s for _, _, s in results)
    print(f"{total['inputs']} {args.generator} inputs (seeds {args.seed}..{args.seed + args.jobs - 1})"
          f" in {time.monotonic() - started:.0f} s: {total['internal errors']} internal errors; "
          f"{total[Outcome.REJECTED]} rejected by the checker; {total['accepted']} accepted, "
          f"every one compiled with gcc and avr-gcc (-Werror), "
          f"{total[Outcome.BUILT]} of them also run clean under ASan/UBSan; "
          f"{len(failures)} failures; {total['hangs']} hangs (front end over {HANG:.0f} s of "
          f"CPU), the slowest {slowest[0]:.2f} s ({slowest[1]})")
    for failure in failures:
        print(f"FAILED:\n{failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
