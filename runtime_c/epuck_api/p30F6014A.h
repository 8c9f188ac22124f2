/* The device header of the e-puck's dsPIC30F6014A, as the e-puck library's
 * programs include it ("p30F6014A.h"; XC16 ships Microchip's).  Written for
 * epuckc from the chip's datasheet (register and bit names and positions),
 * none of Microchip's text: the special function registers that e-puck
 * programs and the library's own headers use, over the simulated robot
 * (host/dspic.c).  They behave as on the robot where the simulation can
 * say (docs/runtime.md, "The dsPIC's registers"):
 *   - the ports' latches LATA/LATC drive the LEDs (LED0 is _LATA6, as in
 *     motor_led/e_epuck_ports.h), read every simulated ms and at every
 *     record of the trace; a write to a PORTx output bit is a write to its
 *     latch, as on the chip; PORTx reads the latch of an output pin and the
 *     simulated input of an input pin (the selector on RG6..RG9, the
 *     remote's receiver on RF6, idle high; the battery is not low, RF1 0);
 *   - RCON says why the chip started: POR and BOR at power-on, SWR after a
 *     `reset` instruction (which restarts main: host/dspic.c);
 *   - the others (I2C, timers, interrupts, UARTs, A/D) hold what a program
 *     writes and nothing reads them: the library's simulation drives the
 *     devices through its functions.
 * Each register is a 16-bit word and its bits (`RCON`, `RCONbits.POR`,
 * `_POR`), in one union, so that both views agree.
 */
#ifndef EPUCK_API_P30F6014A_H
#define EPUCK_API_P30F6014A_H

/* ---- bit layouts (low bit first, 16 bits each) ---------------------------- */

typedef struct { unsigned POR : 1, BOR : 1, IDLE : 1, SLEEP : 1, WDTO : 1, SWDTEN : 1,
                 SWR : 1, EXTR : 1, LVDL : 4, LVDEN : 1, BGST : 1, IOPUWR : 1,
                 TRAPR : 1; } RCONBITS;

/* the pins each port has on the 80-pin 30F6014A */
#define E_DSPIC_PORTA(p) unsigned : 6; unsigned p##6 : 1, p##7 : 1; unsigned : 1; \
    unsigned p##9 : 1, p##10 : 1; unsigned : 1; unsigned p##12 : 1, p##13 : 1, p##14 : 1, \
    p##15 : 1;
#define E_DSPIC_PORTB(p) unsigned p##0 : 1, p##1 : 1, p##2 : 1, p##3 : 1, p##4 : 1, p##5 : 1, \
    p##6 : 1, p##7 : 1, p##8 : 1, p##9 : 1, p##10 : 1, p##11 : 1, p##12 : 1, p##13 : 1, \
    p##14 : 1, p##15 : 1;
#define E_DSPIC_PORTC(p) unsigned : 1; unsigned p##1 : 1, p##2 : 1, p##3 : 1, p##4 : 1; \
    unsigned : 8; unsigned p##13 : 1, p##14 : 1, p##15 : 1;
#define E_DSPIC_PORTF(p) unsigned p##0 : 1, p##1 : 1, p##2 : 1, p##3 : 1, p##4 : 1, p##5 : 1, \
    p##6 : 1, p##7 : 1, p##8 : 1; unsigned : 7;
#define E_DSPIC_PORTG(p) unsigned p##0 : 1, p##1 : 1, p##2 : 1, p##3 : 1; unsigned : 2; \
    unsigned p##6 : 1, p##7 : 1, p##8 : 1, p##9 : 1; unsigned : 6;

typedef struct { E_DSPIC_PORTA(RA) } PORTABITS;
typedef struct { E_DSPIC_PORTA(LATA) } LATABITS;
typedef struct { E_DSPIC_PORTA(TRISA) } TRISABITS;
typedef struct { E_DSPIC_PORTB(RB) } PORTBBITS;
typedef struct { E_DSPIC_PORTB(LATB) } LATBBITS;
typedef struct { E_DSPIC_PORTB(TRISB) } TRISBBITS;
typedef struct { E_DSPIC_PORTC(RC) } PORTCBITS;
typedef struct { E_DSPIC_PORTC(LATC) } LATCBITS;
typedef struct { E_DSPIC_PORTC(TRISC) } TRISCBITS;
typedef struct { E_DSPIC_PORTB(RD) } PORTDBITS;
typedef struct { E_DSPIC_PORTB(LATD) } LATDBITS;
typedef struct { E_DSPIC_PORTB(TRISD) } TRISDBITS;
typedef struct { E_DSPIC_PORTF(RF) } PORTFBITS;
typedef struct { E_DSPIC_PORTF(LATF) } LATFBITS;
typedef struct { E_DSPIC_PORTF(TRISF) } TRISFBITS;
typedef struct { E_DSPIC_PORTG(RG) } PORTGBITS;
typedef struct { E_DSPIC_PORTG(LATG) } LATGBITS;
typedef struct { E_DSPIC_PORTG(TRISG) } TRISGBITS;

