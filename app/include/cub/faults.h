/* faults — the words the bear says when a move's key fails (a song's
 * faults="..." file, assets/songs/faults.words): one line per key feature,
 * set and how it failed, in words for children, for content makers to
 * edit like the songs' hints.
 *
 *   # KEY=SET  HOW     [for=CLIP]           WORDS
 *   RH=up      missed                       Reach up high!
 *   RH=up      mirror                       The other arm!
 *   RH=mid     missed  for=jumping_jacks    Jump!
 *
 * KEY=SET is a key point as a song writes it (a fuzzy feature of
 * cub/fuzzy.h and one of its sets). HOW is how the judge saw it fail
 * (cub/judge.h): missed (its moment passed with no sign of it) or mirror
 * (the other side did it; only for a feature with a side: RH RHE LH LHE
 * RF RFK LF LFK). for=CLIP makes the line a move's own (a dance clip of
 * the library): it is said for that move before the line without for=.
 * WORDS are the rest of the line, as they are shown and spoken (UTF-8, at
 * most CUB_FAULTS_TEXT_LEN - 1 bytes; a '#' starts a comment).
 *
 * Errors name the file and line: a bad key or set, an unknown HOW, a
 * mirror of a feature without a side, a clip the library lacks or that is
 * not a kid's move, no words, words too long, not UTF-8 or with control
 * characters,
 * a line given twice, more than CUB_FAULTS_MAX lines. */
#ifndef CUB_FAULTS_H
#define CUB_FAULTS_H

#include <stddef.h>
#include <stdint.h>

#include "cub/err.h"
#include "cub/io.h"
#include "cub/motion.h"
#include "cub/pack.h"

#define CUB_FAULTS_MAX 128
#define CUB_FAULTS_TEXT_LEN 128

typedef struct cub_fault_words {
    int32_t how;                   /* cub_judge_how: missed, mirror */
    int32_t feature, set;          /* the key */
    char clip[CUB_MOTION_NAME_LEN]; /* for=CLIP; "" = every move */
    char words[CUB_FAULTS_TEXT_LEN];
    int line;
} cub_fault_words;

typedef struct cub_faults {
    int count;
    cub_fault_words w[CUB_FAULTS_MAX];
} cub_faults;

/* Read a table from memory (name for messages); lib checks for=CLIP (may
 * be NULL: not checked). CUB_ERR_FORMAT with diag; out empty then. */
cub_err cub_faults_parse(const char *text, size_t len, const char *name, const cub_library *lib,
                         cub_faults *out, cub_diag *diag);
/* The same from a file (CUB_ERR_IO when it cannot be read). */
cub_err cub_faults_load(const char *path, const cub_library *lib, cub_faults *out,
                        cub_diag *diag);
/* The words for key (feature, set) failing how in move clip: its own
 * line, else the general one; NULL when the table has neither (f NULL). */
const char *cub_faults_words(const cub_faults *f, const char *clip, int32_t how, int32_t feature,
                             int32_t set);

#endif
