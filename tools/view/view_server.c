/* view_server.c - see view_server.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>

#include <microhttpd.h>

#define ASSET_MAX_SIZE (1024 * 1024)
#define STREAM_BLOCK 32768
#define STREAM_WAIT_MS 250 /* a keep-alive comment after this long without an event: a viewer gone is found soon */

static const view_asset_t kAssets[VIEW_ASSETS] = {
    {"/", "index.html", "text/html; charset=utf-8", NULL, 0},
    {"/view.js", "view.js", "text/javascript; charset=utf-8", NULL, 0},
    {"/view.css", "view.css", "text/css; charset=utf-8", NULL, 0},
};

/* folder/name read whole into a new buffer; NULL (said) when missing, unreadable or over the limit. */
static char *read_asset(const char *folder, const char *name, size_t *size)
{
    char path[4096];
    FILE *f;
    char *body;
    snprintf(path, sizeof path, "%s/%s", folder, name);
    f = fopen(path, "rb");
    body = f != NULL ? malloc(ASSET_MAX_SIZE + 1) : NULL;
    if (body == NULL) {
        fprintf(stderr, "hkf-view: cannot read the page's asset %s (--assets DIR)\n", path);
        if (f != NULL) (void)fclose(f);
        return NULL;
    }
    *size = fread(body, 1, ASSET_MAX_SIZE + 1, f);
    if (ferror(f) || fclose(f) != 0 || *size > ASSET_MAX_SIZE) {
        fprintf(stderr, "hkf-view: %s is unreadable or over 1 MiB\n", path);
        free(body);
        return NULL;
    }
    body[*size] = '\0';
    return body;
}

/* Each "@TOKEN@" in the page replaced by the run's token (the page rewritten into a new buffer). */
static int put_token(view_asset_t *page, const char *token)
{
    const char *mark = "@TOKEN@";
    char *at;
    while ((at = strstr(page->body, mark)) != NULL) {
        const size_t before = (size_t)(at - page->body), after = page->size - before - strlen(mark);
        char *body = malloc(before + strlen(token) + after + 1);
        if (body == NULL) return -1;
        memcpy(body, page->body, before);
        memcpy(body + before, token, strlen(token));
        memcpy(body + before + strlen(token), at + strlen(mark), after + 1);
        free(page->body);
        page->body = body;
        page->size = before + strlen(token) + after;
    }
    return 0;
}

static int load_assets(view_server_t *s, const char *folder)
{
    int i;
    for (i = 0; i < VIEW_ASSETS; ++i) {
        s->asset[i] = kAssets[i];
        s->asset[i].body = read_asset(folder, kAssets[i].file, &s->asset[i].size);
        if (s->asset[i].body == NULL) return -1;
    }
    return put_token(&s->asset[0], s->door.token);
}

static void count(view_server_t *s, long *counter, int *gauge, int by)
{
    pthread_mutex_lock(&s->lock);
    if (counter != NULL) *counter += by;
    if (gauge != NULL) *gauge += by;
    pthread_mutex_unlock(&s->lock);
}

static enum MHD_Result answer(struct MHD_Connection *c, unsigned code, const char *type, const void *body,
                              size_t size, enum MHD_ResponseMemoryMode mode)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(size, (void *)body, mode);
    enum MHD_Result result;
    if (r == NULL) return MHD_NO;
    (void)MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, type);
    (void)MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    (void)MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    (void)MHD_add_response_header(r, "X-Frame-Options", "DENY");
    (void)MHD_add_response_header(r, "Cross-Origin-Resource-Policy", "same-origin");
    (void)MHD_add_response_header(r, "Content-Security-Policy",
                                  "default-src 'self'; img-src 'self'; connect-src 'self'; frame-ancestors 'none'");
    result = MHD_queue_response(c, code, r);
    MHD_destroy_response(r);
    return result;
}

static enum MHD_Result say(struct MHD_Connection *c, unsigned code, const char *text)
{
    return answer(c, code, "text/plain; charset=utf-8", text, strlen(text), MHD_RESPMEM_MUST_COPY);
}

typedef struct {
    view_server_t *server;
    uint64_t cursor;
} stream_t;

