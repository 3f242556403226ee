/* libFuzzer target for the parsers of app/io.
 * Input: byte 0 picks the parser, the rest is the text (or bytes).
 *   'T': a bridge tag file (cub/tags.h), validated against a fixed library.
 *   'S': a song's choreography (cub/song.h), against a fixed library.
 *   'F': a fault words table (cub/faults.h), against the same library.
 *   'L': the scripted judge timeline (app/cubdance/timeline.h).
 *   'U': a button timeline (board/common/buttons_script.h).
 *   'G': the box's config file (cub/boxconf.h; also fuzz_boxconf on its own).
 *   'X': a character (XML, cub_character_parse).
 *   'P': a clip pack (version 1 or 2) as is; 'Q': a clip pack whose last 4 bytes the harness
 *        replaces by the right CRC, so mutations get past the CRC check.
 *   'K': a keyframe text clip on a fixed six-joint skeleton.
 *   any other even byte (e.g. 'B'): BVH; bit 1 set: a fixed unit instead of
 *        the guess.
 *   any other odd byte (e.g. 'A'): ASF + AMC, split at the first "\n==AMC==\n".
 * Whatever the input, a parser returns (no crash, hang or overread) and
 * every failure says why; on success the result must be usable: forward
 * kinematics on its frames. Seeds: tests/fuzz/seeds (see make_corpus.cmake). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cub/character.h"
#include "cub/faults.h"
#include "cub/io.h"
#include "cub/keys.h"
#include "cub/pack.h"
#include "cub/song.h"
#include "cub/tags.h"
#include "buttons_script.h"
#include "cub/boxconf.h"
#include "timeline.h"

#define MARK "\n==AMC==\n"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
static int fuzz_tags(const char *text, size_t len);
static int fuzz_song(const char *text, size_t len);
static int fuzz_faults(const char *text, size_t len);

/* A button timeline that parses hands out its edges in time order, as many
 * as it says it has. */
static int fuzz_buttons(const char *text, size_t len)
{
    cub_button_script *s = NULL;
    char err[300];
    if (cub_button_script_parse(text, len, "fuzz.buttons", &s, err, sizeof err) != CUB_OK) {
        if (!err[0]) abort();
        return 0;
    }
    cub_event ev;
    int64_t last = INT64_MIN;
    size_t n = 0;
    while (cub_button_script_next(s, INT64_MAX, &ev)) {
        if (ev.t_us < last || (ev.type != CUB_EV_BUTTON_DOWN && ev.type != CUB_EV_BUTTON_UP))
            abort();
        last = ev.t_us;
        n++;
    }
    if (n != cub_button_script_edges(s)) abort();
    cub_button_script_free(s);
    return 0;
}

/* A box config that parses has its values in their documented ranges. */
static int fuzz_gpio(const char *text, size_t len)
{
    static cub_boxconf cfg;
    char err[300];
    if (cub_boxconf_parse(text, len, "fuzz.conf", &cfg, err, sizeof err) != CUB_OK) {
        if (!err[0]) abort();
        return 0;
    }
    if (cfg.gpio.debounce_ms < 0 || cfg.gpio.debounce_ms > 1000) abort();
    if (cfg.volume < 0 || cfg.volume > 100 || cfg.doze_after_s <= cfg.attract_after_s) abort();
    return 0;
}

/* A timeline that parses hands out its events in time order, each once. */
static int fuzz_timeline(const char *text, size_t len)
{
    cub_timeline *t = NULL;
    char err[300];
    if (cub_timeline_parse(text, len, "fuzz.timeline", &t, err, sizeof err) != CUB_OK) {
        if (!err[0]) abort(); /* every failure says why */
        return 0;
    }
    cub_event ev;
    int64_t last = 0;
    int n = 0;
    while (cub_timeline_next(t, INT64_MAX, &ev)) {
        if (ev.t_us < last) abort();
        last = ev.t_us;
        n++;
    }
    if (n != cub_timeline_count(t)) abort();
    cub_timeline_free(t);
    return 0;
}

static size_t find_mark(const char *s, size_t n)
{
    size_t m = sizeof(MARK) - 1;
    for (size_t i = 0; i + m <= n; i++)
        if (memcmp(s + i, MARK, m) == 0)
            return i;
    return n;
}

/* Forward kinematics on the first and last frames must work. */
static void use_clip(const cub_skeleton *skel, const cub_clip *clip)
{
    static cub_pose pose;
    static cub_vec3 world[CUB_MOTION_MAX_JOINTS];
    int n = clip->frame_count;
    if (skel->joint_count < 1 || skel->joint_count > CUB_MOTION_MAX_JOINTS || n < 1 ||
        clip->skel != skel)
        __builtin_trap();
    int frames[2] = {0, n - 1};
    for (int i = 0; i < 2; i++) {
        if (cub_motion_clip_get_frame(clip, frames[i], &pose) ||
            cub_motion_forward(skel, &pose, world, NULL))
            __builtin_trap();
    }
}

