/* Training and test frames: clips rendered by cub/synth.h, turning and
 * moving about, the player cut out; and the folds that may train. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "cub/forest_train.h"
#include "cub/kinect.h"

#define NPIX (CUB_KINECT_WIDTH * CUB_KINECT_HEIGHT)

/* docs/tracker_eval.md's shippable folds, clip for clip as
 * scripts/eval_folds.sh lists them ("@S": from S seconds). */
static const char *const CMU13[] = {"13_29", "13_29@10", "13_29@20", "13_17@10", "13_18@5", NULL};
static const char *const CMU14[] = {"14_14", "14_14@8", "14_14@16", "14_14@24", "14_14@30", NULL};
static const char *const WALKS[] = {"02_01", "16_11", "07_05", "08_01", "03_01", NULL};
static const char *const DANCE[] = {"05_06", "10_03", "131_03", "141_16", "05_06@3.5", NULL};
static const char *const ANIMDRAW[] = {"dab",           "jumping",     "wave_hello", "zombie",
                                       "jumping_jacks", "jesse_dance", "jesse_dance@5", NULL};
static const struct {
    const char *name;
    const char *const *clips;
} FOLDS[] = {{"cmu13", CMU13},
             {"cmu14", CMU14},
             {"cmu_walks", WALKS},
             {"cmu_dance_sport", DANCE},
             {"animdraw", ANIMDRAW}};
#define NFOLDS ((int)(sizeof(FOLDS) / sizeof(FOLDS[0])))

const char *const *cub_ft_fold(const char *name)
{
    for (int i = 0; i < NFOLDS; i++)
        if (!strcmp(FOLDS[i].name, name)) return FOLDS[i].clips;
    return NULL;
}

const char *cub_ft_fold_name(int i)
{
    return i >= 0 && i < NFOLDS ? FOLDS[i].name : NULL;
}

static int contains_ci(const char *s, const char *word)
{
    for (; *s; s++) {
        size_t k = 0;
        while (word[k] && s[k] && tolower((unsigned char)s[k]) == word[k])
            k++;
        if (!word[k]) return 1;
    }
    return 0;
}

int cub_ft_shippable(const char *clip)
{
    /* Bandai's short names are dataset-1_<motion>_<style>_<take> */
    return !contains_ci(clip, "bandai") && !contains_ci(clip, "dataset-") &&
           !contains_ci(clip, "dog");
}

static cub_err grow(cub_ft_set *set)
{
    if (set->n < set->cap) return CUB_OK;
    int cap = set->cap ? 2 * set->cap : 16;
    cub_ft_frame *f = realloc(set->frames, (size_t)cap * sizeof(*f));
    if (!f) return CUB_ERR_NOMEM;
    set->frames = f;
    set->cap = cap;
    return CUB_OK;
}

/* The frame just rendered, cut to the player, appended. */
static cub_err keep_frame(cub_ft_set *set, cub_synth *s, const uint16_t *raw, const uint8_t *owner)
{
    cub_ft_frame fr = {malloc(NPIX * sizeof(uint16_t)), malloc(NPIX)};
    if (!fr.mm || !fr.part || grow(set)) {
        free(fr.mm);
        free(fr.part);
        return CUB_ERR_NOMEM;
    }
    cub_synth_parts(s, fr.part);
    for (int i = 0; i < NPIX; i++) {
        double mm = raw[i] < 2047 ? cub_synth_raw_to_mm(raw[i]) : 0;
        fr.mm[i] = owner[i] == 1 ? (uint16_t)(mm + 0.5) : 0;
        if (owner[i] != 1) fr.part[i] = CUB_PART_NONE;
    }
    set->frames[set->n++] = fr;
    return CUB_OK;
}

cub_err cub_ft_add_clip(cub_ft_set *set, const cub_ft_render *r, const char *spec, cub_diag *diag)
{
    cub_synth_segment seg = {0};
    snprintf(seg.clip, sizeof(seg.clip), "%s", spec);
    char *at = strchr(seg.clip, '@');
    if (at) *at = 0, seg.from_s = atof(at + 1);
    seg.to_s = seg.from_s + (double)r->frames * r->step / 30.0;
    cub_synth_desc d = {.data_dir = r->data_dir, .seed = r->seed,
                        .yaw_segment_s = r->no_turn ? 0.0f : 1.5f,
                        .max_travel_mm = 700};
    cub_synth *s = NULL;
    cub_err err = cub_synth_open(&d, &seg, 1, &s, diag);
    if (err) return err;
    uint16_t *raw = malloc(NPIX * sizeof(uint16_t));
    uint8_t *owner = malloc(NPIX);
    err = raw && owner ? CUB_OK : CUB_ERR_NOMEM;
    int total = cub_synth_frame_count(s);
    for (int k = 0; k < r->frames && k * r->step < total && !err; k++) {
        err = cub_synth_render(s, k * r->step, raw, NULL, NULL, owner);
        if (!err) err = keep_frame(set, s, raw, owner);
    }
    free(raw);
    free(owner);
    cub_synth_close(s);
    return err;
}

void cub_ft_set_free(cub_ft_set *set)
{
    for (int i = 0; i < set->n; i++) {
        free(set->frames[i].mm);
        free(set->frames[i].part);
    }
    free(set->frames);
    memset(set, 0, sizeof(*set));
}

void cub_ft_score_set(const cub_forest *f, const cub_ft_set *set, int stride, cub_ft_score *s)
{
    uint32_t score[CUB_FOREST_MAX_CLASSES];
    for (int k = 0; k < set->n; k++) {
        const cub_ft_frame *fr = &set->frames[k];
        cub_forest_image im = {fr->mm, CUB_KINECT_WIDTH, CUB_KINECT_HEIGHT};
        for (int i = 0, seen = 0; i < NPIX; i++) {
            if (!fr->mm[i] || !fr->part[i] || seen++ % stride) continue;
            int c = cub_forest_classify(f, &im, i % CUB_KINECT_WIDTH, i / CUB_KINECT_WIDTH, score);
            for (int q = 0; q < f->classes; q++)
                if (q != c && score[q] == score[c]) {
                    s->ties++;
                    break;
                }
            s->n[fr->part[i]]++;
            s->named[fr->part[i]][c < CUB_PART_COUNT ? c : 0]++;
            s->right[fr->part[i]] += c == fr->part[i];
        }
    }
}
