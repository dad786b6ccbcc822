/* cpu_level_mask.c - plays a CPU of a lower instruction-set level to a program that asks the CPU itself
 * (the CPUID instruction) what it has, as onnxruntime's kernels do: preloaded (LD_PRELOAD) with
 * HKF_PLAY_CPUID_LEVEL=avx2, avx (AVX without AVX2, FMA or F16C: Sandy Bridge) or sse4_2 (x86-64-v2: no AVX), it turns on the kernel's CPUID faulting (arch_prctl ARCH_SET_CPUID, on
 * CPUs whose /proc/cpuinfo flags say cpuid_fault) before the program's own code runs, and answers each CPUID
 * the program then executes from the signal handler: the real answer with the features above the level
 * cleared. Threads inherit the faulting; an execve ends it (a program the preloaded one starts is preloaded
 * again through the environment).
 * Without the variable, or with "off", it does nothing. A level it does not know, or a CPU without CPUID
 * faulting, ends the program (exit 3) with a message: a figure "at avx2" must never be the full level's.
 * Only x86-64 Linux. */
#define _GNU_SOURCE
#include <asm/prctl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <ucontext.h>
#include <unistd.h>

enum level { LEVEL_AVX2, LEVEL_AVX, LEVEL_SSE4_2 };
static enum level played;

/* The features a CPU of the played level lacks, by leaf (Intel SDM vol. 2A, CPUID). */
static void clear_above_level(uint32_t leaf, uint32_t subleaf, uint32_t r[4] /* eax ebx ecx edx */)
{
    if (leaf == 7 && subleaf == 0) {
        r[1] &= ~((1u << 16) | (1u << 17) | (1u << 21) | (1u << 26) | (1u << 27) | (1u << 28) | (1u << 30) |
                  (1u << 31));  /* AVX512 F, DQ, IFMA, PF, ER, CD, BW, VL */
        r[2] &= ~((1u << 1) | (1u << 6) | (1u << 11) | (1u << 12) | (1u << 14));  /* VBMI, VBMI2, VNNI, BITALG, VPOPCNTDQ */
        r[3] &= ~((1u << 2) | (1u << 3) | (1u << 8) | (1u << 23));  /* 4VNNIW, 4FMAPS, VP2INTERSECT, FP16 */
        if (played != LEVEL_AVX2) r[1] &= ~((1u << 5) | (1u << 3) | (1u << 8));  /* AVX2, BMI1, BMI2 */
    }
    if (leaf == 7 && subleaf == 1) r[0] &= ~((1u << 4) | (1u << 5));  /* AVX-VNNI, AVX512_BF16 */
    if (leaf == 1 && played == LEVEL_AVX) r[2] &= ~((1u << 12) | (1u << 29));  /* FMA, F16C */
    if (leaf == 1 && played == LEVEL_SSE4_2)
        r[2] &= ~((1u << 12) | (1u << 28) | (1u << 29));  /* FMA, AVX, F16C */
}

static long set_cpuid_allowed(int allowed) { return syscall(SYS_arch_prctl, ARCH_SET_CPUID, allowed); }

/* A faulting CPUID (0F A2) answered: executed with faulting off for the moment, masked, the instruction
 * skipped. Any other fault: the default action, as if the handler were not there. */
static void on_fault(int sig, siginfo_t *info, void *context)
{
    (void)info;
    ucontext_t *uc = context;
    greg_t *g = uc->uc_mcontext.gregs;
    const unsigned char *at = (const unsigned char *)g[REG_RIP];
    if (at[0] != 0x0F || at[1] != 0xA2) {
        signal(sig, SIG_DFL);
        return;  /* the instruction faults again, now fatally */
    }
    uint32_t r[4], leaf = (uint32_t)g[REG_RAX], subleaf = (uint32_t)g[REG_RCX];
    set_cpuid_allowed(1);
    __asm__ volatile("cpuid" : "=a"(r[0]), "=b"(r[1]), "=c"(r[2]), "=d"(r[3]) : "a"(leaf), "c"(subleaf));
    set_cpuid_allowed(0);
    clear_above_level(leaf, subleaf, r);
    g[REG_RAX] = r[0];
    g[REG_RBX] = r[1];
    g[REG_RCX] = r[2];
    g[REG_RDX] = r[3];
    g[REG_RIP] += 2;
}

static void refuse(const char *why)
{
    fprintf(stderr, "cpu_level_mask: %s\n", why);
    _exit(3);
}

__attribute__((constructor)) static void start_masking(void)
{
    const char *name = getenv("HKF_PLAY_CPUID_LEVEL");
    if (name == NULL || name[0] == '\0' || strcmp(name, "off") == 0) return;
    if (strcmp(name, "avx2") == 0)
        played = LEVEL_AVX2;
    else if (strcmp(name, "avx") == 0)
        played = LEVEL_AVX;
    else if (strcmp(name, "sse4_2") == 0)
        played = LEVEL_SSE4_2;
    else
        refuse("HKF_PLAY_CPUID_LEVEL must be avx2, avx, sse4_2 or off");
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_sigaction = on_fault;
    action.sa_flags = SA_SIGINFO;
    sigemptyset(&action.sa_mask);
    if (sigaction(SIGSEGV, &action, NULL) != 0) refuse("cannot install its SIGSEGV handler");
    if (set_cpuid_allowed(0) != 0) refuse("this CPU or kernel has no CPUID faulting (no cpuid_fault in /proc/cpuinfo)");
}
