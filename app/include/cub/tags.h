/* tags — the bridge frames of a clip library (SEEDS.md § 000, "Bridge-frame
 * tagging, three steps" and "Switching"): which frames of each clip are
 * bridge frames, and for every ordered pair of clips (A, B) which bridge
 * frame a of A can switch to which bridge frame b of B, unnoticed:
 * d(a, b) < threshold, best first, B's front half before its back half.
 *
 *   cub_tag_library   tags a library (app/tag, offline). Every decision uses
 *                     the firmware's fixed-point fuzzy features, so the same
 *                     library always gives the same tags, on any CPU.
 *   cub_tags_write    the tag file, XML (app/io/tags_xml.c), same bytes for
 *   cub_tags_read     the same tags; reading validates the file against the
 *                     library it names (clips, frame ranges, numbers, links
 *                     between bridge frames) and says file:line: what.
 * The schema is documented in README.md, "Bridge tags (XML)".
 *
 * Units: d and weights Q16.16 in [0, 1]; head speed Q16.16 degrees per
 * second; frames are 0-based indices into the library's clips.
 */
#ifndef CUB_TAGS_H
#define CUB_TAGS_H

#include <stdint.h>

#include "cub/bridge.h"
#include "cub/err.h"
#include "cub/fuzzy.h"
#include "cub/io.h"
#include "cub/motion.h"
#include "cub/pack.h"

#define CUB_TAGS_VERSION 1
#define CUB_TAGS_LIBRARY_LEN 128

/* How bridge frames are chosen. Zero-initialised = the defaults below
 * (cub_tag_params_defaults fills them in; README explains each choice). */
typedef struct cub_tag_params {
    cub_fuzzy_config fuzzy; /* weights S_k and the threshold; zero = seed defaults */
    /* Step 1: a crisp pose class is frequent when it covers at least
     * class_share of all the library's frames OR occurs in at least
     * class_clips different clips. Defaults 0.02 (Q16.16) and 3. */
    cub_q16 class_share;
    int class_clips;
    /* Step 2: no bridge frame where the head turns faster than this,
     * relative to the chest (degrees/second). Default 120. */
    cub_q16 head_dps;
    /* Thinning: a run of consecutive candidates keeps one frame per
     * spacing_ms window, the stillest one. Default 200. */
    int spacing_ms;
    /* Step 3: links kept per (bridge frame a, clip B, half of B), best
     * first. Default 3; -1 keeps them all. */
    int max_links;
} cub_tag_params;

cub_tag_params cub_tag_params_defaults(const cub_tag_params *p);

typedef struct cub_tag_bridge {
    int frame;
    uint32_t crisp_class; /* cub_fuzzy_crisp_class of the frame */
} cub_tag_bridge;

typedef enum cub_tag_half {
    CUB_TAG_FRONT = 0, /* 2*b < frame_count: searched first */
    CUB_TAG_BACK = 1,
} cub_tag_half;

/* "From frame a of clip A, switch to frame b of clip B." */
typedef struct cub_tag_link {
    int a, b;
    cub_q16 d;
    cub_tag_half half;
} cub_tag_link;

typedef struct cub_tag_clip {
    char name[CUB_MOTION_NAME_LEN];
    int frame_count;
    int bridge_count;
    cub_tag_bridge *bridges; /* ascending frames; heap, owned */
} cub_tag_clip;

/* The links of one ordered clip pair: for each bridge a of A (ascending),
 * its front-half links by (d, b) ascending, then its back-half links. */
typedef struct cub_tag_pair {
    int link_count;
    cub_tag_link *links; /* heap, owned */
} cub_tag_pair;

typedef struct cub_tags {
    char library[CUB_TAGS_LIBRARY_LEN]; /* the library's file name, e.g. "bear.cubclips" */
    cub_tag_params params;              /* as used: defaults filled, weights normalised */
    int clip_count;                     /* the library's clips, in its order */
    cub_tag_clip *clips;
    cub_tag_pair *pairs; /* [from * clip_count + to], self pairs included */
} cub_tags;

/* ---- tagging (app/tag, library cub_tag) --------------------------------- */

