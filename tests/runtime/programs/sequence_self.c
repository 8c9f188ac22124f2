/* A sequence whose last step runs the sequence itself: it starts again at
 * the next poll (no recursion), so it loops once per millisecond until its
 * first step has run 20 times and exits.  It is first run before mainloop,
 * where EPUCK_QUIET must already silence the readable trace. */
#include "epuckrt.h"

static int ticks;

static void tick(void *unused)
{
    (void)unused;
    if (++ticks == 20)
        exit_main(NULL);
}

static param_sequence self;
static const action steps[] = { { tick, NULL }, { run_sequence, &self } };
static param_sequence self = { steps, 2 };

int main(void)
{
    run_sequence(&self);        /* before mainloop: its first steps run at once */
    mainloop();
    return 0;
}