static void use_motion(const cub_io_motion *m)
{
    use_clip(&m->skel, &m->clip);
}

static cub_err fuzz_character(const char *text, size_t len, cub_diag *d)
{
    static cub_character ch;
    cub_err err = cub_character_parse(text, len, "fuzz.xml", &ch, d);
    if (err == CUB_OK) {
        if (cub_motion_skeleton_validate(&ch.skel) || ch.part_count < 1 ||
            ch.part_count > CUB_CHARACTER_MAX_PARTS)
            __builtin_trap();
        for (int i = 0; i < ch.part_count; i++)
            if (ch.parts[i].joint < 0 || ch.parts[i].joint >= ch.skel.joint_count)
                __builtin_trap();
    }
    return err;
}

static uint32_t crc32_ieee(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1)));
    }
    return ~c;
}

static cub_err fuzz_pack(const uint8_t *data, size_t len, int fix_crc, cub_diag *d)
{
    static cub_library lib;
    /* A private copy of exactly len bytes, so ASan catches any overread. */
    uint8_t *copy = malloc(len ? len : 1);
    if (!copy)
        return CUB_ERR_NOMEM;
    memcpy(copy, data, len);
    if (fix_crc && len >= 4) {
        uint32_t c = crc32_ieee(copy, len - 4);
        for (int i = 0; i < 4; i++)
            copy[len - 4 + (size_t)i] = (uint8_t)(c >> (8 * i));
    }
    cub_err err = cub_pack_parse(copy, len, "fuzz.cubclips", &lib, d);
    free(copy);
    if (err == CUB_OK) {
        for (int i = 0; i < lib.clip_count; i++) {
            use_clip(&lib.skel, &lib.clips[i].clip);
            if (cub_library_find(&lib, lib.clips[i].name) != i)
                __builtin_trap();
        }
        cub_library_free(&lib);
    }
    return err;
}

static cub_err fuzz_keys(const char *text, size_t len, cub_diag *d)
{
    static cub_skeleton skel;
    static cub_keys_clip k;
    if (skel.joint_count == 0) {
        static const struct { const char *name; int parent, y; } j[] = {
            {"Hips", -1, 285}, {"Spine", 0, 115}, {"Head", 1, 140},
            {"Head_end", 2, 270}, {"LeftArm", 1, 110}, {"RightArm", 1, 110}};
        int index;
        cub_motion_skeleton_reset(&skel);
        for (int i = 0; i < 6; i++)
            cub_motion_skeleton_add(&skel, j[i].name, j[i].parent,
                                    (cub_vec3){0, CUB_Q16_INT(j[i].y), 0}, &index);
        skel.joints[3].is_end_site = 1;
    }
    cub_err err = cub_keys_parse(text, len, "fuzz.keys", &skel, &k, d);
    if (err == CUB_OK) {
        use_clip(&skel, &k.clip);
        cub_keys_free(&k);
    }
    return err;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cub_io_motion m;
    cub_diag d = {{0}, 0, {0}};
    char msg[600];
    if (size < 1)
        return 0;
    if (data[0] == 'T')
        return fuzz_tags((const char *)data + 1, size - 1);
    if (data[0] == 'U')
        return fuzz_buttons((const char *)data + 1, size - 1);
    if (data[0] == 'G')
        return fuzz_gpio((const char *)data + 1, size - 1);
    if (data[0] == 'L')
        return fuzz_timeline((const char *)data + 1, size - 1);
    if (data[0] == 'S')
        return fuzz_song((const char *)data + 1, size - 1);
    if (data[0] == 'F')
        return fuzz_faults((const char *)data + 1, size - 1);
    const char *text = (const char *)data + 1;
    size_t len = size - 1;
    cub_io_desc desc = {.unit_mm = (data[0] & 2) ? 1.0 : 0.0};
    cub_err err;
    int motion = 0; /* the BVH and ASF/AMC branches fill m */
    if (data[0] == 'X') {
        err = fuzz_character(text, len, &d);
    } else if (data[0] == 'P' || data[0] == 'Q') {
        err = fuzz_pack(data + 1, len, data[0] == 'Q', &d);
    } else if (data[0] == 'K') {
        err = fuzz_keys(text, len, &d);
    } else if ((data[0] & 1) == 0) {
        motion = 1;
        err = cub_io_parse_bvh(text, len, "fuzz.bvh", &desc, &m, &d);
    } else {
        motion = 1;
        size_t k = find_mark(text, len), skip = k < len ? sizeof(MARK) - 1 : 0;
        err = cub_io_parse_asf_amc(text, k, text + k + skip, len - k - skip, "fuzz", &desc, &m,
                                   &d);
    }
    cub_diag_str(&d, msg, sizeof(msg));
    if (strlen(msg) >= sizeof(msg))
        __builtin_trap();
    if (err == CUB_OK && motion) {
        use_motion(&m);
        cub_io_motion_free(&m);
    } else if (err != CUB_OK && d.msg[0] == '\0') {
        __builtin_trap(); /* every failure says why */
    }
    return 0;
}

