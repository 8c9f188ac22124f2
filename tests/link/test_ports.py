"""The robots' ports told apart in pyserial's port list (its own ListPortInfo
records, filled as each system fills them), and a port that cannot be
opened said in one line with the fix: a real permission refusal (a
process without the rights opens a real pty) and a port that is not there."""
import grp
import os

import pytest
from serial.tools.list_ports_common import ListPortInfo

from epuckc.link.ports import (LinkError, bluetooth_ports, check_access, epuck2_monitor_ports,
                               epuck2_programmers, robot_number, wrong_port)


def port(device, vid=None, pid=None, serial=None, location=None, interface=None,
         product=None, manufacturer=None, hwid=None, description=None):
    info = ListPortInfo(device, skip_link_detection=True)
    info.vid, info.pid, info.serial_number = vid, pid, serial
    info.location, info.interface, info.product, info.manufacturer = (location, interface,
                                                                      product, manufacturer)
    if vid is not None:
        info.apply_usb_info()
    if hwid:
        info.hwid = hwid
    if description:
        info.description = description
    return info


def epuck2(device, location, interface=None, serial="EPUCK"):
    return port(device, 0x1D50, 0x6018, serial, location, interface, "e-puck2", "GCtronic/EPFL")


def test_linux_each_robots_gdb_port_is_its_interface_00():
    infos = [
        epuck2("/dev/ttyACM3", "1-1.3:1.2", "e-puck2 Serial Monitor"),
        epuck2("/dev/ttyACM2", "1-1.3:1.0", "e-puck2 GDB Server"),
        epuck2("/dev/ttyACM0", "1-1.2:1.0", "e-puck2 GDB Server"),
        epuck2("/dev/ttyACM1", "1-1.2:1.2", "e-puck2 Serial Monitor"),
        # the main processor's own USB serial port (ChibiOS SDU1), an Arduino, a plain BMP
        port("/dev/ttyACM4", 0x0483, 0x5740, "301", "1-1.4:1.0", None, "STM32F407"),
        port("/dev/ttyACM5", 0x2341, 0x0043, "7543", "1-1.5:1.0", None, "Arduino Uno"),
        port("/dev/ttyACM6", 0x1D50, 0x6018, "7BB180B4", "1-1.6:1.0", "Black Magic GDB Server",
             "Black Magic Probe", "Black Sphere Technologies"),
    ]
    found = epuck2_programmers(infos)
    assert [p.device for p in found] == ["/dev/ttyACM0", "/dev/ttyACM2"]
    assert {p.kind for p in found} == {"epuck2"}
    # the other port of each robot is its serial monitor, the trace's
    assert [p.device for p in epuck2_monitor_ports(infos)] == ["/dev/ttyACM1", "/dev/ttyACM3"]


def test_windows_and_macos_without_interface_strings():
    windows = [epuck2("COM7", "1-2:x.2"), epuck2("COM6", "1-2:x.0")]
    assert [p.device for p in epuck2_programmers(windows)] == ["COM6"]
    macos = [epuck2("/dev/cu.usbmodemEPUCK3", "20-2"), epuck2("/dev/cu.usbmodemEPUCK1", "20-2")]
    assert [p.device for p in epuck2_programmers(macos)] == ["/dev/cu.usbmodemEPUCK1"]


def test_a_robot_whose_gdb_port_is_not_listed_gives_none():
    assert epuck2_programmers([epuck2("/dev/ttyACM1", "1-1.2:1.2",
                                      "e-puck2 Serial Monitor")]) == []


