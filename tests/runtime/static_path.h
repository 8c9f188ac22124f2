/*
 * static_path.h - forced into a runtime test program (-include) to run it
 * on the static registration path: its registration calls go to
 * static_path.c, which collects them into tables and registers those with
 * register_program.  See static_path.c.
 */
#define register_action sp_register_action
#define register_event sp_register_event
#define cancel_action sp_cancel_action
#define cancel_event sp_cancel_event
#define set_event_repeat sp_set_event_repeat
#define name_action sp_name_action
#define name_event sp_name_event
#define mainloop sp_mainloop
#define register_program sp_register_program
#define set_event_priority sp_set_event_priority
#define set_event_mode sp_set_event_mode
#define enter_mode sp_enter_mode
#define disarm_event sp_disarm_event
#define name_mode sp_name_mode
