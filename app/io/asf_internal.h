/* ASF/AMC internals: the bone table read from an ASF file, which the AMC
 * reader turns into a skeleton and a clip. Not public. */
#ifndef CUB_ASF_INTERNAL_H
#define CUB_ASF_INTERNAL_H

#include "io_internal.h"

/* Bones, root included; End Sites added for leaves must fit as well. */
#define ASF_MAX_BONES CUB_MOTION_MAX_JOINTS

typedef struct asf_bone {
    char name[CUB_MOTION_NAME_LEN];
    int parent;        /* bone index, -1 for the root (bone 0) */
    int line;          /* where its "begin" is */
    double dir[3];     /* unit direction of the bone, global frame at rest */
    double len;        /* length in ASF length units */
    double axis[3];    /* the bone's local frame, as angles (ASF angle unit) */
    int axis_order[3]; /* e.g. XYZ = 0,1,2: X applied first */
    int dof[6];        /* 0..2 rx ry rz, 3..5 tx ty tz (root only) */
    int ndof;
} asf_bone;

typedef struct asf_skel {
    asf_bone bone[ASF_MAX_BONES];
    int count;
    double length_unit; /* ":units length": file lengths are inches * this */
    int angle_deg;      /* 1: degrees, 0: radians */
    double root_pos[3]; /* ":root position" */
} asf_skel;

cub_err asf_parse(asf_skel *s, const char *text, size_t len, const char *name, cub_diag *diag);
/* Index of the bone with this name ("root" is 0), or -1. */
int asf_find(const asf_skel *s, const char *name);

#endif
