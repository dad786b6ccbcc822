/*
 * test_lcm_file_url.c - the file:// rules (messages/lcm_file_url.h) with
 * LCM's real file provider: a URL's mode read as lcm_parse_url reads it;
 * inputs a regular file, outputs none of the run's files and no named pipe
 * or device; and a log read back after lcm_destroy holds every event
 * published, or the loss is reported.
 */
#define _XOPEN_SOURCE 700
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "hkf_tracker_command_t.h"
#include "lcm_file_url.h"
#include "safe_files.h"

static char folder[] = "/tmp/hkf_file_url_XXXXXX";

static int make_folder(void **state)
{
    (void)state;
    return mkdtemp(folder) == NULL ? -1 : 0;
}

static int remove_folder(void **state)
{
    char command[128];
    (void)state;
    snprintf(command, sizeof command, "rm -rf '%s'", folder);
    return system(command) == 0 ? 0 : -1;
}

/* The URL of `name` in the test's folder, with `options` after it. */
static const char *url_of(const char *name, const char *options)
{
    static char url[512];
    snprintf(url, sizeof url, "file://%s/%s%s", folder, name, options);
    return url;
}

static void test_parse_modes(void **state)
{
    lcm_file_url_t u;
    (void)state;
    assert_int_equal(lcm_file_url_parse("udpm://239.255.76.67:7667?ttl=0", &u), 0);
    assert_false(u.is_file);
    assert_int_equal(lcm_file_url_parse("file:///a/b.lcmlog", &u), 0);
    assert_true(u.is_file && !u.writes);
    assert_string_equal(u.path, "/a/b.lcmlog");
    assert_int_equal(lcm_file_url_parse("file://rel.lcmlog?speed=0&mode=w", &u), 0);
    assert_true(u.writes && !u.appends);
    assert_string_equal(u.path, "rel.lcmlog");
    assert_int_equal(lcm_file_url_parse("file://x?mode=a", &u), 0);
    assert_true(u.writes && u.appends);
    assert_int_equal(lcm_file_url_parse("file://x?mode=w?mode=r", &u), 0); /* the last counts */
    assert_false(u.writes);
    assert_int_equal(lcm_file_url_parse("file://x?mode=wx", &u), 0); /* LCM reads an unknown mode as r */
    assert_false(u.writes);
}

static void test_check_refuses(void **state)
{
    lcm_file_url_t u;
    char input[256], fifo[256];
    const char *keep[1];
    FILE *f;
    (void)state;
    snprintf(input, sizeof input, "%s/in.lcmlog", folder);
    snprintf(fifo, sizeof fifo, "%s/fifo", folder);
    f = fopen(input, "w");
    assert_non_null(f);
    fclose(f);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    keep[0] = input;
    assert_int_equal(lcm_file_url_check(url_of("in.lcmlog", ""), "input", NULL, 0, "test", &u), 0);
    assert_int_equal(lcm_file_url_check(url_of("missing.lcmlog", ""), "input", NULL, 0, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("in.lcmlog", "?mode=w"), "input", NULL, 0, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("fifo", ""), "input", NULL, 0, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("out.lcmlog", "?mode=w"), "output", keep, 1, "test", &u), 0);
    assert_int_equal(lcm_file_url_check(url_of("in.lcmlog", "?mode=w"), "output", keep, 1, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("./in.lcmlog", "?mode=a"), "output", keep, 1, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("out.lcmlog", ""), "output", keep, 1, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("fifo", "?mode=w"), "output", NULL, 0, "test", &u), -1);
    assert_int_equal(lcm_file_url_check("file:///dev/full?mode=w", "output", NULL, 0, "test", &u), -1);
    assert_int_equal(lcm_file_url_check("memq://", "output", keep, 1, "test", &u), 0);
    assert_int_equal(lcm_file_url_verify(&u, 5, "test"), 0); /* not a file: nothing to read back */
}

/* Round 4: an output is never a file inside an input folder (a source folder of images, a dataset),
 * at any depth, existing or not, through links; never a file that is not an LCM log; '' resolves as
 * LCM resolves it ($LCM_DEFAULT_URL, then LCM's own default), and that URL is checked. */
