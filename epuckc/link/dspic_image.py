"""The e-puck's program memory image, from an XC16 hex file (Intel HEX,
INHX32, read with intelhex), as its Bluetooth bootloader (tinybld) takes
it: rows of 32 instructions, the reset vector pointing at the bootloader,
and the program's own first jump with the robot's number kept in the
bootloader's row.

The dsPIC30F6014A's program memory holds 24-bit instructions at even
addresses; the hex file gives each as 4 bytes (3 and a phantom 0) at twice
its address, and puts the configuration words and the EEPROM above byte
address 0x40000, where the bootloader does not write.
"""
from __future__ import annotations

from pathlib import Path

from ..base.records import record
from .ports import LinkError

PROGRAM_BYTES = 0x40000        # byte addresses below this are program memory
ROW = 32                       # instructions in a row, a packet's worth
ROW_SPAN = 2 * ROW             # program addresses a row spans
BOOTLOADER_ROW = 0x17F00       # the row that keeps the robot's number and the program's jump
BOOTLOADER = 0x17F40           # where the bootloader starts; the reset vector jumps there
GOTO = 0x04                    # the opcode byte of the two-word GOTO
ERASED = 0xFFFFFF
# The bootloader's row: the robot's number, then the two words of the
# jump to the program (instructions 27, 28 and 29 of the row; byte offsets
# 108, 112 and 116 of its 4-byte instructions).
ID_SLOT, JUMP_SLOT = 27, 28
PACKET_DATA = 0x60             # a packet's byte count: 32 instructions of 3 bytes


@record(frozen=True)
class ProgramImage:
    """The program memory of a hex file: `words` maps each even program
    address the file gives to its 24-bit instruction; `eeprom` says whether
    the file also had EEPROM data (which the bootloader does not write)."""
    shown: str
    words: dict
    eeprom: bool = False


def read_hex(path: Path, shown: str) -> ProgramImage:
    """The program memory of an XC16 hex file; LinkError when it cannot be
    read, is not Intel HEX, has no reset vector to patch, or reaches into
    the bootloader."""
    from intelhex import HexReaderError, IntelHex
    try:
        hexfile = IntelHex(str(path))
    except (OSError, IOError) as exc:
        raise LinkError(f"cannot read {shown}: {getattr(exc, 'strerror', None) or exc}") \
            from None
    except HexReaderError as exc:
        raise LinkError(f"{shown} is not an Intel HEX file the bootloader can take ({exc})") \
            from None
    words, eeprom = {}, False
    for address in hexfile.addresses():
        if address >= PROGRAM_BYTES:
            eeprom = eeprom or 0x7FF000 * 2 <= address < 0x800000 * 2
            continue
        word = (address >> 1) & ~1          # the instruction's program address
        if address & 3 == 3:
            continue                        # the phantom byte
        value = words.get(word, ERASED)
        shift = 8 * (address & 3)
        words[word] = (value & ~(0xFF << shift)) | (hexfile[address] << shift)
    if not words:
        raise LinkError(f"{shown} holds no program memory (nothing below byte address "
                        f"0x{PROGRAM_BYTES:x}): is it the e-puck's program?")
    top = max(words)
    if top >= BOOTLOADER_ROW:
        raise LinkError(f"{shown} has code at 0x{top:06x}, where the e-puck's bootloader lives "
                        f"(0x{BOOTLOADER_ROW:06x} and above): the program is too big for the "
                        "e-puck with its bootloader; make it smaller")
    first, second = words.get(0), words.get(2)
    if first is None or first >> 16 != GOTO or second is None or second & 0xFFFF80:
        raise LinkError(f"{shown} does not start with a jump (GOTO) at its reset vector, as "
                        "every XC16 program does: is it a program for the e-puck's dsPIC?")
    return ProgramImage(shown, words, eeprom)


def rows(image: ProgramImage, robot_id: int) -> list:
    """The rows to send, in order, each (program address, 32 instructions):
    the rows the program has data in (instructions it does not give are
    0xFFFFFF, erased flash), the reset vector jumping to the bootloader;
    the bootloader's row with the robot's number and the program's own
    jump; the rows of the first 64 KB of the file (the reset vector's) sent
    last."""
    words = dict(image.words)
    saved_low, saved_high = words[0] & 0xFFFF, words[2] & 0x7F
    words[0] = (GOTO << 16) | (BOOTLOADER & 0xFFFF)
    words[2] = BOOTLOADER >> 16
    starts = sorted({address - address % ROW_SPAN for address in words})
    laid = {start: [words.get(start + 2 * i, ERASED) for i in range(ROW)] for start in starts}
    keep = [ERASED] * ROW
    keep[ID_SLOT] = robot_id & 0xFFFF
    keep[JUMP_SLOT] = (GOTO << 16) | saved_low
    keep[JUMP_SLOT + 1] = saved_high
    first_chunk = 0x10000 // 2          # program addresses of the file's first 64 KB
    late = [s for s in starts if s < first_chunk]
    early = [s for s in starts if s >= first_chunk]
    return ([(s, laid[s]) for s in early] + [(BOOTLOADER_ROW, keep)]
            + [(s, laid[s]) for s in late])


def packet(address: int, instructions: list) -> bytes:
    """One 101-byte packet: the row's program address (3 bytes, little
    endian), 0x60, its 32 instructions of 3 bytes (little endian), and the
    checksum that makes the sum of all 101 bytes 0 modulo 256."""
    body = bytearray(address.to_bytes(3, "little"))
    body.append(PACKET_DATA)
    for instruction in instructions:
        body += instruction.to_bytes(3, "little")
    body.append((-sum(body)) & 0xFF)
    return bytes(body)


def packets(image: ProgramImage, robot_id: int) -> list:
    return [packet(address, row) for address, row in rows(image, robot_id)]
