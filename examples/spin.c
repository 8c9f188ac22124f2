/*
 * spin.c - the extern action `spin` of extern_spin.epk: turn on the spot
 * through a number of whole turns.
 *
 * This file is compiled on its own and linked with the program. epuckc
 * writes extern_spin_externs.h for it: the parameter struct
 *     typedef struct { int turns; int speed; } param_spin;
 * (the declared parameters in order; speed in steps/s), the prototype
 *     void spin(void *);
 * and, through utility.h, the whole runtime API.
 */
#include "extern_spin_externs.h"

static param_start_curve spin_curve;

void spin(void *param)
{
    const param_spin *p = (const param_spin *)param;

    spin_curve.radius = 0;
    spin_curve.degrees = 360 * p->turns;
    spin_curve.speed = p->speed;
    start_curve(&spin_curve);
}
