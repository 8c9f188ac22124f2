"""A robot's contacts in words, the same in the run's summary line and on
the pictures: the physics steps in which it touched walls, obstacles (the
world's boxes and cylinders) and other robots (runtime_c/enki/contacts.h
tells them apart), from the trace's `contacts` record or a run's result."""
from __future__ import annotations

KINDS = (("walls", "walls"), ("objects", "obstacles"), ("robots", "robots"))


def steps_in_contact(counts: dict) -> int:
    """The steps in contact with anything (`steps`; a trace written before
    it was recorded: the kinds' sum)."""
    if "steps" in counts:
        return int(counts["steps"])
    return sum(int(counts.get(key, 0)) for key, _ in KINDS)


def contact_words(counts: dict, steps: str = "steps") -> str:
    """`756 steps in contact with robots`; with several kinds `531 steps in
    contact: 96 with walls, 435 with obstacles` (a step may touch both);
    `no contact`. `steps`: the word for them."""
    parts = [(int(counts.get(key, 0)), words) for key, words in KINDS if counts.get(key)]
    if not parts:
        return "no contact"
    total = steps_in_contact(counts)
    if len(parts) == 1:
        return f"{total} {steps} in contact with {parts[0][1]}"
    return f"{total} {steps} in contact: " + ", ".join(f"{n} with {words}" for n, words in parts)
