/* textures.h - lesson 09's interface: the texture unit's stages, the
 * filters, what its narration carries, and the one rasterizer they plug
 * into. The lesson's files:
 *
 *   sampling.c      the texture unit: a bilinear tap, the level of detail,
 *                   the trilinear mix, anisotropic taps, the five filters
 *   textures.c      the lesson: lesson 05's blocks, then 2 x 2 quads inside
 *                   them, narrated; the descriptor and its variants
 *   quads_sse.c     the fast twin: a quad is four SSE lanes
 *
 * The rules are lessons/CONVENTIONS.md's "Textures" (src/scene/texture.h holds the
 * image, its pyramid and texel addressing).
 *
 * The stages (struct tex_stages) are what an exercise swaps: the lesson's
 * own are tex_stages_lesson; the exercise passes the student's to
 * textures_rasterize(), the very rasterizer the lesson runs, so a student's
 * bilinear tap, level of detail or trilinear mix is drawn, narrated and
 * checked by the lesson's own quads (no second rasterizer).
 */
#ifndef TRISTEP_TEXTURES_H
#define TRISTEP_TEXTURES_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "lesson.h"
#include "tiled.h"           /* the tiled twin's tile, shared with tiled.c */

#ifdef __clang__
#pragma STDC FP_CONTRACT OFF    /* no fused multiply-add: the twin rounds as the lesson does */
#endif

/* Both builds (narrated and fast) link into one program: what one file of
 * the lesson calls in another carries the build in its name. */
#ifndef TRISTEP_NARRATE
#define tex_bilinear tex_bilinear_fast
#define tex_lod tex_lod_fast
#define tex_trilinear tex_trilinear_fast
#define tex_nearest tex_nearest_fast
#define tex_filter_texel tex_filter_texel_fast
#define tex_stages_lesson tex_stages_lesson_fast
#define tex_quad_lod tex_quad_lod_fast
#define tex_rasterize_sse tex_rasterize_sse_fast
#define textures_rasterize textures_rasterize_fast
#define textures_setup textures_setup_fast
#define tex_modulate tex_modulate_fast
#define tex_filter_of tex_filter_of_fast
#define tex_max_aniso_of tex_max_aniso_of_fast
#endif

/* --- the filters (--filter NAME) and the parameter rows ------------------ */

/* Numbered from 1, so that a zeroed raster_params (knob 0) means "the
 * default" (trilinear), as for every lesson's rows. */
enum tex_filter { FILTER_NEAREST = 1, FILTER_BILINEAR, FILTER_MIP_BILINEAR, FILTER_TRILINEAR,
                  FILTER_ANISO };
/* the lesson's rows: p->knob[P_FILTER], p->knob[P_MAX_ANISO], and
 * p->knob[P_AFFINE], --affine as in lesson 04 (every variant then takes
 * the affine exhibit's (s, t)); p->knob[TEX_P_THREADS] after them (tiled.h) */
enum { P_FILTER, P_MAX_ANISO, P_AFFINE };
#define MAX_ANISO_DEFAULT 16

/* The filter and the aniso limit a run's params ask for (defaults for 0). */
enum tex_filter tex_filter_of(const struct raster_params *p);
int tex_max_aniso_of(const struct raster_params *p);

/* --- the stages ------------------------------------------------------------ */

/* A filtered colour: r, g, b in 0..255, not rounded. */
struct texel_rgb {
    float c[3];
};

/* The derivatives of (s, t) a quad (or a pixel) uses, per screen pixel, in
 * texture coordinates (not texels), and the level-0 size that makes texels
 * of them. beyond: a helper pixel lies beyond the horizon (1/z <= 0): no
 * derivatives, the last level. */
struct tex_deriv {
    double dsdx, dtdx, dsdy, dtdy;
    int w0, h0;
    bool beyond;
};

struct tex_stages {
    /* The bilinear tap at level k: u = s W_k - 1/2, v = t H_k - 1/2, the
     * four texels from (floor u, floor v) wrapped as the texture says,
     * weighted by frac u and frac v. */
    struct texel_rgb (*bilinear)(const struct texture *tex, int k, double s, double t);
    /* The level of detail: lambda = log2(rho), rho = the longer of the two
     * derivative vectors in level-0 texels (-inf for rho = 0). */
    double (*lod)(const struct tex_deriv *d);
    /* Trilinear at lambda: lambda clamped to [0, last level], bilinear taps
     * (st->bilinear) at levels floor(lambda) and the next (the last twice at
     * the end), mixed by frac(lambda). */
    struct texel_rgb (*trilinear)(const struct texture *tex, double lambda, double s, double t,
                                  const struct tex_stages *st);
};

/* --- texel addressing, shared by the stages and the twin ----------------- */

/* |u|, |v| beyond this (a helper's extrapolation near the horizon, an
 * aniso tap spread by an enormous derivative) are held here, so that the
 * texel index stays an integer (2^52 texels is a multiple of every size). */
#define TEXEL_COORD_MAX 0x1p52

static inline double tex_coord_held(double u)
{
    return u >= -TEXEL_COORD_MAX ? (u <= TEXEL_COORD_MAX ? u : TEXEL_COORD_MAX) : -TEXEL_COORD_MAX;
}

