/* Hand labels of real frames (tests/labels/skeltrack_labels.txt): one
 * joint a line, `frame joint u v`; errors name the file and the line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/forest_train.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT

static int joint_named(const char *n)
{
    for (int j = 0; j < CUB_KJ_COUNT; j++)
        if (!strcmp(cub_kinect_joint_name(j), n)) return j;
    return -1;
}

/* One line `frame joint u v` (u, v may be `-`); 0 = kept, 1 = skipped. */
static cub_err parse_line(const char *line, const char *name, int ln, cub_ft_labels *out,
                          cub_diag *diag)
{
    char frame[64], joint[32], us[16], vs[16], extra;
    int k = sscanf(line, "%63s %31s %15s %15s %c", frame, joint, us, vs, &extra);
    if (k <= 0 || frame[0] == '#') return CUB_OK;
    if (k != 4)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln,
                             "want `frame joint u v` (u v may be `-`), got %d fields", k);
    int j = joint_named(joint);
    if (j < 0) return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln, "no joint '%s'", joint);
    cub_ft_label l = {{0}, j, -1, -1, ln};
    snprintf(l.frame, sizeof(l.frame), "%s", frame);
    if (strcmp(us, "-") || strcmp(vs, "-")) {
        char *e1, *e2;
        long u = strtol(us, &e1, 10), v = strtol(vs, &e2, 10);
        if (*e1 || *e2 || u < 0 || u >= W || v < 0 || v >= H)
            return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln,
                                 "pixel '%s %s' not in the 640x480 image (or `- -`)", us, vs);
        l.u = (int)u, l.v = (int)v;
    }
    if (out->n == CUB_FT_MAX_LABELS)
        return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln, "more than %d labels",
                             CUB_FT_MAX_LABELS);
    out->l[out->n++] = l;
    return CUB_OK;
}

cub_err cub_ft_labels_parse(const char *text, size_t len, const char *name, cub_ft_labels *out,
                            cub_diag *diag)
{
    out->n = 0;
    out->name = name;
    char line[256];
    size_t at = len >= 3 && !memcmp(text, "\xef\xbb\xbf", 3) ? 3 : 0; /* a BOM */
    int ln = 1;
    for (; at < len; ln++) {
        size_t end = at;
        while (end < len && text[end] != '\n')
            end++;
        if (end - at >= sizeof(line))
            return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln, "line longer than %zu bytes",
                                 sizeof(line) - 1);
        memcpy(line, text + at, end - at);
        line[end - at] = 0;
        if (memchr(line, 0, end - at))
            return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln, "a NUL byte in the line");
        cub_err e = parse_line(line, name, ln, out, diag);
        if (e) return e;
        at = end + 1;
    }
    /* nothing to measure is a mistake (a wrong file), not a table of zeros */
    if (!out->n) return cub_diag_fail(diag, CUB_ERR_FORMAT, name, ln > 1 ? ln - 1 : 1,
                                      "lists no labels");
    return CUB_OK;
}
