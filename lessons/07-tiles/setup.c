/* Lesson 07, stage 1: set-up, once per triangle (llvmpipe's lp_setup_tri.c).
 *
 * Planes of the perspective-correct attributes (the edge-function notes, formula 23): 1/z,
 * and 255 a / z for a = r, g, b, each linear in screen space:
 *
 *     P(x, y) = (P0 + Py (y - miny)) + Px (x - minx)
 *
 * evaluated in that order, in float, at every pixel by every twin (strips.c). */
#include "tiles.h"

/* The record of a triangle that tri_setup() has snapped and normalised
 * (tristep's shared set-up, so coverage is decided on the same numbers as
 * every other lesson); the texture planes only for a textured scene. */
void tri_record(struct tri *r, const struct tri_setup *t, int checker)
{
    r->textured = checker > 0;
    for (int k = 0; k < 3; k++) {
        r->c[k] = edge_value(t, k, 0, 0) + t->bias[k];
        r->di[k] = (int32_t)t->I[k];
        r->dj[k] = (int32_t)t->J[k];
    }
    r->bias_neg = (uint8_t)((t->bias[0] ? 1 : 0) | (t->bias[1] ? 2 : 0) | (t->bias[2] ? 4 : 0));
    r->minx = (int16_t)t->minx, r->miny = (int16_t)t->miny;
    r->maxx = (int16_t)t->maxx, r->maxy = (int16_t)t->maxy;

    /* lesson 04's planes, in double at (minx, miny) (src/shade/quad.c), kept in float */
    struct planes pl;
    planes_solve(&pl, t, &(struct raster_params){ .checker = checker });
    for (int q = 0; q < QUAD_PLANES; q++)
        r->p0[q] = (float)pl.p0[q], r->px[q] = (float)pl.px[q], r->py[q] = (float)pl.py[q];
    for (int q = 0; r->textured && q < ST_COUNT; q++) {
        float *o = r->st + 3 * q;
        o[0] = (float)pl.p0[PL_S + q], o[1] = (float)pl.px[PL_S + q], o[2] = (float)pl.py[PL_S + q];
    }
}


/* Set-up of one triangle, narrated: its record, or false when it covers
 * nothing (zero area, or no pixel centre of the target in its box). */
bool tri_set_up(struct tri *r, const struct tri_setup *t, int checker, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny, .x1 = t->maxx,
            .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return false;
    tri_record(r, t, checker);
    return true;
}
