"""Programs for the e-puck2's flash tests: a small Cortex-M4 ELF made by
arm-none-eabi-gcc, laid out as a firmware is (the vector table at the
flash's start, code and constants, a table in the next flash sector, data
loaded from flash into RAM, the bytes GDB escapes in its binary packets),
and what an ELF puts in flash, as binutils' objcopy computes it (the
load addresses), read back with intelhex."""
from __future__ import annotations

import subprocess
from pathlib import Path

SOURCE = r"""
typedef unsigned int u32;
extern u32 _estack;
void reset(void);
__attribute__((section(".vectors"))) const void *vectors[] = { &_estack, (void *)reset };
int counter = 0x1234;
const char banner[] = "e-puck2 #$}* test";
__attribute__((section(".far"))) const unsigned char far_table[1500] = {
    1, 2, 3, '#', '$', '}', '*', 0x7d, 0x23, 0x24, 0x2a, 0xff, 0 };
void reset(void) { for (;;) counter += banner[counter & 7] + far_table[counter & 1023]; }
"""
LINKER_SCRIPT = """
MEMORY { FLASH (rx) : ORIGIN = 0x08000000, LENGTH = 1024K
         RAM (rwx) : ORIGIN = 0x20000000, LENGTH = 128K }
_estack = ORIGIN(RAM) + LENGTH(RAM);
SECTIONS {
  .vectors : { KEEP(*(.vectors)) } > FLASH
  .text : { *(.text*) *(.rodata*) } > FLASH
  .far 0x08010000 : { KEEP(*(.far)) } > FLASH
  .data : { *(.data*) } > RAM AT > FLASH
  .bss : { *(.bss*) } > RAM
}
"""


def small_elf(folder: Path, gcc: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "prog.c").write_text(SOURCE)
    (folder / "prog.ld").write_text(LINKER_SCRIPT)
    elf = folder / "prog.elf"
    subprocess.run([gcc, "-mcpu=cortex-m4", "-mthumb", "-nostdlib", "-O1", "-T",
                    str(folder / "prog.ld"), str(folder / "prog.c"), "-o", str(elf)],
                   check=True, capture_output=True)
    return elf


def flash_image(elf: Path, objcopy: str) -> dict:
    """{address: byte} of what the ELF puts in memory at its load
    addresses: objcopy's Intel HEX of it."""
    from intelhex import IntelHex
    hexfile = elf.with_suffix(".expected.hex")
    subprocess.run([objcopy, "-O", "ihex", str(elf), str(hexfile)], check=True,
                   capture_output=True)
    image = IntelHex(str(hexfile))
    return {address: image[address] for address in image.addresses()}


def received(probe) -> dict:
    """{address: byte} of every vFlashWrite the fake probe took; an
    address written twice with two values is a failure of the test."""
    got = {}
    for address, data in probe.written:
        for i, byte in enumerate(data):
            assert got.setdefault(address + i, byte) == byte, f"0x{address + i:x} written twice"
    return got
