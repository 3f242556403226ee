/* sf2_trim — see sf2_trim.h. The SoundFont 2.04 layout: RIFF "sfbk" holding
 * LIST INFO (copied as is), LIST sdta (smpl: 16-bit points) and LIST pdta,
 * nine record arrays each ending in a terminal record: presets (phdr) own
 * bags (pbag) of generators (pgen) and modulators (pmod); a preset bag's
 * generator 41 names an instrument (inst, with ibag / igen / imod), an
 * instrument bag's generator 53 a sample header (shdr: offsets into smpl). */
#include "sf2_trim.h"

#include <stdlib.h>
#include <string.h>

#define GUARD_POINTS 46 /* zero points the standard puts after each sample */
#define GEN_INSTRUMENT 41
#define GEN_SAMPLE_ID 53
#define SAMPLE_ROM 0x8000
#define MAX_CHUNK ((uint32_t)1 << 30)

enum { PHDR, PBAG, PMOD, PGEN, INST, IBAG, IMOD, IGEN, SHDR, NREC };
static const char REC_ID[NREC][5] = {"phdr", "pbag", "pmod", "pgen", "inst",
                                     "ibag", "imod", "igen", "shdr"};
static const uint32_t REC_SIZE[NREC] = {38, 4, 10, 4, 22, 4, 10, 4, 46};

typedef struct sf2 {
    FILE *f;
    const char *name;
    cub_diag *diag;
    uint32_t info_at, info_len; /* the INFO list, header included */
    uint32_t smpl_at, smpl_points;
    uint8_t *rec[NREC];
    uint32_t count[NREC]; /* records, terminal included */
} sf2;

/* What the trimmed file keeps, and where each kept thing goes. */
typedef struct plan {
    uint32_t *inst_new, *smp_new; /* old index -> new, UINT32_MAX = dropped */
    uint32_t *smp_lo, *smp_hi;    /* the points copied for each kept sample */
    uint32_t n_inst, n_smp, points;
} plan;

static uint16_t le16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}
static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)le16(p) | (uint32_t)le16(p + 2) << 16;
}
static void put16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v, p[1] = (uint8_t)(v >> 8);
}
static void put32(uint8_t *p, uint32_t v)
{
    put16(p, v), put16(p + 2, v >> 16);
}

static cub_err fail(sf2 *s, cub_err e, const char *what)
{
    return cub_diag_fail(s->diag, e, s->name, 0, "SoundFont: %s", what);
}

static cub_err read_at(sf2 *s, uint32_t at, void *buf, size_t n)
{
    if (fseek(s->f, (long)at, SEEK_SET) != 0 || fread(buf, 1, n, s->f) != n)
        return fail(s, CUB_ERR_FORMAT, "the file ends inside a chunk");
    return CUB_OK;
}

/* A chunk header at `at` inside a list ending at `end`: id and length. */
static cub_err chunk(sf2 *s, uint32_t at, uint32_t end, char id[5], uint32_t *len)
{
    uint8_t h[8];
    if (end - at < 8) return fail(s, CUB_ERR_FORMAT, "a chunk header past its list");
    cub_err e = read_at(s, at, h, 8);
    if (e) return e;
    memcpy(id, h, 4);
    id[4] = '\0';
    *len = le32(h + 4);
    if (*len > end - at - 8) return fail(s, CUB_ERR_FORMAT, "a chunk longer than its list");
    return CUB_OK;
}

static cub_err read_sdta(sf2 *s, uint32_t at, uint32_t end)
{
    for (uint32_t len; at < end; at += 8 + len + (len & 1)) {
        char id[5];
        cub_err e = chunk(s, at, end, id, &len);
        if (e) return e;
        if (!strcmp(id, "sm24")) return fail(s, CUB_ERR_UNSUPPORTED, "24-bit samples (sm24)");
        if (!strcmp(id, "smpl")) s->smpl_at = at + 8, s->smpl_points = len / 2;
        if (len & 1 && end - at - 8 == len) break; /* an odd last chunk without its pad */
    }
    return CUB_OK;
}

