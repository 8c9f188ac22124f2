/*
 * newlib_stubs.c - the system calls Debian's newlib (libnewlib-arm-none-eabi)
 * wants from a program and the e-puck2 firmware's syscalls do not define:
 * `_kill`, `_getpid` and `_exit` (abort() and exit() reach them).  Nothing
 * runs after them on the robot: a program that exits halts.
 */
#include <errno.h>

int _getpid(void);
int _kill(int pid, int sig);
void _exit(int status);

int _getpid(void)
{
    return 1;
}

int _kill(int pid, int sig)
{
    (void)pid;
    (void)sig;
    errno = EINVAL;
    return -1;
}

void _exit(int status)
{
    (void)status;
    for (;;) {
        /* halted */
    }
}
