/*
 * spin.c - the extern action `spin` of extern_spin.epk: turn on the spot
 * through a number of whole turns.
 *
 * epuckc defines, before including this file,
 *     typedef struct { int turns; int speed; } param_spin;
 * (the declared parameters in order; speed in steps/s), and the whole
 * runtime API of utility.h is available.
 */
static param_start_curve spin_curve;

void spin(void *param)
{
    const param_spin *p = (const param_spin *)param;

    spin_curve.radius = 0;
    spin_curve.degrees = 360 * p->turns;
    spin_curve.speed = p->speed;
    spin_curve.outer_steps = 0;     /* 0: the runtime converts radius and degrees */
    spin_curve.inner_speed = 0;
    start_curve(&spin_curve);
}
