/*
 * ground_i2c.c - the e-puck's provider of the e-puck2 firmware's ground
 * API (sensors/ground.h), which rt_ground.c calls on every target.
 *
 * The e-puck library has no driver of GCtronic's ground-sensor module; its
 * own Asercom (program/DemoGCtronic-complete/Asercom.c, the `M` command)
 * reads it over the library's I2C bus, at the module's address 0xC0, one
 * register at a time.  The register map is the one the e-puck2 firmware
 * reads (src/sensors/ground.c): registers 0..5 the three reflected-light
 * readings (left, centre, right), 6..11 the three ambient ones, each most
 * significant byte first.  This file reads them as Asercom does, but tries
 * each register once: the library's e_i2cp_read retries until the bus
 * answers, which hangs a robot whose module is missing; here a register
 * that does not answer leaves the reading as it was (0 at start).  The
 * module is read at most every GROUND_PERIOD_MS (the e-puck2 firmware's
 * thread reads it 25 times a second).  Only in the e-puck's project
 * (RUNTIME_DSPIC_DEVICES).
 */
#include "rt_clock.h"

#include "I2C/e_I2C_master_module.h"
#include "sensors/ground.h"

#define GROUND_ADDRESS 0xC0
#define GROUND_REGISTERS 12
#define GROUND_PERIOD_MS 40

static int values[GROUND_REGISTERS / 2];
static int started;
static long read_at;

/* One register, one attempt: 1 with *byte read, 0 when the bus failed. */
static int read_register(int reg, unsigned char *byte)
{
    char value = 0, ok = 1;

    ok &= e_i2c_start();
    ok &= e_i2c_write((char)GROUND_ADDRESS);
    ok &= e_i2c_write((char)reg);
    ok &= e_i2c_restart();
    ok &= e_i2c_write((char)(GROUND_ADDRESS + 1));      /* bit 0: read */
    ok &= e_i2c_read(&value);
    e_i2c_nack();
    e_i2c_stop();
    if (!ok) {
        e_i2c_reset();
        return 0;
    }
    *byte = (unsigned char)value;
    return 1;
}

static void refresh(void)
{
    unsigned char high, low;
    unsigned word;
    long now = rt_millis();
    int i;

    if (started && now - read_at < GROUND_PERIOD_MS)
        return;
    started = 1;
    read_at = now;
    e_i2c_init();
    e_i2c_enable();
    for (i = 0; i < GROUND_REGISTERS / 2; i++) {
        if (!read_register(2 * i, &high) || !read_register(2 * i + 1, &low))
            continue;
        word = ((unsigned)high << 8) | low;
        values[i] = word > 32767u ? 32767 : (int)word;
    }
    e_i2c_disable();
}

void ground_start(void)
{
}

void ground_stop(void)
{
}

int get_ground_prox(unsigned int sensor_number)
{
    if (sensor_number > 2)
        return 0;
    refresh();
    return values[sensor_number];
}

int get_ground_ambient_light(unsigned int sensor_number)
{
    if (sensor_number > 2)
        return 0;
    refresh();
    return values[3 + sensor_number];
}