static cub_err read_pdta(sf2 *s, uint32_t at, uint32_t end)
{
    if (s->rec[PHDR]) return fail(s, CUB_ERR_FORMAT, "two preset data (pdta) lists");
    for (int r = 0; r < NREC; r++) {
        char id[5];
        uint32_t len;
        cub_err e = chunk(s, at, end, id, &len);
        if (e) return e;
        if (strcmp(id, REC_ID[r]) != 0 || len % REC_SIZE[r] || len < REC_SIZE[r])
            return fail(s, CUB_ERR_FORMAT, "the preset data's nine chunks are not in order");
        s->rec[r] = malloc(len);
        if (!s->rec[r]) return fail(s, CUB_ERR_NOMEM, "out of memory");
        if ((e = read_at(s, at + 8, s->rec[r], len))) return e;
        s->count[r] = len / REC_SIZE[r];
        at += 8 + len;
    }
    return CUB_OK;
}

static const uint8_t *rec(const sf2 *s, int r, uint32_t i)
{
    return s->rec[r] + i * REC_SIZE[r];
}

/* The bag index of a header (offset 20 in inst, 24 in phdr). */
static uint32_t bag_of(const sf2 *s, int r, uint32_t i)
{
    return le16(rec(s, r, i) + (r == PHDR ? 24 : 20));
}

/* Every header's bags, every bag's generators and modulators, increasing
 * and inside their arrays: what the rest relies on. */
static cub_err check_indices(sf2 *s)
{
    static const int hdr[2] = {PHDR, INST}, bag[2] = {PBAG, IBAG}, gen[2] = {PGEN, IGEN},
                     mod[2] = {PMOD, IMOD};
    for (int k = 0; k < 2; k++) {
        for (uint32_t i = 0; i + 1 < s->count[hdr[k]]; i++)
            if (bag_of(s, hdr[k], i) > bag_of(s, hdr[k], i + 1))
                return fail(s, CUB_ERR_FORMAT, "bag indices go backwards");
        if (bag_of(s, hdr[k], s->count[hdr[k]] - 1) >= s->count[bag[k]])
            return fail(s, CUB_ERR_FORMAT, "a bag index past the bags");
        for (uint32_t i = 0; i + 1 < s->count[bag[k]]; i++) {
            const uint8_t *b = rec(s, bag[k], i);
            if (le16(b) > le16(b + 4) || le16(b + 2) > le16(b + 6))
                return fail(s, CUB_ERR_FORMAT, "generator or modulator indices go backwards");
        }
        const uint8_t *last = rec(s, bag[k], s->count[bag[k]] - 1);
        if (le16(last) >= s->count[gen[k]] || le16(last + 2) >= s->count[mod[k]])
            return fail(s, CUB_ERR_FORMAT, "a generator or modulator index past its array");
    }
    return CUB_OK;
}

