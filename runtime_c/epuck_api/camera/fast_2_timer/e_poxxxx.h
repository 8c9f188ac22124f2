/* The e-puck library's camera API (library/camera/fast_2_timer/e_poxxxx.h;
 * the e-puck2 firmware's epuck1x layer has it at the same path, over its
 * po8030 and dcmi): declarations only, for the host build
 * (host/stub_devices.c implements them). */
#ifndef __POXXXX_H__
#define __POXXXX_H__

#define ARRAY_WIDTH 640
#define ARRAY_HEIGHT 480

#define GREY_SCALE_MODE 0
#define RGB_565_MODE 1
#define YUV_MODE 2

int e_poxxxx_config_cam(unsigned int sensor_x1, unsigned int sensor_y1,
                        unsigned int sensor_width, unsigned int sensor_height,
                        unsigned int zoom_fact_width, unsigned int zoom_fact_height,
                        int color_mode);
int e_poxxxx_init_cam(void);
void e_poxxxx_write_cam_registers(void);
void e_poxxxx_launch_capture(char *buf);
int e_poxxxx_is_img_ready(void);

#endif
