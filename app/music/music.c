/* music — FluidSynth behind cub/music.h: one synthesiser, one SoundFont,
 * FluidSynth's own MIDI player timed by the samples it renders (never by a
 * wall clock), and the music clock counted in frames rendered. */
#include <errno.h>
#include <fluidsynth.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/music.h"
#include "sf2_trim.h"

#define PPM 1000000
#define SOUNDFONT_MAX_BYTES ((size_t)1 << 30) /* FluidR3_GM is 141 MB */
#define CUB_MUSIC_POLYPHONY 64 /* voices sounding at once (see cub_music_open) */

struct cub_music {
    fluid_settings_t *settings;
    fluid_synth_t *synth;
    fluid_player_t *player; /* NULL until play */
    uint8_t *midi;          /* the loaded file (FluidSynth copies it per player) */
    size_t midi_len;
    cub_midi_info info;
    int rate;
    int playing;                  /* play called, stop not (under lock) */
    int paused;                   /* held: render gives silence (under lock) */
    pthread_mutex_t lock;         /* render vs load / play / stop */
    atomic_uint_least64_t frames; /* rendered since play */
    atomic_int player_busy;       /* FluidSynth's player has events left */
    atomic_int scale_ppm;         /* clock scale, parts per million */
    char *soundfont;              /* its path */
    int sfont_id;                 /* FluidSynth's id of what is loaded, -1 = none */
    int sfont_whole;              /* the whole SoundFont is loaded (kept for every song) */
};

/* FluidSynth's last error, kept for our diagnostics instead of stderr. */
static _Thread_local char last_error[200];

static void log_quiet(int level, const char *message, void *data)
{
    (void)data;
    if (level <= FLUID_ERR) snprintf(last_error, sizeof(last_error), "%s", message);
}

static cub_err fail(cub_diag *diag, cub_err e, const char *file, const char *what,
                    const char *detail)
{
    if (!diag) return e;
    memset(diag, 0, sizeof(*diag));
    snprintf(diag->file, sizeof(diag->file), "%s", file ? file : "music");
    /* A detail too long for the message is cut: what comes first says enough. */
    if (snprintf(diag->msg, sizeof(diag->msg), "%s%s%s", what, detail && detail[0] ? ": " : "",
                 detail ? detail : "") < 0)
        diag->msg[0] = '\0';
    return e;
}

/* FluidSynth reads SoundFonts through these: real files from disk, and the
 * one trimmed image being loaded (sf2_trim.h) from memory. sfload reads
 * everything before it returns (dynamic sample loading is off), on the
 * calling thread: the image only has to live through that call. */
typedef struct sf_handle {
    FILE *f;
    const uint8_t *p;
    size_t len, at;
} sf_handle;

static _Thread_local const uint8_t *image;
static _Thread_local size_t image_len;
static _Thread_local const char *image_name;

static void *sf_open(const char *name)
{
    sf_handle *h = calloc(1, sizeof(*h));
    if (!h) return NULL;
    if (image && image_name && strcmp(name, image_name) == 0) {
        h->p = image;
        h->len = image_len;
    } else if (!(h->f = fopen(name, "rb"))) {
        free(h);
        return NULL;
    }
    return h;
}

static int sf_read(void *buf, fluid_long_long_t count, void *handle)
{
    sf_handle *h = handle;
    if (count < 0) return FLUID_FAILED;
    if (h->f) return fread(buf, 1, (size_t)count, h->f) == (size_t)count ? FLUID_OK : FLUID_FAILED;
    if ((size_t)count > h->len - h->at) return FLUID_FAILED;
    memcpy(buf, h->p + h->at, (size_t)count);
    h->at += (size_t)count;
    return FLUID_OK;
}

static int sf_seek(void *handle, fluid_long_long_t offset, int origin)
{
    sf_handle *h = handle;
    if (h->f) return fseek(h->f, (long)offset, origin) == 0 ? FLUID_OK : FLUID_FAILED;
    fluid_long_long_t base = origin == SEEK_SET   ? 0
                             : origin == SEEK_CUR ? (fluid_long_long_t)h->at
                                                  : (fluid_long_long_t)h->len;
    if (base + offset < 0 || base + offset > (fluid_long_long_t)h->len) return FLUID_FAILED;
    h->at = (size_t)(base + offset);
    return FLUID_OK;
}

static fluid_long_long_t sf_tell(void *handle)
{
    sf_handle *h = handle;
    return h->f ? (fluid_long_long_t)ftell(h->f) : (fluid_long_long_t)h->at;
}

