/* Lesson 05: q x q block classification.
 *
 * What it shows: seed 000, "block-based" half-space rasterization (after
 * Mileff, Nehez and Dudra, "Accelerated Half-Space Triangle Rasterization",
 * 2015). Instead of testing every pixel of the bounding box, cut the box into
 * blocks of q x q pixels and test only the four corners of each block against
 * each edge. An edge function is linear, so over a rectangle it takes its
 * smallest and largest values at the corners: the corners decide the whole
 * block.
 *
 *     every corner outside one edge   -> the block is EMPTY:   skip it
 *     every corner inside every edge  -> the block is FULL:    RenderBlock,
 *                                        no per-pixel test at all
 *     otherwise                       -> the block is PARTIAL: test its
 *                                        pixels, stepping F from the corner
 *
 * New since lesson 04: the block loop and its three cases; a RenderBlock that
 * fills four pixels per SSE register; partial blocks tested four pixels at a
 * time with integer SSE compares. What stays: lesson 03's exact integer edge
 * values decide coverage (the corners use the very same values and the same
 * top-left bias as the pixel test, so "full" is really full), and lesson 04's
 * planes 1/z and a/z give perspective-correct depth and colour (formula 23).
 *
 * The four-pixel writes test depth before they shade: a quad hidden behind
 * what the target already holds costs its depth and one compare, no colour.
 *
 * Two twins of the partial-block loop sit side by side: one pixel at a time
 * with exact 64-bit edge values, narrating every pixel (what the explorer
 * steps through), and four pixels per register (what the benchmark times).
 * Both shade a pixel with the same function, so they write the same bytes.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"
#include "simd.h"      /* SSE2: four floats or four int32 per register */

static const char *const pseudocode[] = {
    "setup: F0k = I0k x + J0k y + K0k + bias_k, k = 1, 2, 3",         /* 0 */
    "box = [minX, maxX] x [minY, maxY], clipped to the screen",         /* 1 */
    "loop y, x over the q x q blocks of the box:",                      /* 2 */
    "  checkw, checku, checkv = corner signs of F01, F02, F03",         /* 3 */
    "  if checkw == 0 || checku == 0 || checkv == 0: skip   (empty)",   /* 4 */
    "  if checkw == checku == checkv == 0xF: RenderBlock    (full)",    /* 5 */
    "  else loop by, bx over the block's pixels:            (partial)", /* 6 */
    "    F0k stepped from the corner: += I0k, += J0k",                  /* 7 */
    "    if F01 >= 0 && F02 >= 0 && F03 >= 0: RenderPixel(x, y)",       /* 8 */
    NULL,
};

enum { L_SETUP, L_BOX, L_LOOP, L_MASKS, L_EMPTY, L_FULL, L_PARTIAL, L_STEP, L_PIXEL };

/* trace_event.aux[] of this lesson: the block size of a block event, and its
 * level (0: a block of the grid or a coarse block, 1: a sub-block of a coarse
 * block in the hierarchical variant). */
static const char *const aux_names[] = { "q", "level", NULL };

#define Q_DEFAULT 8         /* the paper's best block size */
#define Q_COARSE 64         /* the hierarchical variant's coarse level */

/* --- the edges, as the block loop uses them ------------------------------- */

/* Seed 001's edge functions with the fill rule folded in. The top-left rule
 * says a pixel is covered when F0k + bias_k >= 0 for k = 1, 2, 3 (bias 0 on a
 * top or left edge, -1 otherwise: src/raster/raster.h). Adding the bias to
 * the constant once makes every test below, corner or pixel, a plain sign
 * test, and makes the corners and the pixels agree by construction.
 *
 * Index k = 0, 1, 2 is the source's F01 (edge AB, checkw), F02 (edge BC,
 * checku) and F03 (edge CA, checkv). */
struct edges {
    int64_t f0[3];          /* F0k + bias_k at the centre of pixel (0, 0) */
    int64_t dx[3], dy[3];   /* one pixel right: I0k * 256, one row down: J0k * 256 */
    int64_t bias[3];        /* kept to narrate F0k itself, without the bias */
};

static void edges_setup(struct edges *e, const struct tri_setup *t)
{
    for (int k = 0; k < 3; k++) {
        e->dx[k] = t->I[k] * SUBPIXEL_ONE;
        e->dy[k] = t->J[k] * SUBPIXEL_ONE;
        e->f0[k] = edge_value(t, k, 0, 0) + t->bias[k];
        e->bias[k] = t->bias[k];
    }
}

