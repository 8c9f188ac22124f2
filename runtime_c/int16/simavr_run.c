/*
 * simavr_run.c - `epuckc run --int16`'s runner: an AVR program built with
 * platform_int16.c, on simavr (libsimavr), its GPIOR0 bytes to stdout.
 *
 *     simavr_run PROGRAM.elf MCU MAX_CYCLES [UART.bin]
 *
 * With UART.bin, what the program sends on its USART0 (the robot's trace
 * of `--robot-trace`, int16/uart1_avr.c) is written there, byte for byte;
 * simavr times each byte as its UART would.  The AVR asleep skips to its
 * next event (no wall-clock pacing).  Exit status 0 when the program
 * stopped (after its exit or time-limit line), 1 when it crashed, 4 when
 * it ran MAX_CYCLES without stopping.
 */
#include <stdio.h>
#include <stdlib.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_io.h>
#include <simavr/avr_uart.h>

#define GPIOR0_ADDR 0x3E        /* data address of GPIOR0 (I/O 0x1E) on the ATmega1284P */

static void console(struct avr_t *avr, avr_io_addr_t addr, uint8_t value, void *param)
{
    (void)avr;
    (void)addr;
    (void)param;
    putchar(value);
}

static void uart_byte(struct avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    fputc((int)(value & 0xFFu), (FILE *)param);
}

/* simavr's own sleep would wait for the wall clock to catch up */
static void no_wait(struct avr_t *avr, avr_cycle_count_t how_long)
{
    (void)avr;
    (void)how_long;
}

int main(int argc, char **argv)
{
    static elf_firmware_t fw;
    avr_t *avr;
    int state = cpu_Running;
    unsigned long long max_cycles;

    FILE *uart = NULL;

    if ((argc != 4 && argc != 5) || elf_read_firmware(argv[1], &fw) != 0) {
        fprintf(stderr, "usage: simavr_run PROGRAM.elf MCU MAX_CYCLES [UART.bin]\n");
        return 2;
    }
    if (argc == 5 && (uart = fopen(argv[4], "wb")) == NULL) {
        fprintf(stderr, "simavr_run: cannot write %s\n", argv[4]);
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
    avr->sleep = no_wait;
    avr_register_io_write(avr, GPIOR0_ADDR, console, NULL);
    if (uart != NULL) {
        uint32_t flags = 0;     /* no echo of the bytes on simavr's console */
        avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
        avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                                uart_byte, uart);
    }
    while (state != cpu_Done && state != cpu_Crashed && avr->cycle < max_cycles)
        state = avr_run(avr);
    fflush(stdout);
    if (uart != NULL && fclose(uart) != 0) {
        fprintf(stderr, "simavr_run: cannot write %s\n", argv[4]);
        return 2;
    }
    return state == cpu_Done ? 0 : state == cpu_Crashed ? 1 : 4;
}
