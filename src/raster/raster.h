/* raster.h - the exact core every lesson shares: fixed point, triangle setup,
 * the top-left fill rule, the render target and the reference rasterizer.
 *
 * Screen space (lessons/CONVENTIONS.md): pixels, origin top-left, x right, y DOWN.
 * Pixel (px, py) covers [px, px+1) x [py, py+1); its centre decides coverage.
 */
#ifndef TRISTEP_RASTER_H
#define TRISTEP_RASTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Vertex positions are snapped to 1/256 pixel before any coverage decision.
 *
 * Overflow budget: vertices lie in [-16384, 16384) pixels, so a snapped
 * coordinate needs 15 + 8 = 23 bits (|v| < 2^22). An edge coefficient
 * I = Ay - By or J = Bx - Ax needs 24 bits (|I| < 2^23), and an edge value
 * F = I * (Px - Ax) + J * (Py - Ay) is a sum of two products of 24-bit
 * numbers: |F| < 2^47 (the constant form I*Px + J*Py + K stays below 2^47
 * too). That is far beyond 32 bits and comfortably inside 64: every edge
 * value in tristep is an int64_t. With 32-bit arithmetic, |F| <= 8 R^2 for
 * coordinates |v| <= R (in 1/256 units) must stay below 2^31, so R < 2^14:
 * only 64 pixels either side of the origin (lesson 03 tabulates every choice
 * of sub-pixel bits). */
#define SUBPIXEL_BITS 8
#define SUBPIXEL_ONE  (1 << SUBPIXEL_BITS)     /* one pixel in fixed point */
#define SUBPIXEL_HALF (SUBPIXEL_ONE / 2)       /* offset of a pixel centre */
#define COORD_LIMIT   16384                    /* |vertex| < COORD_LIMIT px */
#define TARGET_MAX    16384                    /* largest framebuffer side */

/* One vertex as a scene gives it: position in pixels, positive view-space
 * depth z, colour in [0, 1], texture coordinates (0 when the scene has none). */
struct vertex {
    double x, y, z;
    double r, g, b;
    double s, t;
};

/* Round to the nearest 1/2^bits pixel, ties to even (lrint in the default
 * rounding mode), and express the result in 1/256 pixel units.
 * bits = SUBPIXEL_BITS is the real thing; fewer bits is lesson 03's exhibit. */
int32_t snap_coord(double v, int bits);

/* The three edges, numbered as the edge-function notes number them:
 *   edge 0: AB, F01    edge 1: BC, F02    edge 2: CA, F03
 * and the barycentric weight of a vertex is the edge value OPPOSITE it
 * divided by the doubled area: u (of A) = F02, v (of B) = F03, w (of C) = F01. */
enum { EDGE_AB, EDGE_BC, EDGE_CA };

/* A triangle ready to rasterize. After setup the orientation is normalised
 * so that every edge value is positive inside:
 *
 *     F(P) = I * Px + J * Py + K,   I = Ay - By,  J = Bx - Ax,  K = Ax By - Ay Bx
 *
 * is the perp-dot product AB x AP of the edge-function notes, formula (3), in 1/256 units: a
 * signed number (the notes write it |AB x AP|, but those are not absolute
 * values: its sign says on which side of AB the point P lies). One unit of F
 * is 1/65536 of a square pixel; F01 + F02 + F03 = 2 * area. */
struct tri_setup {
    struct vertex v[3];      /* A, B, C after normalisation (B and C swapped if needed) */
    int32_t x[3], y[3];      /* snapped positions, 1/256 pixel */
    int64_t I[3], J[3], K[3];/* edge coefficients, edge k from v[k] to v[(k+1)%3] */
    int64_t bias[3];         /* fill rule: 0 for a top or left edge, -1 otherwise */
    int64_t area2;           /* F01 + F02 + F03 anywhere = twice the area, > 0 */
    int target_w, target_h;  /* size of the target the box is clamped to */
    int minx, miny, maxx, maxy; /* pixels whose centre may be covered, clamped to the target */
    bool swapped;            /* B and C were exchanged to normalise the orientation */
    bool empty;              /* zero area, or no pixel centre of the target in the box */
};

