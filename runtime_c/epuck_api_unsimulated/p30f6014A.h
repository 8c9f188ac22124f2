/* The dsPIC's device header as contrib/SWIS_com_module/ComModule.h names it
 * (a lower-case f, which XC16's case-blind file systems find): ours. */
#include "p30F6014A.h"
