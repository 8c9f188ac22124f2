"""The simulated e-puck's chip and accelerometer as a C main sees them
(runtime_c/host/dspic.c, imu.c; no checkout needed): an inline `reset`
starts main again with its globals as the C startup leaves them, RCON
keeping its power-on flag and saying a software reset, the ports back to
inputs; the data EEPROM keeps its words through the reset, a write only
clears bits, an erase sets them; the accelerometer's spherical readings
are the library's formulas over its own e_get_acc values; the camera
refuses the windows its driver refuses, fills exactly the bytes its mode
and size give, and takes a frame's time for them."""
import json
import math

import pytest

from tests.support.programs import epuckc

RESETS = r"""
#include <stdio.h>
#include <string.h>
#include <p30F6014A.h>
#include <motor_led/e_epuck_ports.h>
#include <uart/e_uart_char.h>
#include <utility/utility.h>
int ReadEE(int Page, int Offset, int *DataOut, int Size);
int EraseEE(int Page, int Offset, int Size);
int WriteEE(int *DataIn, int Page, int Offset, int Size);
static int counter = 5;
static void say(const char *text)
{
    e_send_uart1_char(text, (int)strlen(text));
    while (e_uart1_sending());
}
int main(void)
{
    char text[96];
    int word[1], v;
    e_init_uart1();
    counter++;
    ReadEE(0x7F, 0xF000, word, 1);
    sprintf(text, "boot %d counter %d por %d swr %d trisa %x led0 %d\n", word[0], counter,
            RCONbits.POR, RCONbits.SWR, TRISA, LED0);
    say(text);
    if (word[0] == -1) {
        v = 6;
        WriteEE(&v, 0x7F, 0xF000, 1);
        LED0_DIR = OUTPUT_PIN;
        LED0 = 1;
        wait(5000);                     /* 2 ms: seen lit */
        __asm__ volatile ("reset");
    } else if (word[0] == 6) {
        v = 3;
        WriteEE(&v, 0x7F, 0xF000, 1);
        RCONbits.POR = 0;
        __asm__ volatile ("nop");
        __asm__ volatile ("reset");
    }
    EraseEE(0x7F, 0xF000, 1);
    ReadEE(0x7F, 0xF000, word, 1);
    sprintf(text, "erased %d\n", word[0]);
    say(text);
    return 0;
}
"""


def _run(tmp_path, source, *extra, expect=0):
    main = tmp_path / "main.c"
    main.write_text(source)
    trace = tmp_path / "trace.jsonl"
    result = epuckc("run", main, "--trace", trace, "--time-limit", "5s", *extra)
    assert result.returncode == expect, result.stdout + result.stderr
    return [json.loads(line) for line in trace.read_text().splitlines()]


def test_a_reset_starts_main_again_with_the_chip_and_the_eeprom_as_a_dspic_leaves_them(
        tmp_path):
    records = _run(tmp_path, RESETS)
    said = [r["text"] for r in records if r["kind"] == "uart"]
    power_on_tris = "f6c0"          # the port A pins the dsPIC30F6014A has, inputs
    assert said == [
        f"boot -1 counter 6 por 1 swr 0 trisa {power_on_tris} led0 0\n",   # erased: 0xFFFF
        f"boot 6 counter 6 por 1 swr 1 trisa {power_on_tris} led0 0\n",    # POR kept, SWR set
        f"boot {6 & 3} counter 6 por 0 swr 1 trisa {power_on_tris} led0 0\n",  # bits 1 -> 0 only
        "erased -1\n",
    ]
    assert [r["cause"] for r in records if r["kind"] == "reset"] == ["reset instruction"] * 2
    # LED0 lit before the first reset, off when the reset cleared its latch
    led0 = [r["state"] for r in records if r["kind"] == "led" and r["name"] == "led0"]
    assert led0 == [1, 0]


ACCELEROMETER = r"""
#include <stdio.h>
#include <string.h>
#include <a_d/advance_ad_scan/e_ad_conv.h>
#include <a_d/advance_ad_scan/e_acc.h>
#include <acc_gyro/e_lsm330.h>
#include <uart/e_uart_char.h>
#include <utility/utility.h>
int main(void)
{
    char text[200];
    int k;
    e_init_ad_scan(ALL_ADC);
    e_init_uart1();
    for (k = 0; k < COUNT; k++) {
        TypeAccSpheric s;
        TypeAccRaw r;
        wait(491520L);                          /* 200 ms */
        s = e_read_acc_spheric();
        r = e_read_acc_xyz();
        sprintf(text, "%d %d %d %d %d %d %d %d %d %.5f %.5f %.5f %.5f %.5f %.5f\n",
                getXAxisAcc(), getYAxisAcc(), getZAxisAcc(), e_get_acc(0), e_get_acc(1),
                e_get_acc(2), r.acc_x, r.acc_y, r.acc_z, e_read_acc(), e_read_inclination(),
                e_read_orientation(), s.acceleration, s.inclination, s.orientation);
        e_send_uart1_char(text, (int)strlen(text));
        while (e_uart1_sending());
    }
    return 0;
}
"""

# (accx, accy, accz) on the scenario's analog scale (2048 at 0 g), each held
# around a reading: flat, tilted each way, nearly flat, upside down, falling
TILTS = [(2048, 2048, 2816), (2348, 2248, 2713), (1748, 2248, 2713), (1748, 1848, 2713),
         (2348, 1848, 2713), (2048, 2432, 2713), (2060, 2050, 2816), (2048, 2300, 1400),
         (2048, 2048, 2048)]