/* Snap, normalise orientation, compute edges, fill-rule biases and the
 * bounding box clamped to a w x h target. Returns false when the triangle
 * covers nothing (degenerate or off the target); the setup is filled anyway
 * (area2 == 0 for a degenerate triangle) so a viewer can still draw it. */
bool tri_setup(struct tri_setup *t, const struct vertex v[3], int w, int h);
/* The same with vertices snapped to only `bits` fractional bits (0..8). */
bool tri_setup_bits(struct tri_setup *t, const struct vertex v[3], int w, int h, int bits);

/* The top-left rule, read as its definition (y down, interior where F > 0):
 *
 *        top edge: exactly horizontal, triangle below it     A ----> B
 *                  (walking A->B, x increases: J > 0)          \ in /
 *                                                               \  /
 *       left edge: on the triangle's left side, the            C
 *                  interior to its right (+x): walking the
 *                  edge it goes UP the screen (y decreases: I > 0)
 *
 * A pixel centre exactly on an edge (F == 0) is covered only when that edge
 * is a top or a left edge. */
static inline bool is_top_left(int64_t I, int64_t J)
{
    bool left = I > 0;              /* Ay > By: the edge goes up */
    bool top = I == 0 && J > 0;     /* horizontal, walked to the right */
    return left || top;
}

/* Which edges own the centres exactly on them. Every lesson, the
 * explorer and the bench use the top-left rule; the bottom-right rule, a
 * graded exercise's convention (lessons/02-barycentric/exercise-bottom-right.c),
 * is the reference's too, decided as exactly (reference_point_covered_rule
 * and reference_coverage_rule below): a centre exactly on an edge is
 * covered when that edge is a bottom edge (exactly horizontal, the
 * triangle above it) or a right edge (the interior to its left). */
enum fill_convention { FILL_TOP_LEFT, FILL_BOTTOM_RIGHT };

/* Floor and ceiling of a / b for b > 0, also for negative a (C's division
 * truncates toward 0: -3 / 2 is -1, floor_div(-3, 2) is -2). */
static inline int64_t floor_div(int64_t a, int64_t b)
{
    return a / b - (a % b < 0);
}

static inline int64_t ceil_div(int64_t a, int64_t b)
{
    return -floor_div(-a, b);
}

/* Fixed-point coordinate of the centre of pixel column/row p. */
static inline int64_t pixel_centre(int p)
{
    return (int64_t)p * SUBPIXEL_ONE + SUBPIXEL_HALF;
}

/* Edge value of edge k at the centre of pixel (px, py): exact. Costs (for
 * the operation counters, trace/trace.h): I x + J y + K, and the step of one
 * edge value to the next pixel or row, F += 256 I or F += 256 J. */
#define EDGE_VALUE_COST { .mul = 2, .add = 2 }
#define EDGE_STEP_COST { .mul = 0, .add = 1 }
#define EDGE_INCREMENTS_COST { .mul = 2, .add = 0 }    /* 256 I and 256 J, once */

static inline int64_t edge_value(const struct tri_setup *t, int k, int px, int py)
{
    return t->I[k] * pixel_centre(px) + t->J[k] * pixel_centre(py) + t->K[k];
}

/* The fill-rule test on one edge value: inside, or on a top-left edge.
 * Cost: the bias added (a lesson may add it once to K instead). */
#define FILL_RULE_COST { .mul = 0, .add = 1 }

static inline bool edge_inside(const struct tri_setup *t, int k, int64_t f)
{
    return f + t->bias[k] >= 0;
}

/* The edge functions with the fill rule folded in (lessons 05 onwards). The
 * top-left rule covers a point when F_k + bias_k >= 0 for k = 0, 1, 2;
 * adding the bias to the constant once makes every later test, at a pixel,
 * a block's corner or a sample, a plain sign test, and makes them all agree
 * by construction. Stepped from pixel (0, 0): one pixel right adds 256 I_k,
 * one row down 256 J_k, exactly. */
struct biased_edges {
    int64_t f0[3];          /* F_k + bias_k at the centre of pixel (0, 0) */
    int64_t dx[3], dy[3];   /* one pixel right: 256 I_k, one row down: 256 J_k */
    int64_t bias[3];        /* what was folded in, to narrate F_k itself */
};

