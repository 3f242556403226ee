/* stb_truetype's implementation (Debian's libstb-dev header) compiled into
 * fuzz_font with the sanitizers, instead of the uninstrumented libstb.so
 * the renderer links. */
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>
