#include "logread.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int parse_line(const char *text, logread_line *l)
{
    int n = 0;
    memset(l, 0, sizeof *l);
    if (sscanf(text, "t=%lf %31s %31s %n", &l->t_s, l->source, l->event, &n) < 3) return -1;
    snprintf(l->rest, sizeof l->rest, "%s", n > 0 ? text + n : "");
    return 0;
}

int logread_load(const char *path, logread *out)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "r");
    if (!f) {
        printf("logread: cannot open %s\n", path);
        return -1;
    }
    char text[1024];
    int cap = 0, lineno = 0;
    while (fgets(text, sizeof text, f)) {
        lineno++;
        text[strcspn(text, "\r\n")] = '\0';
        if (out->count == cap) {
            cap = cap ? cap * 2 : 64;
            logread_line *grown = realloc(out->lines, (size_t)cap * sizeof *grown);
            if (!grown) break;
            out->lines = grown;
        }
        if (parse_line(text, &out->lines[out->count]) != 0) {
            printf("logread: %s:%d: not an event line: %s\n", path, lineno, text);
            fclose(f);
            return -1;
        }
        out->count++;
    }
    fclose(f);
    return 0;
}

void logread_free(logread *log)
{
    free(log->lines);
    memset(log, 0, sizeof *log);
}

static int matches(const logread_line *l, const char *source, const char *event)
{
    return (!source || !strcmp(l->source, source)) && (!event || !strcmp(l->event, event));
}

int logread_find(const logread *log, int from, const char *source, const char *event)
{
    for (int i = from < 0 ? 0 : from; i < log->count; i++)
        if (matches(&log->lines[i], source, event)) return i;
    return -1;
}

int logread_count(const logread *log, const char *source, const char *event)
{
    int n = 0;
    for (int i = 0; i < log->count; i++) n += matches(&log->lines[i], source, event);
    return n;
}

const char *logread_field(const logread_line *line, const char *key, char *buf, size_t size)
{
    size_t klen = strlen(key);
    for (const char *p = line->rest; *p;) {
        while (*p == ' ') p++;
        const char *end = strchr(p, ' ');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len > klen && !strncmp(p, key, klen) && p[klen] == '=') {
            size_t vlen = len - klen - 1;
            if (vlen >= size) vlen = size - 1;
            memcpy(buf, p + klen + 1, vlen);
            buf[vlen] = '\0';
            return buf;
        }
        p += len;
    }
    return NULL;
}

double logread_number(const logread_line *line, const char *key, int *ok)
{
    char buf[64], *end;
    *ok = 0;
    if (!logread_field(line, key, buf, sizeof buf)) return 0;
    double v = strtod(buf, &end);
    *ok = end != buf && *end == '\0';
    return v;
}
