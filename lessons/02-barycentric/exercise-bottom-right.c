/* Exercise 02, variant bottom-right: lesson 02's rasterizer under the
 * other fill rule.
 *
 * The lesson, and every program of the course, gives a pixel centre that
 * lies exactly on an edge to the triangle whose edge is a top or a left
 * edge. Here the convention is its mirror image, the bottom-right rule: a
 * centre exactly on an edge is covered when that edge is a BOTTOM edge
 * (exactly horizontal, the triangle above it) or a RIGHT edge (on the
 * triangle's right side, the interior to its left). A centre strictly
 * inside is covered as before, and meshes stay watertight: a shared edge is
 * a right edge of one triangle exactly when it is a left edge of the other.
 * README.md section 4 derives the top-left rule; derive this one the same
 * way, from the signs of I and J.
 *
 * Everything around the heart of the lesson is here: the loop over the
 * bounding box, the narration, the interpolation and the write. Three small
 * functions are left for you, each marked TODO. As given, the file
 * compiles and runs and draws nothing.
 *
 *     make exercise LESSON=02 VARIANT=bottom-right
 *                                    the explorer on this file, against the
 *                                    exact rule under the bottom-right rule
 *     make check LESSON=02 VARIANT=bottom-right
 *                                    the lesson's checks, every pixel held to
 *                                    the bottom-right rule
 *
 * What you get (src/raster/raster.h; names as in barycentric.c):
 *   t->x[i], t->y[i]   the vertices A, B, C (i = 0, 1, 2), snapped to 1/256
 *                      pixel: x = 3.5 px is 896. Setup has already ordered
 *                      them so that every edge value is positive inside.
 *   t->I[k], t->J[k], t->K[k]
 *                      the coefficients of edge k (0: AB, 1: BC, 2: CA) in
 *                      F(x, y) = I x + J y + K, x and y in 1/256 pixel:
 *                      I = y_a - y_b, J = x_b - x_a, K = x_a y_b - x_b y_a
 *                      (README formula 1).
 *   t->area2           F_ab + F_bc + F_ca: twice the triangle's area, > 0.
 *   t->minx .. t->maxx, t->miny .. t->maxy
 *                      the pixels whose centres may be inside, clamped to
 *                      the target.
 *   SUBPIXEL_ONE       256: one pixel in those units; SUBPIXEL_HALF is 128.
 *
 * t->bias is the top-left rule's, not this one's: a test built on it
 * fails the check. Write the three functions with the fields above and
 * plain arithmetic. */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 02's pseudo-code, which the explorer lights (barycentric.c). */
enum { L_SETUP, L_BOX, L_LOOP, L_EDGES, L_TEST, L_BARY, L_COLOR, L_DRAW };

/* TODO 1, README section 1 (formulas 1 to 3) and section 3: the three edge
 * values at the centre of pixel (x, y), exactly, in 64-bit integers.
 *   - The centre of pixel x is x + 0.5 pixel: in 1/256 units
 *     x * SUBPIXEL_ONE + SUBPIXEL_HALF. Using x itself (the pixel's corner)
 *     shifts the whole triangle by half a pixel.
 *   - F[0] = F_ab, F[1] = F_bc, F[2] = F_ca: edge k's I, J, K.
 *   - Multiply in int64_t: the products need up to 47 bits. */
static void edge_values(const struct tri_setup *t, int x, int y, int64_t F[3])
{
    (void)t, (void)x, (void)y;
    F[0] = F[1] = F[2] = 0;
}

/* TODO 2: is the centre covered, under the bottom-right rule? Every F > 0
 * is inside; F == 0 (the centre exactly on edge k) counts only when edge k
 * is a bottom edge or a right edge. Read both from the signs of t->I[k] and
 * t->J[k], as README section 4 reads top and left edges: which sign of J
 * has the triangle above a horizontal edge, which sign of I has the
 * interior to the edge's left? F >= 0 on every edge draws shared edges
 * twice, F > 0 leaves cracks, and the lesson's top-left test gives every
 * tie to the other triangle: the check shows each. */
static bool inside(const struct tri_setup *t, const int64_t F[3])
{
    (void)t, (void)F;
    return false;
}

/* TODO 3, README section 2 (formula 5): the barycentric weights of A, B and
 * C at the centre, from its edge values. alpha belongs to A, so it is the
 * edge OPPOSITE A, F_bc, over twice the area; beta = F_ca / area2 and
 * gamma = F_ab / area2. Divide in double: in integers every weight is 0. */
static void weights(const struct tri_setup *t, const int64_t F[3], double *alpha, double *beta,
                    double *gamma)
{
    (void)t, (void)F;
    *alpha = *beta = *gamma = 0;
}

/* The loop of README section 3, ready: it calls your three functions. */
void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    const struct vertex *a = &t->v[0], *b = &t->v[1], *c = &t->v[2];
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    for (int y = t->miny; y <= t->maxy; y++) {
        NARRATE(tr, .kind = TRACE_ROW, .line = L_LOOP, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y);
        for (int x = t->minx; x <= t->maxx; x++) {
            int64_t F[3];
            edge_values(t, x, y, F);
            bool in = inside(t, F);
            double alpha, beta, gamma;
            weights(t, F, &alpha, &beta, &gamma);
            /* the watch panel shows your edge values, and the weights they give */
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .x = x, .y = y,
                    .e = { F[0], F[1], F[2] },
                    .flags = in ? TRACE_INSIDE : 0);
            if (!in)
                continue;
            /* README formula 6 */
            double z = alpha * a->z + beta * b->z + gamma * c->z;
            uint32_t colour = shade_pixel(p, tr, alpha * a->r + beta * b->r + gamma * c->r,
                                          alpha * a->g + beta * b->g + gamma * c->g,
                                          alpha * a->b + beta * b->b + gamma * c->b,
                                          alpha * a->s + beta * b->s + gamma * c->s,
                                          alpha * a->t + beta * b->t + gamma * c->t);
            PLOT(fb, tr, L_DRAW, x, y, (float)z, colour);
        }
    }
}
