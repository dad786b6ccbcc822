/*
 * config_files.h - where hkf-filter finds its settings when no --config is
 * given: the system's file, then the user's, each read over the one before.
 *   system: $HKF_SYSTEM_CONFIG_DIR/hkf-filter.conf, by default /etc/hkf/hkf-filter.conf
 *           (the Debian package's conffile)
 *   user:   $XDG_CONFIG_HOME/hkf/hkf-filter.conf, by default ~/.config/hkf/hkf-filter.conf
 */
#ifndef CONFIG_FILES_H
#define CONFIG_FILES_H

#ifdef __cplusplus
extern "C" {
#endif

#define CONFIG_FILES_MAX 2
#define CONFIG_FILES_PATH_MAX 4096
#define CONFIG_FILES_SYSTEM_DIR "/etc/hkf"
#define CONFIG_FILES_NAME "hkf-filter.conf"

typedef struct {
    char path[CONFIG_FILES_MAX][CONFIG_FILES_PATH_MAX];
    int count;
} config_files_t;

/* The files of the search that exist, in the order to read them. */
void config_files_find(config_files_t *found);

/* The user's file's path, whether it exists or not: 0, or -1 when neither XDG_CONFIG_HOME (absolute) nor HOME
 * is set or the path does not fit. */
int config_files_user_path(char *path, int size);

#ifdef __cplusplus
}
#endif

#endif /* CONFIG_FILES_H */
