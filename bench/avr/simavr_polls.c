/*
 * simavr_polls.c - runs an AVR program built with platform_sim.c under
 * simavr (libsimavr) and prints the cycles of each poll: from the port B
 * write of 2 (a poll starts) to the next write of 1 (it ended).
 *
 *     simavr_polls PROGRAM.elf MCU SKIP COUNT
 *
 * skips the first SKIP polls (start-up, the first poll's immediate
 * events), measures the next COUNT and prints one line:
 *     polls COUNT min C median C max C
 * Exit status 1 when the program crashes, stops or runs out of cycles first.
 */
#include <stdio.h>
#include <stdlib.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/avr_ioport.h>

static avr_t *avr;
static avr_cycle_count_t poll_start;
static long seen, skip, count;
static avr_cycle_count_t *cycles;
static int started;

static void port_b(struct avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    (void)param;
    if (value == 2) {
        poll_start = avr->cycle;
        started = 1;
    } else if (value == 1 && started) {
        if (seen >= skip && seen < skip + count)
            cycles[seen - skip] = avr->cycle - poll_start;
        seen++;
        started = 0;
    }
}

static int compare(const void *a, const void *b)
{
    avr_cycle_count_t x = *(const avr_cycle_count_t *)a, y = *(const avr_cycle_count_t *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    static elf_firmware_t fw;
    int state = cpu_Running;

    if (argc != 5) {
        fprintf(stderr, "usage: simavr_polls PROGRAM.elf MCU SKIP COUNT\n");
        return 2;
    }
    skip = atol(argv[3]);
    count = atol(argv[4]);
    if (count <= 0 || skip < 0 || elf_read_firmware(argv[1], &fw) != 0) {
        fprintf(stderr, "simavr_polls: bad arguments or cannot read %s\n", argv[1]);
        return 2;
    }
    avr = avr_make_mcu_by_name(argv[2]);
    if (avr == NULL) {
        fprintf(stderr, "simavr_polls: simavr does not know %s\n", argv[2]);
        return 2;
    }
    avr_init(avr);
    avr->frequency = 16000000;
    avr->log = 0;
    avr_load_firmware(avr, &fw);
    cycles = calloc((size_t)count, sizeof *cycles);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), IOPORT_IRQ_PIN_ALL),
                            port_b, NULL);
    while (seen < skip + count && state != cpu_Done && state != cpu_Crashed
           && avr->cycle < 4000000000ULL)
        state = avr_run(avr);
    if (seen < skip + count) {
        fprintf(stderr, "simavr_polls: %ld polls seen, the program %s\n", seen,
                state == cpu_Crashed ? "crashed" : state == cpu_Done ? "stopped" : "ran out of cycles");
        return 1;
    }
    qsort(cycles, (size_t)count, sizeof *cycles, compare);
    printf("polls %ld min %llu median %llu max %llu\n", count,
           (unsigned long long)cycles[0], (unsigned long long)cycles[count / 2],
           (unsigned long long)cycles[count - 1]);
    return 0;
}
