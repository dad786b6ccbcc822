/* The live view's door, feed and events (tools/view/): which requests are served, what a slow viewer
 * costs, what the page is sent. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "view_door.h"
#include "view_events.h"
#include "view_feed.h"
#include "view_listen.h"

static void door(view_door_t *d, const char *address)
{
    assert_int_equal(view_door_open(d, address, 7670), 0);
}

static void loopback_view_serves_only_its_own_host(void **state)
{
    view_door_t d;
    (void)state;
    door(&d, "127.0.0.1");
    assert_true(view_door_host_ok(&d, "127.0.0.1:7670"));
    assert_true(view_door_host_ok(&d, "localhost:7670"));
    assert_true(view_door_host_ok(&d, "127.0.0.2:7670"));
    assert_false(view_door_host_ok(&d, NULL));
    assert_false(view_door_host_ok(&d, "127.0.0.1"));           /* no port: port 80, not the view */
    assert_false(view_door_host_ok(&d, "127.0.0.1:7671"));
    assert_false(view_door_host_ok(&d, "127.0.0.1:7670x"));
    assert_false(view_door_host_ok(&d, "evil.example:7670"));   /* DNS rebinding: a name that resolves here */
    assert_false(view_door_host_ok(&d, "localhost.evil.example:7670"));
    assert_false(view_door_host_ok(&d, "192.168.1.5:7670"));    /* not loopback: not this view's address */
    assert_false(view_door_host_ok(&d, ":7670"));
}

static void every_address_view_takes_literals_not_names(void **state)
{
    view_door_t d, one;
    (void)state;
    door(&d, "0.0.0.0");
    assert_true(view_door_host_ok(&d, "192.168.1.5:7670"));
    assert_true(view_door_host_ok(&d, "localhost:7670"));
    assert_false(view_door_host_ok(&d, "gaming-pc.example:7670"));
    door(&one, "192.168.1.5");
    assert_true(view_door_host_ok(&one, "192.168.1.5:7670"));
    assert_false(view_door_host_ok(&one, "127.0.0.1:7670"));
    assert_false(view_door_host_ok(&one, "localhost:7670"));
}

static void origin_must_be_the_view_itself(void **state)
{
    view_door_t d;
    (void)state;
    door(&d, "127.0.0.1");
    assert_true(view_door_origin_ok(&d, NULL));
    assert_true(view_door_origin_ok(&d, "http://127.0.0.1:7670"));
    assert_false(view_door_origin_ok(&d, "http://evil.example"));
    assert_false(view_door_origin_ok(&d, "https://127.0.0.1:7670"));
    assert_false(view_door_origin_ok(&d, "null"));
    assert_false(view_door_origin_ok(&d, "http://127.0.0.1:7670/x"));
}

static void another_sites_subresource_is_refused(void **state)
{
    (void)state;
    assert_true(view_door_fetch_site_ok(NULL));
    assert_true(view_door_fetch_site_ok("same-origin"));
    assert_true(view_door_fetch_site_ok("none"));
    assert_false(view_door_fetch_site_ok("cross-site")); /* <img src=http://127.0.0.1:7670/picture.jpg> elsewhere */
    assert_false(view_door_fetch_site_ok("same-site"));
    assert_false(view_door_fetch_site_ok(""));
}

static void token_is_random_and_exact(void **state)
{
    view_door_t a, b;
    char wrong[VIEW_TOKEN_CHARS + 1];
    (void)state;
    door(&a, "127.0.0.1");
    door(&b, "127.0.0.1");
    assert_int_equal(strlen(a.token), VIEW_TOKEN_CHARS);
    assert_string_not_equal(a.token, b.token);
    assert_true(view_door_token_ok(&a, a.token));
    assert_false(view_door_token_ok(&a, b.token));
    assert_false(view_door_token_ok(&a, NULL));
    assert_false(view_door_token_ok(&a, ""));
    memcpy(wrong, a.token, sizeof wrong);
    wrong[VIEW_TOKEN_CHARS - 1] = wrong[VIEW_TOKEN_CHARS - 1] == '0' ? '1' : '0';
    assert_false(view_door_token_ok(&a, wrong));
    wrong[VIEW_TOKEN_CHARS - 1] = '\0';
    assert_false(view_door_token_ok(&a, wrong)); /* a prefix is not the token */
    assert_int_equal(view_door_open(&a, "localhost", 7670), -1); /* an address, not a name */
}

static void listen_text_is_read_as_documented(void **state)
{
    char host[64], reason[256];
    unsigned port = 0;
    (void)state;
    assert_int_equal(view_listen_parse("7670", host, sizeof host, &port, reason, sizeof reason), 0);
    assert_string_equal(host, "127.0.0.1");
    assert_int_equal(port, 7670);
    assert_int_equal(view_listen_parse("0.0.0.0:8000", host, sizeof host, &port, reason, sizeof reason), 0);
    assert_string_equal(host, "0.0.0.0");
    assert_int_equal(port, 8000);
    assert_int_equal(view_listen_parse("localhost:9", host, sizeof host, &port, reason, sizeof reason), 0);
    assert_string_equal(host, "127.0.0.1");
    assert_int_equal(view_listen_parse("0", host, sizeof host, &port, reason, sizeof reason), -1);
    assert_int_equal(view_listen_parse("70000", host, sizeof host, &port, reason, sizeof reason), -1);
    assert_int_equal(view_listen_parse("example.org:80", host, sizeof host, &port, reason, sizeof reason), -1);
    assert_int_equal(view_listen_parse(":80", host, sizeof host, &port, reason, sizeof reason), -1);
    assert_non_null(strstr(reason, "no host"));
}

