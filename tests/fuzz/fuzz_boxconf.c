/* libFuzzer target: the box's config file (cub/boxconf.h). Any bytes: a
 * refusal always says why, and a file that parses holds only values in the
 * documented ranges, and NUL-terminated strings. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/boxconf.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static cub_boxconf c;
    char err[300];
    if (cub_boxconf_parse((const char *)data, size, "fuzz.conf", &c, err, sizeof err) != CUB_OK) {
        if (strncmp(err, "fuzz.conf:", 10) != 0) abort();
        return 0;
    }
    if (c.gpio.debounce_ms < 0 || c.gpio.debounce_ms > 1000 || c.volume < 0 || c.volume > 100)
        abort();
    if (c.attract_after_s < 1 || c.doze_after_s <= c.attract_after_s) abort();
    if ((c.width == 0) != (c.height == 0)) abort();
    if (!memchr(c.assets_dir, '\0', sizeof c.assets_dir) || !memchr(c.song, '\0', sizeof c.song))
        abort();
    if (c.assets_dir[0] && c.assets_dir[0] != '/') abort();
    for (int i = 0; i < CUB_BOXCONF_LINES; i++)
        if (c.gpio.line[i][0] && i < 2 && strchr(c.gpio.line[i], '/')) abort();
    return 0;
}
