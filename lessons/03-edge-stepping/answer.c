/* Answer to exercise 03: the skeleton exercise.c with its TODOs written as
 * README.md explains them; `make check LESSON=03
 * FILE=lessons/03-edge-stepping/answer.c` passes every check.
 *
 * The one source of both: `make skeletons` writes exercise.c from this
 * file (the tests hold the committed one to it). Your parts are marked:
 * the lines between `#if SKELETON` and `#else` are the skeleton's, those
 * between `#else` and `#endif` (or under `#if !SKELETON`) the answer's.
 *
 * Exercise 03: write lesson 03's stepping yourself.
 *
 * Lesson 02's loop, with the three edge values obtained by additions: one
 * evaluation at the first pixel centre of the bounding box, then "+ 256 I"
 * to the right and "+ 256 J" down (README section 2, formulas 9 and 10).
 * The set-up, the fill rule folded into K (section 3), the colour and depth
 * stepped beside the edges (section 4) and the pixel test are here; the
 * three places where the edge values are made are yours. As given, the
 * file compiles and runs, every edge value stays 0, and every pixel of the
 * bounding box is drawn: a rectangle where the triangle should be.
 *
 *     make exercise LESSON=03        the explorer on this file
 *     make check LESSON=03           the checks, simplest first; the last
 *                                    one is the lesson's own: no
 *                                    multiplication between two pixels of a
 *                                    row
 *
 * The last check reads the counters: every COUNT your code declares, and
 * every call of raster.h's edge_value() or pixel_centre(), which multiply. Evaluating the edge functions at each pixel gives the right
 * picture, and fails it. */
#include "lesson.h"
#include "shade/shade.h"     /* shade_scaled: the colour of pre-scaled values */

/* Lines of lesson 03's pseudo-code, which the explorer lights (edge_stepping.c). */
enum { L_SETUP, L_BIAS, L_FIRST, L_CY, L_LOOP_Y, L_ROW, L_LOOP_X, L_TEST, L_RENDER,
       L_STEP_Y };

/* The edges as the loop uses them: k = 0, 1, 2 are the notes' F01 (AB),
 * F02 (BC), F03 (CA). */
struct edges {
    int64_t I[3], J[3];     /* formulas (6) to (8), 1/256 px */
    int64_t K[3];           /* with the fill rule's bias folded in (section 3) */
    int64_t bias[3];
};

/* TODO 1, README section 2 ("Stepping") and formula (6): the edge values
 * F0k = I0k * X + J0k * Y + K0k at the centre of the first pixel of the box,
 * (t->minx, t->miny). X and Y are that centre in 1/256 pixel:
 * minx * SUBPIXEL_ONE + SUBPIXEL_HALF. The only multiplications of the
 * triangle's edge values are here. */
static void first_centre(const struct tri_setup *t, const struct edges *e, int64_t F[3])
{
#if SKELETON
    (void)t, (void)e;
    F[0] = F[1] = F[2] = 0;
#else
    int64_t X = (int64_t)t->minx * SUBPIXEL_ONE + SUBPIXEL_HALF;
    int64_t Y = (int64_t)t->miny * SUBPIXEL_ONE + SUBPIXEL_HALF;
    for (int k = 0; k < 3; k++)
        F[k] = e->I[k] * X + e->J[k] * Y + e->K[k];
#endif
}

/* TODO 2, formula (9): one pixel to the right. The next centre is 256
 * units further on, so F0k grows by 256 * I0k, not by I0k. Declare what you
 * do: COUNT(tr, 3, EDGE_STEP_COST) for three steps of one addition. */
static void step_right(const struct edges *e, int64_t F[3], struct trace *tr)
{
#if SKELETON
    (void)e, (void)F, (void)tr;
#else
    for (int k = 0; k < 3; k++)
        F[k] += e->I[k] * SUBPIXEL_ONE;     /* a shift: the compiler adds I << 8 */
    COUNT(tr, 3, EDGE_STEP_COST);
#endif
}

/* TODO 3, formula (10): one row down, from the first pixel of this row to
 * the first pixel of the next: F0k grows by 256 * J0k. */
static void step_down(const struct edges *e, int64_t F[3], struct trace *tr)
{
#if SKELETON
    (void)e, (void)F, (void)tr;
#else
    for (int k = 0; k < 3; k++)
        F[k] += e->J[k] * SUBPIXEL_ONE;
    COUNT(tr, 3, EDGE_STEP_COST);
#endif
}