typedef struct { unsigned SEN : 1, RSEN : 1, PEN : 1, RCEN : 1, ACKEN : 1, ACKDT : 1,
                 STREN : 1, GCEN : 1, SMEN : 1, DISSLW : 1, A10M : 1, IPMIEN : 1,
                 SCLREL : 1, I2CSIDL : 1; unsigned : 1; unsigned I2CEN : 1; } I2CCONBITS;
typedef struct { unsigned TBF : 1, RBF : 1, R_W : 1, S : 1, P : 1, D_A : 1, I2COV : 1,
                 IWCOL : 1, ADD10 : 1, GCSTAT : 1, BCL : 1; unsigned : 3;
                 unsigned TRSTAT : 1, ACKSTAT : 1; } I2CSTATBITS;

typedef struct { unsigned INT0IE : 1, IC1IE : 1, OC1IE : 1, T1IE : 1, IC2IE : 1, OC2IE : 1,
                 T2IE : 1, T3IE : 1, SPI1IE : 1, U1RXIE : 1, U1TXIE : 1, ADIE : 1,
                 NVMIE : 1, SI2CIE : 1, MI2CIE : 1, CNIE : 1; } IEC0BITS;
typedef struct { unsigned INT1IE : 1, IC7IE : 1, IC8IE : 1, OC3IE : 1, OC4IE : 1, T4IE : 1,
                 T5IE : 1, INT2IE : 1, U2RXIE : 1, U2TXIE : 1, SPI2IE : 1, C1IE : 1,
                 IC3IE : 1, IC4IE : 1, IC5IE : 1, IC6IE : 1; } IEC1BITS;
typedef struct { unsigned OC5IE : 1, OC6IE : 1, OC7IE : 1, OC8IE : 1, INT3IE : 1, INT4IE : 1,
                 C2IE : 1; unsigned : 2; unsigned DCIIE : 1, LVDIE : 1; unsigned : 5; } IEC2BITS;
typedef struct { unsigned INT0IF : 1, IC1IF : 1, OC1IF : 1, T1IF : 1, IC2IF : 1, OC2IF : 1,
                 T2IF : 1, T3IF : 1, SPI1IF : 1, U1RXIF : 1, U1TXIF : 1, ADIF : 1,
                 NVMIF : 1, SI2CIF : 1, MI2CIF : 1, CNIF : 1; } IFS0BITS;
typedef struct { unsigned INT1IF : 1, IC7IF : 1, IC8IF : 1, OC3IF : 1, OC4IF : 1, T4IF : 1,
                 T5IF : 1, INT2IF : 1, U2RXIF : 1, U2TXIF : 1, SPI2IF : 1, C1IF : 1,
                 IC3IF : 1, IC4IF : 1, IC5IF : 1, IC6IF : 1; } IFS1BITS;
typedef struct { unsigned OC5IF : 1, OC6IF : 1, OC7IF : 1, OC8IF : 1, INT3IF : 1, INT4IF : 1,
                 C2IF : 1; unsigned : 2; unsigned DCIIF : 1, LVDIF : 1; unsigned : 5; } IFS2BITS;
typedef struct { unsigned : 1; unsigned OSCFAIL : 1, STKERR : 1, ADDRERR : 1, MATHERR : 1;
                 unsigned : 3; unsigned COVTE : 1, OVBTE : 1, OVATE : 1; unsigned : 4;
                 unsigned NSTDIS : 1; } INTCON1BITS;
typedef struct { unsigned INT0EP : 1, INT1EP : 1, INT2EP : 1, INT3EP : 1, INT4EP : 1;
                 unsigned : 10; unsigned ALTIVT : 1; } INTCON2BITS;
