/* The event log and its small printf. The firmware may not use stdio, so
 * this formatter implements just the conversions the log needs; %q prints a
 * Q16.16 value as a decimal, which keeps fixed-point figures readable in
 * the log without any float arithmetic. */
#include <stdarg.h>

#include "cub/fx.h"
#include "cub/loop.h"

typedef struct out_buf {
    char *buf;
    size_t size, len;
} out_buf;

static void put_char(out_buf *o, char c)
{
    if (o->len + 1 < o->size) o->buf[o->len++] = c;
}

static void put_str(out_buf *o, const char *s)
{
    if (!s) s = "(null)";
    while (*s) put_char(o, *s++);
}

static void put_unsigned(out_buf *o, unsigned long long v, unsigned base, int min_digits)
{
    char digits[24];
    int n = 0;
    do {
        unsigned d = (unsigned)(v % base);
        digits[n++] = (char)(d < 10 ? '0' + d : 'a' + d - 10);
        v /= base;
    } while (v && n < (int)sizeof digits);
    while (n < min_digits && n < (int)sizeof digits) digits[n++] = '0';
    while (n) put_char(o, digits[--n]);
}

static void put_signed(out_buf *o, long long v)
{
    if (v < 0) {
        put_char(o, '-');
        put_unsigned(o, 0ull - (unsigned long long)v, 10, 1);
    } else {
        put_unsigned(o, (unsigned long long)v, 10, 1);
    }
}

/* Q16.16 to "[-]int.fff", rounded to nearest thousandth. */
static void put_q16(out_buf *o, cub_q16 q)
{
    long long v = q;
    if (v < 0) {
        put_char(o, '-');
        v = -v;
    }
    long long thousandths = (v * 1000 + 32768) >> 16;
    put_unsigned(o, (unsigned long long)(thousandths / 1000), 10, 1);
    put_char(o, '.');
    put_unsigned(o, (unsigned long long)(thousandths % 1000), 10, 3);
}

/* Length modifier: 0 none, 1 'l', 2 'll'. */
static const char *read_length(const char *f, int *longness)
{
    *longness = 0;
    while (*f == 'l' && *longness < 2) {
        (*longness)++;
        f++;
    }
    return f;
}

static void format_one(out_buf *o, char conv, int longness, va_list *ap)
{
    switch (conv) {
    case 'd':
    case 'i':
        if (longness == 2) put_signed(o, va_arg(*ap, long long));
        else if (longness == 1) put_signed(o, va_arg(*ap, long));
        else put_signed(o, va_arg(*ap, int));
        break;
    case 'u':
    case 'x': {
        unsigned base = conv == 'x' ? 16 : 10;
        if (longness == 2) put_unsigned(o, va_arg(*ap, unsigned long long), base, 1);
        else if (longness == 1) put_unsigned(o, va_arg(*ap, unsigned long), base, 1);
        else put_unsigned(o, va_arg(*ap, unsigned), base, 1);
        break;
    }
    case 'q': put_q16(o, (cub_q16)va_arg(*ap, int)); break;
    case 's': put_str(o, va_arg(*ap, const char *)); break;
    case 'c': put_char(o, (char)va_arg(*ap, int)); break;
    case '%': put_char(o, '%'); break;
    default:
        put_char(o, '%');
        if (conv) put_char(o, conv);
        break;
    }
}

static void format_va(out_buf *o, const char *fmt, va_list *ap)
{
    for (const char *f = fmt; f && *f; f++) {
        if (*f != '%') {
            put_char(o, *f);
            continue;
        }
        int longness;
        f = read_length(f + 1, &longness);
        format_one(o, *f, longness, ap);
        if (!*f) break;
    }
}

size_t cub_log_format(char *buf, size_t size, const char *fmt, ...)
{
    if (!buf || size == 0) return 0;
    out_buf o = {buf, size, 0};
    va_list ap;
    va_start(ap, fmt);
    format_va(&o, fmt, &ap);
    va_end(ap);
    buf[o.len] = '\0';
    return o.len;
}

/* "t=12.433": loop time in seconds with milliseconds, truncated so that a
 * line never claims a time later than the event. */
static void put_time(out_buf *o, int64_t t_us)
{
    put_str(o, "t=");
    /* Magnitude in unsigned arithmetic: -INT64_MIN does not fit an int64. */
    unsigned long long mag = (unsigned long long)t_us;
    if (t_us < 0) {
        put_char(o, '-');
        mag = 0ull - mag;
    }
    unsigned long long ms = mag / 1000;
    put_unsigned(o, ms / 1000, 10, 1);
    put_char(o, '.');
    put_unsigned(o, ms % 1000, 10, 3);
}

void cub_log_event(cub_log *log, int64_t t_us, const char *source, const char *event,
                   const char *fmt, ...)
{
    if (!log) return;
    char line[CUB_LOG_LINE_MAX];
    out_buf o = {line, sizeof line, 0};
    put_time(&o, t_us);
    put_char(&o, ' ');
    put_str(&o, source);
    put_char(&o, ' ');
    put_str(&o, event);
    if (fmt && *fmt) {
        put_char(&o, ' ');
        va_list ap;
        va_start(ap, fmt);
        format_va(&o, fmt, &ap);
        va_end(ap);
    }
    line[o.len] = '\0';
    log->lines++;
    if (log->sink) log->sink(log->user, line, o.len);
}
