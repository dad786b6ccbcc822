/*
 * safe_files.h - opening inputs and outputs so that no command line can make
 * a program hang on a named pipe, write over its own input, or report a cut
 * file as success.
 */
#ifndef SAFE_FILES_H
#define SAFE_FILES_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Opens path for reading when it is a regular file; a named pipe, device or
 * folder is refused at once (opening a pipe with no writer would block for
 * ever). NULL with "'PATH' is a named pipe; ..." (or the system's reason) in error.
 * The file is noted as read (safe_note_read). */
FILE *safe_open_input(const char *path, char *error, size_t error_size);

/* safe_open_input for a look at a file that is not an input (an output's kind, before it is written
 * over): not noted as read. */
FILE *safe_open_to_inspect(const char *path, char *error, size_t error_size);

/* Notes that this run reads the file at path, by its device and inode, taken now: from then on no output
 * may be that file under any name (a hard link, a bind mount, a symbolic link). Call it as each input is
 * opened; a path that names nothing is ignored. Safe from any thread. */
void safe_note_read(const char *path);

/* Notes every regular file inside the folder at path, at any depth (a folder of images read as a video,
 * a dataset's labels and images): the files a run will read from it, noted before any output is opened. */
void safe_note_folder(const char *path);

/* 0 when path may be opened as an output; else -1 with why not in reason: it is a file this run reads
 * (noted above, under this or another name), a device or socket, or on a filesystem that is no disk's
 * (/proc, /sys and their kind: a write there changes the system, not a file). A new file in an ordinary
 * folder, an existing regular file no input is, and a named pipe may be written. */
int safe_output_problem(const char *path, char *reason, size_t reason_size);

/* 1 when a and b name one file: the same inode when both exist (through
 * links, "./", "..", hard links), or the same folder and name when they do not
 * exist yet. */
int safe_same_file(const char *a, const char *b);

/* 1 when writing path would write over input: the same file (safe_same_file),
 * or, when input is a folder, a file at any depth inside it (a folder of
 * images read as a video, a dataset's labels and images). */
int safe_writes_over(const char *path, const char *input);

/* 1 when path names a regular file (through symbolic links): what a program may
 * read without a wait on a named pipe or a device. */
int safe_is_regular_file(const char *path);

/* Opens path for writing ("w" or "wb"), refusing one that names any of the
 * `count` paths in `keep` (the program's inputs and its other outputs), or a
 * file inside one that is a folder (safe_writes_over): it would be truncated
 * before it is read; and one that safe_output_problem refuses (checked again on
 * the opened file before it is truncated). A named pipe is opened without
 * blocking: with no reader, a clear error instead of a hang. NULL with a
 * message on stderr. */
FILE *safe_open_output(const char *path, const char *mode, const char *const *keep, int count, const char *program);

/* Flushes, syncs (regular files) and closes f: 0, or -1 when any write, the
 * flush, the sync or the close failed (a full disk shows here at the latest). */
int safe_close(FILE *f);

/* A write beyond the file-size limit (ulimit -f) fails with EFBIG, which the
 * program reports, instead of killing it by SIGXFSZ without a word. Call once
 * at start. */
void safe_files_fail_writes_past_size_limit(void);

#ifdef __cplusplus
}
#endif

#endif /* SAFE_FILES_H */
