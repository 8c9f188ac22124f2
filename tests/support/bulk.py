"""What the tests of idle polls in bulk share (tests/runtime/test_idle_bulk.py,
tests/sim/test_idle_bulk_world.py): the reference setting, programs of the
language fuzzer that the checker accepts, random scenarios."""
from __future__ import annotations

import random
from pathlib import Path

# every ms polled: the reference each bulk run is compared with
EVERY_MS = {"EPUCK_POLL_EVERY_MS": "1"}
GENERATED = 16


def random_scenario(rng: random.Random, limit_ms: int) -> str:
    """Lines at random times changing every kind of input (and some that
    change nothing)."""
    lines, t = [], 0
    while True:
        t += rng.choice([1, 2, 3, 7, 20, 50, 130, 300])
        if t >= limit_ms:
            return "\n".join(lines) + "\n"
        items = []
        for _ in range(rng.randint(1, 3)):
            kind = rng.choice(["ir", "ir", "ir", "amb", "mic", "acc", "selector", "key"])
            if kind in ("ir", "amb"):
                items.append(f"{kind}{rng.randint(0, 7)}={rng.choice([0, 0, 120, 400, 900, 4095])}")
            elif kind == "mic":
                items.append(f"mic{rng.randint(0, 2)}={rng.choice([0, 300, 3000])}")
            elif kind == "acc":
                items.append(f"acc{rng.choice('xyz')}={rng.choice([0, 2048, 2200, 4095])}")
            elif kind == "selector":
                items.append(f"selector={rng.randint(0, 15)}")
            else:
                items.append(f"key={rng.randint(0, 9)}")
        lines.append(f"{t} ms {' '.join(items)}")


def accepted_programs(count: int, seed: int) -> list:
    """`count` programs of the language fuzzer that the checker accepts."""
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report
    from tests.support.language import RandomChoices, language_program
    rng = RandomChoices(random.Random(seed))
    found = []
    while len(found) < count:
        text = language_program(rng).text
        if check_file(Path("g.epk"), Report(), shown_name="g.epk", text=text).checked is not None:
            found.append(text)
    return found
