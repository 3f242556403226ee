/* render_font_check — is a font file safe to hand to stb_truetype?
 *
 * stb_truetype trusts every offset in the file ("no range checking" in its
 * own header), so a half-copied or corrupted font makes it read outside
 * the buffer (a SEGV, issue 18). This walks exactly what the atlas bake
 * reads — the table directory, head, hhea, hmtx, maxp, the cmap subtable
 * stb picks (the last Unicode one), loca, and the outline of every glyph
 * the atlas's codepoints map to, composites included — and checks each
 * offset and length against the file size. CFF outlines (.otf) are
 * refused: stb's CFF reader bounds itself by 512 MB, not by the file. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "render_internal.h"

#define MAX_COMPOSITE_DEPTH 8 /* stb recurses on components: a cycle would never end */

typedef struct font {
    const unsigned char *d;
    uint64_t n;
    uint64_t loca, loca_len, glyf, glyf_len;
    unsigned num_glyphs, loc_format;
    char *why;
    size_t size;
} font;

static int bad(font *f, const char *fmt, unsigned a, unsigned b)
{
    if (f->why && f->size)
        snprintf(f->why, f->size, fmt, a, b);
    return 0;
}

/* Reads that fail (return 0 and clear *ok) past the end of the file. */
static unsigned u16(const font *f, uint64_t at, int *ok)
{
    if (at + 2 > f->n) {
        *ok = 0;
        return 0;
    }
    return (unsigned)f->d[at] << 8 | f->d[at + 1];
}

static uint32_t u32(const font *f, uint64_t at, int *ok)
{
    if (at + 4 > f->n) {
        *ok = 0;
        return 0;
    }
    return (uint32_t)f->d[at] << 24 | (uint32_t)f->d[at + 1] << 16 | (uint32_t)f->d[at + 2] << 8 |
           f->d[at + 3];
}

/* The table's offset (0 when absent, as stbtt__find_table) and its length. */
static uint64_t table(const font *f, uint64_t start, const char *tag, uint64_t *len)
{
    int ok = 1;
    unsigned count = u16(f, start + 4, &ok);
    for (unsigned i = 0; i < count; i++) {
        uint64_t rec = start + 12 + 16 * (uint64_t)i;
        if (memcmp(f->d + rec, tag, 4) == 0) {
            *len = u32(f, rec + 12, &ok);
            return u32(f, rec + 8, &ok);
        }
    }
    *len = 0;
    return 0;
}

static int need(font *f, uint64_t start, const char *tag, uint64_t min_len, uint64_t *at,
                uint64_t *len)
{
    *at = table(f, start, tag, len);
    const char *why = !*at                 ? "no %s table"
                      : *at + *len > f->n ? "the %s table runs past the end of the file"
                      : *len < min_len     ? "the %s table is too short"
                                           : NULL;
    if (why && f->why && f->size)
        snprintf(f->why, f->size, why, tag);
    return !why;
}

