/* libFuzzer target: the one bounded file reader (board/text, cub/text.h)
 * every parser reads through: byte 0 picks the size limit (0: the default)
 * and whether the text is walked line by line; the rest is the file,
 * written to disk and read back with cub_text_read, cub_text_fopen and
 * cub_text_lines + cub_text_words. A read gives exactly the file's bytes,
 * NUL-terminated; a file over the limit is refused naming the file. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/text.h"
#include "fuzz_file.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int lines_seen;

static cub_err on_line(void *ctx, cub_text_line *ln)
{
    char *words[8];
    int n = cub_text_words(ln->s, words, 8);
    if (n < 0 || n > 9) abort(); /* 9: more than 8 words */
    for (int i = 0; i < n && i < 8; i++)
        if (!words[i][0]) abort();
    lines_seen++;
    return n == 8 && words[7][0] == '!' ? cub_text_fail(&ln->at, "stop at %d", ln->at.line) : CUB_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    const char *path = cub_fuzz_file("fuzz_text", "txt", data + 1, size - 1);
    cub_text_src src = {path, "fuzz file", (size_t)(data[0] >> 1) * 64};
    char *text = NULL;
    size_t len = 0;
    cub_diag d;
    cub_err e = cub_text_read(&src, &text, &len, &d);
    cub_fuzz_tally("fuzz_text", !e);
    if (e) {
        if (strcmp(d.file, path) != 0 || !d.msg[0] || text) abort();
        if (src.max_bytes && size - 1 <= src.max_bytes) abort(); /* refused within its limit */
        return 0;
    }
    if (len != size - 1 || memcmp(text, data + 1, len) != 0 || text[len] != '\0') abort();
    FILE *g = NULL;
    size_t fsize = 0;
    if (cub_text_fopen(&src, &g, &fsize, &d) != CUB_OK || fsize != len) abort();
    fclose(g);
    if (data[0] & 1) {
        cub_text t = {text, len, path, &d};
        lines_seen = 0;
        (void)cub_text_lines(&t, on_line, NULL);
    }
    free(text);
    return 0;
}
