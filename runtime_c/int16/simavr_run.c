/*
 * simavr_run.c - `epuckc run --int16`'s runner: an AVR program built with
 * platform_int16.c, on simavr (libsimavr), its GPIOR0 bytes to stdout.
 *
 *     simavr_run PROGRAM.elf MCU MAX_CYCLES
 *
 * Exit status 0 when the program stopped (after its exit or time-limit
 * line), 1 when it crashed, 4 when it ran MAX_CYCLES without stopping.
 */
#include <stdio.h>
#include <stdlib.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_io.h>

#define GPIOR0_ADDR 0x3E        /* data address of GPIOR0 (I/O 0x1E) on the ATmega1284P */

static void console(struct avr_t *avr, avr_io_addr_t addr, uint8_t value, void *param)
{
    (void)avr;
    (void)addr;
    (void)param;
    putchar(value);
}

int main(int argc, char **argv)
{
    static elf_firmware_t fw;
    avr_t *avr;
    int state = cpu_Running;
    unsigned long long max_cycles;

    if (argc != 4 || elf_read_firmware(argv[1], &fw) != 0) {
        fprintf(stderr, "usage: simavr_run PROGRAM.elf MCU MAX_CYCLES\n");
        return 2;
    }
    max_cycles = strtoull(argv[3], NULL, 10);
    avr = avr_make_mcu_by_name(argv[2]);
    if (avr == NULL) {
        fprintf(stderr, "simavr_run: simavr does not know %s\n", argv[2]);
        return 2;
    }
    avr_init(avr);
    avr->frequency = 16000000;
    avr->log = 0;
    avr_load_firmware(avr, &fw);
    avr_register_io_write(avr, GPIOR0_ADDR, console, NULL);
    while (state != cpu_Done && state != cpu_Crashed && avr->cycle < max_cycles)
        state = avr_run(avr);
    fflush(stdout);
    return state == cpu_Done ? 0 : state == cpu_Crashed ? 1 : 4;
}
