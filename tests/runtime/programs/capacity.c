/* Built with -DMAX_ACTIONS=3 -DMAX_EVENTS=4: full arrays return -1. */
#include <stdio.h>
#include "epuckrt.h"

static void user_action(void *p) { (void)p; }

int main(void)
{
    int i, a = register_action(exit_main, NULL);
    int b = register_action(user_action, NULL);
    printf("actions %d %d", a, b);
    cancel_action(b);
    for (i = 0; i < 2; i++)
        printf(" %d", register_action(user_action, NULL));
    printf("\nevents");
    /* events 0..2 never fire: their action was cancelled or is a no-op */
    for (i = 0; i < 3; i++)
        printf(" %d", register_event(event_timer, NULL, 2));
    printf(" %d", register_event(event_immediate, NULL, a));
    printf(" %d\n", register_event(event_immediate, NULL, a));
    fflush(stdout);
    mainloop();
    return 0;
}