/* Texel (i, j) of level l, 0xAARRGGBB. Repeat is the mathematical mod
 * (sizes are powers of two: the low bits of i as an unsigned number, for
 * negative i too); clamp holds i inside 0 .. W - 1. */
static inline uint32_t texel_at(const struct texture_level *l, enum texture_wrap wrap, int64_t i,
                                int64_t j)
{
    int x, y;
    if (wrap == TEXTURE_REPEAT) {
        x = (int)((uint64_t)i & (uint64_t)(l->w - 1));
        y = (int)((uint64_t)j & (uint64_t)(l->h - 1));
    } else {
        x = i < 0 ? 0 : i >= l->w ? l->w - 1 : (int)i;
        y = j < 0 ? 0 : j >= l->h ? l->h - 1 : (int)j;
    }
    return l->texel[(size_t)y * (size_t)l->w + (size_t)x];
}

/* A bilinear tap's top-left texel (i, j) and weights (a, b) at (s, t) on
 * level l: u - 1/2 = i + a, v - 1/2 = j + b. */
static inline void bilinear_corner(const struct texture_level *l, double s, double t, int64_t *i,
                                   int64_t *j, float *a, float *b)
{
    double u = tex_coord_held(s * l->w - 0.5), v = tex_coord_held(t * l->h - 0.5);
    double i0 = floor(u), j0 = floor(v);
    *a = (float)(u - i0), *b = (float)(v - j0);
    *i = (int64_t)i0, *j = (int64_t)j0;
}

/* --- (s, t) at a pixel centre: one reciprocal, exact at texel edges ---------
 *
 * With F_k the edge value opposite vertex k (zero at its edge) and Q_k =
 * 1 / z_k, a pixel's 1/z, s/z and t/z are sum F_k Q_k / (2 area) and sum
 * F_k (s_k Q_k) / (2 area) ..., so
 *
 *     q = sum F_k Q_k,   r = 1 / q,   s = (sum F_k s_k Q_k) r,   z = (2 area) r
 *
 * one division per pixel (the weights F_k / (2 area) / z_k of lesson 04
 * take six). Inside the triangle every F_k >= 0, so the sums have no
 * cancellation in q, and (s, t) moves from the weights' value by a few
 * units of the last place of max |s_k| (tested: at most 2^-48 texels per
 * texel of max |s_k| W, tests/test_lesson09_tiles.c). Only the nearest
 * texel jumps when (s, t) moves that little, and only where the rule's
 * value lies exactly on a texel's edge, as a pixel centre of a 2-D scene
 * often does: there (within TEX_TIE of an edge) nearest takes (s, t) from
 * the weights themselves, in the rule's order. */
#define TEX_TIE 0x1p-40         /* texels per texel of max |s_k| W: 256 times the largest move */

/* (s, t) from the weights of lesson 04, in the rule's order: w_k = F_k /
 * (2 area) / z_k, 1/z = sum w_k, s = (sum w_k s_k) / (1/z). f[k] is the
 * edge value opposite vertex k. */
static inline void tex_st_by_weights(const struct tri_setup *t, const double f[3], double *s, double *tt)
{
    double area2 = (double)t->area2, q = 0, sum_s = 0, sum_t = 0;
    for (int k = 0; k < 3; k++) {
        double w = f[k] / area2 / t->v[k].z;
        q += w;
        sum_s += w * t->v[k].s, sum_t += w * t->v[k].t;
    }
    *s = sum_s / q, *tt = sum_t / q;
}

/* How close to a texel's edge u may lie before nearest asks the weights:
 * TEX_TIE max |s_k| W (of s, and of t with H), for the triangle. */
static inline void tex_tie_bounds(const struct tri_setup *t, int w, int h, double bound[2])
{
    double ms = 0, mt = 0;
    for (int k = 0; k < 3; k++) {
        ms = fabs(t->v[k].s) > ms ? fabs(t->v[k].s) : ms;
        mt = fabs(t->v[k].t) > mt ? fabs(t->v[k].t) : mt;
    }
    bound[0] = TEX_TIE * (ms > 1 ? ms : 1) * w, bound[1] = TEX_TIE * (mt > 1 ? mt : 1) * h;
}

/* Is u (texels) within b of an integer: of a texel's edge? */
static inline bool tex_near_edge(double u, double b)
{
    double d = u - floor(u);
    return d < b || 1 - d < b;
}

/* --- the blocks the quads are walked in (lesson 05's) ------------------------ */

#define TEX_BLOCK 8

/* Is block [x0, x1] x [y0, y1] empty: all four corners outside one edge? */
static inline bool tex_block_empty(const struct biased_edges *e, int x0, int y0, int x1, int y1)
{
    for (int k = 0; k < 3; k++) {
        int64_t f = biased_edge_at(e, k, x0, y0), dx = e->dx[k] * (x1 - x0), dy = e->dy[k] * (y1 - y0);
        if (f < 0 && f + dx < 0 && f + dy < 0 && f + dx + dy < 0)
            return true;
    }
    return false;
}

