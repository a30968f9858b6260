/* Included before every fstapi source (cmake/BusdecodeFstapi.cmake): fstapi ends the
 * process with exit(255) on a corrupt block and prints to stderr; here the exit throws
 * (fst_api.cpp turns it into an InputError) and the message is kept for that error. */
#ifndef BUSDECODE_FST_API_SHIM_H
#define BUSDECODE_FST_API_SHIM_H
#include <stdio.h>
#include <stdlib.h>

#ifdef __cplusplus
extern "C" {
#endif
__attribute__((noreturn)) void busdecode_fst_fatal(int code);
FILE* busdecode_fst_messages(void);
#ifdef __cplusplus
}
#endif

#ifndef BUSDECODE_FST_API_NO_REDIRECT
#undef stderr
#define stderr busdecode_fst_messages()
#define exit(code) busdecode_fst_fatal(code)
#endif
#endif