static cub_err read_file(sf2 *s)
{
    uint8_t h[12];
    if (fseek(s->f, 0, SEEK_END) != 0) return fail(s, CUB_ERR_IO, "cannot seek");
    long size = ftell(s->f);
    if (size < 12 || (unsigned long)size > MAX_CHUNK) return fail(s, CUB_ERR_FORMAT, "a bad size");
    cub_err e = read_at(s, 0, h, 12);
    if (e) return e;
    if (memcmp(h, "RIFF", 4) || memcmp(h + 8, "sfbk", 4))
        return fail(s, CUB_ERR_FORMAT, "no RIFF sfbk header");
    uint32_t end = le32(h + 4) < (uint32_t)size - 8 ? le32(h + 4) + 8 : (uint32_t)size;
    int seen = 0;
    for (uint32_t at = 12, len; at < end; at += 8 + len + (len & 1)) {
        char id[5];
        uint8_t type[4];
        if ((e = chunk(s, at, end, id, &len))) return e;
        if (strcmp(id, "LIST") || len < 4) continue;
        if ((e = read_at(s, at + 8, type, 4))) return e;
        if (!memcmp(type, "INFO", 4)) s->info_at = at, s->info_len = 8 + len, seen |= 1;
        if (!memcmp(type, "sdta", 4) && (e = read_sdta(s, at + 12, at + 8 + len))) return e;
        if (!memcmp(type, "pdta", 4) && (e = read_pdta(s, at + 12, at + 8 + len))) return e;
        if (len & 1 && end - at - 8 == len) break;
    }
    if (!(seen & 1) || !s->smpl_at || !s->rec[SHDR])
        return fail(s, CUB_ERR_FORMAT, "an INFO, sdta or pdta list is missing");
    return check_indices(s);
}

/* Mark `what` (instrument or sample) named by generator `oper` in every
 * bag of header i of array r: new index = order of first use is not kept;
 * marks only, numbered later in the original order. */
static cub_err mark_refs(sf2 *s, int r, uint32_t i, uint16_t oper, uint32_t limit, uint32_t *mark)
{
    int bag = r == PHDR ? PBAG : IBAG, gen = r == PHDR ? PGEN : IGEN;
    for (uint32_t b = bag_of(s, r, i); b < bag_of(s, r, i + 1); b++)
        for (uint32_t g = le16(rec(s, bag, b)); g < le16(rec(s, bag, b + 1)); g++) {
            const uint8_t *gp = rec(s, gen, g);
            if (le16(gp) != oper) continue;
            if (le16(gp + 2) >= limit) return fail(s, CUB_ERR_FORMAT, "a reference past its array");
            mark[le16(gp + 2)] = 0;
        }
    return CUB_OK;
}

static int wanted(const cub_sf2_presets *w, int bank, int program)
{
    for (int i = 0; i < w->count; i++)
        if (w->bank[i] == bank && w->program[i] == program) return 1;
    return 0;
}

/* Number the marked entries 0.. in their original order; return the count. */
static uint32_t number(uint32_t *mark, uint32_t n)
{
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++)
        if (mark[i] == 0)
            mark[i] = k++;
        else
            mark[i] = UINT32_MAX;
    return k;
}

/* The points of sample i to copy: the sample, its loop, the guard points. */
static cub_err sample_range(sf2 *s, uint32_t i, uint32_t *lo, uint32_t *hi)
{
    const uint8_t *h = rec(s, SHDR, i);
    uint32_t start = le32(h + 20), end = le32(h + 24), ls = le32(h + 28), le = le32(h + 32);
    if (le16(h + 44) & SAMPLE_ROM) return fail(s, CUB_ERR_UNSUPPORTED, "a ROM sample");
    if (start > end || end > s->smpl_points)
        return fail(s, CUB_ERR_FORMAT, "a sample outside the sample data");
    *lo = ls < start && ls <= le ? ls : start;
    uint32_t top = le > end && le <= s->smpl_points ? le : end;
    *hi = s->smpl_points - top > GUARD_POINTS ? top + GUARD_POINTS : s->smpl_points;
    /* A loop reaching outside the sample and the data: FluidSynth clamps
     * it against the whole sample chunk, which a cut file would change. */
    if (ls < *lo || le < *lo || le > *hi)
        return fail(s, CUB_ERR_UNSUPPORTED, "a loop outside its sample");
    return CUB_OK;
}

