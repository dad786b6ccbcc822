/* arguments.c - see arguments.h. */
#define _POSIX_C_SOURCE 200809L

#include "arguments.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#ifndef HKF_VERSION
#error "HKF_VERSION is set by the build (add_compile_definitions in CMakeLists.txt)"
#endif

/* The answer reached stdout, or the program ends with exit 1 (a full disk is not an answer). */
static int answered(const char *program)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "%s: writing to standard output failed\n", program);
        exit(1);
    }
    return 1;
}

int argument_help_or_version(const char *arg, const char *program, void (*usage)(FILE *to))
{
    if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
        usage(stdout);
        return answered(program);
    }
    if (strcmp(arg, "--version") == 0) {
        printf("%s %s\n", program, HKF_VERSION);
        return answered(program);
    }
    return 0;
}

int argument_port(const char *text, long low, long *port)
{
    long value = 0;
    const char *c = text;
    for (; *c >= '0' && *c <= '9' && c - text < 5; ++c) {
        value = value * 10 + (*c - '0');
    }
    if (c == text || *c != '\0' || value < low || value > 65535) {
        return 0;
    }
    *port = value;
    return 1;
}

int argument_number(const char *text, double low, double high, double *value)
{
    char *end = NULL;
    errno = 0;
    *value = strtod(text, &end);
    return end != text && *end == '\0' && errno == 0 && *value >= low && *value <= high;
}
