/* Exercise 05: write lesson 05's corner masks and block classification.
 *
 * The block loop of README "The three cases" is here: the q x q grid
 * aligned on the screen and clipped to the bounding box, the edge values
 * with the fill rule folded in, RenderBlock for a full block and the pixel
 * test for a partial one, and perspective-correct shading as lesson 04 does
 * it. Yours: the four-bit corner mask of each edge, and the class the
 * three masks give the block. As given, the file compiles and runs, every
 * mask is 0, every block is called empty, and nothing is drawn.
 *
 *     make exercise LESSON=05        the explorer on this file: the blocks
 *                                    view shows your classes
 *     make check LESSON=05           the checks; the last one is the
 *                                    lesson's own, "corner classes": every
 *                                    block gets exactly the class its four
 *                                    corners give it, EMPTY, FULL, PARTIAL
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 05's pseudo-code, which the explorer lights. */
enum { L_SETUP, L_BOX, L_LOOP, L_MASKS, L_EMPTY, L_FULL, L_PARTIAL, L_STEP, L_PIXEL };

#define Q_DEFAULT 8
enum { P_BLOCK };   /* p->knob[P_BLOCK]: --block-size (the lesson's parameter row 0) */

/* The edges with the fill rule folded in: F0k + bias_k at the centre of
 * pixel (x, y) is f0[k] + dx[k] * x + dy[k] * y, exactly; the pixel is
 * covered when that is >= 0 for k = 0, 1, 2 (F01, F02, F03). */
struct edges {
    int64_t f0[3], dx[3], dy[3];
};

static int64_t edge_at(const struct edges *e, int k, int x, int y)
{
    return e->f0[k] + e->dx[k] * x + e->dy[k] * y;
}

/* TODO 1, README "The three cases" and "The corners are pixel centres":
 * the corner mask of each edge k for the block of pixels x0..x1, y0..y1.
 * Four bits, one per corner, set when edge_at() of that corner is >= 0:
 *
 *     (x0, y0) bit 3  o---------o  bit 2 (x1, y0)
 *                     |  block  |
 *     (x0, y1) bit 1  o---------o  bit 0 (x1, y1)
 *
 * The corners are the centres of the corner PIXELS, x1 and y1 included:
 * (x0 + q, y0) is the next block's first pixel, not this block's corner. */
static void corner_masks(const struct edges *e, int x0, int y0, int x1, int y1, unsigned mask[3])
{
    (void)e, (void)x0, (void)y0, (void)x1, (void)y1;
    mask[0] = mask[1] = mask[2] = 0;
}

/* TODO 2, README "The three cases" and "Why the test must be per edge":
 * the block's class from the three masks, BLOCK_EMPTY, BLOCK_FULL or
 * BLOCK_PARTIAL. Empty when all four corners are outside ONE edge (that
 * edge's mask is 0); full when every corner is inside EVERY edge (all three
 * masks 0xF: the block notes' `||` there is a slip); partial otherwise. */
static enum block_class classify(const unsigned mask[3])
{
    (void)mask;
    return BLOCK_EMPTY;
}

/* --- shading and the block loop, as the lesson has them ------------------------- */

/* Perspective-correct colour and depth at pixel (x, y) from its exact edge
 * values (lesson 04, formula 23), and the write. */
static void shade(const struct tri_setup *t, const struct raster_params *p, const struct edges *e,
                  struct target *fb, struct trace *tr, int x, int y)
{
    double inv = 1.0 / (double)t->area2, w[3];
    for (int k = 0; k < 3; k++)     /* weights of A, B, C: F02, F03, F01 over Area2 */
        w[k] = (double)(edge_at(e, (k + 1) % 3, x, y) - t->bias[(k + 1) % 3]) * inv;
    double q[3], sum = 0;
    for (int i = 0; i < 3; i++)
        sum += q[i] = w[i] / t->v[i].z;
    double z = 1.0 / sum, P[5] = { 0 };
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double a[5] = { v->r, v->g, v->b, v->s, v->t };
        for (int k = 0; k < 5; k++)
            P[k] += q[i] * a[k] * z;
    }
    target_write(fb, x, y, (float)z, shade_pixel(p, tr, P[0], P[1], P[2], P[3], P[4]));
}

static void block(const struct tri_setup *t, const struct raster_params *p, const struct edges *e,
                  struct target *fb, struct trace *tr, int x0, int y0, int x1, int y1, int q)
{
    unsigned m[3];
    corner_masks(e, x0, y0, x1, y1, m);
    enum block_class klass = classify(m);
    NARRATE(tr, .kind = TRACE_BLOCK, .line = klass == BLOCK_EMPTY ? L_EMPTY : klass == BLOCK_FULL ? L_FULL : L_PARTIAL,
            .x = x0, .y = y0, .x1 = x1, .y1 = y1, .klass = (uint8_t)klass,
            .mask = { (uint16_t)m[0], (uint16_t)m[1], (uint16_t)m[2] }, .aux = { (float)q, 0 });
    if (klass == BLOCK_EMPTY)
        return;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            if (klass == BLOCK_PARTIAL) {
                int64_t F[3] = { edge_at(e, 0, x, y), edge_at(e, 1, x, y), edge_at(e, 2, x, y) };
                bool in = F[0] >= 0 && F[1] >= 0 && F[2] >= 0;
                NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_PIXEL, .x = x, .y = y,
                        .e = { F[0] - t->bias[0], F[1] - t->bias[1], F[2] - t->bias[2] },
                        .flags = in ? TRACE_INSIDE : 0);
                if (!in)
                    continue;
            }
            shade(t, p, e, fb, tr, x, y);
        }
}

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_BOX, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    int q = p->knob[P_BLOCK] > 0 ? p->knob[P_BLOCK] : Q_DEFAULT;
    struct edges e;
    for (int k = 0; k < 3; k++) {
        e.dx[k] = t->I[k] * SUBPIXEL_ONE;
        e.dy[k] = t->J[k] * SUBPIXEL_ONE;
        e.f0[k] = t->I[k] * SUBPIXEL_HALF + t->J[k] * SUBPIXEL_HALF + t->K[k] + t->bias[k];
    }
    /* the grid of q x q blocks, aligned on the screen, clipped to the box */
    for (int by = t->miny - t->miny % q; by <= t->maxy; by += q) {
        int y0 = by < t->miny ? t->miny : by, y1 = by + q - 1 > t->maxy ? t->maxy : by + q - 1;
        for (int bx = t->minx - t->minx % q; bx <= t->maxx; bx += q) {
            int x0 = bx < t->minx ? t->minx : bx, x1 = bx + q - 1 > t->maxx ? t->maxx : bx + q - 1;
            block(t, p, &e, fb, tr, x0, y0, x1, y1, q);
        }
    }
}