static int sf_close(void *handle)
{
    sf_handle *h = handle;
    if (h->f) fclose(h->f);
    free(h);
    return FLUID_OK;
}

/* Under the lock (or before anyone else has m): what was loaded goes. */
static void unload_soundfont(cub_music *m)
{
    if (m->sfont_id >= 0) fluid_synth_sfunload(m->synth, m->sfont_id, 1);
    m->sfont_id = -1;
    m->sfont_whole = 0;
}

static cub_err load_whole(cub_music *m, cub_diag *diag)
{
    if (m->sfont_whole) return CUB_OK;
    unload_soundfont(m);
    last_error[0] = '\0';
    m->sfont_id = fluid_synth_sfload(m->synth, m->soundfont, 1);
    if (m->sfont_id == FLUID_FAILED) {
        m->sfont_id = -1;
        return fail(diag, CUB_ERR_FORMAT, m->soundfont, "FluidSynth cannot load this SoundFont",
                    last_error);
    }
    m->sfont_whole = 1;
    return CUB_OK;
}

/* Only the presets of this song (sf2_trim.h): the General MIDI SoundFont
 * whole is 15 MB resident in FluidSynth (5.8 MB of samples, 2063 zones),
 * a song's two presets under 1 MB. The cut file renders bit-identically
 * (same sample points, loops, generators); whatever cannot be cut exactly
 * plays from the whole SoundFont instead, as before. */
static cub_err load_for_song(cub_music *m, const uint8_t *midi, size_t len, cub_diag *diag)
{
    static atomic_uint serial;
    cub_sf2_presets want;
    uint8_t *img = NULL;
    size_t img_len = 0;
    FILE *f = NULL;
    size_t bytes = 0;
    cub_text_src src = {m->soundfont, "SoundFont", SOUNDFONT_MAX_BYTES};
    if (cub_midi_presets(midi, len, &want) != CUB_OK || cub_text_fopen(&src, &f, &bytes, NULL) ||
        cub_sf2_trim(f, m->soundfont, &want, &img, &img_len, NULL) != CUB_OK) {
        if (f) fclose(f);
        return load_whole(m, diag);
    }
    fclose(f);
    char name[64];
    snprintf(name, sizeof(name), "cub-trimmed-soundfont-%u", atomic_fetch_add(&serial, 1));
    unload_soundfont(m);
    image = img, image_len = img_len, image_name = name;
    m->sfont_id = fluid_synth_sfload(m->synth, name, 1);
    image = NULL, image_len = 0, image_name = NULL;
    free(img);
    if (m->sfont_id == FLUID_FAILED) {
        m->sfont_id = -1;
        return load_whole(m, diag);
    }
    return CUB_OK;
}

/* Check the SoundFont now, so that a bad one fails at open; load it when
 * the song is known (load_for_song), or now when it cannot be cut. */
static cub_err open_soundfont(cub_music *m, const char *path, cub_diag *diag)
{
    FILE *f = NULL;
    size_t bytes = 0;
    cub_diag why = {0};
    cub_text_src src = {path, "SoundFont", SOUNDFONT_MAX_BYTES};
    cub_err opened = cub_text_fopen(&src, &f, &bytes, &why);
    /* "cannot open the SoundFont: why" -> "cannot read the SoundFont: why" */
    const char *reason = strstr(why.msg, "SoundFont: ");
    if (opened)
        return fail(diag, opened, path, "cannot read the SoundFont", reason ? reason + 11 : why.msg);
    char head[12] = {0};
    size_t got = fread(head, 1, sizeof(head), f);
    /* FluidSynth would hand other files to its DLS loader, which complains
     * on stderr; a SoundFont 2 is a RIFF file of form "sfbk". */
    if (got < sizeof(head) || memcmp(head, "RIFF", 4) != 0 || memcmp(head + 8, "sfbk", 4) != 0) {
        fclose(f);
        return fail(diag, CUB_ERR_FORMAT, path, "not a SoundFont 2 file (no RIFF sfbk header)",
                    NULL);
    }
    size_t n = strlen(path) + 1;
    m->soundfont = malloc(n);
    if (m->soundfont) memcpy(m->soundfont, path, n);
    if (!m->soundfont) {
        fclose(f);
        return fail(diag, CUB_ERR_NOMEM, path, "out of memory", NULL);
    }
    cub_err e = cub_sf2_check(f, path, NULL);
    fclose(f);
    return e == CUB_OK ? CUB_OK : load_whole(m, diag);
}

