/* Included before every fstapi source (cmake/BusdecodeFstapi.cmake): fstapi ends the
 * process with exit(255) on a corrupt block and prints to stderr; here the exit throws
 * (fst_api.cpp turns it into an InputError) and the message is kept for that error.
 * Its loops over names and varints read on past the end of a corrupt hierarchy for ever
 * (EOF is -1, neither 0 nor below 0x80): a long run of EOFs from one file throws too. */
#ifndef BUSDECODE_FST_API_SHIM_H
#define BUSDECODE_FST_API_SHIM_H
#include <stdio.h>
#include <stdlib.h>

#ifdef __cplusplus
extern "C" {
#endif
__attribute__((noreturn)) void busdecode_fst_fatal(int code);
FILE* busdecode_fst_messages(void);
int busdecode_fst_fgetc(FILE* f);
#ifdef __cplusplus
}
#endif

#ifndef BUSDECODE_FST_API_NO_REDIRECT
#undef stderr
#define stderr busdecode_fst_messages()
#define exit(code) busdecode_fst_fatal(code)
#define fgetc(f) busdecode_fst_fgetc(f)
#endif
#endif
