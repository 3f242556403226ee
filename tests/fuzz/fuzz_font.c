/* libFuzzer target: a font file as the renderer takes it (app/render,
 * render_text.c): the font check (render_font_check.c) and, for a font it
 * passes, stb_truetype's look-ups as the program does them (offset, init,
 * vertical metrics, the atlas bake of glyphs 32..255) plus a glyph index
 * and box per code point. stb_truetype is compiled into this target
 * (stb_truetype_impl.c) so ASan sees its reads. Byte 0 is the pixel
 * height (8 + byte % 40), the rest the font. Seeds: seeds_font/ (a tiny
 * font made by make_seeds.py). Whatever the bytes: no crash, no read past
 * the file. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <stb_truetype.h>

#include "render_internal.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    size_t n = size - 1;
    unsigned char *font = malloc(n ? n : 1); /* exactly the file's size */
    if (!font) return 0;
    memcpy(font, data + 1, n);
    char why[160];
    int usable = cub_render_font_check(font, n, why, sizeof why);
    stbtt_fontinfo info;
    int offset = usable > 0 ? stbtt_GetFontOffsetForIndex(font, 0) : -1;
    int ok = usable > 0 && offset >= 0 && stbtt_InitFont(&info, font, offset);
    cub_fuzz_tally("fuzz_font", ok);
    if (ok) {
        float px = (float)(8 + data[0] % 40);
        int ascent = 0, descent = 0, gap = 0;
        stbtt_GetFontVMetrics(&info, &ascent, &descent, &gap);
        (void)stbtt_ScaleForPixelHeight(&info, px);
        for (int cp = CUB_RENDER_GLYPH_FIRST; cp < CUB_RENDER_GLYPH_FIRST + CUB_RENDER_GLYPH_COUNT; cp++) {
            int x0, y0, x1, y1;
            int g = stbtt_FindGlyphIndex(&info, cp);
            (void)stbtt_GetGlyphBox(&info, g, &x0, &y0, &x1, &y1);
        }
        static unsigned char atlas[512 * 512];
        static stbtt_bakedchar glyphs[CUB_RENDER_GLYPH_COUNT];
        (void)stbtt_BakeFontBitmap(font, 0, px, atlas, 512, 512, CUB_RENDER_GLYPH_FIRST,
                                   CUB_RENDER_GLYPH_COUNT, glyphs);
    } else if (usable == 0 && !why[0]) {
        abort(); /* a refusal says why */
    }
    free(font);
    return 0;
}
