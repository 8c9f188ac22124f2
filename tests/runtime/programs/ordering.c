/* Events are polled in index order within a poll; one-shots disarm; an
 * event whose action was cancelled fires but runs nothing; a cancelled
 * event never fires; a repeating event fires every poll. */
#include <stdio.h>
#include "epuckrt.h"

static int repeats;
static void count(void *p) { (void)p; repeats++; }
static void noop(void *p) { (void)p; }

int main(void)
{
    static param_event_timer five = { 5 };
    int a_noop1 = register_action(noop, NULL);
    int a_noop2 = register_action(noop, NULL);
    int a_cancelled = register_action(noop, NULL);
    int a_count = register_action(count, NULL);
    int a_exit = register_action(exit_main, NULL);
    int e_rep, e_gone;

    name_action(a_noop1, "first");
    name_action(a_noop2, "second");
    register_event(immediate, NULL, a_noop2);       /* event 0 */
    register_event(immediate, NULL, a_noop1);       /* event 1 */
    register_event(immediate, NULL, a_cancelled);   /* event 2 */
    cancel_action(a_cancelled);
    e_gone = register_event(immediate, NULL, a_noop1);  /* event 3 */
    cancel_event(e_gone);
    e_rep = register_event(immediate, NULL, a_count);   /* event 4 */
    set_event_repeat(e_rep, 1);
    name_event(e_rep, "every \"poll\"");
    register_event(timer, &five, a_exit);           /* event 5 */
    set_timer(NULL);                                /* before mainloop: from 0 */
    mainloop();
    printf("repeats %d\n", repeats);
    return 0;
}
