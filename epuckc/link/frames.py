"""The frames of the robot's trace on the wire (runtime_c/rt_trace.c):
COBS (consistent overhead byte stuffing) of a payload and its CRC-16, then
a 0 byte. The 0 ends every frame and never occurs inside one, so a reader
that lost or mangled bytes starts again at the next 0; the CRC tells a
mangled frame from a whole one. `FrameReader` turns any stream of bytes
into whole payloads and the damage between them, counted, never silent."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator, Optional, Union


def crc16(data: bytes, crc: int = 0xFFFF) -> int:
    """CRC-16/MCRF4XX: polynomial 0x1021 reflected (0x8408), initial value
    0xFFFF, no final xor (check value of b"123456789": 0x6F91), bit by bit
    as its definition says; the C computes the same a byte at a time."""
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0x8408 if crc & 1 else crc >> 1
    return crc


def cobs_encode(data: bytes) -> bytes:
    """COBS of `data` (no 0 in the result; one byte more per 254)."""
    out, block = bytearray(), bytearray()
    for byte in data:
        if byte == 0:
            out.append(len(block) + 1)
            out += block
            block.clear()
        else:
            block.append(byte)
            if len(block) == 254:
                out.append(255)
                out += block
                block.clear()
    out.append(len(block) + 1)
    out += block
    return bytes(out)


def cobs_decode(data: bytes) -> Optional[bytes]:
    """The bytes `data` encodes, or None when it is no COBS encoding (a 0
    inside, a code that points past the end)."""
    out, i, n = bytearray(), 0, len(data)
    while i < n:
        code = data[i]
        if code == 0 or i + code > n:
            return None
        block = data[i + 1:i + code]
        if 0 in block:
            return None
        out += block
        i += code
        if code != 255 and i < n:
            out.append(0)
    return bytes(out)


def frame(payload: bytes) -> bytes:
    """A payload as the robot sends it: COBS(payload + CRC, low byte first) + 0."""
    crc = crc16(payload)
    return cobs_encode(payload + bytes((crc & 0xFF, crc >> 8))) + b"\0"


@dataclass
class Damage:
    """Bytes between two whole frames that were no whole frame: `frames`
    pieces (each a would-be frame: a bad CRC, bad COBS, too short), `size`
    bytes in all."""
    frames: int
    size: int


class FrameReader:
    """Bytes in, payloads out: `feed(data)` yields each whole frame's
    payload (CRC checked and stripped) and, before the next whole frame, a
    `Damage` for the pieces since the last one that were not whole frames
    (a frame cut by the start of the reading among them)."""

    def __init__(self):
        self._pending = bytearray()
        self._bad_frames = 0
        self._bad_bytes = 0

    def feed(self, data: bytes) -> Iterator[Union[bytes, Damage]]:
        self._pending += data
        while True:
            end = self._pending.find(0)
            if end < 0:
                return
            piece = bytes(self._pending[:end])
            del self._pending[:end + 1]
            if not piece:
                continue            # two 0s: nothing between them was lost
            payload = self._check(piece)
            if payload is None:
                self._bad_frames += 1
                self._bad_bytes += len(piece) + 1
                continue
            if self._bad_frames:
                yield Damage(self._bad_frames, self._bad_bytes)
                self._bad_frames = self._bad_bytes = 0
            yield payload

    def close(self) -> Optional[Damage]:
        """The end of the stream: what was damaged since the last whole
        frame, an unfinished frame at the end (its 0 never came) with it."""
        if self._pending:
            self._bad_frames += 1
            self._bad_bytes += len(self._pending)
            self._pending.clear()
        if not self._bad_frames:
            return None
        damage = Damage(self._bad_frames, self._bad_bytes)
        self._bad_frames = self._bad_bytes = 0
        return damage

    @staticmethod
    def _check(piece: bytes) -> Optional[bytes]:
        decoded = cobs_decode(piece)
        if decoded is None or len(decoded) < 3:
            return None
        payload, crc = decoded[:-2], decoded[-2] | decoded[-1] << 8
        return payload if crc16(payload) == crc else None