static cub_err make_plan(sf2 *s, const cub_sf2_presets *want, plan *p)
{
    uint32_t ni = s->count[INST] - 1, ns = s->count[SHDR] - 1;
    p->inst_new = malloc((ni + 1) * sizeof *p->inst_new);
    p->smp_new = malloc((ns + 1) * sizeof *p->smp_new);
    p->smp_lo = calloc(ns + 1, sizeof *p->smp_lo);
    p->smp_hi = calloc(ns + 1, sizeof *p->smp_hi);
    if (!p->inst_new || !p->smp_new || !p->smp_lo || !p->smp_hi)
        return fail(s, CUB_ERR_NOMEM, "out of memory");
    memset(p->inst_new, 0xFF, (ni + 1) * sizeof *p->inst_new);
    memset(p->smp_new, 0xFF, (ns + 1) * sizeof *p->smp_new);
    int found = 0;
    for (uint32_t i = 0; i + 1 < s->count[PHDR]; i++) {
        const uint8_t *h = rec(s, PHDR, i);
        if (!wanted(want, le16(h + 22), le16(h + 20))) continue;
        cub_err e = mark_refs(s, PHDR, i, GEN_INSTRUMENT, ni, p->inst_new);
        if (e) return e;
        found++;
    }
    for (int k = 0; k < want->count; k++) {
        int have = 0;
        for (uint32_t i = 0; i + 1 < s->count[PHDR] && !have; i++)
            have = le16(rec(s, PHDR, i) + 22) == want->bank[k] &&
                   le16(rec(s, PHDR, i) + 20) == want->program[k];
        if (!have) return fail(s, CUB_ERR_UNSUPPORTED, "a preset the song uses is missing");
    }
    for (uint32_t i = 0; i < ni; i++) {
        if (p->inst_new[i] != 0) continue;
        cub_err e = mark_refs(s, INST, i, GEN_SAMPLE_ID, ns, p->smp_new);
        if (e) return e;
    }
    /* Stereo pairs: FluidSynth reads a sample's link; keep the partner. */
    for (uint32_t i = 0; i < ns; i++) {
        uint16_t link = le16(rec(s, SHDR, i) + 42);
        if (p->smp_new[i] == 0 && (le16(rec(s, SHDR, i) + 44) & 0xE) && link < ns)
            p->smp_new[link] = 0;
    }
    p->n_inst = number(p->inst_new, ni);
    p->n_smp = number(p->smp_new, ns);
    for (uint32_t i = 0; i < ns; i++) {
        if (p->smp_new[i] == UINT32_MAX) continue;
        cub_err e = sample_range(s, i, &p->smp_lo[i], &p->smp_hi[i]);
        if (e) return e;
        p->points += p->smp_hi[i] - p->smp_lo[i];
    }
    return found ? CUB_OK : fail(s, CUB_ERR_UNSUPPORTED, "no preset the song uses");
}

/* The trimmed file's preset data: headers of kind r (PHDR or INST) kept by
 * keep(), with their bags, generators (oper remapped through map) and
 * modulators. With out NULL only counts; the terminal records included. */
typedef struct counts {
    uint32_t hdr, bag, mod, gen;
} counts;

typedef struct cursor {
    uint8_t *p;
} cursor;

static void put(cursor *c, const void *src, uint32_t n)
{
    if (c->p) memcpy(c->p, src, n), c->p += n;
}