/* --- colour and depth, stepped beside the edges (README section 4) -------------- */

struct attrs {
    double z, r, g, b, s, t;
};

static struct attrs mix(double u, struct attrs A, double v, struct attrs B, double w, struct attrs C)
{
    return (struct attrs){ u * A.z + v * B.z + w * C.z, u * A.r + v * B.r + w * C.r,
                           u * A.g + v * B.g + w * C.g, u * A.b + v * B.b + w * C.b,
                           u * A.s + v * B.s + w * C.s, u * A.t + v * B.t + w * C.t };
}

static struct attrs step(struct attrs P, struct attrs d)
{
    return (struct attrs){ P.z + d.z, P.r + d.r, P.g + d.g, P.b + d.b, P.s + d.s, P.t + d.t };
}

/* A vertex's attributes pre-scaled for shade_scaled(): colour times 255,
 * texture coordinates times the checker's N, so no pixel multiplies. */
static struct attrs attrs_of(const struct vertex *v, const struct raster_params *p)
{
    double n = shade_scale_st(p);
    return (struct attrs){ v->z, v->r * SHADE_SCALE_RGB, v->g * SHADE_SCALE_RGB, v->b * SHADE_SCALE_RGB,
                           v->s * n, v->t * n };
}

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    struct edges e;
    for (int k = 0; k < 3; k++) {
        e.I[k] = t->I[k];
        e.J[k] = t->J[k];
        e.bias[k] = t->bias[k];
        e.K[k] = t->K[k] + t->bias[k];      /* F + bias >= 0 is the whole test */
    }
    /* colour and depth: exact at the start of each row, + dPdx per pixel */
    struct attrs A = attrs_of(&t->v[0], p), B = attrs_of(&t->v[1], p), C = attrs_of(&t->v[2], p);
    double inv_area2 = 1.0 / (double)t->area2;
    struct attrs dPdx = mix((double)(t->I[1] * SUBPIXEL_ONE) * inv_area2, A,
                            (double)(t->I[2] * SUBPIXEL_ONE) * inv_area2, B,
                            (double)(t->I[0] * SUBPIXEL_ONE) * inv_area2, C);
    COUNT(tr, 1, RECIPROCAL_COST);
    COUNT(tr, 3, EDGE_INCREMENTS_COST);
    COUNT(tr, 6, INTERPOLATE_COST);

    int64_t Cy[3];
    first_centre(t, &e, Cy);
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_FIRST, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { Cy[0] - e.bias[0], Cy[1] - e.bias[1], Cy[2] - e.bias[2] });
    for (int y = t->miny; y <= t->maxy; y++) {
        int64_t Cx[3] = { Cy[0], Cy[1], Cy[2] };
        /* the weights u, v, w of A, B, C are F02, F03, F01 over the area */
        struct attrs P = mix((double)(Cx[1] - e.bias[1]) * inv_area2, A,
                             (double)(Cx[2] - e.bias[2]) * inv_area2, B,
                             (double)(Cx[0] - e.bias[0]) * inv_area2, C);
        COUNT(tr, 1, BARYCENTRIC_COST);
        COUNT(tr, 6, INTERPOLATE_COST);
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y,
                .e = { Cx[0] - e.bias[0], Cx[1] - e.bias[1], Cx[2] - e.bias[2] });
        for (int x = t->minx; x <= t->maxx; x++) {
            bool inside = Cx[0] >= 0 && Cx[1] >= 0 && Cx[2] >= 0;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .x = x, .y = y,
                    .e = { Cx[0] - e.bias[0], Cx[1] - e.bias[1], Cx[2] - e.bias[2] },
                    .aux = { (float)P.z, (float)P.r, (float)P.g, (float)P.b, (float)P.s, (float)P.t },
                    .flags = inside ? TRACE_INSIDE : 0);
            if (inside)
                target_write(fb, x, y, (float)P.z, shade_scaled(p, tr, P.r, P.g, P.b, P.s, P.t));
            step_right(&e, Cx, tr);
            P = step(P, dPdx);
            COUNT(tr, 6, PLANE_STEP_COST);
        }
        step_down(&e, Cy, tr);
    }
}