/* F0k + bias_k at the centre of pixel (x, y): exact. */
static int64_t edge_at(const struct edges *e, int k, int x, int y)
{
    return e->f0[k] + e->dx[k] * x + e->dy[k] * y;
}

/* --- shading: lesson 04's planes, four pixels per register -------------- */

/* Formula (23) needs, at every pixel, 1/z and a/z for each attribute a; all of
 * them are linear in screen space, so each is a plane
 *
 *     P(x, y) = P0 + Px (x - x0) + Py (y - y0)       (x0, y0) = the box's corner
 *
 * built as lesson 04 builds D (formulas 18 to 22): the plane of a weight u, v
 * or w is F02, F03 or F01 over Area2. Colours are scaled by 255 and texture
 * coordinates by the checker's N in advance, so the pixel loop only
 * multiplies by z = 1 / (1/z). */
enum { PL_INV_Z, PL_R, PL_G, PL_B, PL_S, PL_T, PL_COUNT };

struct planes {
    int x0, y0;
    double p0[PL_COUNT], px[PL_COUNT], py[PL_COUNT];
    __m128d pair0[PL_COUNT / 2], pair_x[PL_COUNT / 2], pair_y[PL_COUNT / 2];  /* the same, two planes a register */
    __m128 lanes[PL_COUNT];     /* Px * (0, 1, 2, 3): the four pixels of a quad */
    __m128 step[PL_COUNT];      /* Px * 4: from one quad to the next */
    bool checker;
};

