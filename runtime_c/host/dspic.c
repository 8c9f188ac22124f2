/*
 * dspic.c - the simulated e-puck's dsPIC30F6014A: its special function
 * registers (../epuck_api/p30F6014A.h) with their values at power-on and
 * after a reset, the pins they put on the simulated robot (host/outputs.c
 * reads the LEDs' latches), its data EEPROM (what DataEEPROM.s, Microchip's
 * routines that e-puck programs link, reads and writes: ReadEE, WriteEE,
 * EraseEE), and the instructions such programs write inline (`reset`,
 * `pwrsav`, `nop`, `clrwdt`, `disi`), which epuckc's build turns into a call
 * of epuck_dspic_trap (epuckc/build/dspic_asm.py) that saves every register
 * of the host around epuck_dspic_execute.
 */
#include <stdlib.h>
#include <string.h>

#include "p30F6014A.h"
#include "epuck_stub.h"
#include "library_sim.h"

/* ---- registers ----------------------------------------------------------------
 * At power-on: the ports are inputs (TRIS set on every pin the chip has),
 * their latches clear; RCON says power-on and brown-out reset. */
#define TRISA_PINS 0xF6C0u
#define TRISB_PINS 0xFFFFu
#define TRISC_PINS 0xE01Eu
#define TRISD_PINS 0xFFFFu
#define TRISF_PINS 0x01FFu
#define TRISG_PINS 0x03CFu
#define RCON_POR 0x0001u
#define RCON_BOR 0x0002u
#define RCON_SWR 0x0040u

volatile e_dspic_registers e_dspic_sfr = {
    .rcon = { RCON_POR | RCON_BOR },
    .trisa = { TRISA_PINS }, .trisb = { TRISB_PINS }, .trisc = { TRISC_PINS },
    .trisd = { TRISD_PINS }, .trisf = { TRISF_PINS }, .trisg = { TRISG_PINS },
    .portf = { 0x0040u },       /* RF6: the remote's receiver idles high */
};

/* A reset: every register to its value at reset, RCON keeping its flags
 * and saying a software reset (SWR). */
void stub_dspic_reset_registers(void)
{
    unsigned int rcon = e_dspic_sfr.rcon.w;
    unsigned int selector = e_dspic_sfr.portg.w & 0x03C0u;
    memset((void *)&e_dspic_sfr, 0, sizeof e_dspic_sfr);
    e_dspic_sfr.rcon.w = rcon | RCON_SWR;
    e_dspic_sfr.trisa.w = TRISA_PINS;
    e_dspic_sfr.trisb.w = TRISB_PINS;
    e_dspic_sfr.trisc.w = TRISC_PINS;
    e_dspic_sfr.trisd.w = TRISD_PINS;
    e_dspic_sfr.trisf.w = TRISF_PINS;
    e_dspic_sfr.trisg.w = TRISG_PINS;
    e_dspic_sfr.portf.w = 0x0040u;
    e_dspic_sfr.portg.w = selector;     /* the selector is where it was */
}

/* ---- the data EEPROM ------------------------------------------------------------
 * 4 KB at 0x7FF000..0x7FFFFF (page 0x7F, offsets 0xF000..0xFFFE), erased
 * (0xFFFF); its last word, which GCtronic writes with the robot's camera
 * and its mounting, 0xFFFF too: a PO3030K without rotation (camera.c).
 * Kept through a reset; a write or an erase takes the chip's 2 ms.
 * Reading another page reads the program's flash: erased words, 0xFFFF.
 * Kept in memory allocated at the first write.  The routines return what
 * Microchip's leave in W0: ReadEE the page it was given (GCtronic's demos
 * take it for the hardware version: 0x7F, "no rotation"), EraseEE and
 * WriteEE 0; -1 for a size they do not take. */
#define EE_PAGE 0x7F
#define EE_FIRST 0xF000u
#define EE_WORDS 2048
#define EE_WRITE_MS 2

static unsigned short *eeprom;

static int ee_index(int page, int offset)
{
    unsigned int o = (unsigned int)offset & 0xFFFFu;
    if ((page & 0xFF) != EE_PAGE || o < EE_FIRST || (o & 1u) != 0u)
        return -1;
    return (int)((o - EE_FIRST) / 2u);
}

static unsigned int ee_read(int index)
{
    if (index < 0)
        return 0xFFFFu;
    return eeprom != NULL ? eeprom[index] : 0xFFFFu;
}

static int ee_storage(void)
{
    int i;
    if (eeprom != NULL)
        return 1;
    eeprom = malloc(EE_WORDS * sizeof *eeprom);
    if (eeprom == NULL)
        return 0;
    for (i = 0; i < EE_WORDS; i++)
        eeprom[i] = 0xFFFFu;
    return 1;
}

static void ee_busy(void)
{
    stub_wait_cycles((long)EE_WRITE_MS * STUB_CYCLES_PER_MS);
}

int ReadEE(int Page, int Offset, int *DataOut, int Size)
{
    int i, first = ee_index(Page, Offset);
    if (Size != 1 && Size != 16)
        return -1;
    for (i = 0; i < Size; i++)
        DataOut[i] = (int)(short)ee_read(first < 0 || first + i >= EE_WORDS ? -1 : first + i);
    return Page;
}

