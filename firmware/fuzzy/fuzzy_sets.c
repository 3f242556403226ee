/* fuzzy: the membership functions of seed 000 (SEEDS.md § 000, step 2),
 * the crisp pose class and the distance d (step 3).
 *
 * Every membership function is built from one piece: a clamped ramp that
 * is 0 at its foot and 1 at its plateau end, evaluated by exact integer
 * interpolation into Q1.15. At a breakpoint the result is exactly 0 or
 * CUB_FUZZY_ONE, so the breakpoints the seed prints hold bit for bit. */
#include <stddef.h>
#include <stdint.h>

#include "cub/fuzzy.h"

#define DEG(n) ((int64_t)(n)*65536) /* whole degrees (or Posture units) in Q16.16 */

/* 0 at x = foot, 1 at x = top, linear between, clamped outside; foot may be
 * above or below top. Rounded to nearest Q1.15. */
static uint16_t ramp(cub_q16 x, int foot, int top)
{
    int64_t span = DEG(top) - DEG(foot);
    int64_t num = (int64_t)x - DEG(foot);
    if (span < 0) {
        span = -span;
        num = -num;
    }
    if (num <= 0) return 0;
    if (num >= span) return CUB_FUZZY_ONE;
    return (uint16_t)((num * CUB_FUZZY_ONE + span / 2) / span);
}

/* A triangle: 0 at foot_lo, 1 at peak, 0 at foot_hi. */
static uint16_t triangle(cub_q16 x, int foot_lo, int peak, int foot_hi)
{
    return (int64_t)x <= DEG(peak) ? ramp(x, foot_lo, peak) : ramp(x, foot_hi, peak);
}

/* The five shapes; the left-side features mirror the right (same function). */
static void arm_raise(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 90, 20);          /* down = (90-x)/70 on [20,90] */
    mu[1] = triangle(x, 20, 90, 180); /* mid = (x-20)/70, then (180-x)/90 */
    mu[2] = ramp(x, 90, 180);         /* up = (x-90)/90 on [90,180] */
}

static void elbow_bent(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 90, 0);  /* false = (90-x)/90 for x <= 90 */
    mu[1] = ramp(x, 20, 90); /* true = (x-20)/70 on [20,90] */
}

static void posture(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 40, 0);           /* lie = (40-x)/40 on [0,40] */
    mu[1] = triangle(x, 0, 40, 80);   /* sit = x/40, then (80-x)/40 */
    mu[2] = triangle(x, 40, 80, 120); /* stand (the seed's fixed misprint) */
    mu[3] = ramp(x, 80, 120);         /* jump = (x-80)/40 on [80,120] */
}

static void trunk_bent(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 180, 110); /* true = (180-x)/70 on [110,180] */
    mu[1] = ramp(x, 125, 180); /* false = (x-125)/55 on [125,180] */
}

static void leg_out(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 40, 0); /* inward = (40-x)/40 on [0,40] */
    mu[1] = ramp(x, 0, 40); /* outward = x/40 on [0,40] */
}

static void knee_bent(cub_q16 x, uint16_t mu[])
{
    mu[0] = ramp(x, 180, 90);  /* true = (180-x)/90 on [90,180] */
    mu[1] = ramp(x, 100, 180); /* false = (x-100)/80 on [100,180] */
}

typedef struct feature_info {
    const char *name;
    int set_count;
    const char *sets[CUB_FUZZY_MAX_SETS];
    void (*membership)(cub_q16 x, uint16_t mu[]);
} feature_info;

static const feature_info features[CUB_FUZZY_FEATURE_COUNT] = {
    [CUB_FUZZY_RH] = {"RH", 3, {"down", "mid", "up"}, arm_raise},
    [CUB_FUZZY_RHE] = {"RHE", 2, {"false", "true"}, elbow_bent},
    [CUB_FUZZY_LH] = {"LH", 3, {"down", "mid", "up"}, arm_raise},
    [CUB_FUZZY_LHE] = {"LHE", 2, {"false", "true"}, elbow_bent},
    [CUB_FUZZY_POSTURE] = {"Posture", 4, {"lie", "sit", "stand", "jump"}, posture},
    [CUB_FUZZY_TRUNK] = {"Trunk", 2, {"true", "false"}, trunk_bent},
    [CUB_FUZZY_RF] = {"RF", 2, {"inward", "outward"}, leg_out},
    [CUB_FUZZY_RFK] = {"RFK", 2, {"true", "false"}, knee_bent},
    [CUB_FUZZY_LF] = {"LF", 2, {"inward", "outward"}, leg_out},
    [CUB_FUZZY_LFK] = {"LFK", 2, {"true", "false"}, knee_bent},
};

static int valid_feature(cub_fuzzy_feature f)
{
    return (int)f >= 0 && (int)f < CUB_FUZZY_FEATURE_COUNT;
}

int cub_fuzzy_set_count(cub_fuzzy_feature f)
{
    return valid_feature(f) ? features[f].set_count : 0;
}

const char *cub_fuzzy_set_name(cub_fuzzy_feature f, int s)
{
    if (!valid_feature(f) || s < 0 || s >= features[f].set_count) return "?";
    return features[f].sets[s];
}

const char *cub_fuzzy_feature_name(cub_fuzzy_feature f)
{
    return valid_feature(f) ? features[f].name : "?";
}

