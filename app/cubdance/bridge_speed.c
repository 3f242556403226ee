/* What the box shows against the library's joint speed (bridge_speed.h). */
#include "bridge_speed.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/pack.h"

static const char *const kind_names[CUB_BRIDGE_KINDS] = {"taught", "into_groove",
                                                         "out_of_groove"};

cub_err cub_bridge_speed_init(cub_bridge_speed *b, const cub_dance *d)
{
    memset(b, 0, sizeof *b);
    b->p99_mm_s = cub_library_joint_speed_pct(&d->cl.lib, 0.99);
    b->prev_us = -1;
    b->switches = d->dir.switch_count;
    return b->p99_mm_s < 0 ? CUB_ERR_NOMEM : CUB_OK;
}

static bool is_groove(const cub_dance *d, int clip)
{
    const cub_coach_desc *c = &d->dir.desc.coach;
    for (int32_t g = 0; g < c->groove_count; g++)
        if (c->grooves[g].clip == clip) return true;
    return false;
}

static cub_bridge_kind kind_of(const cub_dance *d, const cub_bridge_step *s)
{
    return is_groove(d, s->to_clip)     ? CUB_BRIDGE_KIND_INTO_GROOVE
           : is_groove(d, s->from_clip) ? CUB_BRIDGE_KIND_OUT_OF_GROOVE
                                        : CUB_BRIDGE_KIND_TAUGHT;
}

static cub_err open_span(cub_bridge_speed *b, const cub_dance *d, int64_t t_us)
{
    if (b->count == b->cap) {
        const int cap = b->cap ? 2 * b->cap : 64;
        cub_bridge_span *s = realloc(b->spans, (size_t)cap * sizeof *s);
        if (!s) return CUB_ERR_NOMEM;
        b->spans = s;
        b->cap = cap;
    }
    b->spans[b->count++] = (cub_bridge_span){
        .t_us = t_us, .step = d->dir.last_switch, .kind = kind_of(d, &d->dir.last_switch),
        .max_joint = -1};
    b->open = 1;
    return CUB_OK;
}

static void count(cub_bridge_span *s, double mm_s, int joint, double p99)
{
    s->ticks++;
    s->over += mm_s > p99;
    if (mm_s > s->max_mm_s) s->max_mm_s = mm_s, s->max_joint = joint;
}

/* The fastest joint from pose a to pose b over dt_us (mm/s). */
static double fastest(const cub_vec3 *a, const cub_vec3 *b, int n, int64_t dt_us, int *joint)
{
    double best = 0;
    for (int j = 0; j < n; j++) {
        const double dx = (b[j].x - a[j].x) / 65536.0, dy = (b[j].y - a[j].y) / 65536.0,
                     dz = (b[j].z - a[j].z) / 65536.0;
        const double v = sqrt(dx * dx + dy * dy + dz * dz) * 1e6 / (double)dt_us;
        if (v > best) best = v, *joint = j;
    }
    return best;
}

/* The clip's own pose now, unblended, into b->raw; false when none. */
static bool raw_pose(cub_bridge_speed *b, const cub_dance *d)
{
    return !cub_bridge_player_raw_pose(&d->dir.player, &b->pose) &&
           !cub_motion_forward(&d->cl.lib.skel, &b->pose, b->raw, NULL);
}

void cub_bridge_speed_tick(cub_bridge_speed *b, const cub_dance *d, int64_t t_us)
{
    const bool switched = d->dir.switch_count != b->switches;
    if (switched) {
        b->switches = d->dir.switch_count;
        if (open_span(b, d, t_us)) b->open = 0;
    }
    const int n = d->cl.lib.skel.joint_count;
    const bool raw = raw_pose(b, d);
    if (b->prev_us >= 0 && t_us > b->prev_us) {
        int joint = -1, own_joint = -1;
        const double v = fastest(b->prev, d->world_mm, n, t_us - b->prev_us, &joint);
        cub_bridge_span *s = b->open ? &b->spans[b->count - 1]
                                     : &b->plain[is_groove(d, d->dir.player.clip)];
        count(s, v, joint, b->p99_mm_s);
        const double own = raw && !switched && d->dir.player.clip == b->prev_clip
                               ? fastest(b->prev_raw, b->raw, n, t_us - b->prev_us, &own_joint)
                               : 0;
        if (own > s->own_mm_s) s->own_mm_s = own;
    }
    memcpy(b->prev_raw, b->raw, sizeof b->raw);
    b->prev_clip = d->dir.player.clip;
    /* The switch's tick is counted with the bridge even when its blend is
     * already over (a cut within the threshold fades in a few frames). */
    if (!d->dir.player.blending) b->open = 0;
    memcpy(b->prev, d->world_mm, sizeof b->prev);
    b->prev_us = t_us;
}

static const char *joint_name(const cub_dance *d, int j)
{
    return j >= 0 ? d->cl.lib.skel.joints[j].name : "-";
}

static const char *clip_name(const cub_dance *d, int clip)
{
    const cub_coach_desc *c = &d->dir.desc.coach;
    return clip >= 0 && clip < c->clip_count && c->clip_names && c->clip_names[clip]
               ? c->clip_names[clip]
               : "?";
}

static void print_sums(const cub_bridge_speed *b, const char *what, int kind, FILE *out)
{
    int n = 0, ticks = 0, over = 0, spans_over = 0;
    double top = 0;
    for (int i = 0; i < b->count; i++) {
        const cub_bridge_span *s = &b->spans[i];
        if ((int)s->kind != kind) continue;
        n++, ticks += s->ticks, over += s->over, spans_over += s->over > 0;
        if (s->max_mm_s > top) top = s->max_mm_s;
    }
    fprintf(out, "sum %s bridges=%d over_bridges=%d ticks=%d over_ticks=%d max_mm_s=%.0f\n", what,
            n, spans_over, ticks, over, top);
}

void cub_bridge_speed_print(const cub_bridge_speed *b, const cub_dance *d, FILE *out)
{
    fprintf(out, "library joint speed p99 %.0f mm/s (every joint of every clip at its own rate)\n",
            b->p99_mm_s);
    for (int i = 0; i < b->count; i++) {
        const cub_bridge_span *s = &b->spans[i];
        fprintf(out,
                "bridge t=%.3f kind=%s from=%s@%d to=%s@%d ticks=%d max_mm_s=%.0f joint=%s "
                "over=%d own_mm_s=%.0f\n",
                s->t_us / 1e6, kind_names[s->kind], clip_name(d, s->step.from_clip),
                s->step.from_frame, clip_name(d, s->step.to_clip), s->step.to_frame, s->ticks,
                s->max_mm_s, joint_name(d, s->max_joint), s->over, s->own_mm_s);
    }
    for (int k = 0; k < CUB_BRIDGE_KINDS; k++) print_sums(b, kind_names[k], k, out);
    for (int k = 0; k < 2; k++)
        fprintf(out, "sum %s ticks=%d over_ticks=%d max_mm_s=%.0f joint=%s own_mm_s=%.0f\n",
                k ? "in_groove_clips" : "in_taught_clips", b->plain[k].ticks, b->plain[k].over,
                b->plain[k].max_mm_s, joint_name(d, b->plain[k].max_joint), b->plain[k].own_mm_s);
}

void cub_bridge_speed_free(cub_bridge_speed *b)
{
    free(b->spans);
    memset(b, 0, sizeof *b);
}
