"""Decoding the robot's trace (epuckc/link/stream.py) and `epuckc monitor`
on a capture of the link's bytes: a stream decodes only with its own
program's table (another is refused, saying which tables they are, and an
earlier output is left as it was); without a table its records are named
by number; a stream of another format is refused; a monitor that joins a
run in the middle starts at its next hello and says what it missed; the
readable trace, the JSON lines and the replay page are the host run's."""
import json
import struct

import pytest

from conftest import REPO
from epuckc.build.trace_table import TableError, read_table, trace_table
from epuckc.link.frames import frame
from epuckc.link.stream import TableMismatch, TraceDecoder, TraceError
from tests.support.programs import epuckc
from tests.support.robot_trace import assert_robot_trace_is_hosts, program_of

EXAMPLES = REPO / "examples"


def test_a_stream_is_refused_with_another_programs_table(bump_stream):
    _, data, _ = bump_stream
    other = trace_table(program_of(EXAMPLES / "square.epk"))
    with pytest.raises(TableMismatch) as caught:
        TraceDecoder(other).feed(data)
    text = str(caught.value)
    bump = trace_table(program_of(EXAMPLES / "bump_counter.epk"))
    assert bump["fingerprint"] in text and other["fingerprint"] in text
    assert "another program or another version of it" in text and "--program" in text


def test_the_monitor_refuses_it_and_leaves_the_output_alone(bump_stream, tmp_path):
    _, data, _ = bump_stream
    capture = tmp_path / "robot.bin"
    capture.write_bytes(data)
    out = tmp_path / "out.jsonl"
    out.write_text("an earlier run\n")
    r = epuckc("monitor", capture, "--program", EXAMPLES / "square.epk", "--trace", out)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert "the robot runs a program whose trace table is" in r.stderr
    assert out.read_text() == "an earlier run\n" and not list(tmp_path.glob("*.part"))


def test_the_monitor_shows_the_host_runs_trace(bump_stream, tmp_path):
    """A capture of the robot's link, decoded: the JSON lines are the host's
    (the pose within the odometry's tolerance), the readable trace prints
    as `epuckc run` does, the page replays the run."""
    _, data, _ = bump_stream
    capture = tmp_path / "robot.bin"
    capture.write_bytes(data)
    out, page = tmp_path / "out.jsonl", tmp_path / "replay.html"
    r = epuckc("monitor", capture, "--program", EXAMPLES / "bump_counter.epk", "--trace", out,
               "--html", page)
    assert r.returncode == 0, r.stderr
    robot = [json.loads(line) for line in out.read_text().splitlines()]
    host_trace = tmp_path / "host.jsonl"
    host = epuckc("run", EXAMPLES / "bump_counter.epk", "--scenario", EXAMPLES / "bumps.scn",
                  "--time-limit", "6000ms", "--trace", host_trace)
    assert_robot_trace_is_hosts([json.loads(x) for x in host_trace.read_text().splitlines()],
                                robot)
    assert r.stdout == host.stdout        # bump_counter's poses agree to the tenth
    assert "<svg" in page.read_text() and "bump_counter.epk:13" in page.read_text()


def test_the_table_is_found_beside_a_build(bump_stream, tmp_path):
    """--program may name what `epuckc build --trace` wrote: the table, the
    project folder, the program's .hex (in the folder) or .elf (the
    e-puck2's build/, one below)."""
    _, data, records = bump_stream
    capture = tmp_path / "robot.bin"
    capture.write_bytes(data)
    project = tmp_path / "proj"
    epuckc("build", EXAMPLES / "bump_counter.epk", "--target", "dspic", "--trace", "-o",
           project, env={"XC16_DIR": ""})
    (project / "build").mkdir()
    (project / "build" / "bump_counter.elf").write_bytes(b"")
    (project / "bump_counter.hex").write_bytes(b"")
    for given in (project / "bump_counter.trace.json", project, project / "bump_counter.hex",
                  project / "build" / "bump_counter.elf"):
        r = epuckc("monitor", capture, "--program", given, "--trace", "-")
        assert r.returncode == 0, (given, r.stderr)
        assert [json.loads(line) for line in r.stdout.splitlines()] == records
    r = epuckc("monitor", capture, "--program", tmp_path / "nothing.hex")
    assert r.returncode == 2 and "no nothing.trace.json beside it" in r.stderr


def test_an_edited_table_is_refused(tmp_path):
    table = trace_table(program_of(EXAMPLES / "bump_counter.epk"))
    table["events"][0] = "something else"
    path = tmp_path / "x.trace.json"
    path.write_text(json.dumps(table))
    with pytest.raises(TableError, match="edited after the build"):
        read_table(path)
    path.write_text("not json")
    with pytest.raises(TableError, match="not a trace table"):
        read_table(path)


def test_without_a_table_records_are_named_by_number(bump_stream):
    table, data, records = bump_stream
    notes = []
    decoded = TraceDecoder(None, on_note=notes.append).feed(data)
    assert [r["kind"] for r in decoded] == [r["kind"] for r in records[:len(decoded)]]
    events = [r for r in decoded if r["kind"] == "event"]
    assert events[0]["name"] == f"event#{events[0]['id']}"
    assert any(table["fingerprint"] in note and "by number" in note for note in notes)


def test_a_stream_of_another_format_is_refused():
    hello = bytes([1, 0, 2, 1]) + struct.pack("<II", 0x12345678, 0) + bytes([0, 0, 0, 0, 0])
    with pytest.raises(TraceError, match="format 2; this epuckc reads format 1"):
        TraceDecoder(None).feed(frame(hello))


def test_a_monitor_that_joins_a_run_starts_at_its_next_hello(bump_stream):
    """From the middle of a run: what came before the next hello (every
    second) is a `lost` record, what follows is decoded at its time."""
    table, data, records = bump_stream
    middle = len(data) // 2
    notes = []
    decoder = TraceDecoder(table, on_note=notes.append)
    decoded = decoder.feed(data[middle:]) + decoder.close()
    assert decoded[0]["kind"] == "lost" and decoded[0]["before_start"]
    later = [(r["t_ms"], r["kind"], r.get("name")) for r in decoded[1:] if r["kind"] != "pose"]
    expected = [(r["t_ms"], r["kind"], r.get("name")) for r in records if r["kind"] != "pose"]
    assert later and later == expected[-len(later):]
    assert any("joined a run in progress" in note for note in notes)
