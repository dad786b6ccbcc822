/*
 * startup.c - a bare-metal Cortex-M runtime for the target tests: the vector
 * table, the reset handler (copy .data, zero .bss, enable the FPU, run main,
 * report through semihosting) and semihosting output. Nothing here is part of
 * libhkf, which needs no runtime at all.
 */
#include <stdint.h>

#include "semihosting.h"

extern uint32_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[], __stack_top[];
int main(void);

static int semihosting_call(int operation, const void *argument)
{
    register int r0 __asm__("r0") = operation;
    register const void *r1 __asm__("r1") = argument;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void semihosting_write(const char *text)
{
    (void)semihosting_call(0x04, text); /* SYS_WRITE0 */
}

void semihosting_write_int(long value)
{
    char digits[24];
    int i = (int)sizeof digits - 1;
    unsigned long magnitude = value < 0 ? 0ul - (unsigned long)value : (unsigned long)value;
    digits[i] = '\0';
    do {
        digits[--i] = (char)('0' + magnitude % 10u);
        magnitude /= 10u;
    } while (magnitude != 0u);
    if (value < 0) {
        digits[--i] = '-';
    }
    semihosting_write(&digits[i]);
}

void semihosting_exit(int success)
{
    /* SYS_EXIT with ADP_Stopped_ApplicationExit (exit status 0) or RunTimeErrorUnknown (1) */
    (void)semihosting_call(0x18, (const void *)(uintptr_t)(success ? 0x20026u : 0x20023u));
    for (;;) {
    }
}

void reset_handler(void);
void reset_handler(void)
{
    uint32_t *from = __data_load, *to = __data_start;
    while (to < __data_end) {
        *to++ = *from++;
    }
    for (to = __bss_start; to < __bss_end; ++to) {
        *to = 0;
    }
#if defined(__ARM_FP)
    /* CPACR: full access to coprocessors 10 and 11, the FPU */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    semihosting_exit(main() == 0);
}

static void fault_handler(void)
{
    semihosting_write("target: fault\n");
    semihosting_exit(0);
}

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(uintptr_t)__stack_top, reset_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, 0, 0, 0, 0, fault_handler, fault_handler, 0, fault_handler, fault_handler,
};