typedef struct { unsigned : 1; unsigned TCS : 1, TSYNC : 1, T32 : 1, TCKPS : 2, TGATE : 1;
                 unsigned : 6; unsigned TSIDL : 1; unsigned : 1; unsigned TON : 1; } TCONBITS;

/* ---- the register file ------------------------------------------------------- */

#define E_DSPIC_REG(name, bits) union { unsigned int w; bits b; } name
#define E_DSPIC_WORD(name) union { unsigned int w; } name

typedef struct {
    E_DSPIC_REG(rcon, RCONBITS);
    E_DSPIC_REG(porta, PORTABITS); E_DSPIC_REG(lata, LATABITS); E_DSPIC_REG(trisa, TRISABITS);
    E_DSPIC_REG(portb, PORTBBITS); E_DSPIC_REG(latb, LATBBITS); E_DSPIC_REG(trisb, TRISBBITS);
    E_DSPIC_REG(portc, PORTCBITS); E_DSPIC_REG(latc, LATCBITS); E_DSPIC_REG(trisc, TRISCBITS);
    E_DSPIC_REG(portd, PORTDBITS); E_DSPIC_REG(latd, LATDBITS); E_DSPIC_REG(trisd, TRISDBITS);
    E_DSPIC_REG(portf, PORTFBITS); E_DSPIC_REG(latf, LATFBITS); E_DSPIC_REG(trisf, TRISFBITS);
    E_DSPIC_REG(portg, PORTGBITS); E_DSPIC_REG(latg, LATGBITS); E_DSPIC_REG(trisg, TRISGBITS);
    E_DSPIC_REG(i2ccon, I2CCONBITS); E_DSPIC_REG(i2cstat, I2CSTATBITS);
    E_DSPIC_WORD(i2crcv); E_DSPIC_WORD(i2ctrn); E_DSPIC_WORD(i2cbrg); E_DSPIC_WORD(i2cadd);
    E_DSPIC_REG(iec0, IEC0BITS); E_DSPIC_REG(iec1, IEC1BITS); E_DSPIC_REG(iec2, IEC2BITS);
    E_DSPIC_REG(ifs0, IFS0BITS); E_DSPIC_REG(ifs1, IFS1BITS); E_DSPIC_REG(ifs2, IFS2BITS);
    E_DSPIC_WORD(ipc[12]);
    E_DSPIC_REG(intcon1, INTCON1BITS); E_DSPIC_REG(intcon2, INTCON2BITS);
    E_DSPIC_REG(tcon[5], TCONBITS);
    E_DSPIC_WORD(tmr[5]); E_DSPIC_WORD(pr[5]);
    E_DSPIC_WORD(tblpag); E_DSPIC_WORD(psvpag); E_DSPIC_WORD(corcon); E_DSPIC_WORD(sr);
    E_DSPIC_WORD(u1mode); E_DSPIC_WORD(u1sta); E_DSPIC_WORD(u1brg); E_DSPIC_WORD(u1txreg);
    E_DSPIC_WORD(u1rxreg); E_DSPIC_WORD(u2mode); E_DSPIC_WORD(u2sta); E_DSPIC_WORD(u2brg);
    E_DSPIC_WORD(u2txreg); E_DSPIC_WORD(u2rxreg);
    E_DSPIC_WORD(adcon1); E_DSPIC_WORD(adcon2); E_DSPIC_WORD(adcon3); E_DSPIC_WORD(adchs);
    E_DSPIC_WORD(adpcfg); E_DSPIC_WORD(adcssl); E_DSPIC_WORD(adcbuf[16]);
    E_DSPIC_WORD(osccon);
} e_dspic_registers;

extern volatile e_dspic_registers e_dspic_sfr;

