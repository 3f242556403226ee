#include "tool_util.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cub/io.h"

int cub_tool_make_dir(const char *dir, const char *who)
{
    char path[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof path) {
        fprintf(stderr, "%s: bad directory name '%s'\n", who, dir);
        return -1;
    }
    memcpy(path, dir, n + 1);
    /* Each prefix ending at a '/', then the whole path. */
    for (size_t i = 1; i <= n; i++) {
        if (path[i] != '/' && path[i] != '\0') continue;
        char keep = path[i];
        path[i] = '\0';
        if (mkdir(path, 0755) != 0 && errno != EEXIST) {
            fprintf(stderr, "%s: cannot create %s: %s\n", who, path, strerror(errno));
            return -1;
        }
        path[i] = keep;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "%s: %s is not a directory\n", who, dir);
        return -1;
    }
    return 0;
}

void cub_tool_series_add(cub_tool_series *s, double x, const char *who)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 1024;
        double *nv = realloc(s->v, s->cap * sizeof *nv);
        if (!nv) {
            fprintf(stderr, "%s: out of memory\n", who);
            exit(1);
        }
        s->v = nv;
    }
    s->v[s->n++] = x;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cub_tool_series_pct(cub_tool_series *s, double q)
{
    if (!s->n) return 0;
    qsort(s->v, s->n, sizeof *s->v, cmp_double);
    size_t i = (size_t)(q * (double)s->n + 0.999999);
    return s->v[i ? (i > s->n ? s->n - 1 : i - 1) : 0];
}

static const cub_tool_opt *find_opt(const char *arg, const cub_tool_opt *opts, int n)
{
    for (int k = 0; k < n; k++)
        if (!strcmp(arg, opts[k].name)) return &opts[k];
    return NULL;
}

cub_tool_parsed cub_tool_parse_opts(int argc, char **argv, const cub_tool_opt *opts, int n,
                                    const char **positional, int npos)
{
    int used = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const cub_tool_opt *o = find_opt(a, opts, n);
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) return CUB_TOOL_HELP;
        if (o && o->flag) {
            *o->flag = 1;
        } else if (o && o->value && i + 1 < argc) {
            *o->value = argv[++i];
        } else if (!o && a[0] != '-' && used < npos) {
            positional[used++] = a;
        } else {
            fprintf(stderr, "cubtool %s: unexpected '%s'%s\n", argv[0], a,
                    o ? " (it needs a value)" : "");
            return CUB_TOOL_BAD;
        }
    }
    return CUB_TOOL_RUN;
}

int cub_tool_save_clip_bvh(const cub_skeleton *skel, const cub_clip *clip, const char *path)
{
    static cub_io_motion m; /* static: large */
    memset(&m, 0, sizeof m);
    m.skel = *skel;
    m.clip = *clip;
    m.clip.skel = &m.skel;
    m.unit_mm = 10.0;
    for (int j = 0; j < m.skel.joint_count; j++) {
        if (m.skel.joints[j].is_end_site) continue;
        int pos = j == 0 || clip->trans_mm != NULL;
        m.channels[j].count = (unsigned char)(pos ? 6 : 3);
        m.channels[j].has_pos = (unsigned char)pos;
        memcpy(m.channels[j].rot_order, "ZXY", 4);
        memcpy(m.channels[j].pos_order, pos ? "XYZ" : "", pos ? 4 : 1);
    }
    cub_diag diag = {0};
    char msg[600];
    if (cub_io_save_bvh(path, &m, &diag)) {
        fprintf(stderr, "%s\n", cub_diag_str(&diag, msg, sizeof msg));
        return -1;
    }
    return 0;
}
