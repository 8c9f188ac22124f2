/* The e-puck library's camera API (library/camera/fast_2_timer/e_poxxxx.h;
 * the e-puck2 firmware's epuck1x layer has it at the same path, over its
 * po8030 and dcmi): declarations only, for the host build (host/camera.c:
 * the modes, windows, zooms and return codes of the library's driver of
 * the e-puck 1.3's PO8030D). */
#ifndef __POXXXX_H__
#define __POXXXX_H__

#define POXXXX_FULL 1

#define ARRAY_WIDTH 640
#define ARRAY_HEIGHT 480

#define GREY_SCALE_MODE 0
#define RGB_565_MODE 1
#define YUV_MODE 2

int e_poxxxx_config_cam(unsigned int sensor_x1,unsigned int sensor_y1,
			 unsigned int sensor_width,unsigned int sensor_height,
			 unsigned int zoom_fact_width,unsigned int zoom_fact_height,
			 int color_mode);
int e_poxxxx_init_cam(void);
int e_poxxxx_get_orientation(void);
void e_poxxxx_write_cam_registers(void);
void e_poxxxx_launch_capture(char * buf);
int  e_poxxxx_is_img_ready(void);
void e_poxxxx_set_mirror(int vertical, int horizontal);
int e_poxxxx_apply_timer_config(int pixel_row, int pixel_col, int bpp, int pbp, int bbl);
void e_poxxxx_set_awb_ae(int awb, int ae);
void e_poxxxx_set_rgb_gain(unsigned char r, unsigned char g, unsigned char b);
void e_poxxxx_set_exposure(unsigned long exp);

#endif
