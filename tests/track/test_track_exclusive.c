/* test_track_exclusive.c - one hkf-track per LCM group (tools/track/track_exclusive.c): the claim is keyed
 * on what LCM will use (udpm's group and port, its defaults filled in), not on the URL's text, and a key
 * too long for a socket's name is hashed, not cut. Real abstract sockets are bound, as hkf-track binds
 * them (names this test makes its own with an unused port). */
#define _XOPEN_SOURCE 700
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "track_exclusive.h"

static char folders[8][64];

static int setup(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < 8; ++i) {
        snprintf(folders[i], sizeof folders[i], "/tmp/hkf-exclusive-XXXXXX");
        if (mkdtemp(folders[i]) == NULL) {
            return -1;
        }
    }
    return 0;
}

static int teardown(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < 8; ++i) {
        rmdir(folders[i]);
    }
    return 0;
}

/* One group and port under three spellings is one claim; another port is another. */
static void test_one_group_one_claim(void **state)
{
    track_exclusive_t first, second;
    (void)state;
    assert_int_equal(track_exclusive_claim(&first, "udpm://239.255.76.67:17667?ttl=0", folders[0]), 0);
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.76.67:17667", folders[1]), -1);
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.76.67:17667?ttl=1&recv_buf_size=2097152", folders[1]), -1);
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.076.67:17667", folders[1]), 0); /* not the same text */
    track_exclusive_release(&second);
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.76.67:17668?ttl=0", folders[1]), 0);
    track_exclusive_release(&second);
    track_exclusive_release(&first);
    /* LCM's defaults: an empty group and port are 239.255.76.67:7667 */
    assert_int_equal(track_exclusive_claim(&first, "udpm://", folders[2]), 0);
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.76.67:7667?ttl=0", folders[3]), -1);
    assert_int_equal(track_exclusive_claim(&second, "udpm://:7667", folders[3]), -1);
    track_exclusive_release(&first);
}

/* Hardening round 6, item 4: LCM reads the port with strtol(..., 0) and ignores what follows it, and the group
 * with inet_aton (checked by binding in a private network namespace: 0x1df3, " +7667", 7667abc and 7667.5 bind
 * 7667, 07667 binds 4023, so 016763 is 7667): each spelling of one port is one claim; a port LCM refuses is keyed on its text. */
static void test_port_spelled_as_lcm_reads_it(void **state)
{
    static const char *const same[] = {"udpm://239.255.76.67:0x1df3?ttl=0", "udpm://239.255.76.67:7667abc?ttl=0",
                                       "udpm://239.255.76.67: +7667?ttl=0", "udpm://239.255.76.67:7667.5",
                                       "udpm://239.255.76.67:016763", "udpm://0xefff4c43:7667?ttl=0"};
    track_exclusive_t first, second;
    size_t i;
    (void)state;
    assert_int_equal(track_exclusive_claim(&first, "udpm://239.255.76.67:7667?ttl=0", folders[0]), 0);
    for (i = 0; i < sizeof same / sizeof same[0]; ++i) {
        print_message("%s: the same port\n", same[i]);
        assert_int_equal(track_exclusive_claim(&second, same[i], folders[1]), -1);
    }
    assert_int_equal(track_exclusive_claim(&second, "udpm://239.255.76.67:07667?ttl=0", folders[1]), 0); /* 4023 */
    track_exclusive_release(&second);
    track_exclusive_release(&first);
}

/* Two URLs longer than a socket's name that differ only at their end are two claims. */
static void test_long_urls_hashed_not_cut(void **state)
{
    char a[300], b[300];
    track_exclusive_t first, second, again;
    (void)state;
    memset(a, 0, sizeof a);
    strcpy(a, "tcpq://127.0.0.1:17700?");
    memset(a + strlen(a), 'x', 200);
    strcpy(b, a);
    strcat(a, "1");
    strcat(b, "2");
    assert_int_equal(track_exclusive_claim(&first, a, folders[4]), 0);
    assert_int_equal(track_exclusive_claim(&second, b, folders[5]), 0);
    assert_int_equal(track_exclusive_claim(&again, a, folders[6]), -1); /* the same long URL: refused */
    track_exclusive_release(&second);
    track_exclusive_release(&first);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_group_one_claim),
        cmocka_unit_test(test_port_spelled_as_lcm_reads_it),
        cmocka_unit_test(test_long_urls_hashed_not_cut),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