/* The lesson's own stages (sampling.c), and its pieces by name. */
extern const struct tex_stages tex_stages_lesson;
struct texel_rgb tex_bilinear(const struct texture *tex, int k, double s, double t);
double tex_lod(const struct tex_deriv *d);
struct texel_rgb tex_trilinear(const struct texture *tex, double lambda, double s, double t,
                               const struct tex_stages *st);
struct texel_rgb tex_nearest(const struct texture *tex, double s, double t);

/* What the texture unit did for one pixel, for the narration: the
 * lambda it used (after the horizon and the clamp), the two levels and
 * the weight of the second, the aniso taps. */
struct tex_used {
    float lambda;
    int level0, level1;
    float mix;
    int taps;
};

/* The filtered texel of a pixel at (s, t) in a quad with derivatives d,
 * through stages st. used may be NULL. */
struct texel_rgb tex_filter_texel(const struct texture *tex, enum tex_filter f, int max_aniso,
                                  double s, double t, const struct tex_deriv *d,
                                  const struct tex_stages *st, struct tex_used *used);

/* The pixel's colour: the texel times the interpolated vertex colour
 * (r, g, b in [0, 1]), rounded to 8 bits once. */
uint32_t tex_modulate(struct texel_rgb texel, double r, double g, double b);

/* --- the rasterizer --------------------------------------------------------- */

/* How a variant evaluates (s, t) and the level of detail. */
enum tex_lod_mode { LOD_COARSE, LOD_FINE, LOD_ANALYTIC };
struct tex_options {
    enum tex_lod_mode lod;      /* coarse (the quad's top-left pixel), fine, analytic */
    bool affine;                /* (s, t) interpolated linearly in screen space (lesson 04's swim) */
    bool no_mipmaps;            /* level 0 always, bilinear */
};

/* Lesson 09's algorithm on one triangle with the stages st (the lesson's,
 * or an exercise's) and the options o: what every variant of textures.c
 * runs. */
void textures_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr, const struct tex_stages *st,
                        struct tex_options o);
/* The fast twin (quads_sse.c): the same pixels, the lesson's stages. */
void tex_rasterize_sse(const struct tri_setup *t, const struct raster_params *p,
                       struct target *fb, struct trace *tr);


/* --- what the narration carries -------------------------------------------- */

/* Pseudo-code lines (textures.c). */
enum { L_SETUP, L_BLOCKS, L_EMPTY, L_QUADS, L_COVER, L_SKIP, L_EVAL, L_DERIV, L_LOD, L_FILTER,
       L_WRITE };

/* The events of one quad, in order, and their aux[] (the lesson's
 * aux_names is NULL: the values' meaning depends on the line):
 *
 *   TRACE_BLOCK     L_EMPTY / L_QUADS  an 8 x 8 block by its corners (lesson 05): klass
 *                             BLOCK_EMPTY, or BLOCK_PARTIAL for any other (its quads test
 *                             every pixel: a FULL event would mean written in one step);
 *                             aux[0] = 8
 *   TRACE_PIXEL_TEST L_COVER  each of the quad's 4 pixels: e, flags TRACE_INSIDE when covered
 *   TRACE_STEP      L_SKIP    (x, y) = the quad: no pixel covered, skipped
 *   TRACE_STEP      L_EVAL    each of the 4 pixels, helpers too: flags TRACE_INSIDE
 *                             when covered (else a helper, evaluated, never written);
 *                             aux AUX_U, AUX_V (level-0 texels), AUX_Q (1/z)
 *   TRACE_STEP      L_DERIV..L_LOD  (x, y) = the quad (its top-left pixel),
 *                             mask[0] = its covered pixels (bit 0 top-left, 1 top-right,
 *                             2 bottom-left, 3 bottom-right), flags TRACE_INSIDE unless
 *                             beyond the horizon; aux AUX_DUDX .. AUX_DVDY (level-0
 *                             texels per pixel), AUX_RHO, AUX_LAMBDA
 *   TRACE_STEP      L_FILTER  each covered pixel: aux AUX_U, AUX_V, AUX_USED_LAMBDA,
 *                             AUX_LEVEL0, AUX_LEVEL1, AUX_MIX; mask[1] = aniso taps
 *                             (1 for the other filters), mask[2] = the filter
 *   TRACE_PIXEL_WRITE L_WRITE the write (PLOT)
 *
 * A variant with fine or analytic derivatives narrates L_DERIV..L_LOD once
 * per covered pixel, (x, y) that pixel. Untextured triangles (and the
 * checker) skip L_DERIV..L_FILTER: shaded as every lesson shades. The
 * fast twin (and the tiled twin, which draws its quads) narrates the same
 * events per quad, but no counts, and L_FILTER only for a pixel that passes
 * the depth test (a hidden pixel's texel is never read; its write is told
 * with colour 0). */
enum { AUX_U, AUX_V, AUX_Q };
enum { AUX_DUDX, AUX_DVDX, AUX_DUDY, AUX_DVDY, AUX_RHO, AUX_LAMBDA };
enum { AUX_USED_LAMBDA = 2, AUX_LEVEL0, AUX_LEVEL1, AUX_MIX };

#endif