/* stbtt_FindGlyphIndex for one codepoint, every read bounded. */
static int glyph_of(font *f, uint64_t map, unsigned cp, unsigned *gi)
{
    int ok = 1;
    unsigned format = u16(f, map, &ok);
    *gi = 0;
    if (format == 0) {
        unsigned bytes = u16(f, map + 2, &ok);
        if (cp + 6 < bytes) {
            ok = ok && map + 6 + cp < f->n;
            *gi = ok ? f->d[map + 6 + cp] : 0;
        }
    } else if (format == 6) {
        unsigned first = u16(f, map + 6, &ok), count = u16(f, map + 8, &ok);
        if (cp >= first && cp < first + count)
            *gi = u16(f, map + 10 + (uint64_t)(cp - first) * 2, &ok);
    } else if (format == 4) {
        /* uint32_t arithmetic as stb does it, so a garbage search lands
         * where stb's would, and is then refused. */
        unsigned segcount = u16(f, map + 6, &ok) >> 1;
        unsigned range = u16(f, map + 8, &ok) >> 1;
        unsigned selector = u16(f, map + 10, &ok);
        unsigned shift = u16(f, map + 12, &ok) >> 1;
        uint32_t end_count = (uint32_t)map + 14, search = end_count;
        if (cp >= u16(f, search + shift * 2, &ok))
            search += shift * 2;
        search -= 2;
        while (selector && ok) {
            range >>= 1;
            if (cp > u16(f, (uint32_t)(search + range * 2), &ok))
                search += range * 2;
            --selector;
        }
        search += 2;
        unsigned item = (uint16_t)((search - end_count) >> 1);
        unsigned start = u16(f, (uint32_t)(map + 14 + segcount * 2 + 2 + 2 * item), &ok);
        unsigned last = u16(f, (uint32_t)(end_count + 2 * item), &ok);
        if (ok && cp >= start && cp <= last) {
            uint32_t at = (uint32_t)(map + 14 + segcount * 6 + 2 + 2 * item);
            unsigned offset = u16(f, at, &ok);
            if (offset == 0)
                *gi = (uint16_t)(cp + u16(f, (uint32_t)(map + 14 + segcount * 4 + 2 + 2 * item), &ok));
            else
                *gi = u16(f, (uint32_t)(offset + (cp - start) * 2 + at), &ok);
        }
    } else if (format == 12 || format == 13) {
        uint32_t groups = u32(f, map + 12, &ok);
        if (!ok || map + 16 + (uint64_t)groups * 12 > f->n)
            return bad(f, "the cmap's groups run past the end of the file", 0, 0);
        for (uint32_t lo = 0, hi = groups; lo < hi;) {
            uint32_t mid = lo + ((hi - lo) >> 1);
            uint32_t first = u32(f, map + 16 + (uint64_t)mid * 12, &ok);
            uint32_t last = u32(f, map + 20 + (uint64_t)mid * 12, &ok);
            if (cp < first) {
                hi = mid;
            } else if (cp > last) {
                lo = mid + 1;
            } else {
                uint32_t g = u32(f, map + 24 + (uint64_t)mid * 12, &ok);
                g = format == 12 ? g + (cp - first) : g;
                *gi = g > 0xffff ? 0xffffffu : g;
                break;
            }
        }
    } else {
        return bad(f, "cmap subtable format %u is not supported", format, 0);
    }
    if (!ok)
        return bad(f, "the cmap lookup of U+%04X runs past the end of the file", cp, 0);
    if (*gi >= f->num_glyphs)
        return bad(f, "the cmap maps U+%04X to a glyph past the last (%u)", cp, f->num_glyphs);
    return 1;
}

/* The glyph's bytes [*at, *at + *len) inside glyf; *len 0 for an empty one. */
static int glyph_bytes(font *f, unsigned gi, uint64_t *at, uint64_t *len)
{
    int ok = 1;
    uint64_t a, b;
    if (f->loc_format == 0) {
        a = 2 * (uint64_t)u16(f, f->loca + gi * 2ull, &ok);
        b = 2 * (uint64_t)u16(f, f->loca + gi * 2ull + 2, &ok);
    } else {
        a = u32(f, f->loca + gi * 4ull, &ok);
        b = u32(f, f->loca + gi * 4ull + 4, &ok);
    }
    if (!ok || a > b || b > f->glyf_len)
        return bad(f, "glyph %u lies outside the glyf table", gi, 0);
    *at = f->glyf + a;
    *len = b - a;
    return 1;
}

/* How far a glyph's points reach from its origin (the largest |x|, |y|
 * stb_truetype will hold for it), so a component's placement can be
 * checked against the 16-bit vertices stb keeps. */
typedef struct extent {
    double x, y;
} extent;

static int wrap16(int32_t v)
{
    return (int)(((v + 32768) & 0xFFFF) - 32768);
}

/* One axis of a simple glyph's points, as stb_truetype decodes them: a
 * short delta (flag `short_bit`, sign by `same_bit`), a repeat of the last
 * value (`same_bit` alone), or a 16-bit delta; the sum kept in 16 bits.
 * Reads from *p (bounds already checked); the largest |value| out. */
