"""A world's merged trace as the robots write it (epuckc/sim/live.py): the
lines and their order are merge_traces's whatever the robots' files hold
at each poll, and `epuckc run --world W --trace -` writes the bytes that
`--trace FILE` writes."""
from __future__ import annotations

import json

from hypothesis import given, settings, strategies as st

from epuckc.sim.enki import merge_traces
from epuckc.sim.live import LiveMerge
from epuckc.sim.world import parse_world
from tests.conftest import require_enki
from tests.support.world import EXAMPLES, epuckc


def _record(t: int, kind: str, n: int) -> str:
    return json.dumps({"t_ms": t, "kind": kind, "name": f"n{n}", "id": n})


@st.composite
def robots_and_writes(draw):
    count = draw(st.integers(1, 3))
    traces = []
    for r in range(count):
        times = sorted(draw(st.lists(st.integers(0, 50), max_size=12)))
        lines = [_record(t, "event", i) for i, t in enumerate(times)]
        if draw(st.booleans()):
            lines.append(_record((times[-1] if times else 0) + draw(st.integers(0, 5)),
                                 "timeout", 99))
        traces.append("".join(line + "\n" for line in lines))
    # the order in which the robots' bytes reach their files, in pieces that
    # may cut a line anywhere, and when the reader polls
    steps = []
    left = [len(t) for t in traces]
    while any(left):
        r = draw(st.sampled_from([i for i, n in enumerate(left) if n]))
        n = draw(st.integers(1, left[r]))
        steps.append((r, n, draw(st.booleans())))
        left[r] -= n
    return traces, steps


@settings(max_examples=150, deadline=None)
@given(robots_and_writes())
def test_the_lines_come_out_as_merge_traces_orders_them(tmp_path_factory, case):
    traces, steps = case
    tmp = tmp_path_factory.mktemp("live")
    names = [f"r{i}" for i in range(len(traces))]
    paths = [tmp / f"robot{i}.jsonl" for i in range(len(traces))]
    got = []
    merge = LiveMerge(names, paths, got.extend)
    written = [0] * len(traces)
    for r, n, poll in steps:
        with open(paths[r], "a", encoding="utf-8") as f:
            f.write(traces[r][written[r]:written[r] + n])
        written[r] += n
        if poll:
            merge.poll()
    merge.finish()
    world = parse_world_text(tmp, names)
    expected = merge_traces(world, traces, [], 0).splitlines()[1:]
    assert got == expected


def parse_world_text(tmp, names):
    path = tmp / "w.world"
    path.write_text("".join(f"robot {n} at {10 + 10 * i} cm, 10 cm\n" for i, n in enumerate(names)))
    return parse_world(path)


def test_trace_dash_in_a_world_streams_the_bytes_trace_file_writes(tmp_path):
    require_enki()
    args = ["run", EXAMPLES / "follower.epk", "--world", EXAMPLES / "follow.world",
            "--time-limit", "1500ms", "--pose-interval", "100ms"]
    to_file = epuckc(*args, "--trace", tmp_path / "t.jsonl", cwd=tmp_path)
    streamed = epuckc(*args, "--trace", "-", cwd=tmp_path)
    assert to_file.returncode == streamed.returncode == 3, streamed.stderr
    assert streamed.stdout == (tmp_path / "t.jsonl").read_text()
    # the readable lines are not mixed in; the collision summary is on stderr
    assert "no collision" in streamed.stderr and "no collision" not in streamed.stdout
