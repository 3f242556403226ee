/* cubtool graph — the dance's motion graph by support points (seed 002,
 * § 5.2): per class (which parts touch the floor) its frames and the clip
 * segments in it, the changes of class inside clips as counted edges, and
 * (--png) a drawing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "cub/join.h"
#include "join_src.h"

#define MIN_SEGMENT 3 /* frames: a shorter run of a class belongs to the one before */

static void print_class(const cub_join_db *db, const cub_join_graph *g, unsigned m)
{
    char name[64];
    printf("graph class %-12s frames=%d segments=%d:", cub_join_support_name(m, name, sizeof name),
           g->frames[m], g->segments[m]);
    for (int c = 0; c < db->count; c++) {
        int max = db->clips[c].clip->frame_count;
        cub_join_segment *seg = malloc(sizeof *seg * (size_t)max);
        if (!seg) break;
        int n = cub_join_segments(db, c, MIN_SEGMENT, seg, max);
        for (int i = 0; i < n && i < max; i++)
            if (seg[i].mask == m) printf(" %s@%d-%d", db->clips[c].name, seg[i].first, seg[i].last);
        free(seg);
    }
    printf("\n");
}

static int usage(FILE *f, int code)
{
    fprintf(f, "usage: cubtool graph [LIBRARY.cubclips | CLIP.bvh]... [--png OUT.png]\n"
               "  Support points per frame (LF RF feet, LH RH hands, LK RK knees, HIP),\n"
               "  their classes as the motion graph's nodes, changes inside clips as edges.\n"
               "  Default: the shipped library. BVH files must share the first file's skeleton.\n");
    return code;
}

int cub_cmd_graph(int argc, char **argv)
{
    const char *png = NULL;
    static join_src src;
    cub_join_cfg cfg = {0};
    int files = 0, rc = 0;
    for (int i = 1; i < argc && !rc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage(stdout, 0);
        if (!strcmp(argv[i], "--png") && i + 1 < argc)
            png = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "cubtool graph: unexpected '%s'\n", argv[i]);
            join_src_free(&src);
            return usage(stderr, 2);
        } else
            rc = join_src_add(&src, argv[i], &cfg) ? 1 : 0, files++;
    }
    if (!rc && !files) rc = join_src_add(&src, CUB_ASSETS_DIR "/clips/bear.cubclips", &cfg) ? 1 : 0;
    static cub_join_graph g;
    if (!rc && cub_join_graph_build(&src.db, MIN_SEGMENT, &g)) {
        fprintf(stderr, "graph: out of memory\n");
        rc = 1;
    }
    if (!rc) {
        int classes = 0, edges = 0;
        for (unsigned m = 0; m < CUB_JOIN_CLASSES; m++)
            if (g.frames[m]) {
                classes++;
                print_class(&src.db, &g, m);
            }
        for (unsigned m = 0; m < CUB_JOIN_CLASSES; m++)
            for (unsigned k = 0; k < CUB_JOIN_CLASSES; k++)
                if (g.edges[m][k]) {
                    char a[64], b[64];
                    printf("graph edge %s -> %s count=%d\n", cub_join_support_name(m, a, 64),
                           cub_join_support_name(k, b, 64), g.edges[m][k]);
                    edges++;
                }
        printf("graph: %d clips, %d classes, %d edges\n", src.db.count, classes, edges);
        if (png && cub_join_graph_png(&g, png)) {
            fprintf(stderr, "graph: cannot write %s\n", png);
            rc = 1;
        } else if (png)
            printf("graph: wrote %s\n", png);
    }
    join_src_free(&src);
    return rc;
}