static double axis_extent(const font *in, uint64_t flags_at, unsigned points, uint64_t *p,
                          unsigned char short_bit, unsigned char same_bit)
{
    int ok = 1;
    int32_t v = 0;
    double most = 0;
    unsigned char flags = 0, repeat = 0;
    uint64_t fp = flags_at;
    for (unsigned i = 0; i < points; i++) {
        if (repeat == 0) {
            flags = in->d[fp++];
            if (flags & 8) repeat = in->d[fp++];
        } else {
            --repeat;
        }
        if (flags & short_bit) {
            int d = in->d[(*p)++];
            v += (flags & same_bit) ? d : -d;
        } else if (!(flags & same_bit)) {
            v += (int16_t)u16(in, *p, &ok);
            *p += 2;
        }
        v = wrap16(v);
        if (v < 0 ? -v > most : v > most) most = v < 0 ? -v : v;
    }
    return most;
}

/* Where a component lands (stb_truetype's transform: a 2x2 matrix in
 * F2Dot14, an offset, then each axis scaled by its column's length), from
 * the component's own extent. */
static extent placed(const double mtx[6], extent e)
{
    double m = sqrt(mtx[0] * mtx[0] + mtx[1] * mtx[1]);
    double n = sqrt(mtx[2] * mtx[2] + mtx[3] * mtx[3]);
    return (extent){m * (fabs(mtx[0]) * e.x + fabs(mtx[2]) * e.y + fabs(mtx[4])),
                    n * (fabs(mtx[1]) * e.x + fabs(mtx[3]) * e.y + fabs(mtx[5]))};
}

/* A component's matrix and offset, as stb_truetype reads them at p. */
static void component_matrix(const font *in, uint64_t p, unsigned flags, double mtx[6])
{
    int ok = 1;
    mtx[0] = mtx[3] = 1;
    mtx[1] = mtx[2] = 0;
    if (flags & 1) {
        mtx[4] = (int16_t)u16(in, p, &ok);
        mtx[5] = (int16_t)u16(in, p + 2, &ok);
        p += 4;
    } else {
        mtx[4] = (signed char)in->d[p];
        mtx[5] = (signed char)in->d[p + 1];
        p += 2;
    }
    if (flags & 8) {
        mtx[0] = mtx[3] = (int16_t)u16(in, p, &ok) / 16384.0;
    } else if (flags & 0x40) {
        mtx[0] = (int16_t)u16(in, p, &ok) / 16384.0;
        mtx[3] = (int16_t)u16(in, p + 2, &ok) / 16384.0;
    } else if (flags & 0x80) {
        for (int i = 0; i < 4; i++) mtx[i] = (int16_t)u16(in, p + 2 * (uint64_t)i, &ok) / 16384.0;
    }
}

