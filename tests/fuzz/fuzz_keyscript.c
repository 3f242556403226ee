/* libFuzzer target: cubtool play's key script reader (cub/keyscript.h).
 * The input is the file. A refusal must name the file with a message; an
 * accepted script must hold what the format promises: at most
 * CUB_KEYSCRIPT_MAX_PRESSES presses, frames ascending within range, every
 * key one with a name. Seeds: seeds_keyscript/ (make_seeds.py). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/keyscript.h"
#include "fuzz_tally.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_accepted(const cub_keyscript *s)
{
    if (s->count < 0 || s->count > CUB_KEYSCRIPT_MAX_PRESSES || (s->count && !s->press)) abort();
    for (int i = 0; i < s->count; i++) {
        const cub_keypress *p = &s->press[i];
        if (p->frame < 0 || p->frame > CUB_KEYSCRIPT_MAX_FRAME || p->line < 1) abort();
        if (i && p->frame < s->press[i - 1].frame) abort();
        if (!strcmp(cub_key_name(p->key), "?")) abort();
        if (cub_key_from_name(cub_key_name(p->key)) != p->key) abort(); /* names round-trip */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_keyscript s;
    cub_diag d;
    cub_err e = cub_keyscript_parse((const char *)data, size, "fuzz.keys", &s, &d);
    cub_fuzz_tally("fuzz_keyscript", !e);
    if (!e)
        check_accepted(&s);
    else if ((e != CUB_ERR_FORMAT && e != CUB_ERR_NOMEM) || strcmp(d.file, "fuzz.keys") != 0 ||
             !d.msg[0])
        abort();
    cub_keyscript_free(&s);
    return 0;
}