/* Tag files are read against a library: two clips, a (10 frames) and b (4);
 * the reader only needs their names and frame counts. */
static int fuzz_tags(const char *text, size_t len)
{
    static cub_library_clip clips[2] = {{.name = "a", .kind = "dance"},
                                        {.name = "b", .kind = "coach"}};
    clips[0].clip.frame_count = 10;
    clips[1].clip.frame_count = 4;
    cub_library lib = {.clip_count = 2, .clips = clips};
    cub_tags tags;
    cub_diag d = {{0}, 0, {0}};
    char msg[600];
    cub_err err = cub_tags_parse(text, len, "fuzz.tags.xml", &lib, &tags, &d);
    cub_diag_str(&d, msg, sizeof(msg));
    if (err == CUB_OK) {
        char *again = NULL;
        size_t n = 0;
        if (cub_tags_print(&tags, &again, &n) != CUB_OK)
            __builtin_trap(); /* what reads must write */
        free(again);
        cub_tags_free(&tags);
    } else if (d.msg[0] == '\0') {
        __builtin_trap();
    }
    return 0;
}

/* The spans of a song that reads run from its start to its end without a
 * hole, <free>s and moves where the song put them. */
static void fuzz_song_spans(const cub_song *song)
{
    static cub_song_span sp[CUB_SONG_MAX_SPANS];
    int n = cub_song_spans(song, sp, CUB_SONG_MAX_SPANS), moves = 0, frees = 0;
    if (n < 1 || sp[0].start_us != 0 || sp[n - 1].end_us != cub_song_length_us(song))
        __builtin_trap();
    for (int i = 0; i < n; i++) {
        if (sp[i].bars < 1 || (i > 0 && sp[i].start_us != sp[i - 1].end_us)) __builtin_trap();
        moves += sp[i].kind == CUB_SONG_SPAN_MOVE;
        frees += sp[i].kind == CUB_SONG_SPAN_FREE;
    }
    if (moves != song->move_count || frees != song->free_count) __builtin_trap();
}

/* Songs are read against a library of nine 2-s kid moves "a".."i" and a
 * coach clip "w"; a song that reads must hold what the format promises. */
static int fuzz_song(const char *text, size_t len)
{
    static cub_library_clip clips[10];
    static cub_song song;
    for (int i = 0; i < 10; i++) {
        clips[i].name[0] = (char)(i < 9 ? 'a' + i : 'w');
        memcpy(clips[i].kind, i < 9 ? "dance" : "coach", 6);
        clips[i].clip.frame_count = 60;
        clips[i].clip.frame_ns = 33333333;
    }
    cub_library lib = {.clip_count = 10, .clips = clips};
    cub_diag d = {{0}, 0, {0}};
    char msg[600];
    cub_err err = cub_song_parse(text, len, "fuzz.song.xml", &lib, &song, &d);
    cub_diag_str(&d, msg, sizeof(msg));
    if (err == CUB_OK) {
        if ((song.move_count > 0 && song.distinct_moves < CUB_SONG_MIN_MOVES) ||
            song.distinct_moves > CUB_SONG_MAX_DISTINCT)
            __builtin_trap();
        fuzz_song_spans(&song);
        for (int i = 0; i < song.move_count; i++)
            if (song.moves[i].reps < CUB_SONG_MIN_REPS ||
                song.moves[i].end_us <= song.moves[i].start_us ||
                (i > 0 && song.moves[i].start_us < song.moves[i - 1].end_us) ||
                song.moves[i].end_us > cub_song_length_us(&song))
                __builtin_trap();
    } else if (d.msg[0] == '\0') {
        __builtin_trap();
    }
    return 0;
}

/* A fault table that parses has words for each of its lines: non-empty,
 * NUL-terminated inside their field, found again by their own key. */
static int fuzz_faults(const char *text, size_t len)
{
    static cub_library_clip clips[2] = {{.name = "a", .kind = "dance"},
                                        {.name = "b", .kind = "coach"}};
    cub_library lib = {.clip_count = 2, .clips = clips};
    static cub_faults f;
    cub_diag d = {{0}, 0, {0}};
    if (cub_faults_parse(text, len, "fuzz.words", &lib, &f, &d) != CUB_OK) {
        if (!d.msg[0]) abort();
        return 0;
    }
    if (f.count < 0 || f.count > CUB_FAULTS_MAX) abort();
    for (int i = 0; i < f.count; i++) {
        const cub_fault_words *w = &f.w[i];
        if (!memchr(w->words, 0, sizeof w->words) || !w->words[0]) abort();
        if (cub_faults_words(&f, w->clip[0] ? w->clip : NULL, w->how, w->feature, w->set) !=
            w->words)
            abort();
    }
    return 0;
}