static void test_folders_logs_and_the_default_url(void **state)
{
    lcm_file_url_t u;
    char images[256], image[256], deeper[256], link[256], path[600];
    const char *keep[1];
    FILE *f;
    (void)state;
    snprintf(images, sizeof images, "%s/images", folder);
    snprintf(deeper, sizeof deeper, "%s/images/more", folder);
    snprintf(image, sizeof image, "%s/images/image00002.jpg", folder);
    snprintf(link, sizeof link, "%s/images_link", folder);
    assert_int_equal(mkdir(images, 0700), 0);
    assert_int_equal(mkdir(deeper, 0700), 0);
    assert_int_equal(symlink(images, link), 0);
    f = fopen(image, "w");
    assert_non_null(f);
    assert_true(fputs("\xff\xd8\xff not an LCM log", f) >= 0);
    assert_int_equal(fclose(f), 0);
    keep[0] = images;
    assert_true(safe_writes_over(image, images));
    snprintf(path, sizeof path, "%s/new.lcmlog", deeper);
    assert_true(safe_writes_over(path, images)); /* new, two folders down */
    snprintf(path, sizeof path, "%s/image00002.jpg", link);
    assert_true(safe_writes_over(path, images)); /* through a link */
    snprintf(path, sizeof path, "%s/images.lcmlog", folder);
    assert_false(safe_writes_over(path, images)); /* beside it: a name that starts alike */
    assert_int_equal(lcm_file_url_check(url_of("images/image00002.jpg", "?mode=w"), "output", keep, 1, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("images/more/x.lcmlog", "?mode=w"), "output", keep, 1, "test", &u), -1);
    assert_int_equal(lcm_file_url_check(url_of("images.lcmlog", "?mode=w"), "output", keep, 1, "test", &u), 0);
    assert_int_equal(lcm_file_url_check(url_of("images/image00002.jpg", "?mode=w"), "output", NULL, 0, "test", &u), -1);
    assert_null(safe_open_output(image, "w", keep, 1, "test"));
    assert_int_equal(setenv("LCM_DEFAULT_URL", url_of("images/image00002.jpg", "?mode=w"), 1), 0);
    assert_string_equal(lcm_url_resolve(""), url_of("images/image00002.jpg", "?mode=w"));
    assert_string_equal(lcm_url_resolve(NULL), url_of("images/image00002.jpg", "?mode=w"));
    assert_string_equal(lcm_url_resolve("memq://"), "memq://");
    assert_int_equal(lcm_file_url_check("", "output", keep, 1, "test", &u), -1);
    assert_int_equal(setenv("LCM_DEFAULT_URL", "", 1), 0);
    assert_string_equal(lcm_url_resolve(""), LCM_URL_DEFAULT);
    assert_int_equal(unsetenv("LCM_DEFAULT_URL"), 0);
    assert_string_equal(lcm_url_resolve(""), LCM_URL_DEFAULT);
    f = fopen(image, "rb");
    assert_non_null(f);
    assert_int_equal(fgetc(f), 0xff); /* untouched */
    assert_int_equal(fclose(f), 0);
}

/* Publishes n commands through LCM's file provider at url; returns how many LCM took. */
static unsigned long publish(const char *url, int n)
{
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    lcm_t *lcm = lcm_create(url);
    unsigned long taken = 0;
    int i;
    assert_non_null(lcm);
    for (i = 0; i < n; ++i) {
        command.utime = i;
        taken += hkf_tracker_command_t_publish(lcm, "HEAD_TRACKER_CMD", &command) == 0;
    }
    lcm_destroy(lcm);
    return taken;
}

static void test_verify_counts_events(void **state)
{
    lcm_file_url_t u;
    struct rlimit limit, small;
    unsigned long taken;
    (void)state;
    assert_int_equal(lcm_file_url_check(url_of("log.lcmlog", "?mode=w"), "output", NULL, 0, "test", &u), 0);
    taken = publish(url_of("log.lcmlog", "?mode=w"), 40);
    assert_int_equal(taken, 40);
    assert_int_equal(lcm_file_url_verify(&u, taken, "test"), 0);
    assert_int_equal(lcm_file_url_verify(&u, taken + 1, "test"), -1); /* one more than is there */
    assert_int_equal(lcm_file_url_check(url_of("log.lcmlog", "?mode=a"), "output", NULL, 0, "test", &u), 0);
    assert_int_equal(u.events_before, 40);
    taken = publish(url_of("log.lcmlog", "?mode=a"), 10);
    assert_int_equal(lcm_file_url_verify(&u, taken, "test"), 0);
    /* a file-size limit of 1 KB: LCM says every publish went well, the log says otherwise */
    safe_files_fail_writes_past_size_limit();
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &limit), 0);
    small = limit;
    small.rlim_cur = 1024;
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &small), 0);
    assert_int_equal(lcm_file_url_check(url_of("cut.lcmlog", "?mode=w"), "output", NULL, 0, "test", &u), 0);
    taken = publish(url_of("cut.lcmlog", "?mode=w"), 200);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &limit), 0);
    assert_int_equal(taken, 200);
    assert_int_equal(lcm_file_url_verify(&u, taken, "test"), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_modes),
        cmocka_unit_test(test_check_refuses),
        cmocka_unit_test(test_folders_logs_and_the_default_url),
        cmocka_unit_test(test_verify_counts_events),
    };
    return cmocka_run_group_tests(tests, make_folder, remove_folder);
}
