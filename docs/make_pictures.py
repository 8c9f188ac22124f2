#!/usr/bin/env python3
"""Draws the pictures the README and docs show, from the examples, so that
they stay true: tests/sim/test_enki.py fails when a committed picture
differs from what this script draws today.

    python3 docs/make_pictures.py              # rewrites docs/images/
    python3 docs/make_pictures.py --out DIR    # somewhere else
    python3 docs/make_pictures.py --replay     # also the replay's screenshot

Needs Enki (libenki-dev) and a C++ compiler, as `epuckc run --world` does;
the screenshot of the replay page (replay.png, about 12 s into the same run)
needs Chromium, and is not compared by the tests (a browser's pixels vary
with its fonts).
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
    ("braitenberg.svg", "examples/braitenberg.epk", "examples/braitenberg.world",
     ["--time-limit", "60s"]),
    # half a lap (every switch of its LEDs is a dot on its path)
    ("line_follower.svg", "examples/line_follower.epk", "examples/line_follower.world",
     ["--time-limit", "20s"]),
]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO / "docs" / "images")
    parser.add_argument("--replay", action="store_true", help="also docs/images/replay.png")
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
    if args.replay:
        page = args.out.resolve() / "replay.html"
        result = subprocess.run([sys.executable, "-m", "epuckc", "run", "examples/wander.epk",
                                 "--world", "examples/arena.world", "--time-limit", "60s",
                                 "--html", str(page)], cwd=REPO, env=env, capture_output=True,
                                text=True)
        if result.returncode not in (0, 3):
            sys.stderr.write(result.stdout + result.stderr)
            return 1
        # 1.2 s of play in virtual time: about 12 s of the run
        subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu",
                        "--virtual-time-budget=1200", "--window-size=760,960",
                        f"--screenshot={args.out.resolve() / 'replay.png'}",
                        page.as_uri() + "#play"], check=True, capture_output=True)
        page.unlink()
        print(f"wrote {args.out / 'replay.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