def test_a_port_given_that_is_not_the_one_to_flash_through():
    infos = [epuck2("/dev/ttyACM0", "1-1.2:1.0", "e-puck2 GDB Server"),
             epuck2("/dev/ttyACM1", "1-1.2:1.2", "e-puck2 Serial Monitor"),
             epuck2("/dev/ttyACM2", "1-1.3:1.0", "e-puck2 GDB Server"),
             epuck2("/dev/ttyACM3", "1-1.3:1.2", "e-puck2 Serial Monitor")]
    assert wrong_port("/dev/ttyACM0", "epuck2", infos) is None
    assert wrong_port("/dev/ttyACM3", "epuck2", infos) == (
        "/dev/ttyACM3 is the e-puck2's serial monitor port, not its GDB port (the first of its "
        "two): its GDB port is /dev/ttyACM2")
    assert wrong_port("/dev/ttyACM0", "epuck", infos).startswith(
        "/dev/ttyACM0 is an e-puck2's programmer, and this program is for the e-puck")
    assert wrong_port("/dev/rfcomm0", "epuck", infos) is None       # not in the list: as given
    assert wrong_port("/dev/rfcomm0", "epuck2", infos) is None


def test_bluetooth_ports_of_e_pucks_with_their_numbers():
    infos = [
        port("/dev/rfcomm0"),
        port("/dev/tty.e-puck_3112-COM1"), port("/dev/cu.e-puck_3112-COM1"),
        port("COM5", hwid="BTHENUM\\{00001101-0000-1000-8000-00805F9B34FB}_LOCALMFG&0002",
             description="Standard Serial over Bluetooth link (COM5)"),
        port("/dev/ttyUSB0", 0x0403, 0x6001, "A50285BI", "1-1.1", None, "FT232R USB UART"),
        port("/dev/ttyS0"),
    ]
    found = bluetooth_ports(infos)
    assert [(p.device, p.robot_id) for p in found] == [
        ("/dev/cu.e-puck_3112-COM1", 3112), ("/dev/rfcomm0", None), ("COM5", None)]


@pytest.mark.parametrize("name, number", [
    ("/dev/cu.e-puck_3112-COM1", 3112), ("e-puck_0042", 42), ("/dev/epuck1234", 1234),
    ("E-PUCK 7", 7), ("/dev/rfcomm0", None), ("e-puck2", None), ("e-puck_99999", None)])
def test_the_robots_number_in_a_ports_name(name, number):
    assert robot_number(name) == number


def test_a_port_that_is_not_there():
    with pytest.raises(LinkError) as caught:
        check_access("/dev/ttyACM99-not-here")
    assert str(caught.value).startswith("there is no port /dev/ttyACM99-not-here: plug the "
                                        "robot in")


def _as_nobody(device: str) -> str:
    """check_access(device)'s message in a child process that is nobody."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:                            # the child
        try:
            os.close(read)
            os.setgroups([])
            os.setgid(65534)
            os.setuid(65534)
            try:
                check_access(device)
                said = "opened"
            except LinkError as exc:
                said = str(exc)
            os.write(write, said.encode())
        finally:
            os._exit(0)
    os.close(write)
    chunks = []
    while True:
        chunk = os.read(read, 4096)
        if not chunk:
            break
        chunks.append(chunk)
    os.close(read)
    os.waitpid(pid, 0)
    return b"".join(chunks).decode()


@pytest.fixture
def owned_pty():
    """A real pty whose slave gets the owner and mode a test gives it, as
    udev gives /dev/ttyACM0 root:dialout 0660 (needs root to do so)."""
    if os.getuid() != 0:
        pytest.skip("giving the port to another owner needs root")
    master, slave = os.openpty()
    device = os.ttyname(slave)

    def own(group: str, mode: int) -> str:
        os.chown(device, 0, grp.getgrnam(group).gr_gid)
        os.chmod(device, mode)
        return device
    yield own
    os.close(master)
    os.close(slave)


def test_a_port_of_a_group_names_the_group_and_the_udev_rule(owned_pty):
    device = owned_pty("dialout", 0o660)
    assert _as_nobody(device) == (
        f"cannot open {device}: permission denied: add yourself to the dialout group (sudo "
        "usermod -aG dialout $USER, then log out and in) or install the udev rule in "
        "docs/robots.md")


def test_a_port_of_root_alone_needs_the_udev_rule(owned_pty):
    device = owned_pty("root", 0o600)
    assert _as_nobody(device) == (
        f"cannot open {device}: permission denied: install the udev rule in docs/robots.md (the "
        "port belongs to root alone), then plug the robot in again")
