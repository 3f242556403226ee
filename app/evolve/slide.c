/* Foot slide: how far a joint travels over the floor while it stands on
 * it (the "foot contact slide"), for the child and, to compare,
 * for the parent it comes from. Contacts are app/join's rule. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cub/evolve.h"
#include "cub/join.h"

cub_err cub_evolve_slide(const cub_evolve_motion *m, int joint, cub_evolve_slide_report *out)
{
    memset(out, 0, sizeof(*out));
    if (joint < 0 || joint >= m->skel.joint_count || m->frames < 2) return CUB_ERR_ARG;
    cub_dv3 *pos = malloc((size_t)m->frames * sizeof(cub_dv3));
    unsigned char *on = malloc((size_t)m->frames);
    if (!pos || !on) {
        free(pos);
        free(on);
        return CUB_ERR_NOMEM;
    }
    static cub_dv3 world[CUB_EVOLVE_MAX_JOINTS];
    for (int f = 0; f < m->frames; f++) {
        cub_evolve_forward(m, f, world);
        pos[f] = world[joint];
    }
    cub_join_track t = {pos, 1, 1, m->frames, 1.0 / m->fps};
    cub_join_contacts(&t, NULL, cub_join_track_lowest(&t), on);
    double sum = 0;
    for (int f = 1; f < m->frames; f++) {
        if (!on[f] || !on[f - 1]) continue;
        double d = hypot(pos[f].x - pos[f - 1].x, pos[f].z - pos[f - 1].z);
        sum += d;
        out->max_mm = fmax(out->max_mm, d);
        out->contact_frames++;
    }
    out->mean_mm = out->contact_frames ? sum / out->contact_frames : 0;
    free(pos);
    free(on);
    return CUB_OK;
}
