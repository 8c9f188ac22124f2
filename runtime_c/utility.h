/* utility.h - the paper's umbrella header: include it to use the whole library. */
#ifndef UTILITY_H
#define UTILITY_H
#include "epuckrt.h"
#endif
