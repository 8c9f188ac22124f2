/* e-puck library API, the speaker (library/codec/e_sound.h), declarations
 * only (see ../README.md; host/sound.c).  Offsets and lengths are in words
 * of the samples in codec/e_const_sound.s: "haa" [0, 2112], "spaah"
 * [2116, 1760], "ouah" [3878, 3412], "yaouh" [7294, 3732], "wouaaaaaaaah"
 * [11028, 8016]; the codec plays 7200 words a second.  The flags the
 * library's programs declare themselves (`extern int e_dci_unavailable;`,
 * `extern int e_stop_flag;`) are the library's, as on the robot. */
#ifndef _SOUND
#define _SOUND

void e_init_sound(void);
void e_play_sound(int sound_offset, int sound_length);
void e_close_sound(void);

void e_init_dci_master(void);
void e_init_codec_slave(void);
void e_sub_dci_kickoff(int,int);

#endif
