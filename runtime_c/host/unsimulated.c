/*
 * unsimulated.c - what the e-puck library has and the simulated e-puck does
 * not model (the headers of ../epuck_api_unsimulated/, at the library's
 * paths): every function they declare is defined, so that a program that
 * includes them builds and links (GCtronic's main_c.c, which reaches
 * Bluetooth or I2C on a few positions of its selector only), and a call
 * ends the run there: a message names the function and its device, the
 * trace closes with an "unsimulated" record, exit status 6
 * (stub_unsimulated, platform_host.c; docs/runtime.md, "What is not
 * simulated").  The functions these headers share with the simulated
 * library's (a_d/e_prox.h's e_get_prox) are the simulated ones.
 */
#include "I2C/e_I2C_master_module.h"
#include "I2C/e_I2C_protocol.h"
#include "a_d/e_ad_conv.h"
#include "a_d/e_prox.h"
#include "bluetooth/e_bluetooth.h"
#include "camera/fast_2_timer/e_po3030k.h"
#include "camera/fast_2_timer/e_po6030k.h"
#include "camera/fast_2_timer/e_po8030d.h"
#include "camera/slow_3_timer/e_po3030k.h"
#include "contrib/LIS_sensors_turret/e_devantech.h"
#include "contrib/LIS_sensors_turret/e_sensext.h"
#include "contrib/LIS_sensors_turret/e_sharp.h"
#include "contrib/SWIS_com_module/ComModule.h"
#include "fft/e_fft.h"
#include "fft/e_fft_utilities.h"
#include "matlab/matlab.h"

#include "epuck_stub.h"

/* what each device is, and what the simulated e-puck has instead */
#define I2C_BUS "the I2C bus (the simulated library reaches the camera and the LSM330 " \
    "without it)"
#define BLUETOOTH "Bluetooth (its UART, uart1, goes to the trace)"
#define FFT "the FFT of the microphones' samples"
#define CAMERA_REGISTERS "the camera sensor's registers (the simulated camera is driven " \
    "through camera/fast_2_timer/e_poxxxx.h)"
#define LIS_TURRET "the LIS sensors turret (an extension board)"
#define SWIS_RADIO "the SWIS radio module (an extension board)"
#define MATLAB "the link to Matlab"
#define TIMER_AD "the timer-driven A/D (the simulated e-puck has the advanced scan: " \
    "a_d/advance_ad_scan, e_init_ad_scan(ALL_ADC))"
#define NOT_SIMULATED(device) stub_unsimulated(__func__, device)

/* I2C/e_I2C_master_module.h */

