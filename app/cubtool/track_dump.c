/* track_dump — see track_dump.h. */
#include "track_dump.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/text.h"

#define FRAME_PIXELS CUB_TOOL_FRAME_PIXELS
#define HEADER_MAX_BYTES 64 /* "P5 640 480 65535\n" and room for a comment */
#define INDEX_MAX_BYTES ((size_t)64 << 20)

/* A PGM of the dump: "P5 640 480 65535\n" then little-endian uint16.
 * Malformed or truncated files are refused with a message. */
/* The bounded open (cub/text.h): a file that is not one, or far larger
 * than max, is refused before it is read. */
static FILE *open_file(const char *path, const char *what, size_t max, const char *who)
{
    FILE *f = NULL;
    size_t bytes = 0;
    cub_diag d = {0};
    char msg[600];
    cub_text_src src = {path, what, max};
    if (cub_text_fopen(&src, &f, &bytes, &d)) {
        fprintf(stderr, "%s: %s\n", who, cub_diag_str(&d, msg, sizeof msg));
        return NULL;
    }
    return f;
}

static int read_pgm(const char *path, uint16_t *out, const char *who)
{
    FILE *f = open_file(path, "depth frame", FRAME_PIXELS * 2 + HEADER_MAX_BYTES, who);
    if (!f) return -1;
    int w = 0, h = 0, maxv = 0;
    if (fscanf(f, "P5 %d %d %d", &w, &h, &maxv) != 3 || w != CUB_KINECT_WIDTH || h != CUB_KINECT_HEIGHT ||
        maxv != 65535 || fgetc(f) == EOF) {
        fprintf(stderr, "%s: %s: not a 640x480 16-bit P5 depth frame\n", who, path);
        fclose(f);
        return -1;
    }
    uint8_t *buf = malloc(FRAME_PIXELS * 2);
    size_t got = buf ? fread(buf, 1, FRAME_PIXELS * 2, f) : 0;
    fclose(f);
    if (got != FRAME_PIXELS * 2) {
        fprintf(stderr, "%s: %s: truncated (%zu of %d bytes)\n", who, path, got, FRAME_PIXELS * 2);
        free(buf);
        return -1;
    }
    for (int i = 0; i < FRAME_PIXELS; i++) out[i] = (uint16_t)(buf[2 * i] | buf[2 * i + 1] << 8);
    free(buf);
    return 0;
}

void cub_tool_dump_free(cub_tool_dump *d)
{
    free(d->raw), free(d->t_us), free(d->name);
    memset(d, 0, sizeof *d);
}

int cub_tool_dump_load(const char *dir, cub_tool_dump *d, int max_frames, const char *who)
{
    memset(d, 0, sizeof *d);
    char path[4096];
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    FILE *f = open_file(path, "INDEX.txt", INDEX_MAX_BYTES, who);
    if (!f) return -1;
    char line[512];
    int cap = 0;
    while (fgets(line, sizeof line, f) && d->n < max_frames) {
        line[strcspn(line, "\r\n")] = 0;
        if (line[0] != 'd' || line[1] != '-' || strlen(line) >= 128) continue;
        if (d->n == cap) {
            cap = cap ? cap * 2 : 64;
            d->raw = realloc(d->raw, (size_t)cap * FRAME_PIXELS * sizeof *d->raw);
            d->t_us = realloc(d->t_us, (size_t)cap * sizeof *d->t_us);
            d->name = realloc(d->name, (size_t)cap * sizeof *d->name);
            if (!d->raw || !d->t_us || !d->name) {
                fclose(f);
                return -1;
            }
        }
        snprintf(path, sizeof path, "%s/%s", dir, line);
        if (read_pgm(path, d->raw + (size_t)d->n * FRAME_PIXELS, who)) continue;
        /* d-<sec>.<frac>-<us>.pgm: the seconds stamp */
        double sec = strtod(line + 2, NULL);
        if (!(sec >= 0 && sec < 1e12)) { /* (int64_t) of more is undefined */
            fprintf(stderr, "%s: %s: no usable seconds in the name; skipped\n", who, path);
            continue;
        }
        d->t_us[d->n] = (int64_t)(sec * 1e6);
        snprintf(d->name[d->n], sizeof d->name[d->n], "%s", line);
        d->n++;
    }
    fclose(f);
    if (d->n == 0) fprintf(stderr, "%s: %s: no depth frames\n", who, dir);
    return d->n ? 0 : -1;
}

int cub_tool_forest_load(const char *path, char **bytes, cub_forest *f, const char *who)
{
    char buf[700];
    size_t len = 0;
    cub_diag diag = {0};
    cub_text_src src = {path, "forest", CUB_TEXT_MAX_CLIPS};
    *bytes = NULL;
    if (cub_text_read(&src, bytes, &len, &diag)) {
        fprintf(stderr, "%s: %s\n", who, cub_diag_str(&diag, buf, sizeof(buf)));
        return -1;
    }
    cub_forest_problem why = {0};
    if (cub_forest_open(*bytes, len, f, &why)) {
        fprintf(stderr, "%s: %s: offset %zu: %s\n", who, path, why.offset, why.what);
        free(*bytes);
        *bytes = NULL;
        return -1;
    }
    return 0;
}

cub_tracker *cub_tool_tracker_new(void **mem, const cub_forest *f, const char *who)
{
    cub_track_desc desc = {.forest = f};
    size_t sz = cub_track_mem_size(&desc);
    *mem = aligned_alloc(16, (sz + 15) / 16 * 16);
    cub_tracker *t = NULL;
    if (!*mem || cub_track_init(&desc, *mem, sz, &t)) {
        fprintf(stderr, "%s: cannot set up the tracker\n", who);
        return NULL;
    }
    return t;
}
