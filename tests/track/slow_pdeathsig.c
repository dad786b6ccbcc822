/* slow_pdeathsig.c - an LD_PRELOAD shim for track_test.sh: prctl(PR_SET_PDEATHSIG) waits 0.5 s before it
 * asks, so that hkf-track can be killed between a child's fork and its request for the parent-death
 * signal, the window where a child used to become an orphan (docs/reliability.md, round 5, item 8). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdarg.h>
#include <sys/prctl.h>
#include <time.h>

int prctl(int option, ...)
{
    static int (*real)(int, ...);
    unsigned long a[4];
    va_list ap;
    int i;
    va_start(ap, option);
    for (i = 0; i < 4; ++i) {
        a[i] = va_arg(ap, unsigned long);
    }
    va_end(ap);
    if (real == NULL) {
        *(void **)&real = dlsym(RTLD_NEXT, "prctl");
    }
    if (option == PR_SET_PDEATHSIG) {
        const struct timespec wait = {0, 500000000L};
        nanosleep(&wait, NULL);
    }
    return real(option, a[0], a[1], a[2], a[3]);
}
