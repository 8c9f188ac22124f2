/* register/cancel: return values, ids, bad ids (printed before mainloop). */
#include <stdio.h>
#include "epuckrt.h"

static void user_action(void *p) { (void)p; }

int main(void)
{
    int a0, a1, a2, e0, e1;

    a0 = register_action(exit_main, NULL);
    a1 = register_action(user_action, NULL);
    printf("null_action %d\n", register_action(NULL, NULL));
    a2 = register_action(user_action, NULL);
    printf("actions %d %d %d\n", a0, a1, a2);
    cancel_action(a1);
    cancel_action(a1);          /* again: ignored */
    cancel_action(-5);          /* unknown ids: ignored */
    cancel_action(1000);
    printf("event_null_func %d\n", register_event(NULL, NULL, a0));
    printf("event_bad_action %d %d %d\n", register_event(immediate, NULL, -1),
           register_event(immediate, NULL, 99), register_event(immediate, NULL, 3));
    printf("event_cancelled_action %d\n", register_event(immediate, NULL, a1));
    e0 = register_event(immediate, NULL, a2);
    e1 = register_event(event_immediate, NULL, a0);
    printf("events %d %d\n", e0, e1);
    /* a cancelled slot is not reused */
    printf("after_cancel %d\n", register_action(user_action, NULL));
    cancel_event(-1);
    cancel_event(77);
    set_event_repeat(-3, 1);
    set_event_repeat(50, 1);
    name_action(-1, "x");
    name_action(40, "x");
    name_event(-1, "x");
    name_event(40, "x");
    fflush(stdout);
    mainloop();
    printf("returned\n");
    return 0;
}
