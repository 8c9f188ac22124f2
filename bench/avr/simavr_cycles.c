/*
 * simavr_cycles.c - runs an AVR program under simavr (libsimavr), prints
 * what it writes to GPIOR0 (its output, byte by byte) and, at each write of
 * 2 to GPIOR1, the cycles since the last write of 1 (" @CYCLES").  A
 * program measures a call with GPIOR1 = 1; call; GPIOR1 = 2 (the two
 * writes and the call's arguments and result are counted).
 *
 *     simavr_cycles PROGRAM.elf MCU
 *
 * Exit status 0 when the program stopped (cli; sleep), 1 when it crashed or
 * ran out of cycles.  tests/runtime/test_math.py uses it.
 */
#include <stdio.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_io.h>

#define GPIOR0_ADDR 0x3E        /* data addresses on the ATmega1284P (I/O 0x1E, 0x2A) */
#define GPIOR1_ADDR 0x4A

static avr_cycle_count_t start;

static void console(struct avr_t *avr, avr_io_addr_t addr, uint8_t value, void *param)
{
    (void)avr;
    (void)addr;
    (void)param;
    putchar(value);
}

static void mark(struct avr_t *avr, avr_io_addr_t addr, uint8_t value, void *param)
{
    (void)addr;
    (void)param;
    if (value == 1)
        start = avr->cycle;
    else if (value == 2)
        printf(" @%llu", (unsigned long long)(avr->cycle - start));
}

int main(int argc, char **argv)
{
    static elf_firmware_t fw;
    avr_t *avr;
    int state = cpu_Running;

    if (argc != 3 || elf_read_firmware(argv[1], &fw) != 0) {
        fprintf(stderr, "usage: simavr_cycles PROGRAM.elf MCU\n");
        return 2;
    }
    avr = avr_make_mcu_by_name(argv[2]);
    if (avr == NULL) {
        fprintf(stderr, "simavr_cycles: simavr does not know %s\n", argv[2]);
        return 2;
    }
    avr_init(avr);
    avr->frequency = 16000000;
    avr->log = 0;
    avr_load_firmware(avr, &fw);
    avr_register_io_write(avr, GPIOR0_ADDR, console, NULL);
    avr_register_io_write(avr, GPIOR1_ADDR, mark, NULL);
    while (state != cpu_Done && state != cpu_Crashed && avr->cycle < 20000000000ULL)
        state = avr_run(avr);
    fflush(stdout);
    return state == cpu_Done ? 0 : 1;
}
