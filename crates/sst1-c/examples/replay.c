/* replay.c -- a host program for libsst1: replays a plain-text register trace
 * (docs/traces.md) on an emulated board and writes the buffers its dump lines ask for.
 *
 *   replay TRACE OUTDIR [MODEL]
 *
 * TRACE is an uncompressed text trace; MODEL is hardware (the default), mame,
 * dosbox-staging or 86box. Each `dump BUFFER NAME` line writes OUTDIR/NAME, the buffer
 * as raw little-endian 16-bit values (what `voodoo replay` writes); a front-buffer dump
 * also writes OUTDIR/NAME.rgba, the displayed frame as RGBA8. At the end it prints
 * `swaps N dumps M`: N is the number of swaps the swap callback saw, which must be the
 * board's own count.
 *
 * The parsing is a host's, not a validator's: `#` starts a comment, numbers are 0x hex
 * or decimal, `config` lines (which come before the first access) set the board, and
 * `pci`, `w`, `r` and `dump` lines run in order. A line it cannot read stops it with
 * the line number. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sst1.h"

static const char *trace_path;
static unsigned long line_number;

static void fail(const char *what) {
    fprintf(stderr, "replay: %s:%lu: %s\n", trace_path, line_number, what);
    exit(1);
}

/* Exits with the library's words if `r` is an error. */
static void check(sst1_result r, const char *call) {
    if (r != SST1_OK) {
        fprintf(stderr, "replay: %s:%lu: %s: %s\n", trace_path, line_number, call,
                sst1_error_string(r));
        exit(1);
    }
}

/* A number as the format writes it: 0x hex or decimal, 32 bits. */
static uint32_t number(const char *word) {
    if (word == NULL) {
        fail("missing number");
    }
    int base = 10;
    if (word[0] == '0' && (word[1] == 'x' || word[1] == 'X')) {
        word += 2;
        base = 16;
    }
    if (*word == '\0' || *word == '+' || *word == '-') {
        fail("bad number");
    }
    char *end;
    errno = 0;
    unsigned long long v = strtoull(word, &end, base);
    if (*end != '\0' || errno != 0 || v > 0xffffffffull) {
        fail("bad number");
    }
    return (uint32_t)v;
}

/* The line's words, comment removed: up to 4, the rest ignored. */
static int split(char *line, char *words[4]) {
    char *hash = strchr(line, '#');
    if (hash != NULL) {
        *hash = '\0';
    }
    int n = 0;
    for (char *w = strtok(line, " \t\r\n"); w != NULL && n < 4; w = strtok(NULL, " \t\r\n")) {
        words[n++] = w;
    }
    for (int i = n; i < 4; i++) {
        words[i] = NULL;
    }
    return n;
}

struct swaps_seen {
    uint64_t calls;
    uint64_t last;
};

/* The swap callback: counts the swaps and checks that they arrive one by one. It also
 * reads the displayed frame's size, as a host presenting the frame would. */
static void on_swap(void *user, sst1_board *board, uint64_t swap_count) {
    struct swaps_seen *seen = user;
    seen->calls++;
    if (swap_count != seen->last + 1) {
        fprintf(stderr, "replay: swap %llu reported after %llu\n",
                (unsigned long long)swap_count, (unsigned long long)seen->last);
        exit(1);
    }
    seen->last = swap_count;
    uint32_t w, h;
    check(sst1_display_size(board, &w, &h), "sst1_display_size in the swap callback");
}

static void write_file(const char *dir, const char *name, const char *suffix,
                       const void *data, size_t len) {
    size_t n = strlen(dir) + strlen(name) + strlen(suffix) + 2;
    char *path = malloc(n);
    if (path == NULL) {
        fail("out of memory");
    }
    snprintf(path, n, "%s/%s%s", dir, name, suffix);
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(data, 1, len, f) != len || fclose(f) != 0) {
        fail("cannot write a dump");
    }
    free(path);
}