char e_i2c_init(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_deinit(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_start(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_restart(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_ack(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_nack(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_read(char *a0) { (void)a0; NOT_SIMULATED(I2C_BUS); }
char e_i2c_stop(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_write(char a0) { (void)a0; NOT_SIMULATED(I2C_BUS); }
char e_i2c_enable(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_disable(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2c_reset(void) { NOT_SIMULATED(I2C_BUS); }

/* I2C/e_I2C_protocol.h */

void e_i2cp_init(void) { NOT_SIMULATED(I2C_BUS); }
void e_i2cp_deinit(void) { NOT_SIMULATED(I2C_BUS); }
char e_i2cp_write(char a0, char a1, char a2) { (void)a0; (void)a1; (void)a2; NOT_SIMULATED(I2C_BUS); }
char e_i2cp_read(char a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(I2C_BUS); }
char e_i2cp_read_string(char a0, unsigned char a1[], char a2, char a3)
{ (void)a0; (void)a1; (void)a2; (void)a3; NOT_SIMULATED(I2C_BUS); }
char e_i2cp_write_string(char a0, unsigned char a1[], char a2, char a3)
{ (void)a0; (void)a1; (void)a2; (void)a3; NOT_SIMULATED(I2C_BUS); }
void e_i2cp_enable(void) { NOT_SIMULATED(I2C_BUS); }
void e_i2cp_disable(void) { NOT_SIMULATED(I2C_BUS); }

/* a_d/e_ad_conv.h */

void e_init_ad(void) { NOT_SIMULATED(TIMER_AD); }
int e_read_ad(unsigned int a0) { (void)a0; NOT_SIMULATED(TIMER_AD); }

/* a_d/e_prox.h */

void e_init_prox(void) { NOT_SIMULATED(TIMER_AD); }
void e_stop_prox(void) { NOT_SIMULATED(TIMER_AD); }

/* camera/slow_3_timer/e_po3030k.h (its own; the rest is the fast driver's above) */

void e_po3030k_launch_capture(char *a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_apply_timer_config(int a0, int a1, int a2, int a3, int a4)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_is_img_ready(void) { NOT_SIMULATED(CAMERA_REGISTERS); }

/* bluetooth/e_bluetooth.h */

int e_bt_find_epuck(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_connect_epuck(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_read_local_pin_number(char *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_read_local_name(char *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_write_local_pin_number(char *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_write_local_name(char *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_etablish_SPP_link(char *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_release_SPP_link(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_send_SPP_data(char *a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(BLUETOOTH); }
char e_bt_tranparent_mode(void) { NOT_SIMULATED(BLUETOOTH); }
void e_bt_exit_tranparent_mode(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_list_local_paired_device(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_remove_local_paired_device(int a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
int e_bt_inquiry(struct BtDevice *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_get_friendly_name(struct BtDevice *a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_set_event_filter(char a0) { (void)a0; NOT_SIMULATED(BLUETOOTH); }
char e_bt_get_event_filter(void) { NOT_SIMULATED(BLUETOOTH); }
int e_bt_reset(void) { NOT_SIMULATED(BLUETOOTH); }
char e_bt_factory_reset(void) { NOT_SIMULATED(BLUETOOTH); }

/* camera/fast_2_timer/e_po3030k.h */

int e_po3030k_config_cam(unsigned int a0, unsigned int a1, unsigned int a2, unsigned int a3,
                         unsigned int a4, unsigned int a5, int a6)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; (void)a5; (void)a6; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_get_bytes_per_pixel(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_init_cam(void) { NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_write_cam_registers(void) { NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_color_mode(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_sampling_mode(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_speed(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_wx(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_wy(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_vsync(unsigned int a0, unsigned int a1, unsigned int a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_mirror(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_read_cam_registers(void) { NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_register(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_get_register(unsigned char a0, unsigned char *a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_bias(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_integr_time(unsigned long a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_adc_offset(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_sepia(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_lens_gain(unsigned char a0, unsigned char a1, unsigned char a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_edge_prop(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_gamma_coef(unsigned char a0[12], char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_write_gamma_coef(void) { NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_sync_register_array(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_color_matrix(unsigned char a0[3 * 3]) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_cb_cr_gain(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_brigh_contr(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_sepia_tone(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_ww(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_awb_ae_tol(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_ae_speed(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_exposure(long a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_ref_exposure(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_max_min_exp(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_max_min_awb(unsigned char a0, unsigned char a1, unsigned char a2,
                               unsigned char a3, unsigned char a4, unsigned char a5)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; (void)a5; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_weight_win(unsigned int a0, unsigned int a1, unsigned int a2, unsigned int a3)
{ (void)a0; (void)a1; (void)a2; (void)a3; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_awb_ae(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_color_gain(unsigned char a0, unsigned char a1, unsigned char a2,
                             unsigned char a3, unsigned char a4)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_flicker_mode(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po3030k_set_flicker_detection(int a0, int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po3030k_set_flicker_man_set(int a0, int a1, int a2, int a3, int a4)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; NOT_SIMULATED(CAMERA_REGISTERS); }

/* camera/fast_2_timer/e_po6030k.h */

int e_po6030k_config_cam(unsigned int a0, unsigned int a1, unsigned int a2, unsigned int a3,
                         unsigned int a4, unsigned int a5, int a6)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; (void)a5; (void)a6; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po6030k_get_bytes_per_pixel(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_color_mode(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_bank(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_write_register(unsigned char a0, unsigned char a1, unsigned char a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_bayer_clkdiv(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_pclkdiv(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po6030k_set_mode(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po6030k_set_wx(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po6030k_set_wy(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po6030k_set_vsync(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_sketch_mode(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_mirror(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_awb_ae(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_rgb_gain(unsigned char a0, unsigned char a1, unsigned char a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po6030k_set_exposure(unsigned long a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }

/* camera/fast_2_timer/e_po8030d.h */

int e_po8030d_config_cam(unsigned int a0, unsigned int a1, unsigned int a2, unsigned int a3,
                         unsigned int a4, unsigned int a5, int a6)
{ (void)a0; (void)a1; (void)a2; (void)a3; (void)a4; (void)a5; (void)a6; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po8030d_get_bytes_per_pixel(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_color_mode(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_bank(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_write_register(unsigned char a0, unsigned char a1, unsigned char a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_bayer_clkdiv(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_pclkdiv(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po8030d_set_mode(unsigned char a0, unsigned char a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po8030d_set_wx(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po8030d_set_wy(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
int e_po8030d_set_vsync(unsigned int a0, unsigned int a1)
{ (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_sketch_mode(int a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_mirror(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_awb_ae(int a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_rgb_gain(unsigned char a0, unsigned char a1, unsigned char a2)
{ (void)a0; (void)a1; (void)a2; NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_exposure(unsigned long a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int testWriteReg(unsigned char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }
int init_po8030() { NOT_SIMULATED(CAMERA_REGISTERS); }
void e_po8030d_set_brightness(signed char a0) { (void)a0; NOT_SIMULATED(CAMERA_REGISTERS); }

/* contrib/LIS_sensors_turret/e_devantech.h */

void e_init_devantech(void) { NOT_SIMULATED(LIS_TURRET); }
void e_disable_devantech(void) { NOT_SIMULATED(LIS_TURRET); }
unsigned int e_get_dist_devantech(char a0) { (void)a0; NOT_SIMULATED(LIS_TURRET); }
unsigned int e_get_delay_devantech(char a0) { (void)a0; NOT_SIMULATED(LIS_TURRET); }
char e_get_sr_devantech(char a0) { (void)a0; NOT_SIMULATED(LIS_TURRET); }
unsigned int e_get_light_devantech(char a0) { (void)a0; NOT_SIMULATED(LIS_TURRET); }
void e_set_gain_devantech(char a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }
void e_set_range_devantech(char a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }
void e_i2cd_write(char a0, char a1, char a2) { (void)a0; (void)a1; (void)a2; NOT_SIMULATED(LIS_TURRET); }
char e_i2cd_readb(char a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }
unsigned int e_i2cd_readw(char a0, char a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }

/* contrib/LIS_sensors_turret/e_sensext.h */

void e_init_sensext(void) { NOT_SIMULATED(LIS_TURRET); }
int e_sensext_process(int *a0, unsigned int *a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }
void e_stop_sensext_wait(void) { NOT_SIMULATED(LIS_TURRET); }
void e_start_sensext_wait(void) { NOT_SIMULATED(LIS_TURRET); }
int e_get_sensext_wait(void) { NOT_SIMULATED(LIS_TURRET); }

/* contrib/LIS_sensors_turret/e_sharp.h */

void e_init_sharp(void) { NOT_SIMULATED(LIS_TURRET); }
int e_get_dist_sharp(void) { NOT_SIMULATED(LIS_TURRET); }
void e_set_sharp_led(unsigned int a0, unsigned int a1) { (void)a0; (void)a1; NOT_SIMULATED(LIS_TURRET); }
void e_sharp_led_clear(void) { NOT_SIMULATED(LIS_TURRET); }
void e_sharp_on(void) { NOT_SIMULATED(LIS_TURRET); }
void e_sharp_off(void) { NOT_SIMULATED(LIS_TURRET); }

/* contrib/SWIS_com_module/ComModule.h */

void InitComModule(unsigned char a0, unsigned int a1, unsigned char a2, unsigned char a3)
{ (void)a0; (void)a1; (void)a2; (void)a3; NOT_SIMULATED(SWIS_RADIO); }
int IsModulePlugged() { NOT_SIMULATED(SWIS_RADIO); }
void SetRadioEnabledState(unsigned char a0) { (void)a0; NOT_SIMULATED(SWIS_RADIO); }
void SetHardwareAttenuator(unsigned char a0) { (void)a0; NOT_SIMULATED(SWIS_RADIO); }
void SetSoftwareAttenuator(unsigned char a0) { (void)a0; NOT_SIMULATED(SWIS_RADIO); }
void SetOwnGroup(unsigned char a0) { (void)a0; NOT_SIMULATED(SWIS_RADIO); }
void SetOwnAddress(unsigned int a0) { (void)a0; NOT_SIMULATED(SWIS_RADIO); }
unsigned char GetRadioEnabledState() { NOT_SIMULATED(SWIS_RADIO); }
unsigned char GetHardwareAttenuator() { NOT_SIMULATED(SWIS_RADIO); }
unsigned char GetSoftwareAttenuator() { NOT_SIMULATED(SWIS_RADIO); }
unsigned char GetOwnGroup() { NOT_SIMULATED(SWIS_RADIO); }
unsigned char GetStatus() { NOT_SIMULATED(SWIS_RADIO); }
int SendPacket(unsigned char a0, unsigned int a1, unsigned char *a2, int a3)
{ (void)a0; (void)a1; (void)a2; (void)a3; NOT_SIMULATED(SWIS_RADIO); }
int IsPacketReady(unsigned char *a0, int *a1) { (void)a0; (void)a1; NOT_SIMULATED(SWIS_RADIO); }

/* fft/e_fft.h */

void e_doFFT_asm(fractcomplex *a0) { (void)a0; NOT_SIMULATED(FFT); }

/* fft/e_fft_utilities.h */

void e_fast_copy(int *a0, int *a1, int a2) { (void)a0; (void)a1; (void)a2; NOT_SIMULATED(FFT); }
void e_subtract_mean(int *a0, int a1, int a2) { (void)a0; (void)a1; (void)a2; NOT_SIMULATED(FFT); }

/* matlab/matlab.h */

void e_send_int_to_matlab(int *a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(MATLAB); }
void e_send_char_to_matlab(char *a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(MATLAB); }
int e_receive_int_from_matlab(int *a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(MATLAB); }
int e_receive_char_from_matlab(char *a0, int a1) { (void)a0; (void)a1; NOT_SIMULATED(MATLAB); }

/* the globals they declare */

unsigned char e_bt_local_paired_device[6 * 8];
struct BtDevice e_bt_present_device[10];
struct BtEPuck e_bt_present_epuck[10];
