/*
 * fuzz_input.h - reading a libFuzzer input as the libhkf targets do (fuzz_libhkf.c,
 * fuzz_position.c): bytes and numbers taken from the front, each number any bit
 * pattern of the build's hkf_real_t (a float's, or a Q16.16 int32's). A failed
 * check names the target (FUZZ_NAME, defined before this header) and aborts,
 * which libFuzzer reports as a finding.
 */
#ifndef FUZZ_INPUT_H
#define FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf_real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const uint8_t *data;
    size_t size;
} input_t;

static inline int take_byte(input_t *in, uint8_t *byte)
{
    if (in->size < 1) {
        return 0;
    }
    *byte = in->data[0];
    ++in->data;
    --in->size;
    return 1;
}

/* Any bit pattern at all: a float's, or a Q16.16 int32's; 0 once the input is used up. */
static inline hkf_real_t take_real(input_t *in)
{
#if defined(HKF_REAL_FIXED)
    int32_t value = 0;
#else
    float value = 0.0f;
#endif
    if (in->size >= sizeof value) {
        memcpy(&value, in->data, sizeof value);
        in->data += sizeof value;
        in->size -= sizeof value;
    }
    return (hkf_real_t)value;
}

static inline void check(int condition, const char *what)
{
    if (!condition) {
        fprintf(stderr, FUZZ_NAME ": %s\n", what);
        abort();
    }
}

#ifdef __cplusplus
}
#endif

#endif /* FUZZ_INPUT_H */
