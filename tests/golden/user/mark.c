/* mark.c - extern actions of extern.epk: drive `length` at `pace` and
 * record the arguments so that a test can see they arrived converted. */
#include <stdio.h>

#include "extern_externs.h"

static param_straight_steps mark_motion;

void mark(void *param)
{
    const param_mark *p = (const param_mark *)param;
    printf("mark count=%d length=%d pace=%d turn=%d wait=%ld\n",
           p->count, p->length, p->pace, p->turn, p->wait);
    mark_motion.speed = p->pace;
    mark_motion.steps = p->length;
    straight_steps(&mark_motion);
}

void noop(void *param)
{
    (void)param;
}
