/*
 * semihosting.h - the target tests' only I/O: ARM semihosting calls, which an
 * emulator (qemu-system-arm -semihosting) or a debug probe serves.
 */
#ifndef SEMIHOSTING_H
#define SEMIHOSTING_H

#ifdef __cplusplus
extern "C" {
#endif

void semihosting_write(const char *text);          /* SYS_WRITE0 */
void semihosting_write_int(long value);
void semihosting_exit(int success);                /* SYS_EXIT: the emulator exits 0 or 1 */

#ifdef __cplusplus
}
#endif

#endif /* SEMIHOSTING_H */
