"""The user's C for the simulated e-puck, between the compiler and the
assembler: what the dsPIC's instructions written inline become on the
host, and where the program's globals go.

e-puck programs write dsPIC instructions inline (`__asm__ volatile
("reset")` in GCtronic's main, the library's NOP() and RESET() macros). The
host's assembler does not know them, and must not: the simulation carries
them out. The user's C is compiled to assembly, and each block of inline
assembly the compiler copied into it (between `#APP` and `#NO_APP`, with
the file and line of its `asm` statement) is rewritten:

- `nop` stays (the host's no-operation);
- `clrwdt` (the watchdog timer, which the simulated chip does not run)
  and `disi #N` (interrupts held off for N cycles: the simulation's
  interrupts run between two blocks of main) become nothing;
- `reset`, `pwrsav #0` (sleep) and `pwrsav #1` (idle) call the simulated
  chip (runtime_c/host/dspic.c, epuck_dspic_trap, which saves every
  register around the call): a reset restarts main, sleep ends main for
  good, idle waits for the next interrupt;
- any other instruction is a build error naming it, its file and line.

The program's writable globals (compiled one section each,
-fdata-sections) are moved into two sections of their own,
`epuck_user_data` and `epuck_user_bss`, whose bounds the linker gives
(`__start_epuck_user_data`, ...): a reset puts back what they held when
main first started (runtime_c/host/cmain.c), as the chip's start-up code
does. The rest of the program (the library's simulation, the harness) is
compiled apart and keeps its state.
"""
from __future__ import annotations

import re

# Part of the host build's key: a change of what this module writes
# rebuilds the programs (build/host.py).
FORMAT = 1

# the codes epuck_dspic_execute takes (runtime_c/host/epuck_stub.h STUB_INSN_*)
INSN_RESET, INSN_SLEEP, INSN_IDLE = 1, 2, 3

_MARKER = re.compile(r'#\s*(\d+)\s+"((?:[^"\\]|\\.)*)"')
_SECTION = re.compile(r'(\s*\.section\s+)(\.(?:data(?:\.rel(?:\.local)?)?|bss)(?:\.[^,\s]*)?)'
                      r'(\s*,.*)?$')
_PLAIN = re.compile(r"\s*\.(data|bss)\s*$")


class AsmError(Exception):
    """An instruction the simulation cannot carry out; str() says where."""


# The routines of dsPIC assembly that e-puck programs link beside their C
# (GCtronic's demos: Microchip's DataEEPROM.s), which the simulated library
# has (runtime_c/host/dspic.c): a program's .s file that defines only
# these is stood in for.
STOOD_IN = frozenset({"ReadEE", "WriteEE", "EraseEE"})
_GLOBAL = re.compile(rb"^\s*\.global\s+([^;\n]+)", re.M)


def stood_in(path) -> list:
    """The C names a program's dsPIC assembly file defines, when the
    simulated library has every one of them; else AsmError saying which it
    has not. OSError when it cannot be read."""
    from pathlib import Path
    names = set()
    for m in _GLOBAL.finditer(Path(path).read_bytes()):
        for symbol in re.split(rb"[,\s]+", m.group(1).strip()):
            if symbol.startswith(b"_") and not symbol.startswith(b"__"):
                names.add(symbol[1:].decode("latin-1"))
    missing = sorted(names - STOOD_IN)
    if missing or not names:
        has = ", ".join(sorted(STOOD_IN))
        raise AsmError(f"{path}: dsPIC assembly, which the simulated e-puck does not run; it "
                       f"stands in only for the routines it has itself ({has}, Microchip's "
                       f"DataEEPROM.s), and this file defines {', '.join(missing) or 'no C name'}")
    return sorted(names)


def _trap(code: int) -> list:
    # 128 bytes below the stack pointer are the red zone of the function
    # the instruction sits in: the call goes below them
    return ["\tleaq\t-128(%rsp), %rsp", f"\tpushq\t${code}",
            "\tcall\tepuck_dspic_trap@PLT", "\tleaq\t136(%rsp), %rsp"]


def _instruction(text: str, where: str) -> list:
    """The host's lines for one dsPIC instruction (already stripped)."""
    words = text.replace(",", " ").split()
    op = words[0].lower()
    args = [w.lower() for w in words[1:]]
    if op == "nop" and not args:
        return ["\tnop"]
    if op == "clrwdt" and not args:
        return []
    if op == "disi" and len(args) == 1 and args[0].startswith("#"):
        return []
    if op == "reset" and not args:
        return _trap(INSN_RESET)
    if op == "pwrsav" and args in (["#0"], ["#1"]):
        return _trap(INSN_SLEEP if args == ["#0"] else INSN_IDLE)
    raise AsmError(f"{where}: the dsPIC instruction `{text}` in inline assembly cannot be "
                   f"carried out by the simulated e-puck (it carries out nop, reset, clrwdt, "
                   f"pwrsav #0 and #1, disi #N); keep it out of the simulated build, e.g. "
                   f"under #ifdef __XC16__")


def _unquote(name: str) -> str:
    return re.sub(r"\\(.)", r"\1", name)


def rewrite(assembly: str, source: str) -> str:
    """The compiler's assembly of one file of the user's C, with its inline
    dsPIC instructions carried out by the simulation and its globals in
    the sections a reset restores. AsmError for an instruction it cannot
    carry out."""
    out = []
    in_app = in_template = False
    where = source
    for line in assembly.splitlines():
        stripped = line.strip()
        if stripped == "#APP":
            in_app = True
            continue
        if stripped == "#NO_APP":
            in_app = in_template = False
            continue
        if in_app:
            # an asm statement's text is between `# LINE "FILE" 1` and
            # `# 0 "" 2`; the compiler's own lines (.loc) may come between two
            m = _MARKER.match(stripped)
            if m is not None:
                in_template = m.group(1) != "0"
                if in_template:
                    where = f"{_unquote(m.group(2))}:{m.group(1)}"
                continue
            if not in_template:
                out.append(line)
                continue
            body = stripped.split("//", 1)[0]
            for part in body.split(";"):
                part = part.strip()
                if part and not part.startswith("#"):
                    out.extend(_instruction(part, where))
            continue
        m = _SECTION.match(line)
        if m is not None and not m.group(2).startswith(".data.rel.ro"):
            bss = m.group(2).startswith(".bss")
            out.append(f"{m.group(1)}{'epuck_user_bss' if bss else 'epuck_user_data'},\"aw\""
                       + (",@nobits" if bss else ""))
            continue
        m = _PLAIN.match(line)
        if m is not None:
            bss = m.group(1) == "bss"
            out.append(f"\t.section\t{'epuck_user_bss' if bss else 'epuck_user_data'},\"aw\""
                       + (",@nobits" if bss else ""))
            continue
        out.append(line)
    return "\n".join(out) + "\n"
