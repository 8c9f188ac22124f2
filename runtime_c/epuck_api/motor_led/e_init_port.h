/* e-puck library API, declarations only (see ../README.md). */
#ifndef EPUCK_API_E_INIT_PORT_H
#define EPUCK_API_E_INIT_PORT_H

void e_init_port(void);

#endif
