/*
 * stub_ground.c - the host's provider of the e-puck2 firmware's ground
 * API (sensors/ground.h: GCtronic's ground-sensor module), over a virtual
 * robot: what the runtime's rt_ground.c and C programs call.  The three
 * readings are what stub_set_ground last gave them: a scenario's groundN
 * lines on the stub harness, Enki's ground sensors over the world's floor
 * at every physics step in a world.  Their ambient light (the module's
 * reading with its LEDs off) is 0: nothing models the room's light.
 */
#include "sensors/ground.h"
#include "epuck_stub.h"
#include "stub_ground.h"

static int ground[STUB_GROUND_SENSORS] = { STUB_GROUND_WHITE, STUB_GROUND_WHITE,
                                          STUB_GROUND_WHITE };

void stub_set_ground(int n, int value)
{
    if (n < 0 || n >= STUB_GROUND_SENSORS || ground[n] == value)
        return;
    stub_input_set();
    ground[n] = value;
}

void ground_start(void)
{
}

void ground_stop(void)
{
}

int get_ground_prox(unsigned int sensor_number)
{
    return sensor_number < STUB_GROUND_SENSORS ? ground[sensor_number] : 0;
}

int get_ground_ambient_light(unsigned int sensor_number)
{
    (void)sensor_number;
    return 0;
}
