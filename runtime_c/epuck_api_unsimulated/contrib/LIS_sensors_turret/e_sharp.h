/* e-puck library API: contrib/LIS_sensors_turret/e_sharp.h, which the simulated e-puck does not
 * model (the LIS sensors turret): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the LIS sensors turret (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _SHARP
#define _SHARP
#define SHARP 5
#define SHARP_LED1 _LATG6
#define SHARP_LED2 _LATG7
#define SHARP_LED3 _LATG8
#define SHARP_LED4 _LATG9
#define SHARP_LED5 _LATB6
#define SHARP_VIN _LATB7
#define SHARP_LED1_DIR _TRISG6
#define SHARP_LED2_DIR _TRISG7
#define SHARP_LED3_DIR _TRISG8
#define SHARP_LED4_DIR _TRISG9
#define SHARP_LED5_DIR _TRISB6
#define SHARP_VIN_DIR _TRISB7
void e_init_sharp(void);
int e_get_dist_sharp(void);
void e_set_sharp_led(unsigned int sharp_led_number, unsigned int value);
void e_sharp_led_clear(void);
void e_sharp_on(void);
void e_sharp_off(void);
#endif