static void dump(sst1_board *board, const char *buffer, const char *name, const char *dir) {
    sst1_buffer which;
    if (strcmp(buffer, "front") == 0) {
        which = SST1_BUFFER_FRONT;
    } else if (strcmp(buffer, "back") == 0) {
        which = SST1_BUFFER_BACK;
    } else if (strcmp(buffer, "depth") == 0 || strcmp(buffer, "aux") == 0) {
        which = SST1_BUFFER_AUX;
    } else {
        fail("unknown buffer");
    }
    if (name == NULL || strchr(name, '/') != NULL) {
        fail("bad dump name");
    }
    uint32_t w = 0, h = 0;
    check(sst1_display_size(board, &w, &h), "sst1_display_size");
    size_t count = (size_t)w * h;
    uint16_t *pixels = malloc(count * 2 + 2);
    uint8_t *bytes = malloc(count * 4 + 4);
    if (pixels == NULL || bytes == NULL) {
        fail("out of memory");
    }
    uint32_t rw, rh;
    check(sst1_read_buffer(board, which, pixels, count, &rw, &rh), "sst1_read_buffer");
    if (rw != w || rh != h) {
        fail("buffer size differs from the display size");
    }
    for (size_t i = 0; i < count; i++) {
        bytes[2 * i] = (uint8_t)(pixels[i] & 0xff);
        bytes[2 * i + 1] = (uint8_t)(pixels[i] >> 8);
    }
    write_file(dir, name, "", bytes, count * 2);
    if (which == SST1_BUFFER_FRONT) {
        check(sst1_front_buffer_rgba8(board, bytes, count * 4, NULL, NULL),
              "sst1_front_buffer_rgba8");
        write_file(dir, name, ".rgba", bytes, count * 4);
    }
    free(pixels);
    free(bytes);
}

int main(int argc, char **argv) {
    if (argc < 3 || argc > 4) {
        fprintf(stderr, "usage: replay TRACE OUTDIR [MODEL]\n");
        return 2;
    }
    trace_path = argv[1];
    const char *outdir = argv[2];
    sst1_model model = SST1_MODEL_HARDWARE;
    if (argc == 4) {
        check(sst1_model_from_name(argv[3], &model), "sst1_model_from_name");
    }
    if (sst1_api_version() != SST1_API_VERSION) {
        fprintf(stderr, "replay: libsst1 implements interface %u, sst1.h is %u\n",
                sst1_api_version(), SST1_API_VERSION);
        return 1;
    }
    FILE *trace = fopen(trace_path, "r");
    if (trace == NULL) {
        perror(trace_path);
        return 1;
    }

    char *line = NULL;
    size_t cap = 0;
    char *words[4];

    /* Pass 1: the board's configuration (config lines, before the first access). */
    sst1_config config = {.fbi_mb = 4, .tmus = 1, .tmu_mb = 4};
    line_number = 0;
    while (getline(&line, &cap, trace) != -1) {
        line_number++;
        if (split(line, words) == 0) {
            continue;
        }
        if (strcmp(words[0], "w") == 0 || strcmp(words[0], "r") == 0) {
            break;
        }
        if (strcmp(words[0], "config") == 0) {
            if (words[1] == NULL) {
                fail("config without a key");
            }
            uint32_t v = number(words[2]);
            if (strcmp(words[1], "fbi_mb") == 0) {
                config.fbi_mb = v;
            } else if (strcmp(words[1], "tmus") == 0) {
                config.tmus = v;
            } else if (strcmp(words[1], "tmu_mb") == 0) {
                config.tmu_mb = v;
            } else {
                fail("unknown config key");
            }
        }
    }

    sst1_board *board = NULL;
    check(sst1_create(&config, model, &board), "sst1_create");
    struct swaps_seen seen = {0, 0};
    check(sst1_set_swap_callback(board, on_swap, &seen), "sst1_set_swap_callback");

    /* Pass 2: every access and dump, in order. */
    rewind(trace);
    line_number = 0;
    unsigned long dumps = 0;
    while (getline(&line, &cap, trace) != -1) {
        line_number++;
        if (split(line, words) == 0 || strcmp(words[0], "config") == 0) {
            continue;
        }
        if (strcmp(words[0], "w") == 0) {
            check(sst1_write32(board, number(words[1]), number(words[2])), "sst1_write32");
        } else if (strcmp(words[0], "pci") == 0) {
            check(sst1_pci_write(board, number(words[1]), number(words[2])), "sst1_pci_write");
        } else if (strcmp(words[0], "r") == 0) {
            uint32_t v;
            check(sst1_read32(board, number(words[1]), &v), "sst1_read32");
        } else if (strcmp(words[0], "dump") == 0) {
            if (words[1] == NULL) {
                fail("dump without a buffer");
            }
            dump(board, words[1], words[2], outdir);
            dumps++;
        } else {
            fail("unknown command");
        }
    }
    free(line);
    fclose(trace);

    uint64_t swaps = 0;
    check(sst1_swap_count(board, &swaps), "sst1_swap_count");
    if (swaps != seen.calls || swaps != seen.last) {
        fprintf(stderr, "replay: the board swapped %llu times, the callback saw %llu\n",
                (unsigned long long)swaps, (unsigned long long)seen.calls);
        return 1;
    }
    check(sst1_destroy(board), "sst1_destroy");
    printf("swaps %llu dumps %lu\n", (unsigned long long)swaps, dumps);
    return 0;
}
