/* e-puck library API, the speaker, declarations only (see ../README.md).
 * Offsets and lengths are in words of the samples in codec/e_const_sound.s:
 * "haa" [0, 2112], "spaah" [2116, 1760], "ouah" [3878, 3412],
 * "yaouh" [7294, 3732], "wouaaaaaaaah" [11028, 8016]. */
#ifndef EPUCK_API_E_SOUND_H
#define EPUCK_API_E_SOUND_H

void e_init_sound(void);
void e_play_sound(int sound_offset, int sound_length);
void e_close_sound(void);

#endif