static void planes_setup(struct planes *pl, const struct tri_setup *t,
                         const struct raster_params *p)
{
    int N = p->checker > 0 ? p->checker : 1;
    pl->x0 = t->minx;
    pl->y0 = t->miny;
    pl->checker = p->checker > 0;
    /* vertex values a / Z of each plane, for A, B, C */
    double val[PL_COUNT][3];
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double inv_z = 1.0 / v->z;
        val[PL_INV_Z][i] = inv_z;
        val[PL_R][i] = 255.0 * v->r * inv_z;
        val[PL_G][i] = 255.0 * v->g * inv_z;
        val[PL_B][i] = 255.0 * v->b * inv_z;
        val[PL_S][i] = N * v->s * inv_z;
        val[PL_T][i] = N * v->t * inv_z;
    }
    /* u (of A) = F02 / Area2, v (of B) = F03 / Area2, w (of C) = F01 / Area2 */
    double inv_area2 = 1.0 / (double)t->area2;
    double f[3];
    for (int k = 0; k < 3; k++)
        f[k] = (double)edge_value(t, k, pl->x0, pl->y0);
    for (int q = 0; q < PL_COUNT; q++) {
        const double *a = val[q];   /* A, B, C */
        pl->p0[q] = (f[EDGE_BC] * a[0] + f[EDGE_CA] * a[1] + f[EDGE_AB] * a[2]) * inv_area2;
        pl->px[q] = ((double)t->I[EDGE_BC] * a[0] + (double)t->I[EDGE_CA] * a[1]
                     + (double)t->I[EDGE_AB] * a[2]) * SUBPIXEL_ONE * inv_area2;
        pl->py[q] = ((double)t->J[EDGE_BC] * a[0] + (double)t->J[EDGE_CA] * a[1]
                     + (double)t->J[EDGE_AB] * a[2]) * SUBPIXEL_ONE * inv_area2;
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

/* The planes at the four pixels of one quad: (xq .. xq + 3, y), xq a
 * multiple of 4. A run along a row starts with quad_at() (exact, in double,
 * once per row of a block) and moves right with quad_next() (four float
 * adds). Both partial-block loops walk the same quads in the same way, so
 * they write the same bytes. */
struct quad {
    __m128 inv_z, r, g, b, s, t;
};

static inline struct quad quad_at(const struct planes *pl, int xq, int y)
{
    /* P0 + Px dx + Py dy in double, two planes per register: (1/z, r), (g, b), (s, t) */
    __m128d dx = _mm_set1_pd((double)(xq - pl->x0)), dy = _mm_set1_pd((double)(y - pl->y0));
    __m128 v[PL_COUNT / 2];
    int used = pl->checker ? PL_COUNT / 2 : PL_S / 2;   /* s and t only for the checker */
    for (int q = 0; q < PL_COUNT / 2; q++)
        v[q] = q < used ? _mm_cvtpd_ps(_mm_add_pd(_mm_add_pd(pl->pair0[q], _mm_mul_pd(pl->pair_x[q], dx)),
                                                  _mm_mul_pd(pl->pair_y[q], dy)))
                        : _mm_setzero_ps();
    /* each value spread to the four lanes, plus Px * (0, 1, 2, 3) */
    return (struct quad){
        .inv_z = _mm_add_ps(_mm_shuffle_ps(v[0], v[0], 0x00), pl->lanes[PL_INV_Z]),
        .r = _mm_add_ps(_mm_shuffle_ps(v[0], v[0], 0x55), pl->lanes[PL_R]),
        .g = _mm_add_ps(_mm_shuffle_ps(v[1], v[1], 0x00), pl->lanes[PL_G]),
        .b = _mm_add_ps(_mm_shuffle_ps(v[1], v[1], 0x55), pl->lanes[PL_B]),
        .s = _mm_add_ps(_mm_shuffle_ps(v[2], v[2], 0x00), pl->lanes[PL_S]),
        .t = _mm_add_ps(_mm_shuffle_ps(v[2], v[2], 0x55), pl->lanes[PL_T]),
    };
}

/* The step from one quad to the next, Px * 4 for every plane, as a quad of
 * its own: loops keep it in registers. */
static inline struct quad quad_step(const struct planes *pl)
{
    return (struct quad){ pl->step[PL_INV_Z], pl->step[PL_R], pl->step[PL_G],
                          pl->step[PL_B], pl->step[PL_S], pl->step[PL_T] };
}

static inline void quad_next(struct quad *qd, const struct quad *step, bool checker)
{
    qd->inv_z = _mm_add_ps(qd->inv_z, step->inv_z);
    qd->r = _mm_add_ps(qd->r, step->r);
    qd->g = _mm_add_ps(qd->g, step->g);
    qd->b = _mm_add_ps(qd->b, step->b);
    if (checker) {
        qd->s = _mm_add_ps(qd->s, step->s);
        qd->t = _mm_add_ps(qd->t, step->t);
    }
}

/* floor() of four floats, as int32 (truncation rounds towards zero). */
static __m128i floor_epi32(__m128 v)
{
    __m128i i = _mm_cvttps_epi32(v);
    __m128 too_big = _mm_cmpgt_ps(_mm_cvtepi32_ps(i), v);
    return _mm_add_epi32(i, _mm_castps_si128(too_big));    /* -1 where truncation went up */
}

/* Depth of the four pixels of a quad: z = 1 / (1/z), by a reciprocal
 * estimate and one Newton step (no division). */
static inline __m128 quad_depth(const struct quad *qd)
{
    __m128 z = _mm_rcp_ps(qd->inv_z);                   /* about 12 bits */
    return _mm_mul_ps(z, _mm_sub_ps(_mm_set1_ps(2.0f), _mm_mul_ps(qd->inv_z, z)));  /* about 22 */
}

/* Colour of the four pixels of a quad at depth z: (255 a / z) * z, darkened
 * on the checker's dark squares, packed as four 0xAARRGGBB. */
static inline __m128i quad_colour(const struct quad *qd, __m128 z, bool checker)
{
    __m128 r = _mm_mul_ps(qd->r, z);
    __m128 g = _mm_mul_ps(qd->g, z);
    __m128 b = _mm_mul_ps(qd->b, z);

    if (checker) {
        __m128i square = _mm_add_epi32(floor_epi32(_mm_mul_ps(qd->s, z)),
                                       floor_epi32(_mm_mul_ps(qd->t, z)));
        __m128 dark = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(square, _mm_set1_epi32(1)),
                                                       _mm_set1_epi32(1)));
        __m128 scale = _mm_or_ps(_mm_and_ps(dark, _mm_set1_ps((float)CHECKER_DARK)),
                                 _mm_andnot_ps(dark, _mm_set1_ps(1.0f)));
        r = _mm_mul_ps(r, scale);
        g = _mm_mul_ps(g, scale);
        b = _mm_mul_ps(b, scale);
    }

    /* Round to integers, then saturate to 0..255 while packing: bytes
     * b0 b1 b2 b3 r0 r1 r2 r3 g0 g1 g2 g3 a0 a1 a2 a3, interleaved twice into
     * b0 g0 r0 a0 b1 g1 r1 a1 ..., the bytes of 0xAARRGGBB in memory. */
    __m128i br = _mm_packs_epi32(_mm_cvtps_epi32(b), _mm_cvtps_epi32(r));
    __m128i ga = _mm_packs_epi32(_mm_cvtps_epi32(g), _mm_set1_epi32(255));
    __m128i planar = _mm_packus_epi16(br, ga);
    __m128i bgbg = _mm_unpacklo_epi8(planar, _mm_srli_si128(planar, 8));
    return _mm_unpacklo_epi16(bgbg, _mm_srli_si128(bgbg, 8));
}

