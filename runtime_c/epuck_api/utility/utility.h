/* e-puck library API, utility (library/utility/utility.h), declarations
 * only (see ../README.md).  Not the paper's umbrella header ../../utility.h.
 * wait(num) is the library's busy loop: on the simulated robot it takes
 * the time that loop takes on the dsPIC (docs/runtime.md, the C program
 * model); resetTime and getDiffTimeMs* count the A/D interrupt's ticks
 * (1/16384 s, up to 65535 of them: 4 s) while the scan runs.  (void)
 * where the library's header has (): compatible with its declarations, and
 * a prototype for the runtime, which -Wstrict-prototypes builds (e-puck2). */
#ifndef EPUCK_API_UTILITY_UTILITY_H
#define EPUCK_API_UTILITY_UTILITY_H

void wait(long num);
int getselector(void);
unsigned int getBatteryValueRaw(void);
unsigned int getBatteryValuePercentage(void);
void resetTime(void);
float getDiffTimeMs(void);
float getDiffTimeMsAndReset(void);

#endif
