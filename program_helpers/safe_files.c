/* safe_files.c - see safe_files.h. */
#define _XOPEN_SOURCE 700

#include "safe_files.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

static const char *kind_of(mode_t mode)
{
    return S_ISFIFO(mode) ? "a named pipe" : S_ISDIR(mode) ? "a folder" : S_ISCHR(mode) ? "a character device"
         : S_ISBLK(mode) ? "a block device" : S_ISSOCK(mode) ? "a socket" : "not a regular file";
}

/* The files this run reads, by device and inode (safe_note_read), with the name each was read under. */
struct read_file {
    dev_t dev;
    ino_t ino;
    char *name;
};
static struct read_file *read_files;
static size_t read_count, read_capacity;
static pthread_mutex_t read_lock = PTHREAD_MUTEX_INITIALIZER;

/* A file noted twice is listed twice: harmless for the lookup, and noting stays O(1) (a folder of N files). */
static void note_identity(const struct stat *st, const char *path)
{
    pthread_mutex_lock(&read_lock);
    if (read_count == read_capacity) {
        const size_t capacity = read_capacity == 0 ? 64 : 2 * read_capacity;
        struct read_file *grown = realloc(read_files, capacity * sizeof *grown);
        if (grown == NULL) { /* out of memory: the path rules still hold */
            pthread_mutex_unlock(&read_lock);
            return;
        }
        read_files = grown;
        read_capacity = capacity;
    }
    read_files[read_count].dev = st->st_dev;
    read_files[read_count].ino = st->st_ino;
    read_files[read_count].name = strdup(path);
    if (read_files[read_count].name != NULL) {
        ++read_count;
    }
    pthread_mutex_unlock(&read_lock);
}

/* Copies the name of the read file st is into name (1), or 0 when this run reads no such file. */
static int read_under(const struct stat *st, char *name, size_t size)
{
    size_t i;
    int found = 0;
    pthread_mutex_lock(&read_lock);
    for (i = 0; i < read_count && !found; ++i) {
        if (read_files[i].dev == st->st_dev && read_files[i].ino == st->st_ino) {
            snprintf(name, size, "%s", read_files[i].name);
            found = 1;
        }
    }
    pthread_mutex_unlock(&read_lock);
    return found;
}

void safe_note_read(const char *path)
{
    struct stat st;
    if (path != NULL && stat(path, &st) == 0 && !S_ISDIR(st.st_mode)) {
        note_identity(&st, path);
    }
}

/* Every regular file under folder, to a depth of 8 folders and at most 1,000,000 entries in all. */
static void note_tree(const char *folder, int depth, long *budget)
{
    DIR *dir;
    struct dirent *entry;
    char path[PATH_MAX];
    struct stat st;
    if (depth > 8 || (dir = opendir(folder)) == NULL) {
        return;
    }
    while (*budget > 0 && (entry = readdir(dir)) != NULL) {
        --*budget;
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0 ||
            snprintf(path, sizeof path, "%s/%s", folder, entry->d_name) >= (int)sizeof path || lstat(path, &st) != 0) {
            continue;
        }
        if (S_ISDIR(st.st_mode)) {
            note_tree(path, depth + 1, budget); /* a link to a folder is not followed: no loop */
        } else if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
            note_identity(&st, path);
        }
    }
    closedir(dir);
}

void safe_note_folder(const char *path)
{
    struct stat st;
    long budget = 1000000;
    if (path != NULL && stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        note_tree(path, 0, &budget);
    }
}

/* Filesystems whose files are the system's own state, not data on a disk (statfs's f_type, linux/magic.h). */
static int system_filesystem(long type)
{
    static const long kinds[] = {
        0x9fa0,     /* proc */
        0x62656572, /* sysfs */
        0x64626720, /* debugfs */
        0x74726163, /* tracefs */
        0x73636673, /* securityfs */
        0x27e0eb,   /* cgroup */
        0x63677270, /* cgroup2 */
        0xcafe4a11, /* bpf */
        0x6165676c, /* pstore */
        0x62656570, /* configfs */
        0xde5e81e4, /* efivarfs */
        0x1cd1,     /* devpts */
        0x65735543, /* fusectl */
    };
    size_t i;
    for (i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
        if (type == kinds[i]) {
            return 1;
        }
    }
    return 0;
}

/* safe_output_problem for what stat found (exists) or the folder the file would be made in. */
static int output_problem_of(const char *path, const struct stat *st, int exists, char *reason, size_t size)
{
    struct statfs fs;
    char folder[PATH_MAX], read_name[PATH_MAX];
    if (exists && (S_ISCHR(st->st_mode) || S_ISBLK(st->st_mode) || S_ISSOCK(st->st_mode))) {
        snprintf(reason, size, "'%s' is %s; an output must be a regular file", path, kind_of(st->st_mode));
        return -1;
    }
    if (exists && read_under(st, read_name, sizeof read_name)) {
        snprintf(reason, size, "'%s' is the same file as '%s' (another name for it), which this run reads; refusing to "
                 "write over it", path, read_name);
        return -1;
    }
    if (strlen(path) >= sizeof folder) {
        snprintf(reason, size, "the name '%.60s...' is too long", path);
        return -1;
    }
    strcpy(folder, path);
    if (statfs(exists ? path : dirname(folder), &fs) == 0 && system_filesystem((long)fs.f_type)) {
        snprintf(reason, size, "'%s' is on a system filesystem (/proc, /sys or their kind), not a disk; refusing to "
                 "write there", path);
        return -1;
    }
    return 0;
}

int safe_output_problem(const char *path, char *reason, size_t reason_size)
{
    struct stat st;
    const int exists = stat(path, &st) == 0;
    return output_problem_of(path, &st, exists, reason, reason_size);
}

FILE *safe_open_to_inspect(const char *path, char *error, size_t error_size)
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

FILE *safe_open_input(const char *path, char *error, size_t error_size)
{
    struct stat st;
    FILE *f = safe_open_to_inspect(path, error, error_size);
    if (f != NULL && fstat(fileno(f), &st) == 0) {
        note_identity(&st, path);
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
    char reason[PATH_MAX * 2 + 200];
    if (safe_output_problem(path, reason, sizeof reason) != 0) {
        fprintf(stderr, "%s: %s\n", program, reason);
        return NULL;
    }
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
    if (output_problem_of(path, &st, 1, reason, sizeof reason) != 0) { /* the file opened, before it is cut */
        fprintf(stderr, "%s: %s\n", program, reason);
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