/* Depth and colour of the four pixels of a quad, for the one-pixel loop. */
static inline void shade_quad(const struct planes *pl, const struct quad *qd,
                              __m128 *z_out, __m128i *rgba_out)
{
    *z_out = quad_depth(qd);
    *rgba_out = quad_colour(qd, *z_out, pl->checker);
}

/* target_write() for the lanes of a quad that `mask` keeps (all ones = keep),
 * one pixel at a time: count, depth test (nearer wins), write. */
static void write_quad_pixels(struct target *fb, int xq, int y, __m128i mask,
                              const struct quad *qd, bool checker)
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

/* The same for a whole quad at once, at depth row `dp` and colour row `cp`
 * (the quad's first pixel). The depth test comes first: where no lane is
 * nearer than what the target holds, the colour is never computed, and
 * where every lane is, the old colours are not read. Same bytes as
 * target_write() pixel by pixel. */
static inline void write_quad(float *dp, uint32_t *cp, __m128i mask,
                              const struct quad *qd, bool checker)
{
    __m128 z = quad_depth(qd);
    __m128 old_z = _mm_loadu_ps(dp);
    __m128 pass = _mm_and_ps(_mm_cmplt_ps(z, old_z), _mm_castsi128_ps(mask));
    int passed = _mm_movemask_ps(pass);
    if (passed == 0)
        return;
    __m128i rgba = quad_colour(qd, z, checker);
    if (passed == 0xF) {
        _mm_storeu_ps(dp, z);
        _mm_storeu_si128((__m128i *)cp, rgba);
        return;
    }
    _mm_storeu_ps(dp, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, old_z)));
    __m128i old_c = _mm_loadu_si128((const __m128i *)cp);
    __m128i pass_i = _mm_castps_si128(pass);
    _mm_storeu_si128((__m128i *)cp, _mm_or_si128(_mm_and_si128(pass_i, rgba),
                                                 _mm_andnot_si128(pass_i, old_c)));
}

/* Whole quads may be written at once when nobody counts coverage and the
 * quads xq0 .. xq1 lie on the row; otherwise pixel by pixel. */
static bool quads_fit(const struct target *fb, int xq1)
{
    return !fb->count && xq1 + 4 <= fb->w;
}

/* The lanes of the quad at xq whose pixel lies in [x0, x1]. */
static __m128i lanes_within(int xq, int x0, int x1)
{
    __m128i x = _mm_add_epi32(_mm_set1_epi32(xq), _mm_setr_epi32(0, 1, 2, 3));
    return _mm_and_si128(_mm_cmpgt_epi32(x, _mm_set1_epi32(x0 - 1)),
                         _mm_cmplt_epi32(x, _mm_set1_epi32(x1 + 1)));
}

/* --- the three cases ------------------------------------------------------ */

/* Everything one triangle's blocks share. */
struct run {
    const struct tri_setup *t;
    struct target *fb;
    struct trace *tr;
    struct edges e;
    struct planes pl;
    bool narrate;       /* a live trace in the narrated build: pixel by pixel */
    bool pixelwise;     /* partial blocks pixel by pixel even without a trace */
    bool fits_int32;    /* partial blocks' edge values fit the SSE int32 lanes */
    int size, level;    /* of the blocks being classified, for the narration */
};

/* Writes of a step that has not happened must not reach the target. */
static bool frozen(const struct trace *tr)
{
    return NARRATING && tr && tr->frozen;
}

/* FULL: RenderBlock. Every pixel of the block is covered, so there is no
 * test at all: shade four pixels at a time and write them. Only the first
 * and the last quad of a row may stick out of the block. */
static void render_block(struct run *r, int x0, int y0, int x1, int y1)
{
    int xq0 = x0 & ~3, xq1 = x1 & ~3;
    __m128i first = lanes_within(xq0, x0, x1), last = lanes_within(xq1, x0, x1);
    __m128i all = _mm_set1_epi32(-1);
    struct target *fb = r->fb;
    bool checker = r->pl.checker, whole = quads_fit(fb, xq1);
    struct quad step = quad_step(&r->pl);
    COUNT_OPS(r->tr, 5 * (uint64_t)(x1 - x0 + 1) * (uint64_t)(y1 - y0 + 1),
              4 * (uint64_t)(x1 - x0 + 1) * (uint64_t)(y1 - y0 + 1));
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, xq0, y);
        size_t row = (size_t)y * (size_t)fb->w;
        for (int xq = xq0; xq <= x1; xq += 4) {
            __m128i mask = xq == xq0 ? first : xq == xq1 ? last : all;
            if (whole)
                write_quad(fb->depth + row + xq, fb->color + row + xq, mask, &qd, checker);
            else
                write_quad_pixels(fb, xq, y, mask, &qd, checker);
            quad_next(&qd, &step, checker);
        }
    }
}

