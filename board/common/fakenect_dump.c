/* fakenect_dump — check a fakenect dump; mend bad depth frames through a
 * private view (see fakenect_dump.h for why).
 *
 * Two passes over INDEX.txt: the first only looks (so a refused dump leaves
 * nothing behind), the second builds the view. Names are read the way
 * fakenect reads them: one per line, the first letter is the kind (d depth,
 * r colour, a accelerometer). Every line is looked at: fakenect reads on
 * past an empty line, so the view drops empty lines rather than stopping
 * the check at the first. */
#define _GNU_SOURCE /* mkdtemp, symlink, setenv, putenv, realpath */

#include "fakenect_dump.h"

#include "cub/board.h"
#include "cub/text.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FRAME_PIXELS ((size_t)CUB_DEPTH_W * CUB_DEPTH_H)
#define HEADER_MAX 64 /* fakenect-record's header lines are ~17 bytes */
#define NONE_HEADER "P5 640 480 65535\n" /* as fakenect-record writes it */
#define NAME_MAX_CHARS 1024
#define INDEX_MAX_BYTES ((size_t)64 << 20) /* a name a line: hours of frames */
#define SMALL_FILE_MAX_BYTES ((size_t)1 << 20) /* a-* readings are ~20 bytes */
/* fakenect sleeps between two lines for the difference of their recorded
 * seconds, whatever it is, where no --seconds can end it. A step longer
 * than this is no camera pause a recording holds (the same bound as the
 * Kinect timestamps' in depth_freenect.c): it is replayed as one frame's. */
#define MAX_GAP_S 10.0
#define FRAME_S (1.0 / 30)

/* fakenect keeps the pointer getenv gave it and builds every file path from
 * it while it replays, even after we put the caller's value back: the
 * "FAKENECT_PATH=<view>" string must outlive any depth source, so it is
 * static (fakenect replays one dump per process anyway). */
static char view_env[sizeof "FAKENECT_PATH=" + CUB_FAKENECT_PATH_MAX];

typedef enum file_fault {
    FILE_GOOD,
    FILE_MISSING,     /* will not open: fakenect would exit() */
    FILE_NOT_REGULAR, /* a directory, FIFO or device: fakenect would hang or read nonsense */
    FILE_TOO_BIG,     /* far larger than a frame: fakenect reads a file whole */
    FILE_SHORT,       /* shorter than header + frame: fakenect would over-read */
    FILE_NO_HEADER,   /* no header line: fakenect would exit() */
    FILE_EMPTY,       /* an empty a-* file: fakenect would end the replay there */
} file_fault;

typedef struct file_check {
    file_fault fault;
    long long size_bytes;
    size_t need_bytes; /* header line + frame */
    char why[256];     /* FILE_NOT_REGULAR, FILE_TOO_BIG: what cub_text_open said */
} file_check;

typedef struct index_reader {
    const char *dir;
    FILE *f;
    int line;
} index_reader;

/* What a scan of the index found. */
typedef struct dump_scan {
    int good_frames, bad_frames;
    int empty_accel; /* a-* files of no bytes, replayed as no reading */
    int first_bad_line;
    char first_bad[NAME_MAX_CHARS];
    file_check first_bad_check;
    int path_line; /* first name with a '/' (a view cannot hold it); 0: none */
    int names;       /* lines naming a file */
    int blank_lines; /* empty lines, dropped in the view */
    int first_blank_line;
    int jumps;       /* lines whose recorded seconds jump past MAX_GAP_S */
} dump_scan;

/* The recorded seconds as the view replays them: every jump forward past
 * MAX_GAP_S taken out, so that fakenect's sleep between two lines is
 * bounded. Steps back fakenect does not sleep on: they stay. */
typedef struct gap_clock {
    int have_last;
    double last_s; /* the previous parsed line's recorded seconds */
    double cut_s;  /* seconds taken out so far */
} gap_clock;

/* The seconds line name replays at in *view_s, read the way fakenect reads
 * them ("<kind>-<seconds>-..."), and the jump taken out at it (0: none). A
 * name without readable seconds gets NAN: it is left as it is. */
static double gap_step(gap_clock *g, const char *name, double *view_s)
{
    double s = 0;
    char kind;
    /* Past 1e15 s (31 million years) a difference could overflow. */
    int parsed = sscanf(name, "%c-%lf-", &kind, &s) == 2 && fabs(s) < 1e15;
    double jump = 0;
    if (parsed && g->have_last && s - g->last_s > MAX_GAP_S) {
        jump = s - g->last_s;
        g->cut_s += jump - FRAME_S;
    }
    if (parsed) {
        g->have_last = 1;
        g->last_s = s;
    }
    *view_s = parsed ? s - g->cut_s : NAN;
    return jump;
}

