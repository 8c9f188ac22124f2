/* e-puck library API, agendas (Timer2, tick 0.1 ms), declarations only
 * (see ../../README.md).  Agenda callbacks run inside the timer interrupt. */
#ifndef EPUCK_API_E_AGENDA_H
#define EPUCK_API_E_AGENDA_H

void e_start_agendas_processing(void);
void e_end_agendas_processing(void);
int e_activate_agenda(void (*func)(void), int cycle);
int e_destroy_agenda(void (*func)(void));
int e_set_agenda_cycle(void (*func)(void), int cycle);
int e_reset_agenda(void (*func)(void));
int e_pause_agenda(void (*func)(void));
int e_restart_agenda(void (*func)(void));

#endif