/* PARTIAL, one pixel at a time: the source's inner loop. The edge values
 * start at the block's corner and step by I0k to the right and J0k down
 * (formulas 9 and 10 of seed 001), exact in 64 bits. Every test and every
 * write is a step of the narration. */
static void partial_block_pixels(struct run *r, int x0, int y0, int x1, int y1)
{
    const struct edges *e = &r->e;
    struct quad step = quad_step(&r->pl);
    int64_t cy[3] = { edge_at(e, 0, x0, y0), edge_at(e, 1, x0, y0), edge_at(e, 2, x0, y0) };
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, x0 & ~3, y);
        int64_t cx[3] = { cy[0], cy[1], cy[2] };
        for (int x = x0; x <= x1; x++) {
            if (x > x0 && (x & 3) == 0)     /* the next quad of four pixels */
                quad_next(&qd, &step, r->pl.checker);
            bool in = cx[0] >= 0 && cx[1] >= 0 && cx[2] >= 0;
            COUNT_OPS(r->tr, 0, 3);
            NARRATE(r->tr, .kind = TRACE_PIXEL_TEST, .line = L_PIXEL, .x = x, .y = y,
                    .e = { cx[0] - e->bias[0], cx[1] - e->bias[1], cx[2] - e->bias[2] },
                    .bary = { (float)((double)(cx[1] - e->bias[1]) / (double)r->t->area2),
                              (float)((double)(cx[2] - e->bias[2]) / (double)r->t->area2),
                              (float)((double)(cx[0] - e->bias[0]) / (double)r->t->area2) },
                    .flags = in ? TRACE_INSIDE : 0);
            if (in) {
                __m128 z4;
                __m128i c4;
                float z[4];
                uint32_t rgba[4];
                shade_quad(&r->pl, &qd, &z4, &c4);
                _mm_storeu_ps(z, z4);
                _mm_storeu_si128((__m128i *)rgba, c4);
                COUNT_OPS(r->tr, 5, 4);
                PLOT(r->fb, r->tr, L_PIXEL, x, y, z[x & 3], rgba[x & 3]);
            }
            for (int k = 0; k < 3; k++)
                cx[k] += e->dx[k];
        }
        for (int k = 0; k < 3; k++)
            cy[k] += e->dy[k];
    }
}

/* PARTIAL, four pixels at a time: the same loop with a quad of pixels per
 * register. Only the edges that cross the block are tested; an edge whose
 * four corners are all inside is inside for every pixel of the block.
 *
 *        xq0       x0          x1
 *         |  .  .  [#  #  #  #  #  #  #  #] .  .  |   quads of 4 pixels,
 *         +-----------+-----------+-----------+     aligned on the screen;
 *                                                   lanes outside [x0, x1] off
 *
 * An edge that crosses the block changes sign inside it, so its values there
 * are smaller than its change across the block, (|I0k| + |J0k|) * 256 * q,
 * and the caller checked that this fits an int32 lane. */