static ssize_t stream_events(void *cls, uint64_t pos, char *buf, size_t max)
{
    stream_t *stream = cls;
    long n = view_feed_read(stream->server->feed, &stream->cursor, buf, max, STREAM_WAIT_MS);
    (void)pos;
    if (n < 0) return MHD_CONTENT_READER_END_OF_STREAM;
    if (n == 0 && max >= 3) {
        memcpy(buf, ":\n\n", 3); /* a comment: keeps the connection, and finds a viewer that has gone */
        return 3;
    }
    return n;
}

static void stream_ended(void *cls)
{
    stream_t *stream = cls;
    count(stream->server, NULL, &stream->server->viewers, -1);
    free(stream);
}

/* GET /events: the feed from ~10 s back (the page's traces), as long as the viewer stays. */
static enum MHD_Result open_stream(view_server_t *s, struct MHD_Connection *c)
{
    struct MHD_Response *r;
    stream_t *stream;
    enum MHD_Result result;
    pthread_mutex_lock(&s->lock);
    if (s->viewers >= s->max_viewers) {
        pthread_mutex_unlock(&s->lock);
        return say(c, MHD_HTTP_SERVICE_UNAVAILABLE, "hkf-view: too many viewers\n");
    }
    ++s->viewers;
    pthread_mutex_unlock(&s->lock);
    stream = calloc(1, sizeof *stream);
    r = stream != NULL ? MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, STREAM_BLOCK, stream_events, stream,
                                                             stream_ended)
                       : NULL;
    if (r == NULL) {
        free(stream);
        count(s, NULL, &s->viewers, -1);
        return MHD_NO;
    }
    stream->server = s;
    pthread_mutex_lock(&s->feed->lock);
    stream->cursor = s->feed->written > VIEW_FEED_EVENTS ? s->feed->written - VIEW_FEED_EVENTS : 0;
    pthread_mutex_unlock(&s->feed->lock);
    (void)MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, "text/event-stream");
    (void)MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
    result = MHD_queue_response(c, MHD_HTTP_OK, r);
    MHD_destroy_response(r);
    return result;
}

static enum MHD_Result send_picture(view_server_t *s, struct MHD_Connection *c)
{
    unsigned char *jpeg = malloc(VIEW_FEED_PICTURE_SIZE);
    size_t size = jpeg != NULL ? view_feed_picture(s->feed, jpeg, VIEW_FEED_PICTURE_SIZE) : 0;
    enum MHD_Result result;
    if (size == 0) {
        free(jpeg);
        return say(c, MHD_HTTP_NOT_FOUND, "hkf-view: no camera picture yet (the estimator sends them while a view is open)\n");
    }
    result = answer(c, MHD_HTTP_OK, "image/jpeg", jpeg, size, MHD_RESPMEM_MUST_COPY);
    free(jpeg);
    return result;
}

/* POST /command/VERB: the token first, then the verb and its value. */
static enum MHD_Result run_command(view_server_t *s, struct MHD_Connection *c, const char *verb)
{
    const char *value_text = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "value");
    char reason[256] = "", *end = NULL;
    double value = value_text != NULL ? strtod(value_text, &end) : 0.0;
    if (!view_door_token_ok(&s->door, MHD_lookup_connection_value(c, MHD_HEADER_KIND, "X-HKF-Token"))) {
        count(s, &s->refused, NULL, 1);
        return say(c, MHD_HTTP_FORBIDDEN, "hkf-view: a command needs the page's token\n");
    }
    if (value_text != NULL && (end == value_text || *end != '\0')) {
        return say(c, MHD_HTTP_BAD_REQUEST, "hkf-view: value is not a number\n");
    }
    if (s->command(s->command_user, verb, value, reason, sizeof reason) != 0) {
        return say(c, MHD_HTTP_BAD_REQUEST, reason);
    }
    count(s, &s->commands, NULL, 1);
    return say(c, MHD_HTTP_OK, "done\n");
}