cub_err cub_music_open(const cub_music_desc *desc, cub_music **out, cub_diag *diag)
{
    cub_music_desc d = desc ? *desc : (cub_music_desc){0};
    if (!out) return fail(diag, CUB_ERR_ARG, NULL, "cub_music_open: no output", NULL);
    *out = NULL;
    if (!d.soundfont) d.soundfont = CUB_MUSIC_SOUNDFONT;
    if (!d.rate) d.rate = 44100;
    if (!d.gain_permille) d.gain_permille = 800;
    if (d.rate < 8000 || d.rate > 96000 || d.gain_permille < 0 || d.gain_permille > 10000)
        return fail(diag, CUB_ERR_ARG, NULL, "cub_music_open: rate or gain out of range", NULL);
    for (int level = FLUID_PANIC; level <= FLUID_DBG; level++)
        fluid_set_log_function(level, log_quiet, NULL);
    cub_music *m = calloc(1, sizeof(*m));
    if (!m) return fail(diag, CUB_ERR_NOMEM, NULL, "out of memory", NULL);
    m->rate = d.rate;
    m->sfont_id = -1;
    atomic_init(&m->frames, 0);
    atomic_init(&m->player_busy, 0);
    atomic_init(&m->scale_ppm, PPM);
    pthread_mutex_init(&m->lock, NULL);
    m->settings = new_fluid_settings();
    if (m->settings) {
        fluid_settings_setnum(m->settings, "synth.sample-rate", d.rate);
        fluid_settings_setnum(m->settings, "synth.gain", d.gain_permille / 1000.0);
        /* The player must follow the samples rendered, not the system
         * clock: the audio is the music clock. */
        fluid_settings_setstr(m->settings, "player.timing-source", "sample");
        /* Voices are allocated up front (about 10 KB each): FluidSynth's
         * default 256 cost 2 MB resident. A children's song rings far fewer
         * at once (the shipped songs render bit-identically with 64), and a
         * song that wanted more would have its oldest voices stolen. Dynamic
         * sample loading would save 5.7 MB more but changes the rendered
         * audio (Twinkle: 29 % of its samples differ; cf. FluidSynth
         * issue #1484), so it stays off. */
        fluid_settings_setint(m->settings, "synth.polyphony", CUB_MUSIC_POLYPHONY);
        m->synth = new_fluid_synth(m->settings);
    }
    fluid_sfloader_t *loader = m->synth ? new_fluid_defsfloader(m->settings) : NULL;
    if (loader) {
        fluid_sfloader_set_callbacks(loader, sf_open, sf_read, sf_seek, sf_tell, sf_close);
        fluid_synth_add_sfloader(m->synth, loader); /* the synth owns it now */
    }
    if (!m->synth || !loader) {
        cub_music_close(m);
        return fail(diag, CUB_ERR_DEVICE, NULL, "FluidSynth cannot start a synthesiser",
                    last_error);
    }
    cub_err e = open_soundfont(m, d.soundfont, diag);
    if (e) {
        cub_music_close(m);
        return e;
    }
    *out = m;
    return CUB_OK;
}

/* Under the lock. */
static void drop_player(cub_music *m)
{
    if (m->player) {
        fluid_player_stop(m->player);
        delete_fluid_player(m->player);
        m->player = NULL;
    }
    m->playing = 0;
    m->paused = 0;
    atomic_store(&m->player_busy, 0);
    if (m->synth) fluid_synth_all_notes_off(m->synth, -1);
}

void cub_music_close(cub_music *m)
{
    if (!m) return;
    pthread_mutex_lock(&m->lock);
    drop_player(m);
    pthread_mutex_unlock(&m->lock);
    if (m->synth) delete_fluid_synth(m->synth);
    if (m->settings) delete_fluid_settings(m->settings);
    pthread_mutex_destroy(&m->lock);
    free(m->soundfont);
    free(m->midi);
    free(m);
}