static void partial_block_quads(struct run *r, int x0, int y0, int x1, int y1, const unsigned mask[3])
{
    const struct edges *e = &r->e;
    int xq0 = x0 & ~3;
    __m128i row_f[3], step_x[3], step_y[3];
    for (int k = 0; k < 3; k++) {
        if (mask[k] == 0xF) {   /* inside this edge everywhere: nothing to test */
            row_f[k] = step_x[k] = step_y[k] = _mm_setzero_si128();
            continue;
        }
        int64_t f = edge_at(e, k, xq0, y0);
        row_f[k] = _mm_setr_epi32((int32_t)f, (int32_t)(f + e->dx[k]),
                                  (int32_t)(f + 2 * e->dx[k]), (int32_t)(f + 3 * e->dx[k]));
        step_x[k] = _mm_set1_epi32((int32_t)(4 * e->dx[k]));
        step_y[k] = _mm_set1_epi32((int32_t)e->dy[k]);
    }
    struct target *fb = r->fb;
    bool checker = r->pl.checker, whole = quads_fit(fb, x1 & ~3);
    struct quad step = quad_step(&r->pl);
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, xq0, y);
        size_t row = (size_t)y * (size_t)fb->w;
        __m128i f[3] = { row_f[0], row_f[1], row_f[2] };
        for (int xq = xq0; xq <= x1; xq += 4) {
            /* covered: all three values >= 0, i.e. the sign bit of none is set */
            __m128i any_negative = _mm_srai_epi32(_mm_or_si128(_mm_or_si128(f[0], f[1]), f[2]), 31);
            __m128i covered = _mm_andnot_si128(any_negative, lanes_within(xq, x0, x1));
            bool any = _mm_movemask_ps(_mm_castsi128_ps(covered)) != 0;
            if (any && whole)
                write_quad(fb->depth + row + xq, fb->color + row + xq, covered, &qd, checker);
            else if (any)
                write_quad_pixels(fb, xq, y, covered, &qd, checker);
            quad_next(&qd, &step, checker);
            for (int k = 0; k < 3; k++)
                f[k] = _mm_add_epi32(f[k], step_x[k]);
        }
        for (int k = 0; k < 3; k++)
            row_f[k] = _mm_add_epi32(row_f[k], step_y[k]);
    }
}

/* --- classifying a block by its corners ---------------------------------- */

/* The source's checkw, checku, checkv: one bit per corner, set when that
 * corner is inside the edge. The corners are the CENTRES of the block's
 * corner pixels (the samples the pixel test uses), not the block's outline:
 *
 *      (x0, y0) bit 3  o---------o  bit 2 (x1, y0)
 *                      |  block  |
 *                      |  pixels |
 *      (x0, y1) bit 1  o---------o  bit 0 (x1, y1)
 *
 * A linear F is >= 0 on all four corners exactly when it is >= 0 on every
 * pixel centre between them; it is < 0 on all four exactly when it is < 0 on
 * every one of them. */
static void corner_masks(struct run *r, int x0, int y0, int x1, int y1, unsigned mask[3])
{
    const struct edges *e = &r->e;
    for (int k = 0; k < 3; k++) {
        int64_t tl = edge_at(e, k, x0, y0);
        int64_t tr = tl + e->dx[k] * (x1 - x0);
        int64_t bl = tl + e->dy[k] * (y1 - y0);
        int64_t br = tr + (bl - tl);
        mask[k] = (unsigned)(tl >= 0) << 3 | (unsigned)(tr >= 0) << 2
                | (unsigned)(bl >= 0) << 1 | (unsigned)(br >= 0);
    }
    COUNT_OPS(r->tr, 12, 18);
}

/* How the masks are read. Only the first is right. */
enum block_rule {
    RULE_PER_EDGE,          /* empty: all corners outside ONE edge; full: inside ALL edges */
    RULE_CORNERS_OUTSIDE,   /* exhibit: empty when no corner is inside the triangle */
    RULE_OR_INSIDE,         /* exhibit: the pseudo-code's || in the fully-inside test */
};

static enum block_class classify(const unsigned m[3], enum block_rule rule)
{
    switch (rule) {
    case RULE_CORNERS_OUTSIDE:
        /* "every corner of the block is outside the triangle", read literally:
         * a corner is inside the triangle when it is inside all three edges */
        if ((m[0] & m[1] & m[2]) == 0)
            return BLOCK_EMPTY;
        break;
    case RULE_OR_INSIDE:
        if (m[0] == 0 || m[1] == 0 || m[2] == 0)
            return BLOCK_EMPTY;
        return m[0] == 0xF || m[1] == 0xF || m[2] == 0xF ? BLOCK_FULL : BLOCK_PARTIAL;
    case RULE_PER_EDGE:
        if (m[0] == 0 || m[1] == 0 || m[2] == 0)
            return BLOCK_EMPTY;
        break;
    }
    return m[0] == 0xF && m[1] == 0xF && m[2] == 0xF ? BLOCK_FULL : BLOCK_PARTIAL;
}