static counts zones(const sf2 *s, int r, const uint8_t *keep, uint16_t oper, const uint32_t *map,
                    cursor *hc, cursor *bc, cursor *mc, cursor *gc)
{
    int bag = r == PHDR ? PBAG : IBAG, gen = r == PHDR ? PGEN : IGEN, mod = r == PHDR ? PMOD : IMOD;
    uint32_t bag_at = r == PHDR ? 24 : 20;
    counts n = {0};
    for (uint32_t i = 0; i + 1 <= s->count[r]; i++) {
        int last = i + 1 == s->count[r];
        if (!last && !keep[i]) continue;
        uint8_t h[38];
        memcpy(h, rec(s, r, i), REC_SIZE[r]);
        put16(h + bag_at, n.bag);
        put(hc, h, REC_SIZE[r]);
        n.hdr++;
        if (last) break;
        for (uint32_t b = bag_of(s, r, i); b < bag_of(s, r, i + 1); b++) {
            uint8_t nb[4];
            put16(nb, n.gen), put16(nb + 2, n.mod);
            put(bc, nb, 4);
            n.bag++;
            const uint8_t *bp = rec(s, bag, b);
            for (uint32_t g = le16(bp); g < le16(bp + 4); g++, n.gen++) {
                uint8_t gp[4];
                memcpy(gp, rec(s, gen, g), 4);
                if (le16(gp) == oper) put16(gp + 2, map[le16(gp + 2)]);
                put(gc, gp, 4);
            }
            for (uint32_t m = le16(bp + 2); m < le16(bp + 6); m++, n.mod++)
                put(mc, rec(s, mod, m), REC_SIZE[mod]);
        }
    }
    /* The terminal bag, modulator and generator. */
    uint8_t nb[4];
    put16(nb, n.gen), put16(nb + 2, n.mod);
    put(bc, nb, 4);
    put(mc, rec(s, mod, s->count[mod] - 1), REC_SIZE[mod]);
    put(gc, rec(s, gen, s->count[gen] - 1), 4);
    n.bag++, n.mod++, n.gen++;
    return n;
}

static uint8_t *chunk_head(uint8_t *p, const char *id, uint32_t len)
{
    memcpy(p, id, 4);
    put32(p + 4, len);
    return p + 8;
}

/* Kept samples' points, then their headers with offsets moved. */
static cub_err write_samples(sf2 *s, const plan *p, uint8_t *data, uint8_t *shdr)
{
    uint32_t at = 0, ns = s->count[SHDR] - 1;
    for (uint32_t i = 0; i < ns; i++) {
        if (p->smp_new[i] == UINT32_MAX) continue;
        uint32_t lo = p->smp_lo[i], n = p->smp_hi[i] - lo;
        cub_err e = read_at(s, s->smpl_at + lo * 2, data + (size_t)at * 2, (size_t)n * 2);
        if (e) return e;
        uint8_t *h = shdr + (size_t)p->smp_new[i] * 46;
        memcpy(h, rec(s, SHDR, i), 46);
        for (int k = 0; k < 4; k++)
            put32(h + 20 + 4 * k, at + le32(h + 20 + 4 * k) - lo);
        uint16_t link = le16(h + 42);
        if ((le16(h + 44) & 0xE) && link < ns && p->smp_new[link] != UINT32_MAX)
            put16(h + 42, p->smp_new[link]);
        at += n;
    }
    memcpy(shdr + (size_t)p->n_smp * 46, rec(s, SHDR, ns), 46);
    return CUB_OK;
}

