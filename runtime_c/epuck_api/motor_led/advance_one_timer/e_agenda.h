/* e-puck library API, agendas (Timer2, tick 0.1 ms; library/motor_led/
 * advance_one_timer/e_agenda.h), declarations only (see ../../README.md).
 * Agenda callbacks run inside the timer interrupt: on the simulated robot,
 * between two blocks of main. */
#ifndef EPUCK_API_E_AGENDA_H
#define EPUCK_API_E_AGENDA_H

#define AG_ALREADY_CREATED	1
#define AG_NOT_FOUND		2

typedef struct AgendaType Agenda;

struct AgendaType
{
  unsigned int  cycle;
  int  counter;
  char activate;
  void (*function) (void);
  Agenda *next;
};

void e_start_agendas_processing(void);
void e_end_agendas_processing(void);
int e_activate_agenda(void (*func)(void), int cycle);
int e_destroy_agenda(void (*func)(void));
int e_set_agenda_cycle(void (*func)(void), int cycle);
int e_reset_agenda(void (*func)(void));
int e_pause_agenda(void (*func)(void));
int e_restart_agenda(void (*func)(void));

#endif
