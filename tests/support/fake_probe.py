"""A stand-in for the e-puck2's on-board programmer, a Black Magic Probe
firmware: the GDB remote serial protocol on a pseudo-terminal, as the probe
speaks it (packets `$data#cs` acknowledged with `+`/`-`, its qSupported
answer, the memory map, `monitor swdp_scan`'s text, vAttach, the vFlash
packets, m/M/X, qCRC, `k`), over a model of the STM32F407's memories whose
flash keeps what NOR flash keeps (a write can only clear bits; an erase
sets a whole block to 0xFF).

The facts are the GDB manual's ("Remote Protocol", "Memory Map Format")
and what ../shared/reference/robot-link.md says of the probe; what the
real Debian gdb-multiarch sends beyond them (qTStatus, qAttached, vKill,
...) is answered as the probe answers a packet it does not know: empty.

`threads=True` answers as the probe's firmware does since 2022 (one
thread reported: qC, qfThreadInfo, vKill, stop replies naming it); without
it, as the e-puck2 programmer's firmware (the probe's code of 2020) does.

Staged failures: `no_target` (the scan finds nothing and attach fails),
`bad_crc` (a bit of the flash does not take the program), `vanish_after`
(the port goes away after that many vFlashWrite packets), `mute_on`
(the probe stops answering at the first packet starting with that text),
`attach_fails` (the scan finds the processor, attaching to it fails) and
`erase_fails` (the flash is not erased).
"""
from __future__ import annotations

import os
import select
import threading
import tty

PACKET_SIZE = 0x400     # the probe's PacketSize (its buffer of 1024 bytes)

# The STM32F407's flash as the probe maps it (16, 64 and 128 KB sectors)
# and its RAMs (the core-coupled 64 KB, then SRAM1 and SRAM2).
FLASH_REGIONS = [(0x08000000, 0x10000, 0x4000), (0x08010000, 0x10000, 0x10000),
                 (0x08020000, 0xE0000, 0x20000)]
FLASH_START, FLASH_END = 0x08000000, 0x08100000
RAMS = [(0x10000000, 0x10000), (0x20000000, 0x20000)]

SCAN_FOUND = ("Target voltage: 3.3V\n", "Available Targets:\n", "No. Att Driver\n",
              " 1      STM32F40x M4\n")
SCAN_FAILED = ("Target voltage: 0.0V\n", "SW-DP scan failed!\n")

REGISTERS = [f"r{i}" for i in range(13)] + ["sp", "lr", "pc", "xpsr"]
TARGET_XML = ('<?xml version="1.0"?>\n<!DOCTYPE target SYSTEM "gdb-target.dtd">\n'
              "<target><architecture>arm</architecture>"
              '<feature name="org.gnu.gdb.arm.m-profile">'
              + "".join(f'<reg name="{name}" bitsize="32"'
                        + (' type="data_ptr"' if name == "sp" else
                           ' type="code_ptr"' if name == "pc" else "") + "/>"
                        for name in REGISTERS)
              + "</feature></target>")


def memory_map_xml() -> str:
    rams = "".join(f'<memory type="ram" start="0x{start:x}" length="0x{length:x}"/>'
                   for start, length in RAMS)
    flashes = "".join(f'<memory type="flash" start="0x{start:x}" length="0x{length:x}">'
                      f'<property name="blocksize">0x{block:x}</property></memory>'
                      for start, length, block in FLASH_REGIONS)
    return ('<?xml version="1.0"?>\n<!DOCTYPE memory-map PUBLIC "+//IDN gnu.org//DTD GDB '
            'Memory Map V1.0//EN" "http://sourceware.org/gdb/gdb-memory-map.dtd">\n'
            f"<memory-map>{rams}{flashes}</memory-map>")


def _crc_table():
    table = []
    for byte in range(256):
        crc = byte << 24
        for _ in range(8):
            crc = ((crc << 1) ^ 0x04C11DB7) if crc & 0x80000000 else crc << 1
        table.append(crc & 0xFFFFFFFF)
    return table