#define RCON (e_dspic_sfr.rcon.w)
#define RCONbits (e_dspic_sfr.rcon.b)
#define PORTA (e_dspic_sfr.porta.w)
#define PORTAbits (e_dspic_sfr.porta.b)
#define LATA (e_dspic_sfr.lata.w)
#define LATAbits (e_dspic_sfr.lata.b)
#define TRISA (e_dspic_sfr.trisa.w)
#define TRISAbits (e_dspic_sfr.trisa.b)
#define PORTB (e_dspic_sfr.portb.w)
#define PORTBbits (e_dspic_sfr.portb.b)
#define LATB (e_dspic_sfr.latb.w)
#define LATBbits (e_dspic_sfr.latb.b)
#define TRISB (e_dspic_sfr.trisb.w)
#define TRISBbits (e_dspic_sfr.trisb.b)
#define PORTC (e_dspic_sfr.portc.w)
#define PORTCbits (e_dspic_sfr.portc.b)
#define LATC (e_dspic_sfr.latc.w)
#define LATCbits (e_dspic_sfr.latc.b)
#define TRISC (e_dspic_sfr.trisc.w)
#define TRISCbits (e_dspic_sfr.trisc.b)
#define PORTD (e_dspic_sfr.portd.w)
#define PORTDbits (e_dspic_sfr.portd.b)
#define LATD (e_dspic_sfr.latd.w)
#define LATDbits (e_dspic_sfr.latd.b)
#define TRISD (e_dspic_sfr.trisd.w)
#define TRISDbits (e_dspic_sfr.trisd.b)
#define PORTF (e_dspic_sfr.portf.w)
#define PORTFbits (e_dspic_sfr.portf.b)
#define LATF (e_dspic_sfr.latf.w)
#define LATFbits (e_dspic_sfr.latf.b)
#define TRISF (e_dspic_sfr.trisf.w)
#define TRISFbits (e_dspic_sfr.trisf.b)
#define PORTG (e_dspic_sfr.portg.w)
#define PORTGbits (e_dspic_sfr.portg.b)
#define LATG (e_dspic_sfr.latg.w)
#define LATGbits (e_dspic_sfr.latg.b)
#define TRISG (e_dspic_sfr.trisg.w)
#define TRISGbits (e_dspic_sfr.trisg.b)
#define I2CCON (e_dspic_sfr.i2ccon.w)
#define I2CCONbits (e_dspic_sfr.i2ccon.b)
#define I2CSTAT (e_dspic_sfr.i2cstat.w)
#define I2CSTATbits (e_dspic_sfr.i2cstat.b)
#define I2CRCV (e_dspic_sfr.i2crcv.w)
#define I2CTRN (e_dspic_sfr.i2ctrn.w)
#define I2CBRG (e_dspic_sfr.i2cbrg.w)
#define I2CADD (e_dspic_sfr.i2cadd.w)
#define IEC0 (e_dspic_sfr.iec0.w)
#define IEC0bits (e_dspic_sfr.iec0.b)
#define IEC1 (e_dspic_sfr.iec1.w)
#define IEC1bits (e_dspic_sfr.iec1.b)
#define IEC2 (e_dspic_sfr.iec2.w)
#define IEC2bits (e_dspic_sfr.iec2.b)
#define IFS0 (e_dspic_sfr.ifs0.w)
#define IFS0bits (e_dspic_sfr.ifs0.b)
#define IFS1 (e_dspic_sfr.ifs1.w)
#define IFS1bits (e_dspic_sfr.ifs1.b)
#define IFS2 (e_dspic_sfr.ifs2.w)
#define IFS2bits (e_dspic_sfr.ifs2.b)
#define IPC0 (e_dspic_sfr.ipc[0].w)
#define IPC1 (e_dspic_sfr.ipc[1].w)
#define IPC2 (e_dspic_sfr.ipc[2].w)
#define IPC3 (e_dspic_sfr.ipc[3].w)
#define IPC4 (e_dspic_sfr.ipc[4].w)
#define IPC5 (e_dspic_sfr.ipc[5].w)
#define IPC6 (e_dspic_sfr.ipc[6].w)
#define IPC7 (e_dspic_sfr.ipc[7].w)
#define IPC8 (e_dspic_sfr.ipc[8].w)
#define IPC9 (e_dspic_sfr.ipc[9].w)
#define IPC10 (e_dspic_sfr.ipc[10].w)
#define IPC11 (e_dspic_sfr.ipc[11].w)
#define INTCON1 (e_dspic_sfr.intcon1.w)
#define INTCON1bits (e_dspic_sfr.intcon1.b)
#define INTCON2 (e_dspic_sfr.intcon2.w)
#define INTCON2bits (e_dspic_sfr.intcon2.b)
#define T1CON (e_dspic_sfr.tcon[0].w)
#define T1CONbits (e_dspic_sfr.tcon[0].b)
#define T2CON (e_dspic_sfr.tcon[1].w)
#define T2CONbits (e_dspic_sfr.tcon[1].b)
#define T3CON (e_dspic_sfr.tcon[2].w)
#define T3CONbits (e_dspic_sfr.tcon[2].b)
#define T4CON (e_dspic_sfr.tcon[3].w)
#define T4CONbits (e_dspic_sfr.tcon[3].b)
#define T5CON (e_dspic_sfr.tcon[4].w)
#define T5CONbits (e_dspic_sfr.tcon[4].b)
#define TMR1 (e_dspic_sfr.tmr[0].w)
#define TMR2 (e_dspic_sfr.tmr[1].w)
#define TMR3 (e_dspic_sfr.tmr[2].w)
#define TMR4 (e_dspic_sfr.tmr[3].w)
#define TMR5 (e_dspic_sfr.tmr[4].w)
#define PR1 (e_dspic_sfr.pr[0].w)
#define PR2 (e_dspic_sfr.pr[1].w)
#define PR3 (e_dspic_sfr.pr[2].w)
#define PR4 (e_dspic_sfr.pr[3].w)
#define PR5 (e_dspic_sfr.pr[4].w)
#define TBLPAG (e_dspic_sfr.tblpag.w)
#define PSVPAG (e_dspic_sfr.psvpag.w)
#define CORCON (e_dspic_sfr.corcon.w)
#define SR (e_dspic_sfr.sr.w)
#define U1MODE (e_dspic_sfr.u1mode.w)
#define U1STA (e_dspic_sfr.u1sta.w)
#define U1BRG (e_dspic_sfr.u1brg.w)
#define U1TXREG (e_dspic_sfr.u1txreg.w)
#define U1RXREG (e_dspic_sfr.u1rxreg.w)
#define U2MODE (e_dspic_sfr.u2mode.w)
#define U2STA (e_dspic_sfr.u2sta.w)
#define U2BRG (e_dspic_sfr.u2brg.w)
#define U2TXREG (e_dspic_sfr.u2txreg.w)
#define U2RXREG (e_dspic_sfr.u2rxreg.w)
#define ADCON1 (e_dspic_sfr.adcon1.w)
#define ADCON2 (e_dspic_sfr.adcon2.w)
#define ADCON3 (e_dspic_sfr.adcon3.w)
#define ADCHS (e_dspic_sfr.adchs.w)
#define ADPCFG (e_dspic_sfr.adpcfg.w)
#define ADCSSL (e_dspic_sfr.adcssl.w)
#define ADCBUF0 (e_dspic_sfr.adcbuf[0].w)
#define OSCCON (e_dspic_sfr.osccon.w)

