/*
 * rt_trace_chibios.c - the link of the robot's trace (rt_trace.c) on the
 * e-puck2 (ChibiOS, GCtronic's e-puck2_main-processor firmware): UART3 at
 * 115200 baud 8N1, which the on-board programmer passes through to its
 * second USB serial port (the "monitor" port beside its GDB port; it
 * needs DTR high, which a serial terminal and pyserial set), or, built
 * with EPUCKRT_TRACE_USB (`epuckc build --target epuck2 --trace
 * --trace-link usb`), the main processor's own USB serial port (SDU1,
 * the firmware's usbcfg.c).  ChibiOS copies what is written into the
 * driver's output queue: chnWriteTimeout with TIME_IMMEDIATE takes what
 * fits and returns at once, so the poll never waits; while the USB port is
 * not open nothing is taken, and the tracer counts what it drops.
 */
#include "ch.h"
#include "hal.h"

#include "rt_platform.h"

#ifdef EPUCKRT_TRACE_USB
#include "usbcfg.h"
#define TRACE_CHANNEL ((BaseChannel *)&SDU1)
#else
#define TRACE_CHANNEL ((BaseChannel *)&SD3)
#endif

void rt_trace_port_start(void)
{
#ifdef EPUCKRT_TRACE_USB
    usb_start();
#else
    static const SerialConfig config = {115200, 0, 0, 0};
    sdStart(&SD3, &config);
#endif
}

int rt_trace_port_busy(void)
{
    return 0;       /* the driver copied the bytes */
}

int rt_trace_port_send(const unsigned char *bytes, int n)
{
#ifdef EPUCKRT_TRACE_USB
    if (SDU1.config->usbp->state != USB_ACTIVE)
        return 0;   /* no host has the port open */
#endif
    return (int)chnWriteTimeout(TRACE_CHANNEL, bytes, (size_t)n, TIME_IMMEDIATE);
}

void rt_trace_port_wait(void)
{
    chThdSleepMilliseconds(1);
}
