/* e-puck library API: camera/fast_2_timer/e_po3030k.h, which the simulated e-puck does not
 * model (the camera sensor's registers): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the camera sensor's registers (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef __PO3030K_H__
#define __PO3030K_H__
#include "camera/fast_2_timer/e_poxxxx.h"
#define PO3030K_FULL 1
#define MODE_VGA 0x44
#define MODE_QVGA 0x11
#define MODE_QQVGA 0x33
#define SPEED_2 0x00
#define SPEED_2_3 0x10
#define SPEED_4 0x20
#define SPEED_8 0x30
#define SPEED_16 0x40
#define SPEED_32 0x50
#define SPEED_64 0x60
#define SPEED_128 0x70
int e_po3030k_config_cam(unsigned int sensor_x1,unsigned int sensor_y1,
    unsigned int sensor_width,unsigned int sensor_height,
    unsigned int zoom_fact_width,unsigned int zoom_fact_height,
    int color_mode);
int e_po3030k_get_bytes_per_pixel(int color_mode);
void e_po3030k_init_cam(void);
void e_po3030k_write_cam_registers(void);
int e_po3030k_set_color_mode(int mode);
int e_po3030k_set_sampling_mode(int mode);
int e_po3030k_set_speed(int mode);
int e_po3030k_set_wx(unsigned int start, unsigned int stop);
int e_po3030k_set_wy(unsigned int start, unsigned int stop);
int e_po3030k_set_vsync(unsigned int start,unsigned int stop,unsigned int col);
void e_po3030k_set_mirror(int vertical, int horizontal);
#if PO3030K_FULL
void e_po3030k_read_cam_registers(void);
int e_po3030k_set_register(unsigned char adr,unsigned char value);
int e_po3030k_get_register(unsigned char adr,unsigned char * value);
void e_po3030k_set_bias(unsigned char pixbias, unsigned char opbias);
void e_po3030k_set_integr_time(unsigned long time);
void e_po3030k_set_adc_offset(unsigned char offset);
void e_po3030k_set_sepia(int status);
void e_po3030k_set_lens_gain(unsigned char red, unsigned char green, unsigned char blue);
void e_po3030k_set_edge_prop(unsigned char gain, unsigned char tresh);
void e_po3030k_set_gamma_coef(unsigned char array[12], char color);
void e_po3030k_write_gamma_coef(void);
int e_po3030k_sync_register_array(unsigned char start, unsigned char stop);
void e_po3030k_set_color_matrix(unsigned char array[3*3]);
void e_po3030k_set_cb_cr_gain(unsigned char cg11c, unsigned char cg22c);
void e_po3030k_set_brigh_contr(unsigned char bright, unsigned char contrast);
void e_po3030k_set_sepia_tone(unsigned char cb, unsigned char cr);
void e_po3030k_set_ww(unsigned char ww);
void e_po3030k_set_awb_ae_tol(unsigned char awbm, unsigned char aem);
void e_po3030k_set_ae_speed(unsigned char b, unsigned char d);
void e_po3030k_set_exposure(long t);
void e_po3030k_set_ref_exposure(unsigned char exp);
void e_po3030k_set_max_min_exp(unsigned int min, unsigned int max);
void e_po3030k_set_max_min_awb(unsigned char minb, unsigned char maxb, unsigned char minr,
     unsigned char maxr, unsigned char ratior, unsigned char ratiob);
int e_po3030k_set_weight_win(unsigned int x1, unsigned int x2, unsigned int y1, unsigned int y2);
void e_po3030k_set_awb_ae(int awb, int ae);
int e_po3030k_set_color_gain(unsigned char global, unsigned char red,
      unsigned char green1, unsigned char green2,
      unsigned char blue);
void e_po3030k_set_flicker_mode(int manual);
void e_po3030k_set_flicker_detection(int hz50, int hz60);
int e_po3030k_set_flicker_man_set(int hz50, int hz60, int fdm, int fk, int tol);
#endif
#endif
