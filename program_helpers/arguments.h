/*
 * arguments.h - what every program's command line shares: a number option
 * read whole and checked against its range, --help and --version. (The clocks
 * are clocks.h's.)
 */
#ifndef ARGUMENTS_H
#define ARGUMENTS_H

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* 1 when all of text is a number (strtod's syntax, not out of range) within
 * [low, high]: *value holds it; else 0 (the caller says what it wanted). */
int argument_number(const char *text, double low, double high, double *value);

/* 1 when text is a UDP port: decimal digits alone (no sign, space, point, exponent or 0x), from low to
 * 65535; *port holds it; else 0. The one reading of a port for every program (hkf-track passes its ports on
 * to the bridge, which must read them as hkf-track did). */
int argument_port(const char *text, long low, long *port);

/* 1 when arg is --help or -h (usage(stdout) called) or --version ("PROGRAM
 * VERSION" printed): the program has answered and exits 0; else 0. When the
 * answer cannot be written (stdout on a full disk), it says so and exits 1. */
int argument_help_or_version(const char *arg, const char *program, void (*usage)(FILE *to));

#ifdef __cplusplus
}
#endif

#endif /* ARGUMENTS_H */