static enum MHD_Result route(view_server_t *s, struct MHD_Connection *c, const char *url, const char *method)
{
    int i;
    if (strcmp(method, "POST") == 0) {
        return strncmp(url, "/command/", 9) == 0 ? run_command(s, c, url + 9)
                                                 : say(c, MHD_HTTP_NOT_FOUND, "hkf-view: no such command\n");
    }
    if (strcmp(method, "GET") != 0 && strcmp(method, "HEAD") != 0) {
        return say(c, MHD_HTTP_METHOD_NOT_ALLOWED, "hkf-view: GET or POST\n");
    }
    if (strcmp(url, "/events") == 0) return open_stream(s, c);
    if (strcmp(url, "/picture.jpg") == 0) return send_picture(s, c);
    for (i = 0; i < VIEW_ASSETS; ++i) {
        if (strcmp(url, s->asset[i].name) == 0) {
            return answer(c, MHD_HTTP_OK, s->asset[i].type, s->asset[i].body, s->asset[i].size, MHD_RESPMEM_PERSISTENT);
        }
    }
    return say(c, MHD_HTTP_NOT_FOUND, "hkf-view: not one of the page's files\n");
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                                  const char *version, const char *upload_data, size_t *upload_data_size, void **state)
{
    /* #lizard forgives: libmicrohttpd's access handler, whose 8 parameters are its signature */
    view_server_t *s = cls;
    static int seen; /* the first call per request only announces it (its headers are in) */
    (void)version;
    (void)upload_data;
    if (*state == NULL) {
        *state = &seen;
        return MHD_YES;
    }
    if (*upload_data_size != 0) {
        *upload_data_size = 0; /* a body is not read: commands carry none */
        return MHD_YES;
    }
    if (!view_door_host_ok(&s->door, MHD_lookup_connection_value(c, MHD_HEADER_KIND, MHD_HTTP_HEADER_HOST))) {
        count(s, &s->refused, NULL, 1);
        return say(c, 421, "hkf-view: this Host is not the view's own\n");
    }
    if (!view_door_origin_ok(&s->door, MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Origin")) ||
        !view_door_fetch_site_ok(MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Sec-Fetch-Site"))) {
        count(s, &s->refused, NULL, 1);
        return say(c, MHD_HTTP_FORBIDDEN, "hkf-view: requests from another site's page are refused\n");
    }
    return route(s, c, url, method);
}

int view_server_start(view_server_t *s, const char *folder, view_feed_t *feed, int max_viewers,
                      view_command_fn command, void *command_user)
{
    struct sockaddr_in address;
    s->feed = feed;
    s->max_viewers = max_viewers;
    s->command = command;
    s->command_user = command_user;
    s->viewers = 0;
    s->refused = s->commands = 0;
    memset(s->asset, 0, sizeof s->asset);
    if (pthread_mutex_init(&s->lock, NULL) != 0 || load_assets(s, folder) != 0) return -1;
    memset(&address, 0, sizeof address);
    address.sin_family = AF_INET;
    address.sin_port = htons((uint16_t)s->door.port);
    (void)inet_pton(AF_INET, s->door.address, &address.sin_addr);
    s->daemon = MHD_start_daemon(MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD,
                                 (uint16_t)s->door.port, NULL, NULL, on_request, s, MHD_OPTION_SOCK_ADDR, &address,
                                 MHD_OPTION_CONNECTION_LIMIT, (unsigned)(max_viewers + 8),
                                 MHD_OPTION_CONNECTION_TIMEOUT, 15u, MHD_OPTION_END);
    if (s->daemon == NULL) {
        fprintf(stderr, "hkf-view: cannot listen on %s:%u (in use, or not this host's address)\n", s->door.address,
                s->door.port);
        return -1;
    }
    return 0;
}

int view_server_viewers(view_server_t *s)
{
    int viewers;
    pthread_mutex_lock(&s->lock);
    viewers = s->viewers;
    pthread_mutex_unlock(&s->lock);
    return viewers;
}

void view_server_stop(view_server_t *s)
{
    int i;
    view_feed_close(s->feed);
    if (s->daemon != NULL) MHD_stop_daemon(s->daemon);
    s->daemon = NULL;
    for (i = 0; i < VIEW_ASSETS; ++i) {
        free(s->asset[i].body);
        s->asset[i].body = NULL;
    }
}
