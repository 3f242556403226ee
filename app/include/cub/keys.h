/* keys — hand-written keyframe clips (assets/keys/NAME.keys): a small text
 * format of ours for the coach's own moves (head shake, doze, clap, wave),
 * turned into a cub_clip on a given skeleton (the character's).
 *
 *   # wave.keys — the bear waves its right paw, twice a second
 *   clip wave kind=coach fps=30
 *   key 0.0
 *     RightArm z=60
 *     RightForeArm z=30
 *   key 0.25  RightForeArm z=70
 *   key 0.5   RightForeArm z=30   Head z=-8
 *   loop
 *
 * Lines (blank lines and '#' comments anywhere are ignored):
 *   clip NAME [kind=KIND] [fps=N]   first; KIND defaults to "coach" (or
 *                                   "dance" for a kid move), fps to 30 (1..240).
 *   key T [root=X,Y,Z] [JOINT [x=DEG] [y=DEG] [z=DEG]]...
 *                                   a key pose at T seconds. Joint entries
 *                                   may follow on the key line or on the next
 *                                   lines (any line that starts with a joint
 *                                   name belongs to the key above it).
 *   loop [T]                        last: the clip loops, and T seconds after
 *                                   the first key the pose is the first key's
 *                                   again. Without T the loop closes one
 *                                   first-to-second key gap after the last key.
 *
 * Meaning:
 *   - Times are seconds. The first key is at 0; later keys strictly later.
 *     Each key time is rounded to the nearest frame (1/fps), and two keys
 *     may not fall on the same frame.
 *   - A joint's rotation is given in degrees about the x, y and z axes of its
 *     PARENT's frame (at rest all frames line up with the world: y up, the
 *     character faces +z, its left is +x). The three are applied x first,
 *     then y, then z, each about the parent's fixed axes: q = Rz * Ry * Rx.
 *     An axis not written is 0: "LeftArm z=-80" is exactly 80 degrees about z.
 *   - A joint not written in a key keeps its value from the previous key;
 *     joints never written stay at rest. Likewise root= (millimetres, added
 *     to the rest position of the root; 0,0,0 until first written).
 *   - Between keys every number (each Euler angle, each root coordinate)
 *     follows a smooth curve: a cubic Hermite spline through the keys with
 *     Catmull-Rom tangents over the key times, so motion passes through keys
 *     without stopping; a clip that does not loop eases in at its first key
 *     and out at its last. Angles are not wrapped: z=0 then z=350 turns 350
 *     degrees, as written. Frames are sampled at fps; every key's frame is
 *     that key's pose exactly.
 *   - A clip that does not loop has frames 0 .. last key; a loop of period
 *     T has T*fps frames and is played with CUB_MOTION_LOOP.
 *
 * Errors name the file, the line and the problem: an unknown joint (or one
 * that is an end site), a bad number or axis, a joint twice in one key,
 * times that do not increase, a missing clip line, anything after loop.
 */
#ifndef CUB_KEYS_H
#define CUB_KEYS_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/io.h"
#include "cub/motion.h"

#define CUB_KEYS_MAX_KEYS 256
#define CUB_KEYS_KIND_LEN 16
#define CUB_KEYS_MAX_SECONDS 600

typedef struct cub_keys_clip {
    char name[CUB_MOTION_NAME_LEN];
    char kind[CUB_KEYS_KIND_LEN];
    int loop; /* 1: play with CUB_MOTION_LOOP */
    int fps;
    cub_clip clip; /* clip.skel is the skeleton given to the parser */
    int key_count;
    int key_frame[CUB_KEYS_MAX_KEYS]; /* the frame each key landed on */
    int key_line[CUB_KEYS_MAX_KEYS];  /* the line each key is on */
    void *mem;                        /* frame data, owned; freed by cub_keys_free */
} cub_keys_clip;

/* Parse keys text (need not be NUL-terminated; name is used in messages)
 * into a clip on skel, which must outlive the clip. */
cub_err cub_keys_parse(const char *text, size_t len, const char *name, const cub_skeleton *skel,
                       cub_keys_clip *out, cub_diag *diag);
/* The same from a file. */
cub_err cub_keys_load(const char *path, const cub_skeleton *skel, cub_keys_clip *out,
                      cub_diag *diag);
void cub_keys_free(cub_keys_clip *k);

#endif
