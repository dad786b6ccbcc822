/*
 * instruction_counter.h - instructions spent in a stretch of code on a
 * Cortex-M target under qemu -icount, where every instruction advances the
 * clock by the same time: SysTick counts the clock, and a loop of known
 * length calibrates ticks per instruction. (Not cycles: qemu models no
 * pipeline; dev/benchmarks/cortex_m4_cycles.py estimates those.)
 */
#ifndef HKF_INSTRUCTION_COUNTER_H
#define HKF_INSTRUCTION_COUNTER_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Starts SysTick and measures the ticks of 200,000 instructions. */
void counter_start(void);
/* SysTick's current value (one load, inline: it adds little to what it
 * measures). It counts down; ticks between two readings are
 * counter_ticks(earlier, later). */
static inline uint32_t counter_now(void) { return *(volatile uint32_t *)0xE000E018u; }
static inline uint32_t counter_ticks(uint32_t earlier, uint32_t later) { return (earlier - later) & 0x00FFFFFFu; }
/* Instructions per call for `calls` calls that took `ticks` in all, rounded. */
long counter_instructions_per_call(uint32_t ticks, uint32_t calls);
/* The calibration: ticks for 200,000 instructions. */
uint32_t counter_calibration_ticks(void);

#ifdef __cplusplus
}
#endif

#endif
