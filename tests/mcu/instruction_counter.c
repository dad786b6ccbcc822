/* instruction_counter.c - see instruction_counter.h. Integer-only: the
 * fixed-point target test links no floating-point routine at all. */
#include "instruction_counter.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

static uint32_t calibration_ticks;

uint32_t counter_calibration_ticks(void) { return calibration_ticks; }

void counter_start(void)
{
    uint32_t turns = 100000u, start;
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 0x5u; /* enabled, processor clock, no interrupt */
    start = SYST_CVR;
    /* 2 instructions (subs, bne) per turn */
    __asm__ volatile(".syntax unified\n1: subs %0, %0, #1\n\tbne 1b" : "+l"(turns));
    calibration_ticks = counter_ticks(start, SYST_CVR);
}

/* ticks / calibration_ticks * 200000 / calls, rounded, in integers */
long counter_instructions_per_call(uint32_t ticks, uint32_t calls)
{
    const uint64_t numerator = (uint64_t)ticks * 200000u, denominator = (uint64_t)calibration_ticks * calls;
    uint64_t quotient = 0, bit = 1;
    uint64_t d = denominator, n = numerator + denominator / 2u;
    if (denominator == 0u) {
        return 0;
    }
    while (d <= n / 2u) { /* shift-and-subtract division: no division routine linked in */
        d <<= 1;
        bit <<= 1;
    }
    for (; bit != 0u; d >>= 1, bit >>= 1) {
        if (n >= d) {
            n -= d;
            quotient |= bit;
        }
    }
    return (long)quotient;
}
