"""A robot's end of a serial port: a pseudo-terminal whose other end sends
what a robot's tracer sent (bytes captured on simavr), in pieces over
time, as a robot's Bluetooth or USB serial port delivers them."""
import os
import threading
import time


class FakeRobot:
    """The robot's end of a pty: sends `data` in pieces, 2 ms apart."""

    def __init__(self, data: bytes, stop_after: int = None):
        self.master, slave = os.openpty()
        self.port = os.ttyname(slave)
        self.slave = slave
        self.data = data if stop_after is None else data[:stop_after]
        self.sent = threading.Event()

    def run(self, then_close: bool = False):
        def send():
            for at in range(0, len(self.data), 17):
                os.write(self.master, self.data[at:at + 17])
                time.sleep(0.002)
            self.sent.set()
            if then_close:
                time.sleep(0.3)
                os.close(self.master)
        threading.Thread(target=send, daemon=True).start()

    def close(self):
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except (OSError, TypeError):
                pass                # closed already