/* name as the view lists it: its recorded seconds replaced by view_s when a
 * jump was taken out before it, else as it is. */
static void view_name(const char *name, const gap_clock *g, double view_s, char *out,
                      size_t size)
{
    int end = 0; /* where the seconds end: what follows them is kept byte for byte */
    double s;
    if (g->cut_s == 0 || isnan(view_s) || sscanf(name, "%*c-%lf%n", &s, &end) != 1 || end == 0)
        snprintf(out, size, "%s", name);
    else
        snprintf(out, size, "%c-%.6f%s", name[0], view_s, name + end);
}

/* A renamed line must not take the name of a file already in the view (two
 * spellings of the same seconds): its seconds move on by microseconds. */
static void unique_view_name(const char *view_dir, const char *name, double view_s, char *as,
                             size_t size)
{
    char path[2 * CUB_FAKENECT_PATH_MAX];
    int end = 0;
    double s;
    if (strcmp(name, as) == 0 || sscanf(name, "%*c-%lf%n", &s, &end) != 1 || end == 0) return;
    for (int k = 1; k < 1000; k++) {
        snprintf(path, sizeof path, "%s/%s", view_dir, as);
        if (access(path, F_OK) != 0) return;
        snprintf(as, size, "%c-%.6f%s", name[0], view_s + k * 1e-6, name + end);
    }
}

static size_t frame_bytes(const char *name)
{
    return name[0] == 'd' ? FRAME_PIXELS * 2 : name[0] == 'r' ? FRAME_PIXELS * 3 : 0;
}