cub_err cub_music_load(cub_music *m, const char *midi_path, cub_diag *diag)
{
    if (!m || !midi_path)
        return fail(diag, CUB_ERR_ARG, NULL, "cub_music_load: bad arguments", NULL);
    char *data = NULL;
    size_t len = 0;
    cub_diag scratch;
    cub_text_src src = {midi_path, "MIDI file", CUB_TEXT_MAX_MIDI};
    cub_err e = cub_text_read(&src, &data, &len, diag ? diag : &scratch);
    if (e) return e;
    cub_midi_info info;
    e = cub_midi_scan((const uint8_t *)data, len, midi_path, &info, diag);
    if (!e && info.notes == 0)
        e = fail(diag, CUB_ERR_FORMAT, midi_path, "the song has no notes", NULL);
    if (e) {
        free(data);
        return e;
    }
    pthread_mutex_lock(&m->lock);
    drop_player(m);
    free(m->midi);
    m->midi = (uint8_t *)data;
    m->midi_len = len;
    m->info = info;
    e = m->sfont_whole ? CUB_OK : load_for_song(m, m->midi, len, diag);
    pthread_mutex_unlock(&m->lock);
    return e;
}

cub_err cub_music_play(cub_music *m)
{
    if (!m) return CUB_ERR_ARG;
    cub_err e = CUB_OK;
    pthread_mutex_lock(&m->lock);
    drop_player(m);
    if (!m->midi) {
        e = CUB_ERR_EMPTY;
    } else {
        /* A new player per play: FluidSynth's player starts a file from its
         * beginning only when it loads it. */
        m->player = new_fluid_player(m->synth);
        if (!m->player || fluid_player_add_mem(m->player, m->midi, m->midi_len) != FLUID_OK ||
            fluid_player_play(m->player) != FLUID_OK) {
            drop_player(m);
            e = CUB_ERR_DEVICE;
        } else {
            m->playing = 1;
            m->paused = 0;
            atomic_store(&m->frames, 0);
            atomic_store(&m->player_busy, 1);
        }
    }
    pthread_mutex_unlock(&m->lock);
    return e;
}

void cub_music_stop(cub_music *m)
{
    if (!m) return;
    pthread_mutex_lock(&m->lock);
    drop_player(m);
    pthread_mutex_unlock(&m->lock);
}

void cub_music_render(cub_music *m, int16_t *stereo, int frames)
{
    if (!stereo || frames <= 0) return;
    if (!m) {
        memset(stereo, 0, (size_t)frames * 2 * sizeof(int16_t));
        return;
    }
    pthread_mutex_lock(&m->lock);
    if (m->playing && !m->paused) {
        fluid_synth_write_s16(m->synth, frames, stereo, 0, 2, stereo, 1, 2);
        atomic_fetch_add(&m->frames, (uint64_t)frames);
        /* The song ends at its last tick; FluidSynth's player reports DONE
         * only once the last notes have rung out, seconds later. */
        atomic_store(&m->player_busy,
                     fluid_player_get_status(m->player) == FLUID_PLAYER_PLAYING &&
                         fluid_player_get_current_tick(m->player) < m->info.end_tick);
    } else {
        memset(stereo, 0, (size_t)frames * 2 * sizeof(int16_t));
    }
    pthread_mutex_unlock(&m->lock);
}

void cub_music_pause(cub_music *m, int paused)
{
    if (!m) return;
    pthread_mutex_lock(&m->lock);
    m->paused = m->playing && paused;
    pthread_mutex_unlock(&m->lock);
}

void cub_music_fill(void *user, int16_t *stereo, int frames)
{
    cub_music_render((cub_music *)user, stereo, frames);
}

uint64_t cub_music_frames(const cub_music *m)
{
    return m ? atomic_load(&((cub_music *)m)->frames) : 0;
}

int64_t cub_music_clock_us(const cub_music *m)
{
    if (!m) return 0;
    /* Floor first, then scale: exact frames/rate when the scale is 1, and
     * no overflow for days of audio. */
    int64_t us = (int64_t)(cub_music_frames(m) * PPM / (uint64_t)m->rate);
    int ppm = atomic_load(&((cub_music *)m)->scale_ppm);
    return ppm == PPM ? us : us * ppm / PPM;
}

int64_t cub_music_length_us(const cub_music *m)
{
    return m && m->midi ? m->info.length_us : 0;
}

int cub_music_playing(const cub_music *m)
{
    return m ? atomic_load(&((cub_music *)m)->player_busy) : 0;
}

int cub_music_rate(const cub_music *m)
{
    return m ? m->rate : 0;
}

cub_err cub_music_set_clock_scale(cub_music *m, double scale)
{
    if (!m || !(scale >= 0.5 && scale <= 2.0)) return CUB_ERR_ARG;
    atomic_store(&m->scale_ppm, (int)(scale * PPM + 0.5));
    return CUB_OK;
}
