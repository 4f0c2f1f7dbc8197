/* line.h - aliased lines of width 1, decided exactly (lessons/CONVENTIONS.md,
 * "Lines"): GL's diamond-exit rule (GL 4.6 section 14.5.1) with its "in
 * principle, perturb the endpoints by a tiny amount" made concrete.
 *
 * Pixel (px, py) owns the OPEN diamond around its centre c:
 *
 *                 (cx, cy - 1/2)
 *                      /\
 *                     /  \          D = { p : |p.x - cx| + |p.y - cy| < 1/2 }
 *     (cx - 1/2, cy) <  c  > (cx + 1/2, cy)
 *                     \  /          its four corners and edges are not in D
 *                      \/
 *                 (cx, cy + 1/2)
 *
 * The snapped segment A -> B is moved by the infinitesimal delta = (e, e^2),
 * e -> 0+ (a hair right, and a hair of a hair down). The pixel is drawn iff
 * the moved segment meets D and the moved end B is not inside D; A = B draws
 * nothing. Every decision below is the sign of a0 + a1 e + a2 e^2 with
 * integer a's in 1/256 units, read lexicographically: a0's sign, or a1's
 * when a0 = 0, or a2's when both are 0. Exact, 64-bit, no epsilon.
 *
 * Overflow budget: snapped coordinates |x| <= 2^22 (raster.h), so
 * dx = Bx - Ax and dy need 24 bits, and every product below (a 24-bit
 * difference times a 24-bit difference) stays below 2^48.
 */
#ifndef TRISTEP_LINE_H
#define TRISTEP_LINE_H

#include <stdbool.h>
#include <stdint.h>

#include "raster.h"

/* A segment ready to draw. */
struct line_setup {
    struct vertex v[2];         /* A (the start) and B, as the scene gives them */
    int32_t x[2], y[2];         /* snapped, 1/256 pixel */
    int64_t dx, dy;             /* B - A, 1/256 pixel */
    bool x_major;               /* |dx| >= |dy|: one pixel per column in its middle */
    double inv_len2;            /* 1 / |B - A|^2 (0 when A = B) */
    int target_w, target_h;
    /* the pixels whose diamond the moved segment may meet, clamped to the target */
    int minx, miny, maxx, maxy;
    bool empty;                 /* A = B, or no pixel of the target in its box */
};

/* Snap the ends (1/256 pixel, ties to even), and find the box. False when
 * the line draws nothing (empty). */
bool line_setup(struct line_setup *l, const struct vertex v[2], int w, int h);

/* The sign (-1, 0, 1) of a0 + a1 e + a2 e^2 as e -> 0+. */
static inline int perturbed_sign(int64_t a0, int64_t a1, int64_t a2)
{
    int64_t a = a0 != 0 ? a0 : a1 != 0 ? a1 : a2;
    return (a > 0) - (a < 0);
}

/* Is the point (x, y) (1/256 units) moved by delta inside the open diamond
 * of pixel (px, py)? */
bool line_point_in_diamond(int64_t x, int64_t y, int px, int py);
/* Does the moved segment meet the open diamond of pixel (px, py)? The
 * separating-axis test: the two are disjoint iff their projections on one
 * of the diamond's two edge normals, (1, 1) and (1, -1), or on the
 * segment's normal (-dy, dx), do not overlap. */
bool line_meets_diamond(const struct line_setup *l, int px, int py);
/* The rule: meets the diamond, and B (moved) is not in it. */
bool line_draws(const struct line_setup *l, int px, int py);

/* The exact reference: every pixel of the box decided by line_draws, row
 * by row. Calls cover(ctx, x, y) for each pixel drawn. */
void line_reference(const struct line_setup *l, void (*cover)(void *ctx, int x, int y),
                    void *ctx);

/* The same pixels by walking: one per column of an x-major line (one per
 * row of a y-major one) from A's to B's, Bresenham's midpoint step with an
 * exact integer error term in 1/256 units, the first and last decided by
 * line_draws. Calls plot(ctx, x, y) for each, from A towards B. */
void line_walk(const struct line_setup *l, void (*plot)(void *ctx, int x, int y), void *ctx);

/* The position along the segment of pixel (px, py)'s centre c,
 * t = ((c - A).(B - A)) / |B - A|^2 on the snapped ends, clamped to [0, 1];
 * and z and colour there, (1 - t) a_A + t a_B (linear in the screen). */
static inline double line_param(const struct line_setup *l, int px, int py)
{
    /* the dot product exact (below 2^48), one rounding in the product */
    int64_t dot = (pixel_centre(px) - l->x[0]) * l->dx + (pixel_centre(py) - l->y[0]) * l->dy;
    double t = (double)dot * l->inv_len2;
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

static inline void line_shade(const struct line_setup *l, int px, int py, double *z, double rgb[3])
{
    double t = line_param(l, px, py);
    const struct vertex *a = &l->v[0], *b = &l->v[1];
    *z = (1 - t) * a->z + t * b->z;
    rgb[0] = (1 - t) * a->r + t * b->r;
    rgb[1] = (1 - t) * a->g + t * b->g;
    rgb[2] = (1 - t) * a->b + t * b->b;
}


/* Draw the walk's pixels into fb, each with its z and colour by
 * line_shade, through target_write (counted, depth-tested: the nearer
 * wins, an earlier line keeps a tie). */
void line_draw(const struct line_setup *l, struct target *fb);

#endif