static file_check check_file(const char *dir, const char *name)
{
    file_check c = {FILE_GOOD, 0, 0, ""};
    char path[2 * CUB_FAKENECT_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    size_t frame = frame_bytes(name);
    /* Twice a frame: a frame file is its header line and the frame. */
    cub_text_src src = {path, name[0] == 'd'   ? "depth frame"
                              : name[0] == 'r' ? "colour frame"
                                               : "dump file",
                        frame ? 2 * frame : SMALL_FILE_MAX_BYTES};
    FILE *f = NULL;
    size_t bytes = 0;
    cub_diag d = {0};
    cub_err e = cub_text_fopen(&src, &f, &bytes, &d);
    struct stat st;
    if (e) {
        /* a name that is not there (or a dangling link) is "missing" */
        c.fault = e == CUB_ERR_FORMAT ? FILE_TOO_BIG
                  : stat(path, &st) != 0 && errno == ENOENT ? FILE_MISSING
                                                            : FILE_NOT_REGULAR;
        const char *why = strstr(d.msg, ": ");
        snprintf(c.why, sizeof c.why, "%.250s", e == CUB_ERR_FORMAT || !why ? d.msg : why + 2);
        return c;
    }
    st.st_size = (off_t)bytes;
    char head[HEADER_MAX];
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    /* fakenect reads a whole a-* file in one fread, which fails on none. A
     * reading of another size it only warns about. */
    if (name[0] == 'a' && st.st_size == 0) c.fault = FILE_EMPTY;
    if (frame == 0) return c; /* a-* and others: fakenect only needs them to open */
    const char *nl = memchr(head, '\n', got);
    c.size_bytes = (long long)st.st_size;
    c.need_bytes = (nl ? (size_t)(nl - head + 1) : strlen(NONE_HEADER)) + frame;
    if ((unsigned long long)st.st_size < c.need_bytes) {
        c.fault = FILE_SHORT;
    } else if (!nl || memchr(head, '\0', (size_t)(nl - head))) {
        c.fault = FILE_NO_HEADER; /* fakenect finds the line's end with strchr */
    }
    return c;
}

static const char *describe(file_check c, char *buf, size_t size)
{
    switch (c.fault) {
    case FILE_GOOD: snprintf(buf, size, "good"); break;
    case FILE_MISSING: snprintf(buf, size, "missing"); break;
    case FILE_NOT_REGULAR: snprintf(buf, size, "not a regular file (%s)", c.why); break;
    case FILE_TOO_BIG: snprintf(buf, size, "%s", c.why); break;
    case FILE_SHORT:
        snprintf(buf, size, "truncated: %lld of %zu bytes", c.size_bytes, c.need_bytes);
        break;
    case FILE_NO_HEADER: snprintf(buf, size, "no header line"); break;
    case FILE_EMPTY: snprintf(buf, size, "empty"); break;
    }
    return buf;
}

static cub_err open_index(index_reader *r, const char *dir, char *err, size_t err_size)
{
    char path[CUB_FAKENECT_PATH_MAX + 16];
    snprintf(path, sizeof path, "%s/INDEX.txt", dir);
    r->dir = dir;
    r->line = 0;
    cub_text_src src = {path, "INDEX.txt", INDEX_MAX_BYTES};
    size_t bytes = 0;
    cub_diag d = {0};
    cub_err e = cub_text_fopen(&src, &r->f, &bytes, &d);
    if (e) {
        const char *why = strstr(d.msg, ": ");
        snprintf(err, err_size, "fakenect dump %s: cannot open INDEX.txt: %s", dir,
                 e == CUB_ERR_FORMAT || !why ? d.msg : why + 2);
        return e;
    }
    return CUB_OK;
}

/* The next line: 1 a name; 2 an empty line; 0 at the end of the file; -1
 * with err on a line too long to be a file name. */
static int next_name(index_reader *r, char *name, char *err, size_t err_size)
{
    if (!fgets(name, NAME_MAX_CHARS, r->f)) return 0;
    r->line++;
    size_t len = strlen(name);
    if (len > 0 && name[len - 1] == '\n') {
        name[len - 1] = '\0';
    } else if (!feof(r->f)) {
        snprintf(err, err_size, "fakenect dump %s: INDEX.txt:%d: line longer than %d characters",
                 r->dir, r->line, NAME_MAX_CHARS - 2);
        return -1;
    }
    if (r->line == 1 && memcmp(name, "\xEF\xBB\xBF", 3) == 0) {
        snprintf(err, err_size,
                 "fakenect dump %s: INDEX.txt:1: starts with a UTF-8 byte order mark (BOM), "
                 "which fakenect would take as part of the first name: save it without one",
                 r->dir);
        return -1;
    }
    return name[0] ? 1 : 2;
}

/* A fault in a file that is not a depth frame refuses the dump, as before. */
static cub_err refuse_other(const index_reader *r, const char *name, file_check c, char *err,
                            size_t err_size)
{
    char why[320];
    if (c.fault == FILE_MISSING) {
        snprintf(err, err_size, "fakenect dump %s: INDEX.txt:%d: cannot open %s", r->dir, r->line,
                 name);
    } else if (frame_bytes(name) == 0) {
        snprintf(err, err_size, "fakenect dump %s: INDEX.txt:%d: %s: %s", r->dir, r->line, name,
                 describe(c, why, sizeof why));
    } else {
        snprintf(err, err_size,
                 "fakenect dump %s: INDEX.txt:%d: %s is not a 640x480 frame (header line + %zu "
                 "bytes): %s",
                 r->dir, r->line, name, frame_bytes(name), describe(c, why, sizeof why));
    }
    return CUB_ERR_FORMAT;
}

static void note_depth(dump_scan *scan, const index_reader *r, const char *name, file_check c)
{
    if (c.fault == FILE_GOOD) {
        scan->good_frames++;
        return;
    }
    if (scan->bad_frames++ == 0) {
        scan->first_bad_line = r->line;
        snprintf(scan->first_bad, sizeof scan->first_bad, "%s", name);
        scan->first_bad_check = c;
    }
}

/* Pass one: look at every file, touch nothing. */
static cub_err scan_dump(const char *dir, dump_scan *scan, char *err, size_t err_size)
{
    index_reader r;
    cub_err e = open_index(&r, dir, err, err_size);
    char name[NAME_MAX_CHARS];
    int more = 0;
    gap_clock g = {0};
    double view_s;
    while (!e && (more = next_name(&r, name, err, err_size)) > 0) {
        if (more == 2) {
            if (scan->blank_lines++ == 0) scan->first_blank_line = r.line;
            continue;
        }
        scan->names++;
        if (gap_step(&g, name, &view_s) > 0) scan->jumps++;
        file_check c = check_file(dir, name);
        if (strchr(name, '/') && !scan->path_line) scan->path_line = r.line;
        if (name[0] == 'd') {
            note_depth(scan, &r, name, c);
        } else if (c.fault == FILE_EMPTY) {
            scan->empty_accel++;
        } else if (c.fault != FILE_GOOD) {
            e = refuse_other(&r, name, c, err, err_size);
        }
    }
    if (r.f) fclose(r.f);
    return e ? e : more < 0 ? CUB_ERR_FORMAT : CUB_OK;
}

/* A view mends a dump by rewriting INDEX.txt, which a name with a directory
 * in it does not survive: refuse, saying what could not be mended. */
static cub_err refuse_path(const char *dir, const dump_scan *scan, const char *what, char *err,
                           size_t err_size)
{
    snprintf(err, err_size,
             "fakenect dump %s: INDEX.txt:%d: a name with a directory in it; cannot %s around it",
             dir, scan->path_line, what);
    return CUB_ERR_FORMAT;
}

/* Bad frames are replayed only when there is something real around them. */
static cub_err judge_scan(const char *dir, const dump_scan *scan, char *err, size_t err_size)
{
    char why[320], what[NAME_MAX_CHARS + 64];
    if (scan->names == 0) {
        snprintf(err, err_size, "fakenect dump %s: INDEX.txt lists no files: nothing to replay",
                 dir);
        return CUB_ERR_FORMAT;
    }
    if (scan->blank_lines > 0 && scan->path_line) {
        snprintf(what, sizeof what, "drop the empty line at INDEX.txt:%d", scan->first_blank_line);
        return refuse_path(dir, scan, what, err, err_size);
    }
    if (scan->bad_frames > 0 && scan->good_frames == 0) {
        snprintf(err, err_size,
                 "fakenect dump %s: INDEX.txt:%d: %s: %s; no good depth frame in the dump: "
                 "nothing to replay",
                 dir, scan->first_bad_line, scan->first_bad,
                 describe(scan->first_bad_check, why, sizeof why));
        return CUB_ERR_FORMAT;
    }
    if (scan->bad_frames > 0 && scan->path_line) {
        snprintf(what, sizeof what, "replay the bad frame %s (INDEX.txt:%d)", scan->first_bad,
                 scan->first_bad_line);
        return refuse_path(dir, scan, what, err, err_size);
    }
    if (scan->jumps > 0 && scan->path_line)
        return refuse_path(dir, scan, "replay the jumps of its recorded seconds", err, err_size);
    if (scan->empty_accel > 0 && scan->path_line)
        return refuse_path(dir, scan, "replay the empty accelerometer files", err, err_size);
    return CUB_OK;
}

/* Raw 2047 everywhere (the Kinect's "no reading"), little-endian, as
 * tests/scenario/make_garbage_dump.sh writes none.pgm. */
static int write_none_frame(const char *path)
{
    FILE *f = fopen(path, "wbx"); /* x: a name listed twice is written once */
    if (!f) return errno == EEXIST ? 0 : -1;
    unsigned char row[CUB_DEPTH_W * 2];
    for (size_t i = 0; i < sizeof row; i += 2) {
        row[i] = CUB_DEPTH_NO_READING & 0xff;
        row[i + 1] = CUB_DEPTH_NO_READING >> 8;
    }
    int ok = fputs(NONE_HEADER, f) >= 0;
    for (int y = 0; ok && y < CUB_DEPTH_H; y++) ok = fwrite(row, sizeof row, 1, f) == 1;
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* An accelerometer reading of zeros (libfreenect's freenect_raw_tilt_state:
 * int16 x y z, int8 angle, a pad byte, int32 status), which the box takes
 * for no reading. */
static int write_no_accel(const char *path)
{
    FILE *f = fopen(path, "wbx");
    if (!f) return errno == EEXIST ? 0 : -1;
    static const unsigned char zeros[12];
    int ok = fwrite(zeros, sizeof zeros, 1, f) == 1;
    return fclose(f) == 0 && ok ? 0 : -1;
}

static int copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wbx") : NULL;
    char buf[4096];
    size_t n;
    int ok = in && out;
    while (ok && (n = fread(buf, 1, sizeof buf, in)) > 0) ok = fwrite(buf, 1, n, out) == n;
    ok = ok && !ferror(in);
    if (in) fclose(in);
    if (out && fclose(out) != 0) ok = 0;
    return ok ? 0 : -1;
}

/* view/as, a link to real_dir/name. A name listed twice is linked once; a
 * renamed line whose new name is taken by another file fails. */
static int link_as(const char *real_dir, const char *view, const char *name, const char *as)
{
    char target[2 * CUB_FAKENECT_PATH_MAX], path[2 * CUB_FAKENECT_PATH_MAX];
    char there[2 * CUB_FAKENECT_PATH_MAX];
    snprintf(target, sizeof target, "%s/%s", real_dir, name);
    snprintf(path, sizeof path, "%s/%s", view, as);
    if (symlink(target, path) == 0) return 0;
    if (errno != EEXIST) return -1;
    ssize_t n = readlink(path, there, sizeof there - 1);
    if (n >= 0) there[n] = '\0';
    return n >= 0 && strcmp(there, target) == 0 ? 0 : (errno = EEXIST, -1);
}

static int link_file(const char *real_dir, const char *view, const char *name)
{
    return link_as(real_dir, view, name, name);
}

static cub_err view_failed(cub_fakenect_view *v, const char *what, const char *name, char *err,
                           size_t err_size)
{
    snprintf(err, err_size, "fakenect dump: cannot build the replay view %s: %s %s: %s", v->dir,
             what, name, strerror(errno));
    cub_fakenect_dump_release(v);
    return CUB_ERR_IO;
}

/* One file of the dump into the view: a link, a frame without readings,
 * or an accelerometer without a reading. */
static int add_to_view(cub_fakenect_view *v, const index_reader *r, const char *real_dir,
                       const char *name, const char *as)
{
    int mendable = name[0] == 'd' || name[0] == 'a';
    file_check c = mendable ? check_file(r->dir, name) : (file_check){FILE_GOOD, 0, 0, ""};
    if (c.fault == FILE_GOOD) return link_as(real_dir, v->dir, name, as);
    char path[2 * CUB_FAKENECT_PATH_MAX], why[320];
    snprintf(path, sizeof path, "%s/%s", v->dir, as);
    if (name[0] == 'a') {
        if (write_no_accel(path) != 0) return -1;
        fprintf(stderr, "depth: fakenect dump %s: INDEX.txt:%d: %s: empty: replayed as no "
                        "accelerometer reading\n", r->dir, r->line, name);
        return 0;
    }
    if (write_none_frame(path) != 0) return -1;
    v->bad_frames++;
    fprintf(stderr,
            "depth: fakenect dump %s: INDEX.txt:%d: %s: %s: replayed as a frame without "
            "readings\n",
            r->dir, r->line, name, describe(c, why, sizeof why));
    return 0;
}

static cub_err make_view_dir(cub_fakenect_view *v, char *err, size_t err_size)
{
    const char *tmp = getenv("TMPDIR");
    int n = snprintf(v->dir, sizeof v->dir, "%s/cubdance-replay-XXXXXX",
                     tmp && tmp[0] ? tmp : "/tmp");
    if (n < 0 || (size_t)n >= sizeof v->dir || !mkdtemp(v->dir)) {
        snprintf(err, err_size, "fakenect dump: cannot make a replay view under %s: %s",
                 tmp && tmp[0] ? tmp : "/tmp", n >= 0 ? strerror(errno) : "path too long");
        v->dir[0] = '\0';
        return CUB_ERR_IO;
    }
    return CUB_OK; /* mkdtemp makes it 0700 */
}

/* A line whose recorded seconds jump: said, and what the view lists. */
static void note_jump(const index_reader *r, const char *name, double jump, const char *as)
{
    fprintf(stderr,
            "depth: fakenect dump %s: INDEX.txt:%d: %s: the recorded time jumps %.1f s ahead "
            "(more than %.0f s): replayed one frame later, as %s\n",
            r->dir, r->line, name, jump, MAX_GAP_S, as);
}

/* Pass two: the view (links are absolute, FAKENECT_PATH may be relative).
 * rewrite: INDEX.txt is written anew (no empty lines, jumps taken out). */
static cub_err build_view(cub_fakenect_view *v, const char *dir, int rewrite, char *err,
                          size_t err_size)
{
    char real_dir[CUB_FAKENECT_PATH_MAX], from[CUB_FAKENECT_PATH_MAX + 16];
    char to[CUB_FAKENECT_PATH_MAX + 16], name[NAME_MAX_CHARS], as[NAME_MAX_CHARS + 32];
    if (!realpath(dir, real_dir)) return view_failed(v, "resolving", dir, err, err_size);
    cub_err e = make_view_dir(v, err, err_size);
    if (e) return e;
    snprintf(from, sizeof from, "%s/INDEX.txt", dir);
    snprintf(to, sizeof to, "%s/INDEX.txt", v->dir);
    /* Copied as it is when nothing in it is mended, so that a mended replay
     * reads the very same index. */
    FILE *index = NULL;
    if (!rewrite && copy_file(from, to) != 0)
        return view_failed(v, "copying", from, err, err_size);
    if (rewrite && !(index = fopen(to, "wx")))
        return view_failed(v, "writing", to, err, err_size);
    index_reader r;
    if ((e = open_index(&r, dir, err, err_size))) {
        if (index) fclose(index);
        cub_fakenect_dump_release(v);
        return e;
    }
    int more, written = 1;
    gap_clock g = {0};
    double view_s;
    while ((more = next_name(&r, name, err, err_size)) > 0) {
        if (more == 2) {
            fprintf(stderr, "depth: fakenect dump %s: INDEX.txt:%d: an empty line: dropped\n",
                    dir, r.line);
            continue;
        }
        double jump = gap_step(&g, name, &view_s);
        view_name(name, &g, view_s, as, sizeof as);
        unique_view_name(v->dir, name, view_s, as, sizeof as);
        if (jump > 0) note_jump(&r, name, jump, as);
        if (index) written = written && fprintf(index, "%s\n", as) > 0;
        if (strcmp(name, "INDEX.txt") && add_to_view(v, &r, real_dir, name, as) != 0) break;
    }
    fclose(r.f);
    if (index && fclose(index) != 0) written = 0;
    if (!written) return view_failed(v, "writing", to, err, err_size);
    if (more != 0) return view_failed(v, "adding", name, err, err_size);
    snprintf(from, sizeof from, "%s/device.json", dir); /* newer fakenects read it */
    if (access(from, F_OK) == 0 && link_file(real_dir, v->dir, "device.json") != 0) {
        return view_failed(v, "linking", from, err, err_size);
    }
    return CUB_OK;
}

static cub_err point_env(cub_fakenect_view *v, const char *dir, char *err, size_t err_size)
{
    v->saved_path = strdup(dir);
    snprintf(view_env, sizeof view_env, "FAKENECT_PATH=%s", v->dir);
    if (!v->saved_path || putenv(view_env) != 0) {
        snprintf(err, err_size, "fakenect dump %s: cannot point FAKENECT_PATH at the view", dir);
        cub_fakenect_dump_release(v);
        return CUB_ERR_NOMEM;
    }
    v->env_pointed = 1;
    return CUB_OK;
}

cub_err cub_fakenect_dump_prepare(cub_fakenect_view *v, char *err, size_t err_size)
{
    const char *dir = getenv("FAKENECT_PATH");
    if (!dir || !dir[0]) {
        snprintf(err, err_size, "depth: fakenect is loaded but FAKENECT_PATH is not set "
                                "(set it to a dump directory)");
        return CUB_ERR_DEVICE;
    }
    if (strlen(dir) >= CUB_FAKENECT_PATH_MAX) {
        snprintf(err, err_size, "depth: FAKENECT_PATH is longer than %d characters",
                 CUB_FAKENECT_PATH_MAX - 1);
        return CUB_ERR_DEVICE;
    }
    dump_scan scan = {0};
    cub_err e = scan_dump(dir, &scan, err, err_size);
    if (!e) e = judge_scan(dir, &scan, err, err_size);
    if (e || scan.bad_frames + scan.empty_accel + scan.blank_lines + scan.jumps == 0) return e;
    /* Copied: point_env replaces the environment string dir points into. */
    char dump_dir[CUB_FAKENECT_PATH_MAX];
    snprintf(dump_dir, sizeof dump_dir, "%s", dir);
    e = build_view(v, dump_dir, scan.blank_lines + scan.jumps > 0, err, err_size);
    return e ? e : point_env(v, dump_dir, err, err_size);
}

void cub_fakenect_dump_restore_env(cub_fakenect_view *v)
{
    if (!v->env_pointed) return;
    setenv("FAKENECT_PATH", v->saved_path, 1);
    v->env_pointed = 0;
}

static void remove_view(const char *view)
{
    DIR *d = opendir(view);
    struct dirent *ent;
    char path[CUB_FAKENECT_PATH_MAX + NAME_MAX_CHARS + 2];
    while (d && (ent = readdir(d))) {
        if (strcmp(ent->d_name, ".") && strcmp(ent->d_name, "..")) {
            snprintf(path, sizeof path, "%s/%s", view, ent->d_name);
            unlink(path);
        }
    }
    if (d) closedir(d);
    rmdir(view);
}

void cub_fakenect_dump_release(cub_fakenect_view *v)
{
    if (!v) return;
    cub_fakenect_dump_restore_env(v);
    free(v->saved_path);
    v->saved_path = NULL;
    if (v->dir[0]) remove_view(v->dir);
    v->dir[0] = '\0';
}