/* What tagging measures on one frame. */
typedef struct cub_tag_frame {
    cub_fuzzy_frame fuzzy;
    uint32_t crisp_class;
    cub_q16 head_dps;  /* head angular speed relative to the chest, deg/s */
    cub_q16 motion_mm; /* how far the joints move around it, relative to the root */
} cub_tag_frame;

/* The body's joints, found by name in another skeleton (the library's).
 * CUB_ERR_FORMAT with diag naming the missing joint. */
cub_err cub_tag_map_body(const cub_skeleton *from, const cub_fuzzy_body *body,
                         const cub_skeleton *to, cub_fuzzy_body *out, cub_diag *diag);

/* Measure every frame of a clip; out has clip->frame_count entries.
 * CUB_ERR_ARG if the body does not fit the clip's skeleton. */
cub_err cub_tag_analyse_clip(const cub_clip *clip, const cub_fuzzy_body *body, cub_tag_frame *out);

/* Progress for long runs (may be NULL): called once per clip and step. */
typedef void (*cub_tag_progress)(void *user, const char *step, int done, int total);

/* Tag a whole library. body is on the library's skeleton; library_name is
 * what the file records (a base name). out is freed with cub_tags_free. */
cub_err cub_tag_library(const cub_library *lib, const char *library_name,
                        const cub_fuzzy_body *body, const cub_tag_params *params, cub_tags *out,
                        cub_tag_progress progress, void *user);

/* A clip made after the library was tagged (the groove's, issue 23) gets
 * its bridge frames by the same rules: */
/* Step 1 over frames given by their crisp class and clip index (total of
 * each): the frequent classes, ascending (heap, free with free()). */
cub_err cub_tag_frequent_classes(const uint32_t *classes, const int *clips, size_t total,
                                 const cub_tag_params *p, uint32_t **out, int *out_count);
/* Steps 1 and 2 and the thinning on one clip measured by
 * cub_tag_analyse_clip: out->bridges (heap, free with free()) and
 * out->bridge_count; the name and frame count are left as they are. */
cub_err cub_tag_pick_clip(const cub_clip *clip, const cub_tag_frame *frames, const uint32_t *freq,
                          int freq_count, const cub_tag_params *p, cub_tag_clip *out);
/* A library's frequent classes as its bridge table holds them. */
typedef struct cub_tag_classes {
    uint32_t *classes; /* ascending; heap, free with free() */
    int count;
} cub_tag_classes;
/* Step 1 over the table's first clip_count clips (the library's, not the
 * clips appended after them), from the features the table measured. */
cub_err cub_tag_table_classes(const cub_bridge_table *t, int clip_count, const cub_tag_params *p,
                              cub_tag_classes *out);
/* Measure a made clip (frames: frame_count of them) and pick its bridge
 * frames against the library's classes (cub_tag_pick_clip). */
cub_err cub_tag_made_clip(const cub_clip *clip, const cub_fuzzy_body *body,
                          const cub_tag_classes *freq, const cub_tag_params *p,
                          cub_tag_frame *frames, cub_tag_clip *out);

/* Shortest chain of clips from clip `from` to clip `to` through links:
 * 1 = joined directly, k = through k-1 other clips, -1 = unreachable. */
int cub_tags_chain_length(const cub_tags *tags, int from, int to);

/* ---- the tag file (app/io/tags_xml.c, library cub_io) ------------------- */

/* The tags as XML text (heap, NUL-terminated, free with free()). */
cub_err cub_tags_print(const cub_tags *tags, char **out, size_t *out_len);
cub_err cub_tags_write(const char *path, const cub_tags *tags, cub_diag *diag);
/* Read and validate against lib: every clip of the library present with its
 * frame count, frame indices in range, numbers finite and in range, links
 * only between bridge frames. CUB_ERR_FORMAT with diag "file:line: what". */
cub_err cub_tags_read(const char *path, const cub_library *lib, cub_tags *out, cub_diag *diag);
cub_err cub_tags_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                       cub_tags *out, cub_diag *diag);
/* Free what the tags own; the struct is zeroed. NULL is fine. */
void cub_tags_free(cub_tags *tags);

#endif
