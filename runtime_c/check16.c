/*
 * check16.c - compiled by `make check16` only: fails to compile unless the
 * target has the e-puck's (dsPIC30F, XC16) data model, so that the 16-bit
 * check of the runtime really runs with 16-bit int.  C99 has no
 * _Static_assert: a negative array size is the error.
 */
#include <limits.h>

#define CHECK16_ASSERT(name, cond) typedef char check16_##name[(cond) ? 1 : -1]

CHECK16_ASSERT(int_is_16_bits, INT_MAX == 32767 && sizeof(int) * CHAR_BIT == 16);
CHECK16_ASSERT(long_is_32_bits, LONG_MAX == 2147483647L);
CHECK16_ASSERT(pointer_is_16_bits, sizeof(void *) == 2);
CHECK16_ASSERT(long_long_is_64_bits, sizeof(long long) * CHAR_BIT == 64);
