/* quad.c - the parts of quad.h that run once per triangle or per stray quad. */
#include "shade/quad.h"

void planes_solve(struct planes *pl, const struct tri_setup *t, const struct raster_params *p)
{
    int N = p->checker > 0 ? p->checker : 1;
    pl->x0 = t->minx;
    pl->y0 = t->miny;
    pl->checker = p->checker > 0;
    int used = pl->checker ? PL_COUNT : PL_S;   /* s and t only for the checker */
    /* vertex values a / Z of each plane, for A, B, C */
    double val[PL_COUNT][3];
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double inv_z = 1.0 / v->z;
        val[PL_INV_Z][i] = inv_z;
        val[PL_R][i] = 255.0 * v->r * inv_z;
        val[PL_G][i] = 255.0 * v->g * inv_z;
        val[PL_B][i] = 255.0 * v->b * inv_z;
        if (pl->checker) {
            val[PL_S][i] = N * v->s * inv_z;
            val[PL_T][i] = N * v->t * inv_z;
        }
    }
    /* u (of A) = F02 / Area2, v (of B) = F03 / Area2, w (of C) = F01 / Area2 */
    double inv_area2 = 1.0 / (double)t->area2;
    double f[3];
    for (int k = 0; k < 3; k++)
        f[k] = (double)edge_value(t, k, pl->x0, pl->y0);
    for (int q = 0; q < used; q++) {
        const double *a = val[q];   /* A, B, C */
        pl->p0[q] = (f[EDGE_BC] * a[0] + f[EDGE_CA] * a[1] + f[EDGE_AB] * a[2]) * inv_area2;
        pl->px[q] = ((double)t->I[EDGE_BC] * a[0] + (double)t->I[EDGE_CA] * a[1]
                     + (double)t->I[EDGE_AB] * a[2]) * SUBPIXEL_ONE * inv_area2;
        pl->py[q] = ((double)t->J[EDGE_BC] * a[0] + (double)t->J[EDGE_CA] * a[1]
                     + (double)t->J[EDGE_AB] * a[2]) * SUBPIXEL_ONE * inv_area2;
    }
    for (int q = used; q < PL_COUNT; q++)
        pl->p0[q] = pl->px[q] = pl->py[q] = 0;
}

void planes_setup(struct planes *pl, const struct tri_setup *t, const struct raster_params *p)
{
    planes_solve(pl, t, p);
    for (int q = 0; q < PL_COUNT; q++) {
        float s = (float)pl->px[q];
        pl->lanes[q] = _mm_setr_ps(0.0f, s, 2.0f * s, 3.0f * s);
        pl->step[q] = _mm_set1_ps(4.0f * s);
    }
    for (int q = 0; q < PL_COUNT; q += 2) {
        pl->pair0[q / 2] = _mm_setr_pd(pl->p0[q], pl->p0[q + 1]);
        pl->pair_x[q / 2] = _mm_setr_pd(pl->px[q], pl->px[q + 1]);
        pl->pair_y[q / 2] = _mm_setr_pd(pl->py[q], pl->py[q + 1]);
    }
}

/* target_write() for the lanes of a quad that `mask` keeps (all ones = keep),
 * one pixel at a time: count, depth test (nearer wins), write. */
void write_quad_pixels(struct target *fb, int xq, int y, __m128i mask, const struct quad *qd,
                       bool checker)
{
    __m128 z4 = quad_depth(qd);
    __m128i c4 = quad_colour(qd, z4, checker);
    int keep = _mm_movemask_ps(_mm_castsi128_ps(mask));
    float zs[4];
    uint32_t cs[4];
    _mm_storeu_ps(zs, z4);
    _mm_storeu_si128((__m128i *)cs, c4);
    for (int i = 0; i < 4; i++)
        if (keep & (1 << i))
            target_write(fb, xq + i, y, zs[i], cs[i]);
}
