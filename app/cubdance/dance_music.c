/* The dance's music (see dance_music.h). */
#include "dance_music.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cub/coach.h"

#define PCM_FRAMES 4096
/* What the audio device holds before the speaker: the music clock counts
 * frames handed to SDL, which run about one buffer ahead (board.h). */
#define AUDIO_LATENCY_FRAMES 1024

static cub_err fail(char *err, size_t size, const cub_diag *diag, const char *what)
{
    char buf[600];
    snprintf(err, size, "%s: %s", what, cub_diag_str(diag, buf, sizeof buf));
    return CUB_ERR_FORMAT;
}

/* The audio thread's fill: the music, then the voice over it. */
static void fill_device(void *user, int16_t *stereo, int frames)
{
    cub_dance_music *m = user;
    cub_music_render(m->music, stereo, frames);
    cub_voice_mix(&m->voice, stereo, frames);
}

/* The voice pack, or a warning: the box goes on showing its words. */
static void open_voice(cub_dance_music *m, const cub_app_options *o, int rate)
{
    if (!o->speech || !o->voice_path) return;
    cub_diag diag;
    char buf[600];
    if (cub_voicepack_read(o->voice_path, &m->voicepack, &diag)) {
        fprintf(stderr, "cubdance: warning: speech off: %s (the words are shown, not spoken)\n",
                cub_diag_str(&diag, buf, sizeof buf));
        return;
    }
    if (cub_voice_init(&m->voice, &m->voicepack, rate)) {
        fprintf(stderr, "cubdance: warning: speech off: %s: the device's %d Hz is out of range\n",
                o->voice_path, rate);
        cub_voicepack_free(&m->voicepack);
        cub_voice_init(&m->voice, NULL, 44100);
    }
}

cub_err cub_dance_music_open(cub_dance_music *m, const cub_app_options *o, cub_board *board,
                             const char *midi_path, char *err, size_t size)
{
    memset(m, 0, sizeof *m);
    m->board = board;
    cub_diag diag;
    cub_music_desc md = {.rate = cub_board_audio_rate(board), .soundfont = o->soundfont};
    if (cub_music_open(&md, &m->music, &diag)) return fail(err, size, &diag, "music");
    if (cub_music_load(m->music, midi_path, &diag)) return fail(err, size, &diag, "song");

    m->pcm = malloc(PCM_FRAMES * 2 * sizeof(int16_t));
    if (!m->pcm) return CUB_ERR_NOMEM;
    open_voice(m, o, md.rate);
    /* Real time: the audio device plays the music and clocks it. Virtual
     * time, or no audio device: the tick renders it. */
    m->pull = o->virtual_clock;
    if (!m->pull) {
        if (cub_board_audio_start(board, fill_device, m) == CUB_OK)
            m->audio_open = 1;
        else
            m->pull = 1;
    }
    /* --music-clock-scale: rendered here, the music itself runs off its
     * rate; played by a device we cannot speed up, only its clock lies. */
    m->pull_scale_ppm = (uint32_t)(o->music_clock_scale * 1000000 + 0.5);
    if (m->audio_open && o->music_clock_scale != 1.0 &&
        cub_music_set_clock_scale(m->music, o->music_clock_scale))
        return snprintf(err, size, "--music-clock-scale out of range"), CUB_ERR_ARG;
    return CUB_OK;
}

void cub_dance_music_close(cub_dance_music *m)
{
    if (m->audio_open) cub_board_audio_stop(m->board); /* before the voice pack goes */
    cub_music_close(m->music);
    free(m->pcm);
    cub_voicepack_free(&m->voicepack);
    memset(m, 0, sizeof *m);
}

int32_t cub_dance_music_ms(const cub_dance_music *m)
{
    if (!m->started) return CUB_COACH_NO_MUSIC;
    int64_t us = cub_music_clock_us(m->music);
    if (m->audio_open) {
        us -= (int64_t)AUDIO_LATENCY_FRAMES * 1000000 / cub_music_rate(m->music);
        if (us < 0) us = 0;
    }
    return (int32_t)(us / 1000);
}

void cub_dance_music_start(cub_dance_music *m, int64_t t_us)
{
    if (cub_music_play(m->music) != CUB_OK) return;
    m->started = 1;
    m->paused = 0;
    m->end_told = 0;
    m->pull_origin_us = t_us;
}

void cub_dance_music_stop(cub_dance_music *m)
{
    cub_music_stop(m->music);
    m->started = 0;
    m->paused = 0;
}

/* Rendered music starts counting its due frames again from where it held. */
void cub_dance_music_pause(cub_dance_music *m, int paused, int64_t t_us)
{
    if (!m->started || paused == m->paused) return;
    cub_music_pause(m->music, paused);
    m->paused = paused;
    if (paused)
        m->paused_at_us = t_us;
    else
        m->pull_origin_us += t_us - m->paused_at_us;
}

/* Under the virtual clock the music is rendered here, exactly as much as
 * the loop's time says. A sound card off its rate (--music-clock-scale)
 * takes that many more or fewer frames a second; the music clock counts
 * them, true to the music it played. */
static void render_due(cub_dance_music *m, int64_t t_us)
{
    if (!m->pull || !m->started || m->paused) return;
    uint64_t card_us = (uint64_t)(t_us - m->pull_origin_us) * m->pull_scale_ppm / 1000000u;
    uint64_t due = card_us * (uint64_t)cub_music_rate(m->music) / 1000000u;
    while (cub_music_frames(m->music) < due) {
        uint64_t n = due - cub_music_frames(m->music);
        cub_music_render(m->music, m->pcm, (int)(n > PCM_FRAMES ? PCM_FRAMES : n));
    }
}

int cub_dance_music_poll(cub_dance_music *m, int64_t now_us)
{
    render_due(m, now_us);
    if (!m->started || m->end_told || cub_music_playing(m->music)) return 0;
    m->end_told = 1;
    return 1;
}

cub_dance_said cub_dance_music_say(cub_dance_music *m, const char *text)
{
    if (!m->voicepack.count) return CUB_DANCE_UNSAID;
    int phrase = cub_voicepack_find(&m->voicepack, text);
    if (phrase < 0) return CUB_DANCE_NO_PHRASE;
    if (m->audio_open) cub_voice_say(&m->voice, phrase);
    return CUB_DANCE_SAID;
}

uint64_t cub_dance_music_device_frames(const cub_dance_music *m)
{
    return m->audio_open ? cub_board_audio_frames(m->board) : 0;
}