/* fill_rule false folds in no bias: every edge inclusive (an exhibit's). */
static inline void biased_edges_setup(struct biased_edges *e, const struct tri_setup *t,
                                      bool fill_rule)
{
    for (int k = 0; k < 3; k++) {
        e->bias[k] = fill_rule ? t->bias[k] : 0;
        e->dx[k] = t->I[k] * SUBPIXEL_ONE;
        e->dy[k] = t->J[k] * SUBPIXEL_ONE;
        e->f0[k] = edge_value(t, k, 0, 0) + e->bias[k];
    }
}

/* F_k + bias_k at the centre of pixel (x, y): exact. */
static inline int64_t biased_edge_at(const struct biased_edges *e, int k, int x, int y)
{
    return e->f0[k] + e->dx[k] * x + e->dy[k] * y;
}

/* Barycentric weights (u, v, w) of A, B, C from the three edge values. Cost:
 * three products with 1 / area2, which a lesson computes once per triangle. */
#define BARYCENTRIC_COST { .mul = 3, .add = 0 }

static inline void barycentric(const struct tri_setup *t, const int64_t f[3], double out[3])
{
    double inv = 1.0 / (double)t->area2;
    out[0] = (double)f[EDGE_BC] * inv;  /* u: weight of A */
    out[1] = (double)f[EDGE_CA] * inv;  /* v: weight of B */
    out[2] = (double)f[EDGE_AB] * inv;  /* w: weight of C */
}

/* --- the render target ---------------------------------------------------- */

/* Colour is RGBA with 8 bits per channel, packed in one uint32_t as
 * 0xAARRGGBB (cairo's ARGB32 layout, always opaque). Depth holds view-space z;
 * the nearest surface wins (smaller z), ties keep the earlier triangle, and the
 * buffer starts at +infinity. `count` counts the triangles that covered each
 * pixel, saturating at 255, whatever the depth test said; a target whose
 * count is NULL (the bench's timed runs) does not count. */
struct target {
    int w, h;
    uint32_t *color;
    float *depth;
    uint8_t *count;
    uint32_t background;
    struct target_samples *samples;     /* NULL: one sample per pixel (every lesson but 08) */
};

/* --- samples (lesson 08) --------------------------------------------------- */

/* Sample positions inside pixel (px, py), in 1/256 pixel from its top-left
 * corner: the standard patterns of Direct3D and Vulkan (lessons/CONVENTIONS.md,
 * "Samples"). A sample is decided exactly like a pixel centre: the edge
 * value at (256 px + x, 256 py + y), the top-left rule. */
#define SAMPLES_MAX 8

struct sample_pattern {
    int n;
    uint8_t x[SAMPLES_MAX], y[SAMPLES_MAX];
};

/* The standard pattern of n = 1, 4 or 8 samples (anything else: NULL). */
const struct sample_pattern *sample_pattern(int n);
/* A regular grid of n = 1, 4 or 8 samples, lesson 08's exhibit: the centre,
 * the quarter points (64 or 192, 64 or 192), a 4 x 2 grid. */
const struct sample_pattern *sample_grid(int n);

/* Per-sample storage of a multisample target: n colours and n depths per
 * pixel, sample s of pixel i at index i * n + s. target_write() never looks
 * at it, so the one-sample lessons pay nothing for it; lesson 08 writes the
 * samples and resolves each pixel it touches into color (the mean of its
 * samples), depth (the nearest sample) and count (covered samples). */
struct target_samples {
    int n;
    uint32_t *color;
    float *depth;
};

/* Give fb per-sample storage of n samples (2..SAMPLES_MAX), cleared to the
 * background; n <= 1 drops it. False when memory runs out (fb unchanged).
 * The drivers (render_scene, replay) call it with the run's params.samples;
 * lesson 08 also makes it on a target that has none. */
bool target_multisample(struct target *fb, int n);

bool target_init(struct target *fb, int w, int h, uint32_t background);
void target_clear(struct target *fb);
void target_free(struct target *fb);
bool target_copy(struct target *dst, const struct target *src); /* same size or fresh dst */

/* A colour in [0, 1] as 0xAARRGGBB. Cost: v * 255 + 0.5 per channel. */
#define PACK_RGB_COST { .mul = 3, .add = 3 }