static int check_glyph(font *f, unsigned gi, int depth, extent *reach)
{
    *reach = (extent){0, 0};
    uint64_t g, len;
    if (!glyph_bytes(f, gi, &g, &len))
        return 0;
    if (len == 0)
        return 1;
    font in = *f; /* reads bounded by this glyph's own bytes */
    in.n = g + len;
    int ok = 1;
    if (len < 10)
        return bad(f, "glyph %u is shorter than its header", gi, 0);
    int contours = (int16_t)u16(&in, g, &ok);
    /* stb_truetype sizes the glyph's bitmap from this box: inverted, the
     * width is negative and the bake's memset runs wild. */
    int x_min = (int16_t)u16(&in, g + 2, &ok), y_min = (int16_t)u16(&in, g + 4, &ok);
    int x_max = (int16_t)u16(&in, g + 6, &ok), y_max = (int16_t)u16(&in, g + 8, &ok);
    if (x_min > x_max || y_min > y_max)
        return bad(f, "glyph %u has an inverted bounding box", gi, 0);
    if (contours > 0) {
        uint64_t ends = g + 10;
        unsigned prev = 0, last_start = 0;
        for (int c = 0; c < contours && ok; c++) {
            unsigned e = u16(&in, ends + 2 * (uint64_t)c, &ok);
            if (c && e < prev)
                return bad(f, "glyph %u has its contours out of order", gi, 0);
            /* An empty contour (its end repeats the last one's) starts
             * nothing: stb_truetype's last start is the last non-empty one. */
            unsigned start = c ? prev + 1 : 0;
            if (e >= start)
                last_start = start;
            prev = e;
        }
        unsigned ins = u16(&in, ends + 2 * (uint64_t)contours, &ok);
        uint64_t p = ends + 2 * (uint64_t)contours + 2 + ins;
        unsigned points = prev + 1, xy = 0;
        unsigned char flags = 0, repeat = 0;
        for (unsigned i = 0; i < points && ok; i++) {
            if (repeat == 0) {
                ok = p < in.n;
                flags = ok ? in.d[p++] : 0;
                if (flags & 8) {
                    ok = ok && p < in.n;
                    repeat = ok ? in.d[p++] : 0;
                }
            } else {
                --repeat;
            }
            /* stb_truetype reads the point after a contour's off-curve
             * start: past its array when that start is the last point. */
            if (i == points - 1 && i == last_start && !(flags & 1))
                return bad(f, "glyph %u ends with a contour of one off-curve point", gi, 0);
            xy += (flags & 2) ? 1 : (flags & 16) ? 0 : 2;
            xy += (flags & 4) ? 1 : (flags & 32) ? 0 : 2;
        }
        if (!ok || p + xy > in.n)
            return bad(f, "the outline of glyph %u runs past its end", gi, 0);
        uint64_t flags_at = ends + 2 * (uint64_t)contours + 2 + ins, at = p;
        reach->x = axis_extent(&in, flags_at, points, &at, 2, 16);
        reach->y = axis_extent(&in, flags_at, points, &at, 4, 32);
    } else if (contours < 0) {
        if (depth >= MAX_COMPOSITE_DEPTH)
            return bad(f, "glyph %u nests its components too deep (a cycle?)", gi, 0);
        uint64_t p = g + 10;
        unsigned flags;
        do {
            flags = u16(&in, p, &ok);
            unsigned part = u16(&in, p + 2, &ok);
            if (!ok)
                break;
            if (!(flags & 2))
                return bad(f, "glyph %u places a component by points (unsupported)", gi, 0);
            uint64_t args = p + 4;
            p += 4 + ((flags & 1) ? 4 : 2);
            p += (flags & 8) ? 2 : (flags & 0x40) ? 4 : (flags & 0x80) ? 8 : 0;
            extent part_reach;
            if (p > in.n)
                ok = 0;
            else if (part >= f->num_glyphs)
                return bad(f, "glyph %u uses glyph %u, past the last", gi, part);
            else if (!check_glyph(f, part, depth + 1, &part_reach))
                return 0;
            if (!ok)
                break;
            /* stb_truetype keeps vertices in 16 bits: a component placed
             * beyond them would be converted out of range (undefined). */
            double mtx[6];
            component_matrix(&in, args, flags, mtx);
            extent e = placed(mtx, part_reach);
            if (e.x > 32767 || e.y > 32767)
                return bad(f, "glyph %u places glyph %u beyond 16-bit coordinates", gi, part);
            reach->x = fmax(reach->x, e.x);
            reach->y = fmax(reach->y, e.y);
        } while (ok && (flags & 0x20));
        if (!ok)
            return bad(f, "the components of glyph %u run past its end", gi, 0);
    }
    return 1;
}

