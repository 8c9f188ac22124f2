#!/usr/bin/env python3
"""Draws the pictures the README and docs show, from the examples, so that
they stay true: tests/sim/test_enki.py fails when a committed picture
differs from what this script draws today.

    python3 docs/make_pictures.py              # rewrites docs/images/
    python3 docs/make_pictures.py --out DIR    # somewhere else

Needs Enki (libenki-dev) and a C++ compiler, as `epuckc run --world` does.
"""
import argparse
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

# (picture, program, world, extra options)
PICTURES = [
    ("wander.svg", "examples/wander.epk", "examples/arena.world", ["--time-limit", "60s"]),
]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "images")
    args = parser.parse_args()
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               EPUCK_QUIET="1")
    args.out.mkdir(parents=True, exist_ok=True)
    for picture, program, world, extra in PICTURES:
        # run from the repository, so the labels read examples/...:line
        result = subprocess.run([sys.executable, "-m", "epuckc", "run", program, "--world", world,
                                 "--svg", str(args.out.resolve() / picture), *extra],
                                cwd=REPO, env=env, capture_output=True, text=True)
        if result.returncode not in (0, 3):        # 3: the time limit, as intended
            sys.stderr.write(result.stdout + result.stderr)
            return 1
        print(f"wrote {args.out / picture}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
