#!/usr/bin/env python3
"""A long campaign of the property of tests/emit/test_property.py: random
programs with hostile names; every one the checker accepts must compile with
gcc and 16-bit avr-gcc under -std=c99 -Wall -Wextra -Werror -pedantic and run
clean under ASan/UBSan on the host harness.

    python3 bench/fuzz_campaign.py [--count N] [--seed S]

Prints how many programs were generated, accepted (built and ran clean) and
rejected; stops at the first failure and prints it (exit status 1). An
interrupt (Ctrl-C, or `kill PID`) ends the campaign with the counts so far.
The last count goes in docs/performance.md."""
from __future__ import annotations

import argparse
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=3000, help="programs to generate")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    cc, avr = shutil.which("cc"), shutil.which("avr-gcc")
    if not cc or not avr:
        print("needs cc and avr-gcc", file=sys.stderr)
        return 2
    counts: Counter = Counter()
    started = time.monotonic()

    def interrupted(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, interrupted)      # `kill PID` reports too
    with tempfile.TemporaryDirectory(prefix="epuckc-fuzz-") as tmp:
        tmp = Path(tmp)
        runtime = runtime_objects(tmp, cc)

        @seed(args.seed)
        @settings(max_examples=args.count, deadline=None, database=None,
                  suppress_health_check=list(HealthCheck))
        @given(programs())
        def campaign(program):
            n = sum(counts.values())
            work = tmp / str(n)
            counts[check_one(program, work, cc, avr, runtime)] += 1
            shutil.rmtree(work, ignore_errors=True)
            if (n + 1) % 100 == 0:
                print(f"  {n + 1} programs, {counts[Outcome.BUILT]} built", file=sys.stderr)

        stopped = ""
        try:
            campaign()
        except AssertionError as exc:
            print(f"FAILED after {sum(counts.values())} programs:\n{exc}")
            return 1
        except KeyboardInterrupt:       # Ctrl-C or kill: report what was done
            stopped = " (interrupted)"
    total = sum(counts.values())
    print(f"{total} programs generated{stopped} in {time.monotonic() - started:.0f} s: "
          f"{counts[Outcome.BUILT]} accepted, built with gcc and avr-gcc (-Werror) and run "
          f"clean under ASan/UBSan; {counts[Outcome.REJECTED]} rejected by the checker; "
          f"0 failures")
    return 0


if __name__ == "__main__":
    sys.exit(main())
