/*
 * host_harness.h - what the stub harness's files share (platform_host.c,
 * scenario.c): nothing else sees it.
 */
#ifndef HOST_HARNESS_H
#define HOST_HARNESS_H

#define MAX_SCENARIO_MS 1000000000L     /* 11.6 days of virtual time */

/* platform_host.c: a bad setting or scenario ends the run (exit status 2),
 * with the message; an input of the scenario other than the proximity
 * sensors is traced ("input" records). */
#if defined(__GNUC__)
__attribute__((noreturn))
#endif
void host_fail(const char *fmt, ...);
void host_record_input(const char *name, int index, int value);

/* scenario.c */
void host_load_scenario(const char *path);
void host_scenario_apply(long t);      /* the lines whose time has come */
long host_scenario_next_ms(void);      /* the next line's time; -1: none */

#endif
