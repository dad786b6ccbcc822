/* config_files.c - see config_files.h. */
#define _POSIX_C_SOURCE 200809L

#include "config_files.h"

#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

/* Adds FOLDER[/SUB]/hkf-filter.conf when it exists (any kind of file, a dangling or looping link
 * included: reading it says what is wrong). */
static void add_if_present(config_files_t *found, const char *folder, const char *sub)
{
    struct stat info;
    char *path = found->path[found->count];
    int n = snprintf(path, CONFIG_FILES_PATH_MAX, "%s%s/%s", folder, sub, CONFIG_FILES_NAME);
    if (n > 0 && n < CONFIG_FILES_PATH_MAX && lstat(path, &info) == 0) ++found->count;
}

void config_files_find(config_files_t *found)
{
    const char *system = getenv("HKF_SYSTEM_CONFIG_DIR");
    const char *xdg = getenv("XDG_CONFIG_HOME");
    const char *home = getenv("HOME");
    found->count = 0;
    add_if_present(found, system != NULL && system[0] != '\0' ? system : CONFIG_FILES_SYSTEM_DIR, "");
    if (xdg != NULL && xdg[0] == '/') { /* the XDG rule: a relative value is ignored */
        add_if_present(found, xdg, "/hkf");
    } else if (home != NULL && home[0] != '\0') {
        add_if_present(found, home, "/.config/hkf");
    }
}

int config_files_user_path(char *path, int size)
{
    const char *xdg = getenv("XDG_CONFIG_HOME");
    const char *home = getenv("HOME");
    int n;
    if (xdg != NULL && xdg[0] == '/') {
        n = snprintf(path, (size_t)size, "%s/hkf/%s", xdg, CONFIG_FILES_NAME);
    } else if (home != NULL && home[0] != '\0') {
        n = snprintf(path, (size_t)size, "%s/.config/hkf/%s", home, CONFIG_FILES_NAME);
    } else {
        return -1;
    }
    return n > 0 && n < size ? 0 : -1;
}