static inline uint32_t pack_rgb(double r, double g, double b)
{
    /* clamp then round to nearest: colours interpolate inside [0, 1] but
     * rounding error may step just outside (and a NaN becomes 0) */
    double c[3] = { r, g, b };
    uint32_t out = 0xff000000u;
    for (int i = 0; i < 3; i++) {
        double v = c[i] > 0 ? (c[i] < 1 ? c[i] : 1) : 0;
        out |= (uint32_t)(v * 255.0 + 0.5) << (16 - 8 * i);
    }
    return out;
}

/* Would a fragment at depth z pass the depth test at (x, y)? */
static inline bool target_depth_pass(const struct target *fb, int x, int y, float z)
{
    return z < fb->depth[(size_t)y * (size_t)fb->w + (size_t)x];
}

/* One covered pixel: count it, then depth test and write. */
static inline void target_write(struct target *fb, int x, int y, float z, uint32_t rgba)
{
    size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
    if (fb->count && fb->count[i] < 255)
        fb->count[i]++;
    if (z < fb->depth[i]) {
        fb->depth[i] = z;
        fb->color[i] = rgba;
    }
}

/* Is a written pixel (colour, depth) close enough to the exact one? What
 * make check and the explorer's diff hold a student's code (or an exhibit)
 * to: colour within PIXEL_COLOUR_LEVELS of 255 per channel (the lessons
 * interpolate in float or double and round to 8 bits: a right formula lands
 * within one level, a wrong one misses by far more), depth within
 * PIXEL_DEPTH_RELATIVE of z (lesson 04's float lanes keep 1/z to about 1e-5
 * over a row; affine z on a receding triangle is off by tens of percent). */
#define PIXEL_COLOUR_LEVELS 2
#define PIXEL_DEPTH_RELATIVE 1e-3

static inline bool pixel_close(uint32_t want_rgba, float want_z, uint32_t got_rgba, float got_z)
{
    for (int shift = 0; shift < 24; shift += 8) {
        int d = (int)((want_rgba >> shift) & 255) - (int)((got_rgba >> shift) & 255);
        if (d > PIXEL_COLOUR_LEVELS || d < -PIXEL_COLOUR_LEVELS)
            return false;
    }
    float dz = got_z - want_z;
    return dz == 0 || (dz <= PIXEL_DEPTH_RELATIVE * want_z && -dz <= PIXEL_DEPTH_RELATIVE * want_z);
}

/* --- the reference ---------------------------------------------------------- */

/* Is the point (sx, sy), in 1/256 pixel units, covered by t? Edge values
 * from the snapped vertices and the top-left rule, as for a pixel centre
 * (lesson 08's samples; the explorer's drawing of them). */
bool reference_point_covered(const struct tri_setup *t, int64_t sx, int64_t sy);
/* The same under either fill rule (reference_point_covered: FILL_TOP_LEFT). */
bool reference_point_covered_rule(const struct tri_setup *t, enum fill_convention rule,
                                  int64_t sx, int64_t sy);

/* Does the edge with coefficients (I, J), of a triangle set up as above,
 * own the centres on it under the rule? */
bool reference_edge_owns(enum fill_convention rule, int64_t I, int64_t J);

/* The exact area of pixel (px, py) that t covers, in square pixels (0..1):
 * the snapped triangle clipped against the pixel's square, in double
 * precision. What a pixel's samples estimate (lesson 08's "area" view). */
double reference_pixel_area(const struct tri_setup *t, int px, int py);

/* The oracle of every test: bounding box, every pixel centre evaluated
 * directly from the snapped vertices with the cross product of the edge-function notes
 * formula (2), nothing incremental, nothing clever. Calls cover(x, y) for
 * each covered pixel. */
void reference_coverage(const struct tri_setup *t,
                        void (*cover)(void *ctx, int x, int y), void *ctx);
/* The same under either fill rule (reference_coverage: FILL_TOP_LEFT). */
void reference_coverage_rule(const struct tri_setup *t, enum fill_convention rule,
                             void (*cover)(void *ctx, int x, int y), void *ctx);

/* Reference colour and z at a pixel centre, in double precision: linear in
 * screen space (lessons 01-03) or perspective-correct (04 onwards). */
void reference_shade(const struct tri_setup *t, int px, int py, bool perspective,
                     double *z, double rgb[3], double st[2]);

#endif
