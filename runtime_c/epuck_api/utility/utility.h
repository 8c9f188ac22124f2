/* e-puck library API, utility, declarations only (see ../README.md).
 * Not the paper's umbrella header ../../utility.h: this one is the
 * library's library/utility/utility.h.  The host stub defines only
 * getselector (wait would clash with the C library's). */
#ifndef EPUCK_API_UTILITY_UTILITY_H
#define EPUCK_API_UTILITY_UTILITY_H

void wait(long num);
int getselector(void);

#endif