void cub_fuzzy_membership(cub_fuzzy_feature f, cub_q16 x, uint16_t mu[CUB_FUZZY_MAX_SETS])
{
    if (!mu) return;
    for (int s = 0; s < CUB_FUZZY_MAX_SETS; s++)
        mu[s] = 0; /* unused sets (and unknown features) read 0 */
    if (valid_feature(f)) features[f].membership(x, mu);
}

uint32_t cub_fuzzy_crisp_class(const cub_fuzzy_frame *f)
{
    if (!f) return 0;
    uint32_t cls = 0;
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        int best = 0;
        for (int s = 1; s < features[k].set_count; s++)
            if (f->mu[k][s] > f->mu[k][best]) best = s; /* strict: ties keep the lower */
        cls |= (uint32_t)best << (2 * k);
    }
    return cls;
}

/* Default weights S_k, before normalisation. The seed (with its fix) ranks
 * them: arms largest, the body features (Posture and Trunk) equal to the
 * arms, legs smallest. 3 : 1 keeps that with clear steps; the arms carry
 * the dance moves the child copies, while the Kinect's leg joints are the
 * noisiest, so a leg difference should count least. Trunk stays at 2 (sum
 * 21): Trunk at 3 gave the same bench-bridge figures and would move every
 * link (README, "Trunk's weight"). */
static const int default_weight[CUB_FUZZY_FEATURE_COUNT] = {
    [CUB_FUZZY_RH] = 3,      [CUB_FUZZY_RHE] = 3,   [CUB_FUZZY_LH] = 3, [CUB_FUZZY_LHE] = 3,
    [CUB_FUZZY_POSTURE] = 3, [CUB_FUZZY_TRUNK] = 2, [CUB_FUZZY_RF] = 1, [CUB_FUZZY_RFK] = 1,
    [CUB_FUZZY_LF] = 1,      [CUB_FUZZY_LFK] = 1,
};

#define DEFAULT_THRESHOLD ((cub_q16)26214) /* 0.4 (seed 000) */

/* Scale w (non-negative, sum > 0) so it sums to exactly CUB_Q16_ONE: each
 * rounded to nearest, the rounding remainder given to the largest. */
static void normalise(const int64_t w[], int64_t sum, cub_q16 out[])
{
    int64_t total = 0;
    int largest = 0;
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        out[k] = (cub_q16)((w[k] * CUB_Q16_ONE + sum / 2) / sum);
        total += out[k];
        if (w[k] > w[largest]) largest = k;
    }
    out[largest] += (cub_q16)(CUB_Q16_ONE - total);
}

cub_fuzzy_config cub_fuzzy_config_defaults(const cub_fuzzy_config *cfg)
{
    cub_fuzzy_config out = {0};
    int64_t w[CUB_FUZZY_FEATURE_COUNT], sum = 0;
    /* Negative weights mean nothing here: they count as 0. */
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        w[k] = cfg && cfg->weight[k] > 0 ? cfg->weight[k] : 0;
        sum += w[k];
    }
    if (sum == 0) {
        for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
            w[k] = default_weight[k];
            sum += w[k];
        }
    }
    normalise(w, sum, out.weight);
    out.threshold = cfg && cfg->threshold > 0 ? cfg->threshold : DEFAULT_THRESHOLD;
    return out;
}

/* d^2 = sum_k S_k * (sum_sets (mu1-mu2)^2) / 2. Each feature's sum of
 * squares is at most 2 (the memberships of each feature lie in [0,1] and
 * at most two sets differ fully: down vs up, lie vs stand...), so halving
 * it puts every feature's term in [0, 1] and, with sum S_k = 1, d in
 * [0, 1] as the header promises; the seed's threshold 0.4 applies to this
 * d. The weights are normalised here, so any cfg gives d in [0, 1]. */
cub_q16 cub_fuzzy_distance(const cub_fuzzy_frame *a, const cub_fuzzy_frame *b,
                           const cub_fuzzy_config *cfg)
{
    if (!a || !b) return CUB_Q16_ONE; /* nothing known: as far apart as can be */
    cub_fuzzy_config c = cub_fuzzy_config_defaults(cfg);
    int64_t d2_q46 = 0; /* Q16 weight x Q30 squares */
    for (int k = 0; k < CUB_FUZZY_FEATURE_COUNT; k++) {
        int64_t sq_q30 = 0; /* at most 4 * 2^30 */
        for (int s = 0; s < features[k].set_count; s++) {
            int64_t diff = (int64_t)a->mu[k][s] - b->mu[k][s];
            sq_q30 += diff * diff;
        }
        d2_q46 += (int64_t)c.weight[k] * sq_q30;
    }
    /* Halve (see above), go to Q32 with rounding, then sqrt gives Q16. */
    uint64_t d2_q32 = ((uint64_t)d2_q46 + ((uint64_t)1 << 14)) >> 15;
    uint32_t d = cub_fx_isqrt64(d2_q32);
    /* Round the square root to nearest: d or d+1, whichever squares closer. */
    if ((uint64_t)d * d + d < d2_q32) d++;
    return d > (uint32_t)CUB_Q16_ONE ? CUB_Q16_ONE : (cub_q16)d;
}