/* Classify one block (pixels x0..x1, y0..y1), narrate it, and act. */
static enum block_class block(struct run *r, enum block_rule rule, int x0, int y0, int x1, int y1,
                              bool act_on_partial)
{
    unsigned m[3];
    corner_masks(r, x0, y0, x1, y1, m);
    enum block_class klass = classify(m, rule);
    NARRATE(r->tr, .kind = TRACE_BLOCK, .line = klass == BLOCK_EMPTY ? L_EMPTY : klass == BLOCK_FULL ? L_FULL : L_PARTIAL,
            .x = x0, .y = y0,
            .x1 = x1, .y1 = y1, .klass = (uint8_t)klass,
            .mask = { (uint16_t)m[0], (uint16_t)m[1], (uint16_t)m[2] },
            .e = { edge_at(&r->e, 0, x0, y0) - r->e.bias[0], edge_at(&r->e, 1, x0, y0) - r->e.bias[1],
                   edge_at(&r->e, 2, x0, y0) - r->e.bias[2] },
            .aux = { (float)r->size, (float)r->level });
    if (klass == BLOCK_FULL && !frozen(r->tr))
        render_block(r, x0, y0, x1, y1);
    if (klass != BLOCK_PARTIAL || !act_on_partial)
        return klass;
    if (r->narrate || r->pixelwise || !r->fits_int32)
        partial_block_pixels(r, x0, y0, x1, y1);
    else
        partial_block_quads(r, x0, y0, x1, y1, m);
    return klass;
}

/* The q x q grid over the part x0..x1, y0..y1 of the box. The grid is aligned
 * on the screen (block edges at multiples of q), so neighbouring triangles
 * share blocks and a block's rows line up with the SSE quads; blocks are
 * clipped to the box. A box that fits in one block is that block. */
static void blocks(struct run *r, enum block_rule rule, int x0, int y0, int x1, int y1, int q, int level)
{
    r->size = q;
    r->level = level;
    if (x1 - x0 < q && y1 - y0 < q) {
        block(r, rule, x0, y0, x1, y1, true);
        return;
    }
    for (int by = y0 - y0 % q; by <= y1; by += q) {
        int ya = by < y0 ? y0 : by, yb = by + q - 1 > y1 ? y1 : by + q - 1;
        for (int bx = x0 - x0 % q; bx <= x1; bx += q) {
            int xa = bx < x0 ? x0 : bx, xb = bx + q - 1 > x1 ? x1 : bx + q - 1;
            block(r, rule, xa, ya, xb, yb, true);
        }
    }
}

/* --- the rasterizer ----------------------------------------------------------- */

struct block_options {
    int q;                  /* block size; 0 = --block-size, else Q_DEFAULT */
    int coarse;             /* > 0: hierarchical, coarse blocks of this size first */
    enum block_rule rule;
    bool pixelwise;         /* partial blocks one pixel at a time, always */
};

static void rasterize_blocks(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr, struct block_options o)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_BOX, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    int q = o.q > 0 ? o.q : p->block_size > 0 ? p->block_size : Q_DEFAULT;
    if (q > Q_COARSE)
        q = Q_COARSE;

    struct run r;       /* set field by field: an initializer would clear all of it, per triangle */
    r.t = t;
    r.fb = fb;
    r.tr = tr;
    r.narrate = NARRATING && tr;
    r.pixelwise = o.pixelwise;
    r.size = q;
    r.level = 0;
    edges_setup(&r.e, t);
    planes_setup(&r.pl, t, p);
    /* the SSE partial loop keeps edge values in int32 lanes: see there */
    int64_t widest = 0;
    for (int k = 0; k < 3; k++) {
        int64_t span = llabs(r.e.dx[k]) + llabs(r.e.dy[k]);
        widest = span > widest ? span : widest;
    }
    r.fits_int32 = widest * (q + 4) < INT32_MAX;

    if (o.coarse <= 0 || (t->maxx - t->minx < q && t->maxy - t->miny < q)) {
        blocks(&r, o.rule, t->minx, t->miny, t->maxx, t->maxy, q, 0);
        return;
    }
    /* Hierarchical: a coarse block that is empty or full settles all of its
     * sub-blocks at once; only a partial one is looked at q x q block by
     * q x q block. */
    int c = o.coarse;
    for (int cy = t->miny - t->miny % c; cy <= t->maxy; cy += c) {
        int ya = cy < t->miny ? t->miny : cy, yb = cy + c - 1 > t->maxy ? t->maxy : cy + c - 1;
        for (int cx = t->minx - t->minx % c; cx <= t->maxx; cx += c) {
            int xa = cx < t->minx ? t->minx : cx, xb = cx + c - 1 > t->maxx ? t->maxx : cx + c - 1;
            r.size = c;
            r.level = 0;
            if (block(&r, o.rule, xa, ya, xb, yb, false) == BLOCK_PARTIAL)
                blocks(&r, o.rule, xa, ya, xb, yb, q, 1);
        }
    }
}

