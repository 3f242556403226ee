/* Kinect v1 effects on a clean depth image: the projector's shadow, edge
 * jitter and dropout, small holes, the disparity quantisation and the
 * 0.5-4 m range. Constants are rough fits to what real v1 frames show: at
 * depth edges the 9x9 correlation window of the sensor loses or smears
 * about half of the pixels, and a few small blobs fail on dark or shiny
 * spots. */
#include "synth_internal.h"

#define W CUB_KINECT_WIDTH
#define H CUB_KINECT_HEIGHT
#define EDGE_DROP_P 0.35f    /* an edge pixel with no reading */
#define EDGE_SMEAR_P 0.30f   /* an edge pixel taking a neighbour's depth */
#define PIXEL_DROP_P 0.001f  /* scattered single-pixel holes */
#define DISPARITY_SIGMA 0.2f /* raw units of noise before rounding */

uint64_t synth_rng_next(synth_rng *r)
{
    /* splitmix64: tiny, and the same sequence on every machine */
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

float synth_rng_unit(synth_rng *r)
{
    return (float)(synth_rng_next(r) >> 40) / 16777216.0f;
}

float synth_rng_gauss(synth_rng *r)
{
    /* Irwin-Hall of 4 uniforms: close enough to normal, no libm */
    float s = synth_rng_unit(r) + synth_rng_unit(r) + synth_rng_unit(r) + synth_rng_unit(r);
    return (s - 2.0f) * 1.7320508f;
}

/* The raw levels whose depth lies within 500..4000 mm: 405 (500.7 mm) to
 * 1005 (3994.3 mm); tests/synth checks them against the formula. */
#define RAW_LO 405
#define RAW_HI 1005

/* A depth in range, plus disparity noise, to a raw level in range (so
 * noise never leaves the range the Kinect reports). */
static uint16_t quantise(float mm, float noise_raw)
{
    if (!(mm >= CUB_SYNTH_MIN_MM && mm <= CUB_SYNTH_MAX_MM)) return CUB_KINECT_NO_READING;
    long r = lround(CUB_KINECT_RAW_PER_RAD * (atan(mm / CUB_KINECT_MM_SCALE) - CUB_KINECT_RAW_OFFSET_RAD) +
                    noise_raw);
    return (uint16_t)(r < RAW_LO ? RAW_LO : r > RAW_HI ? RAW_HI : r);
}

uint16_t cub_synth_mm_to_raw(double mm)
{
    return quantise((float)mm, 0);
}

double cub_synth_raw_to_mm(uint16_t raw)
{
    double a = raw / CUB_KINECT_RAW_PER_RAD + CUB_KINECT_RAW_OFFSET_RAD;
    if (raw >= CUB_KINECT_NO_READING || a >= 1.5707963267948966) return 0;
    return CUB_KINECT_MM_SCALE * tan(a);
}

/* Camera pixels whose surface the projector (75 mm to +x, same axes)
 * cannot light: the same row, shifted by the parallax 75 * F / z. */
static int shadowed(const float *proj, int u, int v, float z)
{
    float up = u - CUB_SYNTH_PROJECTOR_X_MM * CUB_KINECT_FOCAL_PX / z;
    int u0 = (int)floorf(up);
    if (u0 < 0 || u0 + 1 >= W) return 0;
    float a = proj[v * W + u0], b = proj[v * W + u0 + 1];
    float zp = fmaxf(a, b); /* the farther: no false shadow on slanted surfaces */
    return zp > 0 && z > zp * 1.01f + 15.0f;
}

static int is_edge(const float *d, int u, int v)
{
    float z = d[v * W + u];
    float tol = fmaxf(40.0f, 0.03f * z);
    static const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; k++) {
        int x = u + du[k], y = v + dv[k];
        if (x < 0 || y < 0 || x >= W || y >= H) continue;
        float n = d[y * W + x];
        if (n == 0 || fabsf(n - z) > tol) return 1;
    }
    return 0;
}

static void holes(synth_rng *rng, uint16_t *raw)
{
    int blobs = 3 + (int)(synth_rng_next(rng) % 6);
    for (int b = 0; b < blobs; b++) {
        int cu = (int)(synth_rng_next(rng) % W), cv = (int)(synth_rng_next(rng) % H);
        int r = 1 + (int)(synth_rng_next(rng) % 3);
        for (int y = cv - r; y <= cv + r; y++)
            for (int x = cu - r; x <= cu + r; x++)
                if (x >= 0 && y >= 0 && x < W && y < H &&
                    (x - cu) * (x - cu) + (y - cv) * (y - cv) <= r * r)
                    raw[y * W + x] = CUB_KINECT_NO_READING;
    }
}

void synth_kinect_apply(const float *depth, const float *proj, int clean, synth_rng *rng,
                        uint16_t *raw)
{
    for (int v = 0; v < H; v++)
        for (int u = 0; u < W; u++) {
            int i = v * W + u;
            float z = depth[i];
            if (z <= 0) {
                raw[i] = CUB_KINECT_NO_READING;
                continue;
            }
            if (clean) {
                raw[i] = quantise(z, 0);
                continue;
            }
            if (shadowed(proj, u, v, z) || synth_rng_unit(rng) < PIXEL_DROP_P) {
                raw[i] = CUB_KINECT_NO_READING;
                continue;
            }
            if (is_edge(depth, u, v)) {
                float r = synth_rng_unit(rng);
                if (r < EDGE_DROP_P) {
                    raw[i] = CUB_KINECT_NO_READING;
                    continue;
                }
                if (r < EDGE_DROP_P + EDGE_SMEAR_P) {
                    int x = u + (int)(synth_rng_next(rng) % 5) - 2;
                    int y = v + (int)(synth_rng_next(rng) % 5) - 2;
                    if (x >= 0 && y >= 0 && x < W && y < H) z = depth[y * W + x];
                    if (z <= 0) {
                        raw[i] = CUB_KINECT_NO_READING;
                        continue;
                    }
                }
            }
            raw[i] = quantise(z, DISPARITY_SIGMA * synth_rng_gauss(rng));
        }
    if (!clean) holes(rng, raw);
}
