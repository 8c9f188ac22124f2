/*
 * library_sim.h - what the files of the e-puck library's simulation share
 * (epuck_stub.c, outputs.c, sound.c, imu.c, camera.c, epuck_more.c,
 * dspic.c), and the library's globals that its sources define and that
 * programs declare themselves (`extern int e_dci_unavailable;` in
 * GCtronic's demos): declared here with the types GCtronic's sources give
 * them, so that their definitions are checked against them (and
 * tests/sim/test_library_coverage.py checks them against the sources).
 * Never included by user C.
 */
#ifndef LIBRARY_SIM_H
#define LIBRARY_SIM_H

#include "a_d/advance_ad_scan/e_ad_conv.h"

/* a_d/advance_ad_scan/e_ad_conv.c: the A/D scan's buffers and counters */
extern int e_mic_scan[3][MIC_SAMP_NB];
extern int e_acc_scan[3][ACC_SAMP_NB];
extern unsigned int e_last_mic_scan_id;
extern unsigned int e_last_acc_scan_id;
extern int e_ambient_ir[10];
extern int e_ambient_and_reflected_ir[10];
extern int selector;
extern unsigned char updateAccI2CCounter;
extern unsigned int tickAdcIsr;
/* a_d/advance_ad_scan/e_acc.c */
extern unsigned char isCalibratingFlag;
extern int centre_z;
extern int lastAccX, lastAccY, lastAccZ;
/* acc_gyro/e_lsm330.c */
extern signed int gyroOffsetX, gyroOffsetY, gyroOffsetZ;
/* motor_led/e_init_port.c */
extern unsigned char isPresentFlag;
/* codec/e_sub_dci_kickoff.s: a sample plays (-1), told to stop (1) or
 * stopped (-1: the last interrupt sets it) */
extern int e_dci_unavailable;
extern int e_stop_flag;
/* uart/e_uart*_rx_char.s: what the UART interrupts clear (unused here) */
extern void *e_uart1_int_clr_addr;
extern int e_uart1_int_clr_mask;
extern void *e_uart2_int_clr_addr;
extern int e_uart2_int_clr_mask;
extern char U1RXBuf[64], U2RXBuf[64];
extern int U1RXRcvCnt, U1RXReadCnt, U2RXRcvCnt, U2RXReadCnt;

/* program/DemoGCtronic-complete/DataEEPROM.s (Microchip's routines):
 * the data EEPROM (dspic.c) */
int ReadEE(int Page, int Offset, int *DataOut, int Size);
int EraseEE(int Page, int Offset, int Size);
int WriteEE(int *DataIn, int Page, int Offset, int Size);

/* ---- between the simulation's files --------------------------------------------- */

/* The ms that ended (stub_devices_ms): each device's share; the cycle the
 * current ms began at (main's clock is past it while main's C runs). */
unsigned long long stub_ms_began_cycles(void);
void stub_sound_ms(long now_ms, long n);
void stub_more_ms(long now_ms, long n);
void stub_imu_ms(long now_ms, long n);
void stub_camera_ms(long now_ms, long n);
/* the ms of the frame coming (stub_devices_next_ms), -1: none */
long stub_camera_next_ms(void);
/* the UARTs' lines not written yet, at the run's end (epuck_more.c) */
void stub_uart_end(void);
/* The A/D scan started (1) or stopped (0) now (epuck_stub.c tells
 * epuck_more.c, which counts its ticks: 16384 a second, at main's clock,
 * while it runs). */
void stub_ad_scan_changed(int running);
unsigned long long stub_ad_ticks(void);

#endif
