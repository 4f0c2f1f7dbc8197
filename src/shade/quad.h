/* quad.h - shading four pixels at once with SSE: lesson 04's planes of 1/z
 * and a/z (perspective-correct, formula 23 of the edge-function notes) evaluated for a quad
 * of four neighbouring pixels of one row, their depth by a reciprocal, their
 * colour packed to 0xAARRGGBB, and their write with the depth test.
 *
 * Not a lesson's idea: lessons 05 onwards shade with it, so that a lesson's
 * file holds what it teaches (lesson 05: corners -> classify -> blocks) and
 * every SIMD lesson writes the same bytes for the same pixel. A quad is
 * aligned on the screen (its first pixel's x is a multiple of 4); lanes
 * outside the pixels wanted are masked off.
 *
 *     x:      xq     xq+1    xq+2    xq+3
 *     1/z  [ 1/z  | 1/z   | 1/z   | 1/z   ]   += 4 Px per quad to the right
 *     r    [ 255 r/z | ...                ]   (g, b, s, t likewise)
 */
#ifndef TRISTEP_SHADE_QUAD_H
#define TRISTEP_SHADE_QUAD_H

#include <stdbool.h>

#include "lesson.h"
#include "shade/shade.h"
#include "simd.h"       /* SSE2 intrinsics, native or through SIMDe */

/* Named costs per pixel (one lane), for COUNT (trace/trace.h):
 *   QUAD_DEPTH_COST    z = 1 / (1/z): a reciprocal estimate and one Newton step
 *   QUAD_COLOUR_COST   r, g, b = (255 a / z) * z; rounding and packing are
 *                      conversions, not arithmetic
 *   the planes one quad on: PLANE_STEP_COST (shade/shade.h) per plane, lane by lane */
#define QUAD_DEPTH_COST { .mul = 3, .add = 1 }
#define QUAD_COLOUR_COST { .mul = 3, .add = 0 }
#define QUAD_PLANES 4   /* planes stepped per quad without a checker: 1/z, r, g, b */

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

/* The planes of triangle t, relative to its box's corner (minX, minY);
 * those of s and t are 0 without a checker. planes_solve() fills x0, y0,
 * checker and the planes in double only (for a lesson that keeps its own
 * registers, lesson 07), planes_setup() the SSE registers too. */
void planes_solve(struct planes *pl, const struct tri_setup *t, const struct raster_params *p);
void planes_setup(struct planes *pl, const struct tri_setup *t, const struct raster_params *p);

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
static inline __m128i floor_epi32(__m128 v)
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

/* The checker's factor for four pixels at texture coordinates (s, t):
 * CHECKER_DARK where floor(s) + floor(t) is odd, 1 elsewhere. */
static inline __m128 checker_scale(__m128 s, __m128 t)
{
    __m128i square = _mm_add_epi32(floor_epi32(s), floor_epi32(t));
    __m128 dark = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(square, _mm_set1_epi32(1)),
                                                   _mm_set1_epi32(1)));
    return _mm_or_ps(_mm_and_ps(dark, _mm_set1_ps((float)CHECKER_DARK)),
                     _mm_andnot_ps(dark, _mm_set1_ps(1.0f)));
}

/* Colour of the four pixels of a quad at depth z: (255 a / z) * z, darkened
 * on the checker's dark squares, packed as four 0xAARRGGBB. */
static inline __m128i quad_colour(const struct quad *qd, __m128 z, bool checker)
{
    __m128 r = _mm_mul_ps(qd->r, z);
    __m128 g = _mm_mul_ps(qd->g, z);
    __m128 b = _mm_mul_ps(qd->b, z);

    if (checker) {
        __m128 scale = checker_scale(_mm_mul_ps(qd->s, z), _mm_mul_ps(qd->t, z));
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
void write_quad_pixels(struct target *fb, int xq, int y, __m128i mask, const struct quad *qd,
                       bool checker);

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
static inline bool quads_fit(const struct target *fb, int xq1)
{
    return !fb->count && xq1 + 4 <= fb->w;
}

/* The lanes of the quad at xq whose pixel lies in [x0, x1]. */
static inline __m128i lanes_within(int xq, int x0, int x1)
{
    __m128i x = _mm_add_epi32(_mm_set1_epi32(xq), _mm_setr_epi32(0, 1, 2, 3));
    return _mm_and_si128(_mm_cmpgt_epi32(x, _mm_set1_epi32(x0 - 1)),
                         _mm_cmplt_epi32(x, _mm_set1_epi32(x1 + 1)));
}

#endif
