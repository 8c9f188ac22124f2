#include "utility.h"
int main(void){
    int a1, a2, e1, e2;
    param_start_straight sample = {250, 100};
    a1 = register_action(start_straight, &sample);
    a2 = register_action(exit_main, NULL);
    e1 = register_event(immediate, NULL, a1);
    e2 = register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}
