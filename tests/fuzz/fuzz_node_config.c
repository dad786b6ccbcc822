/*
 * fuzz_node_config.c - libFuzzer target for hkf-filter's settings: arbitrary
 * bytes as a config file (node_config_read_file) and, line by line, as --set
 * assignments (node_config_set). Checks: a rejection always says why; an
 * accepted configuration (model names included: one rule for sections, --set
 * and messages) prints, reads back to the same settings and model table, and
 * prints again to the same text (what --print-config promises); the read-back
 * configuration passes or fails node_config_check as the original does, and a
 * failure always says why.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "model_name.h"
#include "node_config.h"

static void check(int condition, const char *what)
{
    if (!condition) {
        fprintf(stderr, "fuzz_node_config: %s\n", what);
        abort();
    }
}

/* The configuration as --print-config text, in a buffer. */
static size_t print_to(const node_config_t *config, char *buffer, size_t size)
{
    FILE *f = fmemopen(buffer, size, "w");
    size_t length;
    check(f != NULL, "fmemopen");
    node_config_print(config, f);
    length = (size_t)ftell(f);
    fclose(f);
    return length;
}

static int write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        return -1;
    }
    fwrite(data, 1, size, f);
    return fclose(f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static node_config_t config, again;
    static char first[65536], second[65536], error[600], path[64], line[512];
    size_t start, i, length;
    if (path[0] == '\0') {
        snprintf(path, sizeof path, "/tmp/fuzz_node_config.%ld.conf", (long)getpid());
    }
    node_config_defaults(&config);
    check(write_file(path, data, size) == 0, "cannot write the temporary config file");
    error[0] = '\0';
    if (node_config_read_file(&config, path, error, sizeof error) != 0) {
        check(error[0] != '\0', "a rejected file without a message");
    }
    /* each line as a --set assignment */
    for (start = 0; start < size; start = i + 1) {
        for (i = start; i < size && data[i] != '\n'; ++i) {
        }
        length = i - start < sizeof line - 1 ? i - start : sizeof line - 1;
        memcpy(line, data + start, length);
        line[length] = '\0';
        error[0] = '\0';
        if (node_config_set(&config, line, error, sizeof error) != 0) {
            check(error[0] != '\0', "a rejected --set without a message");
        }
    }
    /* print, read back, print: the same text */
    length = print_to(&config, first, sizeof first);
    check(length < sizeof first - 1, "printed configuration too long");
    check(write_file(path, first, length) == 0, "cannot write the printed config");
    node_config_defaults(&again);
    error[0] = '\0';
    if (node_config_read_file(&again, path, error, sizeof error) != 0) {
        fprintf(stderr, "%s\n", error);
        check(0, "the printed configuration does not read back");
    }
    check(print_to(&again, second, sizeof second) == length && memcmp(first, second, length) == 0,
          "the configuration read back prints differently");
    check(memcmp(&again.settings, &config.settings, sizeof config.settings) == 0 &&
              again.model_count == config.model_count && again.second_alone_from_yaw == config.second_alone_from_yaw,
          "the configuration read back has other settings");
    for (i = 0; i < (size_t)config.model_count; ++i) {
        int known;
        const hkf_settings_t a = node_config_for_model(&again, config.models[i].name, &known);
        const hkf_settings_t b = node_config_for_model(&config, config.models[i].name, &known);
        check(strcmp(again.models[i].name, config.models[i].name) == 0 && model_name_valid(config.models[i].name) &&
                  memcmp(&a, &b, sizeof a) == 0,
              "a model read back differs, or has a name the message cannot carry");
    }
    error[0] = '\0';
    {
        const int verdict = node_config_check(&config, error, sizeof error);
        check(verdict == 0 || error[0] != '\0', "node_config_check failed without a message");
        check(node_config_check(&again, second, sizeof second) == verdict, "the read-back config checks differently");
    }
    unlink(path);
    return 0;
}