/* ---- single bits, as XC16 names them (_POR, _LATA6, _RG6, ...) -------------- */

#define _POR RCONbits.POR
#define _BOR RCONbits.BOR
#define _SWR RCONbits.SWR
#define _EXTR RCONbits.EXTR
#define _WDTO RCONbits.WDTO
#define _I2CEN I2CCONbits.I2CEN
#define _T1IE IEC0bits.T1IE
#define _T2IE IEC0bits.T2IE
#define _T3IE IEC0bits.T3IE
#define _T4IE IEC1bits.T4IE
#define _T5IE IEC1bits.T5IE
#define _U1RXIE IEC0bits.U1RXIE
#define _U1TXIE IEC0bits.U1TXIE
#define _U2RXIE IEC1bits.U2RXIE
#define _U2TXIE IEC1bits.U2TXIE
#define _ADIE IEC0bits.ADIE
#define _INT0IE IEC0bits.INT0IE
#define _T1IF IFS0bits.T1IF
#define _T2IF IFS0bits.T2IF
#define _T3IF IFS0bits.T3IF
#define _T4IF IFS1bits.T4IF
#define _T5IF IFS1bits.T5IF
#define _ADIF IFS0bits.ADIF
#define _INT0IF IFS0bits.INT0IF
#define _NSTDIS INTCON1bits.NSTDIS

#define _RA6 PORTAbits.RA6
#define _RA7 PORTAbits.RA7
#define _RA9 PORTAbits.RA9
#define _RA10 PORTAbits.RA10
#define _RA12 PORTAbits.RA12
#define _RA13 PORTAbits.RA13
#define _RA14 PORTAbits.RA14
#define _RA15 PORTAbits.RA15
#define _LATA6 LATAbits.LATA6
#define _LATA7 LATAbits.LATA7
#define _LATA9 LATAbits.LATA9
#define _LATA10 LATAbits.LATA10
#define _LATA12 LATAbits.LATA12
#define _LATA13 LATAbits.LATA13
#define _LATA14 LATAbits.LATA14
#define _LATA15 LATAbits.LATA15
#define _TRISA6 TRISAbits.TRISA6
#define _TRISA7 TRISAbits.TRISA7
#define _TRISA9 TRISAbits.TRISA9
#define _TRISA10 TRISAbits.TRISA10
#define _TRISA12 TRISAbits.TRISA12
#define _TRISA13 TRISAbits.TRISA13
#define _TRISA14 TRISAbits.TRISA14
#define _TRISA15 TRISAbits.TRISA15

