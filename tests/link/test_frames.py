"""The robot trace's framing (epuckc/link/frames.py, runtime_c/rt_trace.c):
CRC-16/MCRF4XX as catalogued, COBS both ways, and the reader that
resynchronises: a real stream of the tracer, damaged at random (bytes
dropped, changed, inserted, frames cut or run together), decodes every
frame the damage left whole into exactly its records, reports the damage
as `lost` records, and never decodes a damaged frame into a record."""
import random

from hypothesis import given, settings, strategies as st

from epuckc.link.frames import FrameReader, cobs_decode, cobs_encode, crc16, frame
from epuckc.link.stream import TraceDecoder


def test_the_crc_is_crc16_mcrf4xx():
    # the catalogue's check value (Greg Cook's CRC catalogue: CRC-16/MCRF4XX)
    assert crc16(b"123456789") == 0x6F91
    assert crc16(b"") == 0xFFFF


@given(st.binary(max_size=600))
def test_cobs_round_trips_and_leaves_no_zero(data):
    encoded = cobs_encode(data)
    assert 0 not in encoded
    assert cobs_decode(encoded) == data
    assert len(encoded) <= len(data) + 1 + len(data) // 254


def test_a_reader_takes_frames_whole_and_counts_the_rest():
    reader = FrameReader()
    good = frame(b"\x10\x01\x00\x05")
    bad = bytearray(frame(b"\x10\x02\x00\x06"))
    bad[2] ^= 0x40
    out = list(reader.feed(good + bytes(bad) + good))
    assert out[0] == b"\x10\x01\x00\x05" and out[2] == b"\x10\x01\x00\x05"
    assert out[1].frames == 1 and out[1].size == len(bad)
    assert list(reader.feed(good[:3])) == [] and reader.close().frames == 1


def test_a_frame_lost_whole_is_counted_by_the_sequence_numbers(bump_stream):
    """A frame whose bytes all vanished, its 0 with them, leaves no damage
    behind: the numbers of the frames around it tell."""
    table, data, records = bump_stream
    frames = _frames(data)
    gone = frames[:5] + frames[8:]
    decoded = TraceDecoder(table).feed(b"".join(gone))
    lost = [r for r in decoded if r["kind"] == "lost"]
    assert len(lost) == 1 and lost[0]["frames"] == 3 and lost[0]["bytes"] == 0


def _frames(data: bytes) -> list:
    """The stream's frames, each with its 0."""
    pieces = data.split(b"\0")
    assert pieces[-1] == b""
    return [p + b"\0" for p in pieces[:-1]]


def _records_of_each(table, frames: list) -> list:
    """The records each frame decodes to, in a faultless stream."""
    decoder, out = TraceDecoder(table), []
    for f in frames:
        out.append(decoder.feed(f))
    return out


def _without_pose(r):
    return {k: v for k, v in r.items() if k not in ("x_mm", "y_mm", "heading_deg")}


def _damage(rng: random.Random, f: bytes, how: str) -> bytes:
    body = bytearray(f[:-1])
    at = rng.randrange(len(body))
    if how == "flip":
        body[at] ^= rng.randrange(1, 256)
    elif how == "drop":
        del body[at]
    elif how == "insert":       # bytes that are no 0 (a 0 would end a frame there)
        body[at:at] = bytes(rng.randrange(1, 256) for _ in range(rng.randrange(1, 6)))
    elif how == "noise":        # between two frames, a 0 its end: no frame lost
        return bytes(rng.randrange(256) for _ in range(rng.randrange(0, 8))) + b"\0" + f
    elif how == "cut":
        del body[at:]
        body += bytes(rng.randrange(1, 256) for _ in range(rng.randrange(0, 3)))
    return bytes(body) + (b"" if how == "merge" else b"\0")


@settings(max_examples=60, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2 ** 32 - 1), share=st.floats(0.01, 0.4),
       chunk=st.integers(1, 64))
def test_after_random_damage_the_reader_keeps_every_whole_frame(bump_stream, seed, share,
                                                               chunk):
    table, data, _ = bump_stream
    rng = random.Random(seed)
    frames = _frames(data)
    expected = _records_of_each(table, frames)
    damaged, hit = bytearray(), set()
    for k, f in enumerate(frames):
        # the first hello starts the decoding, and the last frame is the one
        # after which nothing tells how many were lost: both left whole (a
        # stream joined in the middle is test_decoder's); a frame run into
        # by the one before is lost with it, and left as it is
        if 0 < k < len(frames) - 2 and k not in hit and rng.random() < share:
            how = rng.choice(["flip", "drop", "insert", "cut", "merge", "noise"])
            damaged += _damage(rng, f, how)
            if how != "noise":
                hit.add(k)
            if how == "merge":
                hit.add(k + 1)      # ran into the next frame: both lost
        else:
            damaged += f
    decoder, got = TraceDecoder(table), []
    for at in range(0, len(damaged), chunk):      # as a port gives it, in pieces
        got += decoder.feed(bytes(damaged[at:at + chunk]))
    got += decoder.close()
    lost = [r for r in got if r["kind"] == "lost"]
    kept = [_without_pose(r) for r in got if r["kind"] != "lost"]
    whole = [_without_pose(r) for k, rs in enumerate(expected) if k not in hit
             for r in rs if r["kind"] != "dropped"]
    assert [r for r in kept if r["kind"] != "dropped"] == whole
    # each frame lost counted, by the sequence numbers of the frames around it
    assert sum(r["frames"] for r in lost) == len(hit)
    assert all(r["t_ms"] <= r["until_ms"] for r in lost)
    # times and the wheels' totals survive what was lost
    assert [r["t_ms"] for r in kept] == sorted(r["t_ms"] for r in kept)
