/* e-puck library API: contrib/SWIS_com_module/ComModule.h, which the simulated e-puck does not
 * model (the SWIS radio module): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the SWIS radio module (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _COM_MODULE
#define _COM_MODULE
#define COM_MODULE_HW_ATTENUATOR_25DB 1
#define COM_MODULE_HW_ATTENUATOR_0DB 0
#define COM_MODULE_DEFAULT_GROUP 0x7d
#define COM_MODULE_MAXSIZE 108
#include "p30F6014A.h"
void InitComModule(unsigned char owngroup, unsigned int ownaddress, unsigned char hardwareattenuatormode, unsigned char softwareattenuatorvalue);
int IsModulePlugged();
void SetRadioEnabledState(unsigned char mode);
void SetHardwareAttenuator(unsigned char AttenuatorMode);
void SetSoftwareAttenuator(unsigned char AttenuatorValue);
void SetOwnGroup(unsigned char GroupID);
void SetOwnAddress(unsigned int ownaddress);
unsigned char GetRadioEnabledState();
unsigned char GetHardwareAttenuator();
unsigned char GetSoftwareAttenuator();
unsigned char GetOwnGroup();
unsigned char GetStatus();
int SendPacket(unsigned char destinationgroup, unsigned int destinationaddress, unsigned char* packet, int packetsize);
int IsPacketReady(unsigned char* packet, int* packetSize);
#endif
