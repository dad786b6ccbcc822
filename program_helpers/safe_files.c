/* safe_files.c - see safe_files.h. */
#define _XOPEN_SOURCE 700

#include "safe_files.h"

#include <errno.h>
#include <signal.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind_of(mode_t mode)
{
    return S_ISFIFO(mode) ? "a named pipe" : S_ISDIR(mode) ? "a folder" : S_ISCHR(mode) ? "a character device"
         : S_ISBLK(mode) ? "a block device" : S_ISSOCK(mode) ? "a socket" : "not a regular file";
}

FILE *safe_open_input(const char *path, char *error, size_t error_size)
{
    struct stat st;
    FILE *f;
    /* O_NONBLOCK: opening a named pipe does not wait for a writer; fstat then tells what it is */
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(error, error_size, "cannot read '%s': %s", path, strerror(errno));
        return NULL;
    }
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(error, error_size, "'%s' is %s, not a regular file", path,
                 fstat(fd, &st) != 0 ? "unreadable" : kind_of(st.st_mode));
        close(fd);
        return NULL;
    }
    if (fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0 || (f = fdopen(fd, "rb")) == NULL) {
        snprintf(error, error_size, "cannot read '%s': %s", path, strerror(errno));
        close(fd);
        return NULL;
    }
    return f;
}

/* The absolute path of path's folder joined with its last name, for a file
 * that does not exist yet; 0 on success. */
static int resolved_name(const char *path, char *out, size_t size)
{
    char a[PATH_MAX], b[PATH_MAX], folder[PATH_MAX];
    if (strlen(path) >= sizeof a) {
        return -1;
    }
    strcpy(a, path);
    strcpy(b, path);
    if (realpath(dirname(a), folder) == NULL) {
        return -1;
    }
    return snprintf(out, size, "%s/%s", folder, basename(b)) < (int)size ? 0 : -1;
}

int safe_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    char ra[PATH_MAX + NAME_MAX + 2], rb[PATH_MAX + NAME_MAX + 2];
    const int has_a = stat(a, &sa) == 0, has_b = stat(b, &sb) == 0;
    if (has_a && has_b) {
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    }
    if (has_a != has_b) {
        return 0;
    }
    return resolved_name(a, ra, sizeof ra) == 0 && resolved_name(b, rb, sizeof rb) == 0 && strcmp(ra, rb) == 0;
}

/* The absolute name of path with every link of its folders resolved (and of itself, when it
 * exists); 0 on success. */
static int absolute_name(const char *path, char *out, size_t size)
{
    char full[PATH_MAX];
    if (realpath(path, full) != NULL) {
        return snprintf(out, size, "%s", full) < (int)size ? 0 : -1;
    }
    return resolved_name(path, out, size);
}

int safe_writes_over(const char *path, const char *input)
{
    struct stat st;
    char folder[PATH_MAX], name[PATH_MAX + NAME_MAX + 2];
    size_t length;
    if (safe_same_file(path, input)) {
        return 1;
    }
    if (stat(input, &st) != 0 || !S_ISDIR(st.st_mode) || realpath(input, folder) == NULL ||
        absolute_name(path, name, sizeof name) != 0) {
        return 0;
    }
    length = strlen(folder);
    if (length > 0 && folder[length - 1] == '/') {
        --length; /* the root folder: every file is inside it */
    }
    return strncmp(name, folder, length) == 0 && name[length] == '/';
}

int safe_is_regular_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

FILE *safe_open_output(const char *path, const char *mode, const char *const *keep, int count, const char *program)
{
    struct stat st;
    FILE *f;
    int i, fd;
    for (i = 0; i < count; ++i) {
        if (keep[i] != NULL && safe_writes_over(path, keep[i])) {
            fprintf(stderr, "%s: '%s' is %s '%s', which this run reads or writes; refusing to write over it\n",
                    program, path, safe_same_file(path, keep[i]) ? "also" : "inside", keep[i]);
            return NULL;
        }
    }
    fd = open(path, O_WRONLY | O_CREAT | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd < 0) {
        fprintf(stderr, "%s: cannot write '%s': %s%s\n", program, path, strerror(errno),
                errno == ENXIO ? " (a named pipe that nothing reads)" : "");
        return NULL;
    }
    if (fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
        fprintf(stderr, "%s: cannot write '%s': a folder\n", program, path);
        close(fd);
        return NULL;
    }
    /* truncated only now: after every check, and only a regular file */
    if ((S_ISREG(st.st_mode) && ftruncate(fd, 0) != 0) || fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0 ||
        (f = fdopen(fd, mode)) == NULL) {
        fprintf(stderr, "%s: cannot write '%s': %s\n", program, path, strerror(errno));
        close(fd);
        return NULL;
    }
    return f;
}

int safe_close(FILE *f)
{
    struct stat st;
    int failed = ferror(f) != 0;
    failed |= fflush(f) != 0;
    if (!failed && fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)) {
        failed |= fsync(fileno(f)) != 0;
    }
    failed |= fclose(f) != 0;
    return failed ? -1 : 0;
}

void safe_files_fail_writes_past_size_limit(void)
{
    signal(SIGXFSZ, SIG_IGN);
}