static cub_err write_trimmed(sf2 *s, const plan *p, const cub_sf2_presets *want, uint8_t **out,
                             size_t *out_len)
{
    uint8_t *keep_p = calloc(s->count[PHDR], 1), *keep_i = calloc(s->count[INST], 1);
    if (!keep_p || !keep_i) {
        free(keep_p), free(keep_i);
        return fail(s, CUB_ERR_NOMEM, "out of memory");
    }
    for (uint32_t i = 0; i + 1 < s->count[PHDR]; i++)
        keep_p[i] = (uint8_t)wanted(want, le16(rec(s, PHDR, i) + 22), le16(rec(s, PHDR, i) + 20));
    for (uint32_t i = 0; i + 1 < s->count[INST]; i++)
        keep_i[i] = p->inst_new[i] != UINT32_MAX;
    cursor none = {0};
    counts cp = zones(s, PHDR, keep_p, GEN_INSTRUMENT, p->inst_new, &none, &none, &none, &none);
    counts ci = zones(s, INST, keep_i, GEN_SAMPLE_ID, p->smp_new, &none, &none, &none, &none);
    uint32_t len[NREC] = {cp.hdr * 38, cp.bag * 4,  cp.mod * 10, cp.gen * 4,         ci.hdr * 22,
                          ci.bag * 4,  ci.mod * 10, ci.gen * 4,  (p->n_smp + 1) * 46};
    uint32_t info = s->info_len + (s->info_len & 1), sdta = 4 + 8 + p->points * 2, pdta = 4;
    for (int r = 0; r < NREC; r++)
        pdta += 8 + len[r];
    size_t total = 12 + info + 8 + sdta + 8 + pdta;
    uint8_t *buf = calloc(1, total);
    cub_err e = buf ? read_at(s, s->info_at, buf + 12, s->info_len)
                    : fail(s, CUB_ERR_NOMEM, "out of memory");
    if (!e) {
        memcpy(chunk_head(buf, "RIFF", (uint32_t)total - 8), "sfbk", 4);
        uint8_t *q = chunk_head(buf + 12 + info, "LIST", sdta);
        memcpy(q, "sdta", 4);
        uint8_t *data = chunk_head(q + 4, "smpl", p->points * 2);
        q = chunk_head(data + (size_t)p->points * 2, "LIST", pdta);
        memcpy(q, "pdta", 4);
        uint8_t *at[NREC];
        q += 4;
        for (int r = 0; r < NREC; r++)
            at[r] = chunk_head(q, REC_ID[r], len[r]), q = at[r] + len[r];
        cursor h = {at[PHDR]}, b = {at[PBAG]}, m = {at[PMOD]}, g = {at[PGEN]};
        zones(s, PHDR, keep_p, GEN_INSTRUMENT, p->inst_new, &h, &b, &m, &g);
        h.p = at[INST], b.p = at[IBAG], m.p = at[IMOD], g.p = at[IGEN];
        zones(s, INST, keep_i, GEN_SAMPLE_ID, p->smp_new, &h, &b, &m, &g);
        e = write_samples(s, p, data, at[SHDR]);
    }
    free(keep_p), free(keep_i);
    if (e) {
        free(buf);
        return e;
    }
    *out = buf;
    *out_len = total;
    return CUB_OK;
}

static void free_sf2(sf2 *s, plan *p)
{
    for (int r = 0; r < NREC; r++)
        free(s->rec[r]);
    free(p->inst_new);
    free(p->smp_new);
    free(p->smp_lo);
    free(p->smp_hi);
}

cub_err cub_sf2_presets_add(cub_sf2_presets *p, int bank, int program)
{
    if (!p || bank < 0 || bank > 128 || program < 0 || program > 127) return CUB_ERR_ARG;
    if (wanted(p, bank, program)) return CUB_OK;
    if (p->count == CUB_SF2_MAX_PRESETS) return CUB_ERR_FULL;
    p->bank[p->count] = (uint16_t)bank;
    p->program[p->count++] = (uint8_t)program;
    return CUB_OK;
}

cub_err cub_sf2_trim(FILE *f, const char *name, const cub_sf2_presets *want, uint8_t **out,
                     size_t *out_len, cub_diag *diag)
{
    cub_diag scratch;
    sf2 s = {.f = f, .name = name ? name : "(soundfont)", .diag = diag ? diag : &scratch};
    plan p = {0};
    if (!f || !want || !out || !out_len) return CUB_ERR_ARG;
    *out = NULL;
    *out_len = 0;
    cub_err e = read_file(&s);
    if (!e) e = make_plan(&s, want, &p);
    if (!e) e = write_trimmed(&s, &p, want, out, out_len);
    free_sf2(&s, &p);
    return e;
}

cub_err cub_sf2_check(FILE *f, const char *name, cub_diag *diag)
{
    cub_diag scratch;
    sf2 s = {.f = f, .name = name ? name : "(soundfont)", .diag = diag ? diag : &scratch};
    plan p = {0};
    if (!f) return CUB_ERR_ARG;
    cub_err e = read_file(&s);
    free_sf2(&s, &p);
    return e;
}