_CRC_TABLE = _crc_table()


def gdb_crc32(data: bytes) -> int:
    """qCRC's checksum as the GDB manual defines it: CRC-32 with the
    polynomial of IEEE 802.3, each byte taken most significant bit first,
    starting from 0xffffffff, the result not inverted."""
    crc = 0xFFFFFFFF
    for byte in data:
        crc = ((crc << 8) & 0xFFFFFFFF) ^ _CRC_TABLE[((crc >> 24) ^ byte) & 0xFF]
    return crc


def _checksum(data: bytes) -> bytes:
    return b"%02x" % (sum(data) & 0xFF)


class FakeProbe:
    """One programmer on one pty (`port` is its path). `flash` is the
    STM32F407's 1 MB of flash, which starts holding an older program (a
    pattern); `written` lists (address, bytes) of every vFlashWrite,
    `erased` the (address, length) of every vFlashErase, `packets` every
    packet received, `errors` what a real probe would not have taken."""

    def __init__(self, *, no_target=False, bad_crc=False, vanish_after=None, mute_on=None,
                 threads=False, attach_fails=False, erase_fails=False):
        self.no_target, self.bad_crc, self.threads = no_target, bad_crc, threads
        self.attach_fails, self.erase_fails = attach_fails, erase_fails
        self.vanish_after, self.mute_on = vanish_after, mute_on
        self.flash = bytearray((i * 37 + 11) & 0xFF for i in range(FLASH_END - FLASH_START))
        self.rams = {start: bytearray(length) for start, length in RAMS}
        self.written, self.erased, self.packets, self.errors = [], [], [], []
        self.attached = False
        self.killed = False             # reset and let go: the new program runs
        self.vanished = False
        self._flash_mode = False
        self.registers = None
        self._last_reply = b""
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)         # no echo of what gdb writes, before gdb sets it too
        self.port = os.ttyname(self._slave)
        self._stop = threading.Event()
        self._buffer = bytearray()
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    # -- the link --------------------------------------------------------

    def close(self):
        self._stop.set()
        self._thread.join(timeout=5)
        self._close_fds()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _close_fds(self):
        for fd in (self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass
        self._master = self._slave = -1

    def vanish(self):
        """The cable is pulled: both ends of the pty close, so gdb reads an
        error from then on."""
        self.vanished = True
        self._close_fds()

    def _read_byte(self):
        while not self._buffer:
            if self._stop.is_set() or self._master < 0:
                return None
            ready, _, _ = select.select([self._master], [], [], 0.05)
            if not ready:
                continue
            try:
                chunk = os.read(self._master, 4096)
            except OSError:
                return None
            if not chunk:
                return None
            self._buffer += chunk
        byte = self._buffer[0]
        del self._buffer[0]
        return byte

    def _write(self, data: bytes):
        if self._master >= 0:
            os.write(self._master, data)

    def _send(self, data: bytes):
        self._last_reply = b"$" + data + b"#" + _checksum(data)
        self._write(self._last_reply)

    def _read_packet(self):
        """The next packet's data, unescaped (None: the link closed); acks
        are taken on the way, and a `-` resends the last reply."""
        while True:
            byte = self._read_byte()
            if byte is None:
                return None
            if byte == ord("-"):
                self._write(self._last_reply)
                continue
            if byte != ord("$"):
                continue            # `+`, or a Ctrl-C the probe has nothing to stop for
            raw = bytearray()
            while True:
                byte = self._read_byte()
                if byte is None:
                    return None
                if byte == ord("#"):
                    break
                raw.append(byte)
            given = bytes(b for b in (self._read_byte(), self._read_byte()) if b is not None)
            if given.lower() != _checksum(raw):
                self.errors.append(f"bad checksum {given!r} on {bytes(raw[:40])!r}")
                self._write(b"-")
                continue
            self._write(b"+")
            data, escaped = bytearray(), False
            for byte in raw:
                if escaped:
                    data.append(byte ^ 0x20)
                    escaped = False
                elif byte == ord("}"):
                    escaped = True
                else:
                    data.append(byte)
            return bytes(data)

    def _serve(self):
        while not self._stop.is_set():
            packet = self._read_packet()
            if packet is None:
                return
            self.packets.append(packet)
            if self.mute_on is not None and packet.startswith(self.mute_on):
                return              # hung: reads nothing more, answers nothing
            reply = self._handle(packet)
            if self.vanished:
                return
            if reply is not None:
                self._send(reply)

    # -- the packets -----------------------------------------------------

    def _handle(self, packet: bytes):
        kind = packet[:1]
        if kind == b"q":
            return self._query(packet)
        if kind == b"v":
            return self._v_packet(packet)
        if kind == b"?":
            return self._stopped() if self.attached else b"W00"
        if kind == b"!":
            return b"OK"
        if kind == b"g":
            return self._registers() if self.attached else b"EFF"
        if kind == b"G":
            if not self.attached:
                return b"EFF"
            self.registers = bytes.fromhex(packet[1:].decode())
            return b"OK"
        if kind == b"H" and self.threads:
            return b"OK"
        if kind == b"m":
            return self._read_memory(packet)
        if kind in (b"M", b"X"):
            return self._write_memory(packet)
        if kind == b"k":                # reset and detach; the probe answers nothing
            self.attached = False
            self.killed = True
            return None
        if kind == b"D":
            self.attached = False
            return b"OK"
        return b""                      # not supported

    def _query(self, packet: bytes):
        if packet.startswith(b"qSupported"):
            return b"PacketSize=%X;qXfer:memory-map:read+;qXfer:features:read+" % PACKET_SIZE
        if packet.startswith(b"qRcmd,"):
            command = bytes.fromhex(packet[6:].decode()).decode()
            if command.strip() == "swdp_scan":
                lines = SCAN_FAILED if self.no_target else SCAN_FOUND
                for line in lines:
                    self._send(b"O" + line.encode().hex().encode())
                return b"E" if self.no_target else b"OK"
            return b""
        if packet.startswith(b"qXfer:memory-map:read::"):
            return self._string_reply(memory_map_xml(), packet[23:]) if self.attached \
                else b"E01"
        if packet.startswith(b"qXfer:features:read:target.xml:"):
            return self._string_reply(TARGET_XML, packet[31:]) if self.attached else b"E01"
        if self.threads and packet == b"qC":
            return b"QC1" if self.attached else b""
        if self.threads and packet == b"qfThreadInfo":
            return b"m1" if self.attached else b"l"
        if self.threads and packet == b"qsThreadInfo":
            return b"l"
        if packet.startswith(b"qCRC:"):
            if not self.attached:
                return b"E01"
            address, length = (int(x, 16) for x in packet[5:].split(b","))
            data = self._memory(address, length)
            return b"E01" if data is None else b"C%x" % gdb_crc32(data)
        return b""

    @staticmethod
    def _string_reply(text: str, where: bytes) -> bytes:
        offset, length = (int(x, 16) for x in where.split(b","))
        data = text.encode()
        if offset < len(data):
            return b"m" + data[offset:offset + length]
        return b"l" if offset == len(data) else b"E01"

    def _v_packet(self, packet: bytes):
        if packet.startswith(b"vAttach;"):
            if self.no_target or self.attach_fails or int(packet[8:], 16) != 1:
                return b"E01"
            self.attached = True
            return self._stopped()
        if packet.startswith(b"vFlashErase:"):
            if not self.attached:
                return b"EFF"
            address, length = (int(x, 16) for x in packet[12:].split(b","))
            self._flash_mode = True
            if self.erase_fails:
                return b"EFF"               # the processor's flash controller said no
            return b"OK" if self._erase(address, length) else b"EFF"
        if packet.startswith(b"vFlashWrite:"):
            head, _, data = packet[12:].partition(b":")
            address = int(head, 16)
            if not self.attached or not self._flash_write(address, data):
                return b"EFF"
            if self.vanish_after is not None and len(self.written) >= self.vanish_after:
                self.vanish()
                return None
            return b"OK"
        if packet.startswith(b"vKill;") and self.threads:
            self.attached = False           # reset and detach: the program runs
            self.killed = True
            return b"OK"
        if packet == b"vFlashDone":
            self._flash_mode = False
            if self.bad_crc and self.written:
                address = self.written[0][0] + len(self.written[0][1]) // 2
                self.flash[address - FLASH_START] ^= 0x10       # a bit that did not take
            return b"OK"
        return b""

    def _erase(self, address: int, length: int) -> bool:
        end = address + length
        for start, size, block in FLASH_REGIONS:
            # each part of the range in a region must be whole blocks of it
            lo, hi = max(address, start), min(end, start + size)
            if lo < hi and ((lo - start) % block or (hi - start) % block):
                self.errors.append(f"vFlashErase:{address:x},{length:x} is not whole blocks")
                return False
        if address < FLASH_START or end > FLASH_END:
            self.errors.append(f"vFlashErase:{address:x},{length:x} is outside the flash")
            return False
        self.flash[address - FLASH_START:end - FLASH_START] = b"\xff" * length
        self.erased.append((address, length))
        return True

    def _flash_write(self, address: int, data: bytes) -> bool:
        if address < FLASH_START or address + len(data) > FLASH_END:
            self.errors.append(f"vFlashWrite at {address:x} is outside the flash")
            return False
        offset = address - FLASH_START
        for i, byte in enumerate(data):
            self.flash[offset + i] &= byte      # NOR flash: a write only clears bits
        self.written.append((address, bytes(data)))
        return True

    def _place(self, address: int, length: int):
        """(buffer, offset) holding [address, address + length), or None."""
        if FLASH_START <= address and address + length <= FLASH_END:
            return self.flash, address - FLASH_START
        for start, size in RAMS:
            if start <= address and address + length <= start + size:
                return self.rams[start], address - start
        return None

    def _memory(self, address: int, length: int):
        place = self._place(address, length)
        if place is None:
            return None
        buffer, offset = place
        return bytes(buffer[offset:offset + length])

    def _read_memory(self, packet: bytes):
        if not self.attached:
            return b"EFF"
        address, length = (int(x, 16) for x in packet[1:].split(b","))
        if length > PACKET_SIZE // 2:
            return b"E02"
        data = self._memory(address, length)
        return b"E01" if data is None else data.hex().encode()

    def _write_memory(self, packet: bytes):
        if not self.attached:
            return b"EFF"
        head, _, data = packet[1:].partition(b":")
        address, length = (int(x, 16) for x in head.split(b","))
        if packet[:1] == b"M":
            data = bytes.fromhex(data.decode())
        if len(data) != length:
            return b"E02"
        place = self._place(address, length)
        if place is None or place[0] is self.flash:
            return b"E01"       # the flash is written with vFlash packets only
        buffer, offset = place
        buffer[offset:offset + length] = data
        return b"OK"

    def _stopped(self) -> bytes:
        return b"T05thread:1;" if self.threads else b"T05"

    def _registers(self) -> bytes:
        sp = int.from_bytes(self.flash[0:4], "little")
        pc = int.from_bytes(self.flash[4:8], "little") & ~1
        values = [0] * 13 + [sp, 0xFFFFFFFF, pc, 0x01000000]
        return b"".join(v.to_bytes(4, "little").hex().encode() for v in values)

    def flash_bytes(self, address: int, length: int) -> bytes:
        return bytes(self.flash[address - FLASH_START:address - FLASH_START + length])