int EraseEE(int Page, int Offset, int Size)
{
    int i, first = ee_index(Page, Offset), count;
    unsigned int size = (unsigned int)Size & 0xFFFFu;
    if (size != 1u && size != 16u && size != 0xFFFFu)
        return -1;
    ee_busy();
    if (size == 0xFFFFu) {
        first = 0;
        count = EE_WORDS;
    } else {
        if (size == 16u && first >= 0)
            first -= first % 16;            /* a row is 16 words */
        count = (int)size;
    }
    if (first < 0 || !ee_storage())
        return 0;
    for (i = first; i < first + count && i < EE_WORDS; i++)
        eeprom[i] = 0xFFFFu;
    return 0;
}

int WriteEE(int *DataIn, int Page, int Offset, int Size)
{
    int i, first = ee_index(Page, Offset);
    if (Size != 1 && Size != 16)
        return -1;
    ee_busy();
    if (first < 0 || !ee_storage())
        return 0;
    /* a write programs the word: bits go from 1 to 0 only (erase first) */
    for (i = 0; i < Size && first + i < EE_WORDS; i++)
        eeprom[first + i] = (unsigned short)(eeprom[first + i] & ((unsigned int)DataIn[i] & 0xFFFFu));
    return 0;
}

/* ---- the instructions of inline assembly ---------------------------------------- */

void (*stub_chip_hook)(int instruction);

void stub_reset_chip(void)
{
    if (stub_chip_hook != NULL)
        stub_chip_hook(STUB_INSN_RESET);
}

void stub_sleep_chip(void)
{
    if (stub_chip_hook != NULL)
        stub_chip_hook(STUB_INSN_SLEEP);
}

void stub_idle_chip(void)
{
    if (stub_chip_hook != NULL)
        stub_chip_hook(STUB_INSN_IDLE);
}

void epuck_dspic_execute(int instruction)
{
    switch (instruction) {
    case STUB_INSN_RESET:
        stub_reset_chip();          /* never returns: main starts again */
        break;
    case STUB_INSN_SLEEP:
        stub_sleep_chip();          /* main sleeps for good */
        break;
    case STUB_INSN_IDLE:
        stub_idle_chip();           /* until the next interrupt */
        break;
    default:
        break;
    }
}

#if defined(__x86_64__) && defined(__ELF__)
/* epuck_dspic_trap: called by the user's code where its inline assembly
 * was (the instruction's code pushed, 128 bytes below the stack pointer
 * left to the red zone): saves the flags, every register the SysV ABI lets
 * a call clobber and xmm0..xmm15, aligns the stack, calls
 * epuck_dspic_execute(code), restores them; the caller drops the code. */
__asm__(
    "    .text\n"
    "    .globl epuck_dspic_trap\n"
    "    .type epuck_dspic_trap, @function\n"
    "epuck_dspic_trap:\n"
    "    pushfq\n"
    "    pushq %rax\n    pushq %rcx\n    pushq %rdx\n    pushq %rsi\n    pushq %rdi\n"
    "    pushq %r8\n    pushq %r9\n    pushq %r10\n    pushq %r11\n"
    "    pushq %rbp\n"
    "    movq %rsp, %rbp\n"
    "    andq $-16, %rsp\n"
    "    subq $256, %rsp\n"
    "    movdqu %xmm0, 0(%rsp)\n    movdqu %xmm1, 16(%rsp)\n    movdqu %xmm2, 32(%rsp)\n"
    "    movdqu %xmm3, 48(%rsp)\n    movdqu %xmm4, 64(%rsp)\n    movdqu %xmm5, 80(%rsp)\n"
    "    movdqu %xmm6, 96(%rsp)\n    movdqu %xmm7, 112(%rsp)\n    movdqu %xmm8, 128(%rsp)\n"
    "    movdqu %xmm9, 144(%rsp)\n    movdqu %xmm10, 160(%rsp)\n    movdqu %xmm11, 176(%rsp)\n"
    "    movdqu %xmm12, 192(%rsp)\n    movdqu %xmm13, 208(%rsp)\n    movdqu %xmm14, 224(%rsp)\n"
    "    movdqu %xmm15, 240(%rsp)\n"
    "    movl 96(%rbp), %edi\n"      /* the code: above the 11 saved words and the return */
    "    call epuck_dspic_execute@PLT\n"
    "    movdqu 0(%rsp), %xmm0\n    movdqu 16(%rsp), %xmm1\n    movdqu 32(%rsp), %xmm2\n"
    "    movdqu 48(%rsp), %xmm3\n    movdqu 64(%rsp), %xmm4\n    movdqu 80(%rsp), %xmm5\n"
    "    movdqu 96(%rsp), %xmm6\n    movdqu 112(%rsp), %xmm7\n    movdqu 128(%rsp), %xmm8\n"
    "    movdqu 144(%rsp), %xmm9\n    movdqu 160(%rsp), %xmm10\n    movdqu 176(%rsp), %xmm11\n"
    "    movdqu 192(%rsp), %xmm12\n    movdqu 208(%rsp), %xmm13\n    movdqu 224(%rsp), %xmm14\n"
    "    movdqu 240(%rsp), %xmm15\n"
    "    movq %rbp, %rsp\n"
    "    popq %rbp\n"
    "    popq %r11\n    popq %r10\n    popq %r9\n    popq %r8\n"
    "    popq %rdi\n    popq %rsi\n    popq %rdx\n    popq %rcx\n    popq %rax\n"
    "    popfq\n"
    "    ret\n"
    "    .size epuck_dspic_trap, .-epuck_dspic_trap\n");
#endif