static void slow_viewer_skips_ahead_and_never_blocks_the_writer(void **state)
{
    view_feed_t *feed = malloc(sizeof *feed);
    static char out[1 << 16];
    uint64_t cursor = 0;
    char json[64];
    long n;
    int i;
    (void)state;
    assert_int_equal(view_feed_init(feed), 0);
    for (i = 0; i < VIEW_FEED_EVENTS + 100; ++i) { /* a viewer that read nothing for a whole ring */
        snprintf(json, sizeof json, "{\"i\":%d}", i);
        view_feed_write(feed, json);
    }
    n = view_feed_read(feed, &cursor, out, sizeof out, 0);
    assert_true(n > 0);
    assert_int_equal(feed->skipped, 100);
    assert_memory_equal(out, "data: {\"i\":100}\n\n", 17); /* the oldest kept, whole */
    while (view_feed_read(feed, &cursor, out, sizeof out, 0) > 0) {
    }
    assert_int_equal(cursor, VIEW_FEED_EVENTS + 100);
    assert_int_equal(view_feed_read(feed, &cursor, out, sizeof out, 10), 0); /* nothing new: waits, then 0 */
    view_feed_close(feed);
    assert_int_equal(view_feed_read(feed, &cursor, out, sizeof out, 1000), -1);
    view_feed_destroy(feed);
    free(feed);
}

static void events_are_json_without_nan(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t p;
    char out[VIEW_FEED_EVENT_SIZE];
    (void)state;
    memset(&m, 0, sizeof m);
    m.model = (char *)"mesh\"pnp";
    m.valid = 1;
    m.pitch = NAN;
    m.yaw = 12.5f;
    m.roll = INFINITY;
    assert_true(view_event_raw(&m, out, sizeof out) > 0);
    assert_non_null(strstr(out, "\"model\":\"mesh\\\"pnp\""));
    assert_non_null(strstr(out, "\"pitch\":null"));
    assert_non_null(strstr(out, "\"yaw\":12.5"));
    assert_non_null(strstr(out, "\"roll\":null"));
    assert_null(strstr(out, "nan"));
    memset(&p, 0, sizeof p);
    p.status = HKF_HEAD_POSE_T_COASTING;
    p.latency_us = 23500;
    assert_true(view_event_pose(&p, out, sizeof out) > 0);
    assert_non_null(strstr(out, "\"status\":\"COASTING\""));
    assert_non_null(strstr(out, "\"latency_ms\":23.5"));
    p.yaw = 15.0f;
    p.center[1] = 10.0f;
    assert_true(view_event_pose(&p, out, sizeof out) > 0);
    assert_non_null(strstr(out, "\"from_center\":[0,5,0]")); /* as hkf-track's line and opentrack take it */
    /* the longest each event can be still fits one slot of the feed: every number at its widest */
    p.utime = p.seq = p.latency_us = INT64_MIN;
    p.pitch = p.yaw = p.roll = p.x = p.y = p.z = -1.2345e-38f;
    p.center[0] = p.center[1] = p.center[2] = -1.2345e-38f;
    assert_true(view_event_pose(&p, out, sizeof out) > 0);
    m.model = (char *)"\x01\x02\x03\x04\x05\x06\x07\x08\x01\x02\x03\x04\x05\x06\x07\x08"
                      "\x01\x02\x03\x04\x05\x06\x07\x08\x01\x02\x03\x04\x05\x06\x07"; /* 31: MODEL_NAME_MAX */
    m.utime = m.seq = INT64_MIN;
    m.pitch = m.yaw = m.roll = m.z = -1.2345e-38f;
    m.face_box[0] = m.face_box[1] = m.face_box[2] = m.face_box[3] = -1.2345e-38f;
    assert_true(view_event_raw(&m, out, sizeof out) > 0);
    {
        hkf_tracker_status_t s;
        memset(&s, 0, sizeof s);
        s.rest = HKF_TRACKER_STATUS_T_MEASURED;
        s.rest_progress = s.rest_time = s.stillness = s.wander = -1.2345e-38f;
        s.rests_spoiled = s.commands = s.settings_saved = s.settings_unsaved = INT32_MIN;
        s.rest_spread[0] = s.rest_spread[1] = s.rest_spread[2] = -1.2345e-38f;
        s.rest_noise[0] = s.rest_noise[1] = s.rest_noise[2] = -1.2345e-38f;
        assert_true(view_event_status(&s, out, sizeof out) > 0);
    }
    assert_true(view_event_line("a\tb\n", out, sizeof out) > 0);
    assert_string_equal(out, "{\"t\":\"line\",\"text\":\"a\\u0009b\\u000a\"}");
    assert_int_equal(view_event_line("too long", out, 10), 0); /* cut short: nothing half-written is sent */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(loopback_view_serves_only_its_own_host),
        cmocka_unit_test(every_address_view_takes_literals_not_names),
        cmocka_unit_test(origin_must_be_the_view_itself),
        cmocka_unit_test(another_sites_subresource_is_refused),
        cmocka_unit_test(token_is_random_and_exact),
        cmocka_unit_test(listen_text_is_read_as_documented),
        cmocka_unit_test(slow_viewer_skips_ahead_and_never_blocks_the_writer),
        cmocka_unit_test(events_are_json_without_nan),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