/* --- the variants ------------------------------------------------------------- */

static void rasterize_q8(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0 });
}

static void rasterize_q4(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 4 });
}

static void rasterize_q16(const struct tri_setup *t, const struct raster_params *p,
                          struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 16 });
}

static void rasterize_hier(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0, .coarse = Q_COARSE });
}

static void rasterize_pixelwise(const struct tri_setup *t, const struct raster_params *p,
                                struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0, .pixelwise = true });
}

static void rasterize_corners_outside(const struct tri_setup *t, const struct raster_params *p,
                                      struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .rule = RULE_CORNERS_OUTSIDE });
}

static void rasterize_or_inside(const struct tri_setup *t, const struct raster_params *p,
                                struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .rule = RULE_OR_INSIDE });
}

/* --- what the explorer draws ----------------------------------------------------
 *
 * In the blocks and coverage views, at each of the four corner pixel centres
 * of the block just classified, three small discs, one per edge in the
 * edge's colour from left to right (F01, F02, F03): filled with a "+" when the
 * corner is inside that edge (its bit of the mask is set), hollow with a "-"
 * when it is outside. The class follows from the twelve signs: one edge all
 * "-" is empty, all twelve "+" is full, anything else partial. */
static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    (void)t, (void)p;
    if (!last || last->kind != TRACE_BLOCK)
        return;
    if (strcmp(c->view, "blocks") != 0 && strcmp(c->view, "coverage") != 0)
        return;
    cairo_t *cr = c->cr;
    const double u = c->unit, r = 4.5 * u, gap = 10.5 * u;
    /* corners as corner_masks() numbers them: bit 3 top-left ... bit 0 bottom-right */
    const int cx[4] = { last->x1, last->x, last->x1, last->x };
    const int cy[4] = { last->y1, last->y1, last->y, last->y };
    for (int bit = 0; bit < 4; bit++) {
        double x = cx[bit] + 0.5, y = cy[bit] + 0.5;
        cairo_set_source_rgba(cr, 0, 0, 0, 0.75);
        cairo_rectangle(cr, x - 1.5 * gap, y - gap * 0.6, 3 * gap, 1.2 * gap);
        cairo_fill(cr);
        for (int k = 0; k < 3; k++) {
            uint32_t h = c->edge_rgb[k];
            double er = (h >> 16 & 255) / 255.0, eg = (h >> 8 & 255) / 255.0, eb = (h & 255) / 255.0;
            double dx = x + (k - 1) * gap;
            bool in = (last->mask[k] >> bit) & 1;
            cairo_arc(cr, dx, y, r, 0, 6.283185307179586);
            cairo_set_source_rgb(cr, er, eg, eb);
            if (in)
                cairo_fill(cr);
            else {
                cairo_set_line_width(cr, 1.5 * u);
                cairo_stroke(cr);
            }
            cairo_set_line_width(cr, 1.5 * u);
            if (in)
                cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_move_to(cr, dx - r * 0.6, y);
            cairo_line_to(cr, dx + r * 0.6, y);
            if (in) {
                cairo_move_to(cr, dx, y - r * 0.6);
                cairo_line_to(cr, dx, y + r * 0.6);
            }
            cairo_stroke(cr);
        }
    }
}

static const struct lesson_variant variants[] = {
    { "q8", "8 x 8 blocks (or --block-size Q), partial blocks four pixels at a time",
      rasterize_q8, false },
    { "q4", "4 x 4 blocks", rasterize_q4, false },
    { "q16", "16 x 16 blocks", rasterize_q16, false },
    { "hier", "64 x 64 coarse blocks, the partial ones cut into 8 x 8 blocks", rasterize_hier, false },
    { "q8-pixel", "8 x 8 blocks, partial blocks one pixel at a time (64-bit edge values)",
      rasterize_pixelwise, false },
    { "corners-outside", "exhibit: skip a block when every corner is outside the triangle",
      rasterize_corners_outside, true },
    { "or-inside", "exhibit: the pseudo-code's || makes a block full when inside ONE edge",
      rasterize_or_inside, true },
};

static const char *const compare[] = { "02-barycentric", "03-edge-stepping", NULL };

const struct lesson lesson_05 = {
    .id = "05-block-classification",
    .title = "q x q block classification",
    .pseudocode = pseudocode,
    .builtin_scene = "blocks",
    .exhibit_scene = "blocks-exhibits",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .params = LESSON_PARAM_BLOCK,
    .compare = compare,
    .overlay = overlay,
};
