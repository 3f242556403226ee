/* character — a coach character described as data (assets/bear/bear.xml):
 * its skeleton, which joints the fuzzy features read, and its body as
 * rounded parts hung on joints. Loaded with tinyxml2 (through cub/xml.h).
 * Every problem in the file is reported with file, line and what is wrong. */
#ifndef CUB_CHARACTER_H
#define CUB_CHARACTER_H

#include "cub/err.h"
#include "cub/fuzzy.h"
#include "cub/io.h"
#include "cub/motion.h"

#define CUB_CHARACTER_MAX_PARTS 64

typedef enum cub_part_shape {
    CUB_PART_ELLIPSOID = 0, /* centre + radii in the joint's frame */
    CUB_PART_CAPSULE,       /* along the bone from the joint to its (first) child */
} cub_part_shape;

typedef struct cub_character_part {
    int joint;
    cub_part_shape shape;
    float centre_mm[3], radii_mm[3]; /* ellipsoid */
    float radius_mm, end_radius_mm;  /* capsule */
    float rgb[3];                    /* 0..1, sRGB */
} cub_character_part;

typedef struct cub_character {
    char name[32];
    cub_skeleton skel;     /* rest pose: standing, feet on y = 0 */
    cub_fuzzy_body body;   /* joint indices; stand_cog_mm from the rest pose */
    int part_count;
    cub_character_part parts[CUB_CHARACTER_MAX_PARTS];
    /* Per joint, 1 for optional="1": a joint only some clips move (the
     * winged bear's wings, bird_flying only); the renderer draws its parts
     * only while the scene's skeleton has it. */
    uint8_t optional[CUB_MOTION_MAX_JOINTS];
} cub_character;

/* Load and validate (joints exist, parents first, feature joints present,
 * parts on existing joints, numbers finite and positive where they must be). */
cub_err cub_character_load(const char *path, cub_character *out, cub_diag *diag);
cub_err cub_character_parse(const char *xml, size_t len, const char *name, cub_character *out,
                            cub_diag *diag);

#endif