#define _RB0 PORTBbits.RB0
#define _RB1 PORTBbits.RB1
#define _RB2 PORTBbits.RB2
#define _RB3 PORTBbits.RB3
#define _RB4 PORTBbits.RB4
#define _RB5 PORTBbits.RB5
#define _RB6 PORTBbits.RB6
#define _RB7 PORTBbits.RB7
#define _RB8 PORTBbits.RB8
#define _RB9 PORTBbits.RB9
#define _RB10 PORTBbits.RB10
#define _RB11 PORTBbits.RB11
#define _RB12 PORTBbits.RB12
#define _RB13 PORTBbits.RB13
#define _RB14 PORTBbits.RB14
#define _RB15 PORTBbits.RB15
#define _LATB0 LATBbits.LATB0
#define _LATB1 LATBbits.LATB1
#define _LATB2 LATBbits.LATB2
#define _LATB3 LATBbits.LATB3
#define _LATB4 LATBbits.LATB4
#define _LATB5 LATBbits.LATB5
#define _LATB6 LATBbits.LATB6
#define _LATB7 LATBbits.LATB7
#define _LATB8 LATBbits.LATB8
#define _LATB9 LATBbits.LATB9
#define _LATB10 LATBbits.LATB10
#define _LATB11 LATBbits.LATB11
#define _LATB12 LATBbits.LATB12
#define _LATB13 LATBbits.LATB13
#define _LATB14 LATBbits.LATB14
#define _LATB15 LATBbits.LATB15
#define _TRISB0 TRISBbits.TRISB0
#define _TRISB1 TRISBbits.TRISB1
#define _TRISB2 TRISBbits.TRISB2
#define _TRISB3 TRISBbits.TRISB3
#define _TRISB4 TRISBbits.TRISB4
#define _TRISB5 TRISBbits.TRISB5
#define _TRISB6 TRISBbits.TRISB6
#define _TRISB7 TRISBbits.TRISB7
#define _TRISB8 TRISBbits.TRISB8
#define _TRISB9 TRISBbits.TRISB9
#define _TRISB10 TRISBbits.TRISB10
#define _TRISB11 TRISBbits.TRISB11
#define _TRISB12 TRISBbits.TRISB12
#define _TRISB13 TRISBbits.TRISB13
#define _TRISB14 TRISBbits.TRISB14
#define _TRISB15 TRISBbits.TRISB15

#define _RC1 PORTCbits.RC1
#define _RC2 PORTCbits.RC2
#define _RC3 PORTCbits.RC3
#define _RC4 PORTCbits.RC4
#define _RC13 PORTCbits.RC13
#define _RC14 PORTCbits.RC14
#define _RC15 PORTCbits.RC15
#define _LATC1 LATCbits.LATC1
#define _LATC2 LATCbits.LATC2
#define _LATC3 LATCbits.LATC3
#define _LATC4 LATCbits.LATC4
#define _LATC13 LATCbits.LATC13
#define _LATC14 LATCbits.LATC14
#define _LATC15 LATCbits.LATC15
#define _TRISC1 TRISCbits.TRISC1
#define _TRISC2 TRISCbits.TRISC2
#define _TRISC3 TRISCbits.TRISC3
#define _TRISC4 TRISCbits.TRISC4
#define _TRISC13 TRISCbits.TRISC13
#define _TRISC14 TRISCbits.TRISC14
#define _TRISC15 TRISCbits.TRISC15