int cub_render_font_check(const unsigned char *data, size_t n, char *why, size_t size)
{
    font f = {.d = data, .n = n, .why = why, .size = size};
    int ok = 1;
    uint64_t start = 0;
    if (n >= 4 && memcmp(data, "ttcf", 4) == 0) {
        start = u32(&f, 12, &ok);
        if (!ok || start + 4 > n)
            return bad(&f, "the collection's first font lies past the end of the file", 0, 0);
    }
    if (start + 4 > n)
        return -1;
    const unsigned char *tag = data + start;
    if (memcmp(tag, "OTTO", 4) == 0)
        return bad(&f, "CFF outlines (.otf) are not supported", 0, 0);
    if (memcmp(tag, "\0\1\0\0", 4) != 0 && memcmp(tag, "true", 4) != 0 && memcmp(tag, "1\0\0\0", 4) != 0 &&
        memcmp(tag, "typ1", 4) != 0)
        return -1;
    unsigned tables = u16(&f, start + 4, &ok);
    if (!ok || start + 12 + 16 * (uint64_t)tables > n)
        return bad(&f, "its table directory (%u tables) runs past the end of the file", tables, 0);

    /* A table cut off is a half-copied file, even one the bake never reads. */
    for (unsigned i = 0; i < tables; i++) {
        uint64_t rec = start + 12 + 16 * (uint64_t)i;
        if ((uint64_t)u32(&f, rec + 8, &ok) + u32(&f, rec + 12, &ok) > n) {
            char name[5] = {0};
            for (int k = 0; k < 4; k++)
                name[k] = data[rec + k] >= 0x20 && data[rec + k] < 0x7f ? (char)data[rec + k] : '?';
            if (why && size)
                snprintf(why, size, "the %s table runs past the end of the file", name);
            return 0;
        }
    }
    uint64_t head, hhea, hmtx, maxp, cmap, at_len, hmtx_len, cmap_len;
    if (!need(&f, start, "head", 54, &head, &at_len) || !need(&f, start, "hhea", 36, &hhea, &at_len) ||
        !need(&f, start, "maxp", 6, &maxp, &at_len) || !need(&f, start, "hmtx", 0, &hmtx, &hmtx_len) ||
        !need(&f, start, "cmap", 4, &cmap, &cmap_len) ||
        !need(&f, start, "loca", 0, &f.loca, &f.loca_len) ||
        !need(&f, start, "glyf", 0, &f.glyf, &f.glyf_len))
        return 0;
    f.num_glyphs = u16(&f, maxp + 4, &ok);
    f.loc_format = u16(&f, head + 50, &ok);
    if (f.loc_format > 1)
        return bad(&f, "unknown loca format %u", f.loc_format, 0);
    if (f.loca_len < ((uint64_t)f.num_glyphs + 1) * (f.loc_format ? 4 : 2))
        return bad(&f, "the loca table is too short for %u glyphs", f.num_glyphs, 0);
    unsigned long_metrics = u16(&f, hhea + 34, &ok);
    uint64_t metrics_len = 4 * (uint64_t)long_metrics +
                           (f.num_glyphs > long_metrics ? 2 * (uint64_t)(f.num_glyphs - long_metrics) : 0);
    if (long_metrics == 0 || hmtx_len < metrics_len)
        return bad(&f, "the hmtx table is too short for %u metrics", long_metrics, 0);
    int ascent = (int16_t)u16(&f, hhea + 4, &ok), descent = (int16_t)u16(&f, hhea + 6, &ok);
    if (ascent - descent <= 0)
        return bad(&f, "the hhea table gives no line height", 0, 0);

    /* The subtable stb picks: the last Microsoft Unicode or Unicode one. */
    unsigned subtables = u16(&f, cmap + 2, &ok);
    if (4 + 8 * (uint64_t)subtables > cmap_len)
        return bad(&f, "the cmap lists %u subtables it does not hold", subtables, 0);
    uint64_t map = 0;
    for (unsigned i = 0; i < subtables; i++) {
        uint64_t rec = cmap + 4 + 8 * (uint64_t)i;
        unsigned platform = u16(&f, rec, &ok), encoding = u16(&f, rec + 2, &ok);
        if (platform == 0 || (platform == 3 && (encoding == 1 || encoding == 10)))
            map = cmap + u32(&f, rec + 4, &ok);
    }
    if (!map)
        return bad(&f, "no Unicode cmap", 0, 0);
    if (map + 14 > n)
        return bad(&f, "the cmap subtable lies past the end of the file", 0, 0);

    for (unsigned cp = CUB_RENDER_GLYPH_FIRST; cp < CUB_RENDER_GLYPH_FIRST + CUB_RENDER_GLYPH_COUNT; cp++) {
        unsigned gi;
        extent reach;
        if (!glyph_of(&f, map, cp, &gi) || !check_glyph(&f, gi, 0, &reach))
            return 0;
    }
    return 1;
}
