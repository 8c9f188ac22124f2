/* e-puck library API: matlab/matlab.h, which the simulated e-puck does not
 * model (the Matlab link): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the Matlab link (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef MATLAB_H
#define MATLAB_H
void e_send_int_to_matlab(int* data, int array_size);
void e_send_char_to_matlab(char * data, int array_size);
int e_receive_int_from_matlab(int* data, int array_size);
int e_receive_char_from_matlab(char* data, int array_size);
#endif
