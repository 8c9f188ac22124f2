"""Intel HEX (INHX32) files laid out as XC16's bin2hex writes them for the
dsPIC30F6014A, made from known instructions (there is no XC16 here): each
24-bit instruction at program address A is 4 bytes (3 and a phantom 0) at
byte address 2*A; type-04 records give the upper 16 bits of the byte
addresses; the configuration words (program address 0xF80000) and the
EEPROM (0x7FF000) come in chunks of their own. Written by hand, record by
record, so that a test's expectation never goes through the reader it
tests; and what the robot's program memory holds once the bootloader has
taken such a file (`expected_memory`), from the instructions and the
bootloader's byte layout."""
from __future__ import annotations

import random
from pathlib import Path


def _record(kind: int, address: int, data: bytes) -> str:
    body = bytes([len(data), (address >> 8) & 0xFF, address & 0xFF, kind]) + data
    return ":" + (body + bytes([(-sum(body)) & 0xFF])).hex().upper()


def inhx32(blocks: dict) -> str:
    """The file's text for {byte address: byte}; 16-byte data records, a
    type-04 record at each new upper 16 bits, the end record."""
    lines, upper = [], None
    addresses = sorted(blocks)
    i = 0
    while i < len(addresses):
        start = addresses[i]
        run = [blocks[start]]
        while (i + len(run) < len(addresses) and addresses[i + len(run)] == start + len(run)
               and len(run) < 16 and (start + len(run)) & 0xFFFF):
            run.append(blocks[start + len(run)])
        if start >> 16 != upper:
            upper = start >> 16
            lines.append(_record(4, 0, upper.to_bytes(2, "big")))
        lines.append(_record(0, start & 0xFFFF, bytes(run)))
        i += len(run)
    lines.append(":00000001FF")
    return "\n".join(lines) + "\n"


def program_bytes(words: dict) -> dict:
    """{byte address: byte} of instructions {program address: value}."""
    out = {}
    for address, value in words.items():
        for k, byte in enumerate(value.to_bytes(3, "little") + b"\x00"):
            out[2 * address + k] = byte
    return out


def write_program(path: Path, words: dict, config=None, eeprom=None) -> Path:
    """A hex file with the instructions `words`, the configuration words
    `config` ({program address: 16-bit value}) and the EEPROM words
    `eeprom` ({program address: 16-bit value}), as XC16 lays them out."""
    blocks = program_bytes(words)
    for address, value in {**(config or {}), **(eeprom or {})}.items():
        for k, byte in enumerate(value.to_bytes(2, "little") + b"\x00\x00"):
            blocks[2 * address + k] = byte
    path.write_text(inhx32(blocks))
    return path


def example_words(seed: int = 7, size: int = 700) -> dict:
    """A program as XC16 links one: the reset vector's GOTO at 0 (to
    0x000200), the interrupt vectors, code from 0x100 on, and a block of
    constants past 64 KB of the file (program address 0x8000 and up, in a
    chunk of its own)."""
    rng = random.Random(seed)
    words = {0: 0x040200, 2: 0x000000}
    for address in range(4, 0x80, 2):
        words[address] = 0x040200 | rng.randrange(0, 0x100, 2)      # the vectors
    for k in range(size):
        words[0x100 + 2 * k] = rng.randrange(0, 1 << 24)
    for k in range(90):
        words[0x8010 + 2 * k] = rng.randrange(0, 1 << 24)
    return words


BOOTLOADER_ROW = 0x17F00


def _instructions(page: bytes, start: int) -> dict:
    """{program address: instruction} of a row given as 4-byte slots."""
    return {start + 2 * i: int.from_bytes(page[4 * i:4 * i + 3], "little")
            for i in range(len(page) // 4)}


def expected_memory(words: dict, robot_id: int, old: dict) -> dict:
    """What the robot's program memory holds after the upload: the old
    program where the new one has no row; each row the new program has
    data in, whole (erased 0xFFFFFF where it gives nothing); the reset
    vector's 8 bytes made a GOTO 0x017F40 (40 7F 04 00 01 00 00 00); the
    bootloader's row with the robot's number at bytes 108-109 and the
    program's own first jump (its bytes 0, 1 and 4) at 112-117."""
    file_bytes = {}
    for address, value in words.items():
        file_bytes.update({2 * address + k: b for k, b in
                           enumerate(value.to_bytes(3, "little") + b"\0")})
    original = [file_bytes[k] for k in range(8)]
    file_bytes.update(dict(enumerate([0x40, 0x7F, 0x04, 0x00, 0x01, 0x00, 0x00, 0x00])))
    memory = dict(old)
    for row in {a - a % 64 for a in words}:
        page = bytes(file_bytes.get(2 * row + k, 0xFF if k % 4 != 3 else 0) for k in range(128))
        memory.update(_instructions(page, row))
    page = bytearray(b"\xff\xff\xff\x00" * 32)
    page[108:120] = bytes([robot_id & 0xFF, robot_id >> 8, 0, 0, original[0], original[1], 4, 0,
                           original[4], 0, 0, 0])
    memory.update(_instructions(bytes(page), BOOTLOADER_ROW))
    return memory


CONFIG = {0xF80000: 0xC703, 0xF80002: 0x803F, 0xF80004: 0x87B3, 0xF8000A: 0x0003}
EEPROM = {0x7FFC00: 0x1234, 0x7FFC02: 0xBEEF}
