/* Exercise 04: write lesson 04's vector step and perspective divide.
 *
 * The register (1/z, w, u, v) of README "The register, lane by lane": its
 * value at the first pixel centre F and its steps I (one pixel right) and
 * J (one row down) are set up here from formulas (19) to (22), as
 * simd_perspective.c's persp_setup() does; the coverage is decided by
 * lesson 03's exact integer edge values, stepped beside the lanes
 * ("Coverage stays exact"). Yours: the two vector steps and, at each
 * covered pixel, the perspective divide of formula (23). As given, the file
 * compiles and runs, the register never moves and every pixel gets the
 * first pixel's depth and a black colour.
 *
 *     make exercise LESSON=04        the explorer on this file (the watch
 *                                    panel shows your four lanes)
 *     make check LESSON=04           the checks; colour and depth are held
 *                                    against the perspective-correct
 *                                    reference
 *
 * Four floats here; with SSE, float[4] becomes one __m128 and each TODO one
 * or two intrinsics (_mm_add_ps, _mm_div_ss): that is the lesson's point,
 * four lanes moved by one instruction. make check reads the lanes' values
 * (the watch panel's too), which are the same either way: it cannot tell
 * the scalar version from the SSE one. Write the scalar version first,
 * check it, then the SSE one (#include <xmmintrin.h>) and check it again.
 * The depth is 1 / lane 0 to float precision: _mm_rcp_ss's estimate alone
 * is up to 4e-4 off, and where two surfaces cross at a shallow angle the
 * check finds the band of pixels it gives to the farther one. */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 04's pseudo-code, which the explorer lights. */
enum { L_BOX, L_DEPTH_EDGE, L_F, L_DIVIDE, L_ROW, L_PIXEL, L_TEST, L_DEPTH, L_ZTEST, L_ATTR,
       L_WRITE, L_STEP_Y };

enum { LANE_INV_Z, LANE_W, LANE_U, LANE_V };

/* TODO 1, "The register, lane by lane": Cx += I, lane by lane. The same
 * function does Cy += J at the end of a row. */
static void vector_step(float C[4], const float D[4])
{
    (void)C, (void)D;
}

/* TODO 2, formula (23) and "Why screen-space weights are not enough": the
 * depth of the pixel is 1 over lane 0, and an attribute P is
 *
 *     P = (u * PA/ZA + v * PB/ZB + w * PC/ZC) * Depth
 *
 * with u, v, w the lanes LANE_U, LANE_V, LANE_W (the weights of A, B and C)
 * and PA/ZA, PB/ZB, PC/ZC given as QA, QB, QC (each vertex's attribute
 * already divided by its z). Leave out "* Depth" and you have the affine
 * exhibit: the check's colour test finds it on the first receding
 * triangle. */
static float depth_of(const float C[4])
{
    (void)C;
    return 1.0f;
}

static float attribute(const float C[4], float depth, float QA, float QB, float QC)
{
    (void)C, (void)depth, (void)QA, (void)QB, (void)QC;
    return 0.0f;
}

/* --- the set-up and the loop, as the lesson has them ----------------------------- */

enum { ATTR_R, ATTR_G, ATTR_B, ATTR_S, ATTR_T, ATTR_COUNT };

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_BOX, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    const struct vertex *a = &t->v[0], *b = &t->v[1], *c = &t->v[2];
    /* (19) to (22): lane 0 is D = F02/ZA + F03/ZB + F01/ZC, lanes 1 to 3 the
     * edge functions F01, F02, F03; all divided by Area2, steps times 256 */
    double X = (double)t->minx * SUBPIXEL_ONE + SUBPIXEL_HALF;
    double Y = (double)t->miny * SUBPIXEL_ONE + SUBPIXEL_HALF;
    double I00 = t->I[EDGE_BC] / a->z + t->I[EDGE_CA] / b->z + t->I[EDGE_AB] / c->z;
    double J00 = t->J[EDGE_BC] / a->z + t->J[EDGE_CA] / b->z + t->J[EDGE_AB] / c->z;
    double K00 = t->K[EDGE_BC] / a->z + t->K[EDGE_CA] / b->z + t->K[EDGE_AB] / c->z;
    double Ik[4] = { I00, (double)t->I[0], (double)t->I[1], (double)t->I[2] };
    double Jk[4] = { J00, (double)t->J[0], (double)t->J[1], (double)t->J[2] };
    double Kk[4] = { K00, (double)t->K[0], (double)t->K[1], (double)t->K[2] };
    float F[4], I[4], J[4];
    for (int lane = 0; lane < 4; lane++) {
        F[lane] = (float)((Ik[lane] * X + Jk[lane] * Y + Kk[lane]) / (double)t->area2);
        I[lane] = (float)(Ik[lane] * SUBPIXEL_ONE / (double)t->area2);
        J[lane] = (float)(Jk[lane] * SUBPIXEL_ONE / (double)t->area2);
    }
    /* each vertex's attributes over its z, for (23) */
    float Q[3][ATTR_COUNT];
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double q = 1.0 / v->z;
        float row[ATTR_COUNT] = { (float)(v->r * q), (float)(v->g * q), (float)(v->b * q),
                                  (float)(v->s * q), (float)(v->t * q) };
        for (int k = 0; k < ATTR_COUNT; k++)
            Q[i][k] = row[k];
    }
    /* coverage: lesson 03's exact integer edge values, with the fill rule */
    int64_t ey[3], ex[3], dy[3];
    for (int k = 0; k < 3; k++) {
        ey[k] = t->I[k] * ((int64_t)t->minx * SUBPIXEL_ONE + SUBPIXEL_HALF)
              + t->J[k] * ((int64_t)t->miny * SUBPIXEL_ONE + SUBPIXEL_HALF) + t->K[k] + t->bias[k];
        ex[k] = t->I[k] * SUBPIXEL_ONE;
        dy[k] = t->J[k] * SUBPIXEL_ONE;
    }
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_F, .x = t->minx, .y = t->miny, .x1 = t->maxx,
            .y1 = t->maxy, .aux = { F[0], F[1], F[2], F[3] });

    float Cy[4] = { F[0], F[1], F[2], F[3] };
    for (int y = t->miny; y <= t->maxy; y++) {
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y);
        float Cx[4] = { Cy[0], Cy[1], Cy[2], Cy[3] };
        int64_t e[3] = { ey[0], ey[1], ey[2] };
        for (int x = t->minx; x <= t->maxx; x++) {
            bool in = e[0] >= 0 && e[1] >= 0 && e[2] >= 0;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .x = x, .y = y,
                    .e = { e[0] - t->bias[0], e[1] - t->bias[1], e[2] - t->bias[2] },
                    .aux = { Cx[0], Cx[1], Cx[2], Cx[3] }, .flags = in ? TRACE_INSIDE : 0);
            if (in) {
                float depth = depth_of(Cx);
                float P[ATTR_COUNT];
                for (int k = 0; k < ATTR_COUNT; k++)
                    P[k] = attribute(Cx, depth, Q[0][k], Q[1][k], Q[2][k]);
                target_write(fb, x, y, depth,
                             shade_pixel(p, tr, P[ATTR_R], P[ATTR_G], P[ATTR_B], P[ATTR_S], P[ATTR_T]));
            }
            vector_step(Cx, I);
            for (int k = 0; k < 3; k++)
                e[k] += ex[k];
        }
        vector_step(Cy, J);
        for (int k = 0; k < 3; k++)
            ey[k] += dy[k];
    }
}