#define _RD0 PORTDbits.RD0
#define _RD1 PORTDbits.RD1
#define _RD2 PORTDbits.RD2
#define _RD3 PORTDbits.RD3
#define _RD4 PORTDbits.RD4
#define _RD5 PORTDbits.RD5
#define _RD6 PORTDbits.RD6
#define _RD7 PORTDbits.RD7
#define _RD8 PORTDbits.RD8
#define _RD9 PORTDbits.RD9
#define _RD10 PORTDbits.RD10
#define _RD11 PORTDbits.RD11
#define _RD12 PORTDbits.RD12
#define _RD13 PORTDbits.RD13
#define _RD14 PORTDbits.RD14
#define _RD15 PORTDbits.RD15
#define _LATD0 LATDbits.LATD0
#define _LATD1 LATDbits.LATD1
#define _LATD2 LATDbits.LATD2
#define _LATD3 LATDbits.LATD3
#define _LATD4 LATDbits.LATD4
#define _LATD5 LATDbits.LATD5
#define _LATD6 LATDbits.LATD6
#define _LATD7 LATDbits.LATD7
#define _LATD8 LATDbits.LATD8
#define _LATD9 LATDbits.LATD9
#define _LATD10 LATDbits.LATD10
#define _LATD11 LATDbits.LATD11
#define _LATD12 LATDbits.LATD12
#define _LATD13 LATDbits.LATD13
#define _LATD14 LATDbits.LATD14
#define _LATD15 LATDbits.LATD15
#define _TRISD0 TRISDbits.TRISD0
#define _TRISD1 TRISDbits.TRISD1
#define _TRISD2 TRISDbits.TRISD2
#define _TRISD3 TRISDbits.TRISD3
#define _TRISD4 TRISDbits.TRISD4
#define _TRISD5 TRISDbits.TRISD5
#define _TRISD6 TRISDbits.TRISD6
#define _TRISD7 TRISDbits.TRISD7
#define _TRISD8 TRISDbits.TRISD8
#define _TRISD9 TRISDbits.TRISD9
#define _TRISD10 TRISDbits.TRISD10
#define _TRISD11 TRISDbits.TRISD11
#define _TRISD12 TRISDbits.TRISD12
#define _TRISD13 TRISDbits.TRISD13
#define _TRISD14 TRISDbits.TRISD14
#define _TRISD15 TRISDbits.TRISD15

#define _RF0 PORTFbits.RF0
#define _RF1 PORTFbits.RF1
#define _RF2 PORTFbits.RF2
#define _RF3 PORTFbits.RF3
#define _RF4 PORTFbits.RF4
#define _RF5 PORTFbits.RF5
#define _RF6 PORTFbits.RF6
#define _RF7 PORTFbits.RF7
#define _RF8 PORTFbits.RF8
#define _LATF0 LATFbits.LATF0
#define _LATF1 LATFbits.LATF1
#define _LATF2 LATFbits.LATF2
#define _LATF3 LATFbits.LATF3
#define _LATF4 LATFbits.LATF4
#define _LATF5 LATFbits.LATF5
#define _LATF6 LATFbits.LATF6
#define _LATF7 LATFbits.LATF7
#define _LATF8 LATFbits.LATF8
#define _TRISF0 TRISFbits.TRISF0
#define _TRISF1 TRISFbits.TRISF1
#define _TRISF2 TRISFbits.TRISF2
#define _TRISF3 TRISFbits.TRISF3
#define _TRISF4 TRISFbits.TRISF4
#define _TRISF5 TRISFbits.TRISF5
#define _TRISF6 TRISFbits.TRISF6
#define _TRISF7 TRISFbits.TRISF7
#define _TRISF8 TRISFbits.TRISF8

#define _RG0 PORTGbits.RG0
#define _RG1 PORTGbits.RG1
#define _RG2 PORTGbits.RG2
#define _RG3 PORTGbits.RG3
#define _RG6 PORTGbits.RG6
#define _RG7 PORTGbits.RG7
#define _RG8 PORTGbits.RG8
#define _RG9 PORTGbits.RG9
#define _LATG0 LATGbits.LATG0
#define _LATG1 LATGbits.LATG1
#define _LATG2 LATGbits.LATG2
#define _LATG3 LATGbits.LATG3
#define _LATG6 LATGbits.LATG6
#define _LATG7 LATGbits.LATG7
#define _LATG8 LATGbits.LATG8
#define _LATG9 LATGbits.LATG9
#define _TRISG0 TRISGbits.TRISG0
#define _TRISG1 TRISGbits.TRISG1
#define _TRISG2 TRISGbits.TRISG2
#define _TRISG3 TRISGbits.TRISG3
#define _TRISG6 TRISGbits.TRISG6
#define _TRISG7 TRISGbits.TRISG7
#define _TRISG8 TRISGbits.TRISG8
#define _TRISG9 TRISGbits.TRISG9

#endif
