/* e-puck library API: motor_led/advance_one_timer/fast_agenda/e_agenda_fast.h,
 * the fast agenda, a variant of the agendas whose functions differ from the
 * ones the simulated e-puck has (e_activate_agenda returns nothing there,
 * and takes an unsigned cycle): stop at the build, never at a link error. */
#ifndef EPUCK_API_FAST_AGENDA_E_AGENDA_FAST_H
#define EPUCK_API_FAST_AGENDA_E_AGENDA_FAST_H
#error "motor_led/advance_one_timer/fast_agenda/e_agenda_fast.h: the fast agenda is not simulated by epuckc; include <motor_led/advance_one_timer/e_agenda.h> (the agendas of Timer2, whose functions it has)"
#endif
