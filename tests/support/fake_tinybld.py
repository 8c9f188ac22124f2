"""A stand-in for an e-puck with its Bluetooth bootloader (tinybld) on a
pseudo-terminal, as ../shared/reference/robot-link.md describes it: a
program runs until the robot is reset (the user presses the button
`reset_after` seconds after the first byte comes, or sercom's `R\\n`
resets it); the bootloader then listens for a moment for 0xC1, answers
`q` `K`, and takes packets of 101 bytes, each checked for its layout (the
row's address, 0x60, the checksum) and answered `K` or `N`, until the end
0x95 0x00 0x00 0xFF; a packet whose bytes stop coming is given up after
`byte_timeout` (the bootloader then starts the program).

`flash` is the program memory (program address -> 24-bit instruction),
starting with `old` (a previous program) and otherwise erased; a row
written replaces its 32 instructions. `rows_written` lists the rows in the
order they came; `errors` what a real bootloader would not have taken
(bad layouts, rows over the bootloader).

Staged trouble: `corrupt` (numbers of packets whose first arrival gets a
byte changed, so the checksum fails), `refuse_all` (every packet refused),
`drop_first_call` (the first 0xC1 after the reset is lost on the way, so
only a call sent again is answered), `drop_packet_byte` (the
number of a packet that loses a byte on the way), `sercom` (a program that
resets on `R\\n`), `reset_after` (None: the button is never pressed).
"""
from __future__ import annotations

import os
import select
import threading
import time
import tty

BOOTLOADER_ROW, BOOTLOADER = 0x17F00, 0x17F40
END = bytes([0x95, 0x00, 0x00, 0xFF])


class FakeTinybld:
    def __init__(self, *, reset_after=0.3, sercom=False, listen=1.5, byte_timeout=0.5,
                 corrupt=(), refuse_all=False, drop_first_call=False, drop_packet_byte=None,
                 old=None, answer_delay=0.0):
        self.reset_after, self.sercom, self.listen = reset_after, sercom, listen
        self.byte_timeout = byte_timeout
        self.corrupt, self.refuse_all = set(corrupt), refuse_all
        self.drop_first_call, self.drop_packet_byte = drop_first_call, drop_packet_byte
        self.answer_delay = answer_delay    # a Bluetooth round trip, per packet
        self.flash = dict(old or {})
        self.rows_written, self.errors, self.answers = [], [], []
        self.handshakes = 0
        self.calls = 0              # 0xC1 bytes the bootloader heard
        self.received_packets = 0
        self.finished = threading.Event()
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        self.port = os.ttyname(self._slave)
        self._stop = threading.Event()
        self._pending = bytearray()
        self._dropped = False
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def close(self):
        self._stop.set()
        self._thread.join(timeout=5)
        for fd in (self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _read(self, timeout: float):
        """One byte, or None after `timeout` seconds (or when stopping)."""
        end = time.monotonic() + timeout
        while not self._pending:
            left = end - time.monotonic()
            if left <= 0 or self._stop.is_set():
                return None
            ready, _, _ = select.select([self._master], [], [], min(left, 0.05))
            if ready:
                try:
                    self._pending += os.read(self._master, 4096)
                except OSError:
                    return None
        byte = self._pending[0]
        del self._pending[0]
        return byte

    def _write(self, data: bytes):
        self.answers.append(data)
        os.write(self._master, data)

    def _run(self):
        while not self._stop.is_set():
            self._run_program()
            if self._stop.is_set():
                return
            self._run_bootloader()

    def _run_program(self):
        """The robot runs a program until it is reset."""
        pressed_at = None
        line = bytearray()
        while not self._stop.is_set():
            if pressed_at is not None and time.monotonic() >= pressed_at:
                return
            byte = self._read(0.05)
            if byte is None:
                continue
            if pressed_at is None and self.reset_after is not None:
                pressed_at = time.monotonic() + self.reset_after
            line.append(byte)
            if byte == ord("\n"):
                if self.sercom and bytes(line).endswith(b"V\n"):
                    self._write(b"v\r\nVersion 1.2.2 August 2008 GCtronic\r\n")
                if self.sercom and bytes(line).endswith(b"R\n"):
                    return
                line.clear()

    def _run_bootloader(self):
        """After a reset: listen for 0xC1 for a moment, then take packets;
        back to the program at the end, or when bytes stop coming."""
        end = time.monotonic() + self.listen
        while True:
            byte = self._read(max(0.0, end - time.monotonic()))
            if byte is None:
                return              # nobody called: the program starts
            if byte == 0xC1:
                if self.drop_first_call and self.handshakes == 0 and not self._dropped:
                    self._dropped = True        # lost on the way: never heard
                    continue
                self.calls += 1
                break
        self.handshakes += 1
        self._write(b"qK")
        while not self._stop.is_set():
            head = self._take(4, first_wait=5.0)
            if head is None:
                return
            if head == END:
                self.finished.set()
                return
            self.received_packets += 1
            lose = 6 if self.received_packets == self.drop_packet_byte else None
            rest = self._take(97, lose=lose)
            if rest is None:
                return              # bytes stopped coming: the bootloader gives up
            self._packet(head + rest)

    def _take(self, count: int, first_wait: float = None, lose=None):
        """`count` bytes; the one at index `lose` is lost on the way."""
        data, seen = bytearray(), 0
        while len(data) < count:
            wait = first_wait if (not data and first_wait) else self.byte_timeout
            byte = self._read(wait)
            if byte is None:
                return None
            if seen != lose:
                data.append(byte)
            seen += 1
        return bytes(data)

    def _packet(self, data: bytes):
        number = self.received_packets
        if number in self.corrupt:
            self.corrupt.discard(number)
            data = data[:10] + bytes([data[10] ^ 0x41]) + data[11:]
        address = int.from_bytes(data[:3], "little")
        if data[3] != 0x60:
            self.errors.append(f"packet {number}: byte 3 is 0x{data[3]:02x}, not 0x60")
        if address % 64:
            self.errors.append(f"packet {number}: address 0x{address:06x} is not a row's")
        if address >= BOOTLOADER:
            self.errors.append(f"packet {number}: row 0x{address:06x} is the bootloader's")
        if sum(data) & 0xFF or self.refuse_all:
            self._write(b"N")
            return
        for i in range(32):
            self.flash[address + 2 * i] = int.from_bytes(data[4 + 3 * i:7 + 3 * i], "little")
        self.rows_written.append(address)
        time.sleep(self.answer_delay)
        self._write(b"K")