CST_RADIAN = 180.0 / 3.1415         # the library's constant


def _twelve_bits(v: int) -> int:
    return (v >> 4) - (v >> 6)


def test_the_accelerometers_spherical_readings_are_the_librarys_formulas(tmp_path):
    scenario = tmp_path / "s.scn"
    scenario.write_text("".join(f"{100 + 200 * k} ms accx={x} accy={y} accz={z}\n"
                                for k, (x, y, z) in enumerate(TILTS)))
    records = _run(tmp_path, ACCELEROMETER.replace("COUNT", str(len(TILTS))),
                   "--scenario", scenario)
    lines = [r["text"].split() for r in records if r["kind"] == "uart"]
    assert len(lines) == len(TILTS)
    seen = set()
    for fields in lines:
        lx, ly, lz, ax, ay, az, rx, ry, rz = map(int, fields[:9])
        acc, incl, orient, s_acc, s_incl, s_orient = map(float, fields[9:])
        # e-puck 1.3: the LSM330's axes exchanged, 12 bits, centre z 2000
        assert (ax, ay, az) == (_twelve_bits(ly), _twelve_bits(lx), _twelve_bits(lz - 2000))
        assert (rx, ry, rz) == (ax, ay, az)
        want_acc = math.sqrt(ax * ax + ay * ay + az * az)
        want_incl = 90.0 - math.atan2(az, math.hypot(ax, ay)) * CST_RADIAN
        want_orient = 0.0 if want_incl < 5 or want_incl > 160 else \
            math.atan2(ax, ay) * CST_RADIAN + 180.0
        assert acc == pytest.approx(want_acc, rel=1e-5, abs=1e-3)
        assert incl == pytest.approx(want_incl, abs=2e-3)
        assert orient == pytest.approx(want_orient, abs=2e-3)
        assert (s_acc, s_incl, s_orient) == (acc, incl, orient)
        seen.add("flat" if want_incl < 5 else "over" if want_incl > 160 else
                 f"quadrant {int(want_orient // 90)}")
    # every quadrant of atan2, both ends where the orientation is 0
    assert seen >= {"flat", "over", "quadrant 0", "quadrant 1", "quadrant 2", "quadrant 3"}


CAMERA = r"""
#include <stdio.h>
#include <string.h>
#include <a_d/advance_ad_scan/e_ad_conv.h>
#include <camera/fast_2_timer/e_poxxxx.h>
#include <uart/e_uart_char.h>
#include <utility/utility.h>
static char buffer[1000];
static void say(const char *text)
{
    e_send_uart1_char(text, (int)strlen(text));
    while (e_uart1_sending());
}
/* a capture of the window: the bytes it wrote, the ms it took */
static void capture(const char *name, int width, int height, int zoom, int mode)
{
    char text[120];
    int code, n;
    float ms;
    memset(buffer, 0x55, sizeof buffer);
    code = e_poxxxx_config_cam((ARRAY_WIDTH - width) / 2, (ARRAY_HEIGHT - height) / 2,
                               width, height, zoom, zoom, mode);
    e_poxxxx_write_cam_registers();
    resetTime();
    e_poxxxx_launch_capture(buffer);
    while (!e_poxxxx_is_img_ready());
    ms = getDiffTimeMs();
    for (n = (int)sizeof buffer; n > 0 && buffer[n - 1] == 0x55; n--);
    sprintf(text, "%s %d %d %.0f\n", name, code, n, ms);
    say(text);
}
int main(void)
{
    char text[120];
    e_init_ad_scan(ALL_ADC);
    e_init_uart1();
    sprintf(text, "init %x codes %d %d %d %d %d\n", e_poxxxx_init_cam(),
            e_poxxxx_config_cam(600, 0, 80, 80, 4, 4, GREY_SCALE_MODE),
            e_poxxxx_config_cam(0, 0, 82, 80, 4, 4, GREY_SCALE_MODE),
            e_poxxxx_config_cam(0, 0, 80, 80, 0, 4, GREY_SCALE_MODE),
            e_poxxxx_config_cam(0, 0, 80, 80, 4, 4, 7),
            e_poxxxx_config_cam(0, 0, 640, 8, 1, 8, RGB_565_MODE));
    say(text);
    capture("grey", 80, 80, 4, GREY_SCALE_MODE);
    capture("rgb", 240, 4, 4, RGB_565_MODE);
    return 0;
}
"""


def test_the_camera_takes_the_drivers_windows_and_fills_what_they_give(tmp_path):
    records = _run(tmp_path, CAMERA)
    said = [r["text"].split() for r in records if r["kind"] == "uart"]
    # a PO3030K; a window leaving the sensor, a width not a multiple of the
    # zoom, a zoom of 0, no such mode, a line longer than the driver's table
    assert said[0] == ["init", "3030", "codes", "-1", "-1", "-1", "-1", "-1"]
    grey, rgb = said[1], said[2]
    # 20 x 20 pixels of a byte; 60 x 1 of two (black: nothing in view)
    assert grey[:3] == ["grey", "0", str(20 * 20)] and rgb[:3] == ["rgb", "0", str(60 * 2)]
    # a frame: 8.6 a second in grey at a zoom of 4, 4.3 in colour (getDiffTimeMs
    # counts the A/D interrupt's 0.061 ms ticks)
    assert float(grey[3]) == pytest.approx(1000 / 8.6, abs=1.0)
    assert float(rgb[3]) == pytest.approx(1000 / 4.3, abs=2.0)
