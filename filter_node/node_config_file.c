/* node_config_file.c - see node_config.h: the text a user writes, a config file's lines and --set's
 * "key = value", read into the configuration (node_config.c applies each assignment). */
#define _POSIX_C_SOURCE 200809L
#include "node_config.h"

#include "node_config_parts.h"
#include "safe_files.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

static char *trim(char *s)
{
    char *end;
    while (isspace((unsigned char)*s)) {
        ++s;
    }
    end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1])) {
        *--end = '\0';
    }
    return s;
}

/* Splits "key = value" (comments already removed). */
static int split_assignment(char *line, char **key, char **value)
{
    char *eq = strchr(line, '=');
    if (eq == NULL) {
        return -1;
    }
    *eq = '\0';
    *key = trim(line);
    *value = trim(eq + 1);
    return (*key)[0] != '\0' && (*value)[0] != '\0' ? 0 : -1;
}

int node_config_set(node_config_t *config, const char *assignment, char *error, size_t error_size)
{
    char line[512], *key, *value;
    node_assignment_t a;
    if (strlen(assignment) >= sizeof line) {
        snprintf(error, error_size, "setting too long");
        return -1;
    }
    strcpy(line, assignment);
    if (split_assignment(line, &key, &value) != 0) {
        snprintf(error, error_size, "'%s' is not KEY=VALUE", assignment);
        return -1;
    }
    a.key = key;
    a.value = value;
    a.origin = "--set";
    return node_config_apply(config, NULL, &a, error, error_size);
}

/* One line of in (without its newline) into line: 1, 0 at the end, -1 for a
 * line longer than size - 1, -2 for a NUL byte (not a text file). */
static int read_line(FILE *in, char *line, size_t size)
{
    size_t n = 0;
    int c;
    while ((c = fgetc(in)) != EOF && c != '\n') {
        if (c == '\0') {
            return -2;
        }
        if (n + 1 >= size) {
            return -1;
        }
        line[n++] = (char)c;
    }
    line[n] = '\0';
    return c == EOF && n == 0 ? 0 : 1;
}

/* One line's content (comment and blanks removed, not empty): a [model NAME] section, whose name goes to
 * model, or KEY = VALUE applied to model's settings (the base's when model is ""). 0, or -1 with what is
 * wrong in message. */
static int read_config_line(node_config_t *config, char *text, const char *origin, char *model, char *message,
                            size_t message_size)
{
    char *key, *value;
    node_assignment_t a;
    if (text[0] == '[') {
        char name[NODE_MODEL_NAME_MAX + 1];
        int n = 0;
        if (sscanf(text, "[model %32[^] \t]]%n", name, &n) != 1 || n == 0 || text[n] != '\0') {
            snprintf(message, message_size, "a section is [model NAME], not '%s'", text);
            return -1;
        }
        if (node_config_model_entry(config, name, message, message_size) == NULL) {
            return -1;
        }
        strcpy(model, name);
        return 0;
    }
    if (split_assignment(text, &key, &value) != 0) {
        snprintf(message, message_size, "expected KEY = VALUE, got '%s'", text);
        return -1;
    }
    a.key = key;
    a.value = value;
    a.origin = origin;
    return node_config_apply(config, model[0] != '\0' ? model : NULL, &a, message, message_size);
}

int node_config_read_file(node_config_t *config, const char *path, char *error, size_t error_size)
{
    FILE *in = safe_open_input(path, error, error_size); /* a named pipe is refused, not waited on */
    char line[512], model[NODE_MODEL_NAME_MAX + 1] = "";
    char message[400], origin[NODE_ORIGIN_MAX];
    int number = 0, got;
    if (in == NULL) {
        return -1;
    }
    while ((got = read_line(in, line, sizeof line)) != 0) {
        char *text, *hash;
        ++number;
        if (got < 0) {
            snprintf(error, error_size, "%s:%d: %s", path, number,
                     got == -2 ? "a NUL byte (not a text file?)" : "line too long (at most 511 characters)");
            fclose(in);
            return -1;
        }
        snprintf(origin, sizeof origin, "%.80s:%d", path, number);
        if (number == 1 && strncmp(line, "\xef\xbb\xbf", 3) == 0) { /* a UTF-8 byte order mark (Notepad's): not text */
            memmove(line, line + 3, strlen(line + 3) + 1);
        }
        hash = strchr(line, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        text = trim(line);
        if (text[0] != '\0' && read_config_line(config, text, origin, model, message, sizeof message) != 0) {
            snprintf(error, error_size, "%s:%d: %s", path, number, message);
            fclose(in);
            return -1;
        }
    }
    if (ferror(in)) {
        snprintf(error, error_size, "%s: read error", path);
        fclose(in);
        return -1;
    }
    fclose(in);
    return 0;
}
