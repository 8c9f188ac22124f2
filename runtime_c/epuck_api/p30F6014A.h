/* The device header of the e-puck's dsPIC30F6014A, as the e-puck library's
 * programs include it ("p30F6014A.h").  Declarations only (see README.md):
 * on the host nothing of the chip's registers is simulated; the pins the
 * library names (the LEDs, the selector) are in motor_led/e_epuck_ports.h,
 * over the simulated robot.  A program that uses a register directly (TRISA,
 * IEC0bits, ...) fails to compile naming it. */
#ifndef EPUCK_API_P30F6014A_H
#define EPUCK_API_P30F6014A_H

#endif
