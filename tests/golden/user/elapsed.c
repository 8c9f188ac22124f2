/* elapsed.c - an extern event: occurs once `ms` milliseconds of polls have
 * passed since it was registered (one poll per millisecond on the harness). */
#include "extern_externs.h"

void elapsed(void *param, void *status)
{
    const param_elapsed *p = (const param_elapsed *)param;
    event_status *s = (event_status *)status;
    s->memory++;
    if (s->memory >= p->ms)
        s->occurred = 1;
}
