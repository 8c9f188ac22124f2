/* e-puck library API: bluetooth/e_bluetooth.h, which the simulated e-puck does not
 * model (Bluetooth): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming Bluetooth (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _BLUETOOTH
#define _BLUETOOTH
struct BtDevice
{
  unsigned char address[6];
  unsigned char class[3];
  char friendly_name[20];
};
struct BtEPuck
{
  unsigned char address[6];
  unsigned char number[5];
};
extern unsigned char e_bt_local_paired_device[6*8];
extern struct BtDevice e_bt_present_device[10];
extern struct BtEPuck e_bt_present_epuck[10];
int e_bt_find_epuck(void);
char e_bt_connect_epuck(void);
char e_bt_read_local_pin_number(char *PIN);
char e_bt_read_local_name(char *name);
char e_bt_write_local_pin_number(char *PIN);
char e_bt_write_local_name(char *name);
char e_bt_etablish_SPP_link(char *address);
char e_bt_release_SPP_link(void);
char e_bt_send_SPP_data(char *data,char datalenght);
char e_bt_tranparent_mode(void);
void e_bt_exit_tranparent_mode(void);
char e_bt_list_local_paired_device(void);
char e_bt_remove_local_paired_device(int);
int e_bt_inquiry(struct BtDevice *device);
char e_bt_get_friendly_name(struct BtDevice *device);
char e_bt_set_event_filter(char event);
char e_bt_get_event_filter(void);
int e_bt_reset(void);
char e_bt_factory_reset(void);
#endif
