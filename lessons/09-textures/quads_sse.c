/* Lesson 09's fast twin: the quads of textures.c with a quad in SSE lanes.
 *
 * The same pixels, the same bytes: every value a pixel's colour depends on
 * is computed by the same IEEE operations in the same order, only four
 * pixels at a time (two pairs of doubles: a textured pixel's one
 * reciprocal, an untextured one's weights and divides).
 * What is different: a quad's four pixels are evaluated at once (and a
 * level's taps for all four), trilinear takes one lambda per quad (the
 * quad's, which every pixel of it uses anyway), and a pixel's texel is
 * sampled only once it passes the depth test; an untextured quad without
 * the checker needs no s and t, and packs its four colours at once (the
 * narrated build shades it pixel by pixel, as the lesson does, so that its
 * counts are the lesson's). The walk is the lesson's:
 * the 8 x 8 blocks of the box, the empty ones skipped, then their quads,
 * on the target, or (the tiled twin, tiled.c) the part of the box in one
 * worker's 64 x 64 tile buffer. Narrated, it tells each quad as the lesson
 * does (textures.h), so the explorer steps this very code.
 *
 *      lanes:   [ TL | TR ]  the quad's top row     (x0, x0 + 1) at y0
 *               [ BL | BR ]  its bottom row         (x0, x0 + 1) at y0 + 1
 *
 * The edge values are exact integers below 2^47, so they and their sums
 * are exact in doubles too: coverage tested on doubles is the integer
 * test, and the sums of F_k / z_k are the narrated ones, bit for bit.
 */
#include <math.h>
#include <string.h>

#include "shade/shade.h"
#include "simd.h"
#include "textures.h"

/* A quad's values, top row and bottom row, each a pair of doubles. */
struct quad2 {
    __m128d top, bottom;
};

/* sum_k w_k a_k, from 0 and left to right as the narrated sum */
static inline struct quad2 pair_sum3(const struct quad2 w[3], const double a[3])
{
    struct quad2 sum = { _mm_setzero_pd(), _mm_setzero_pd() };
    for (int k = 0; k < 3; k++) {
        __m128d ak = _mm_set1_pd(a[k]);
        sum.top = _mm_add_pd(sum.top, _mm_mul_pd(w[k].top, ak));
        sum.bottom = _mm_add_pd(sum.bottom, _mm_mul_pd(w[k].bottom, ak));
    }
    return sum;
}

static inline struct quad2 pair_div(struct quad2 a, struct quad2 b)
{
    return (struct quad2){ _mm_div_pd(a.top, b.top), _mm_div_pd(a.bottom, b.bottom) };
}

static inline struct quad2 pair_mul(struct quad2 a, struct quad2 b)
{
    return (struct quad2){ _mm_mul_pd(a.top, b.top), _mm_mul_pd(a.bottom, b.bottom) };
}

/* --- the texture unit, a texel's channels in four float lanes ------------------
 *
 * tex_bilinear, tex_trilinear and tex_modulate (sampling.c) with the three
 * channels of a texel side by side: lanes b, g, r, a, its bytes in memory
 * order. Each lane does the scalar code's operations on its channel, in
 * the same order, so each channel comes out the same. */

static inline __m128 texel4(uint32_t texel)
{
    __m128i c = _mm_cvtsi32_si128((int)texel);
    __m128i zero = _mm_setzero_si128();
    return _mm_cvtepi32_ps(_mm_unpacklo_epi16(_mm_unpacklo_epi8(c, zero), zero));
}

/* Columns (or rows) i and i + 1 wrapped as texel_at wraps them. */
static inline void wrap_pair(int64_t i, int n, enum texture_wrap wrap, int *x0, int *x1)
{
    if (wrap == TEXTURE_REPEAT) {
        *x0 = (int)((uint64_t)i & (uint64_t)(n - 1));
        *x1 = (int)((uint64_t)(i + 1) & (uint64_t)(n - 1));
    } else {
        *x0 = i < 0 ? 0 : i >= n ? n - 1 : (int)i;
        *x1 = i + 1 < 0 ? 0 : i + 1 >= n ? n - 1 : (int)(i + 1);
    }
}

/* One level's bilinear taps for the quad's four pixels: where each
 * pixel's four texels are in the level (offsets into its texels, wrapped as
 * texel_at wraps them) and its weights, as bilinear_corner finds them. */
struct level_taps {
    int o00[4], o10[4], o01[4], o11[4];
    float a[4], b[4];
};

/* floor(u) of two doubles below 2^31 in size, and the same as int32 in
 * the low two lanes of *i: the truncation, one less where it rounded up. */
static inline __m128d floor2(__m128d u, __m128i *i)
{
    __m128i t = _mm_cvttpd_epi32(u);
    __m128d f = _mm_cvtepi32_pd(t);
    __m128d above = _mm_cmpgt_pd(f, u);
    *i = _mm_add_epi32(t, _mm_shuffle_epi32(_mm_castpd_si128(above), _MM_SHUFFLE(3, 3, 2, 0)));
    return _mm_sub_pd(f, _mm_and_pd(above, _mm_set1_pd(1)));
}

/* u - 1/2 (or v) of four pixels, its floor as four int32 and its fraction
 * as four floats; false when a lane is 2^30 texels out or more (or NaN). */
static inline bool corner4(const double s[4], double w, __m128i *i, __m128 *a)
{
    const __m128d scale = _mm_set1_pd(w), half = _mm_set1_pd(0.5), limit = _mm_set1_pd(0x1p30);
    const __m128d sign = _mm_set1_pd(-0.0);
    __m128d u0 = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(s), scale), half);
    __m128d u1 = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(s + 2), scale), half);
    __m128d in = _mm_and_pd(_mm_cmplt_pd(_mm_andnot_pd(sign, u0), limit),
                            _mm_cmplt_pd(_mm_andnot_pd(sign, u1), limit));
    if (_mm_movemask_pd(in) != 3)
        return false;
    __m128i i0, i1;
    __m128 a0 = _mm_cvtpd_ps(_mm_sub_pd(u0, floor2(u0, &i0)));
    __m128 a1 = _mm_cvtpd_ps(_mm_sub_pd(u1, floor2(u1, &i1)));
    *i = _mm_unpacklo_epi64(i0, i1);
    *a = _mm_movelh_ps(a0, a1);
    return true;
}

/* Four int32 held inside 0 .. hi (SSE2 has no min and max of int32). */
static inline __m128i clamp4(__m128i v, __m128i hi)
{
    v = _mm_and_si128(v, _mm_cmpgt_epi32(v, _mm_setzero_si128()));     /* below 0: 0 */
    __m128i above = _mm_cmpgt_epi32(v, hi);
    return _mm_or_si128(_mm_and_si128(above, hi), _mm_andnot_si128(above, v));
}

/* log2 of a power of two: the exponent of its float, exact */
static inline int log2_size(int n)
{
    float f = (float)n;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    return (int)(bits >> 23) - 127;
}

/* s and t of the quad's pixels (a helper's: anything, even NaN; `lanes`
 * says which are wanted). */
static inline void level_taps(const struct texture_level *l, enum texture_wrap wrap, const double s[4],
                              const double t[4], unsigned lanes, struct level_taps *o)
{
    double sl[4], tl[4];
    for (int p = 0; p < 4; p++)
        sl[p] = lanes >> p & 1 ? s[p] : 0, tl[p] = lanes >> p & 1 ? t[p] : 0;
    __m128i iu, iv;
    __m128 a, b;
    if (corner4(sl, l->w, &iu, &a) && corner4(tl, l->h, &iv, &b)) {
        const __m128i one = _mm_set1_epi32(1), mw = _mm_set1_epi32(l->w - 1), mh = _mm_set1_epi32(l->h - 1);
        int log2w = log2_size(l->w);
        __m128i x0, x1, y0, y1;
        if (wrap == TEXTURE_REPEAT) {   /* the mathematical mod of a power of two: the low bits, negatives too */
            x0 = _mm_and_si128(iu, mw), x1 = _mm_and_si128(_mm_add_epi32(iu, one), mw);
            y0 = _mm_and_si128(iv, mh), y1 = _mm_and_si128(_mm_add_epi32(iv, one), mh);
        } else {                        /* clamp: held inside 0 .. size - 1 */
            x0 = clamp4(iu, mw), x1 = clamp4(_mm_add_epi32(iu, one), mw);
            y0 = clamp4(iv, mh), y1 = clamp4(_mm_add_epi32(iv, one), mh);
        }
        __m128i row0 = _mm_sll_epi32(y0, _mm_cvtsi32_si128(log2w));
        __m128i row1 = _mm_sll_epi32(y1, _mm_cvtsi32_si128(log2w));
        _mm_storeu_si128((__m128i *)o->o00, _mm_add_epi32(row0, x0));
        _mm_storeu_si128((__m128i *)o->o10, _mm_add_epi32(row0, x1));
        _mm_storeu_si128((__m128i *)o->o01, _mm_add_epi32(row1, x0));
        _mm_storeu_si128((__m128i *)o->o11, _mm_add_epi32(row1, x1));
        _mm_storeu_ps(o->a, a);
        _mm_storeu_ps(o->b, b);
        return;
    }
    for (int p = 0; p < 4; p++) {       /* far out: bilinear_corner itself */
        int64_t i, j;
        int x0, x1, y0, y1;
        bilinear_corner(l, sl[p], tl[p], &i, &j, &o->a[p], &o->b[p]);
        wrap_pair(i, l->w, wrap, &x0, &x1);
        wrap_pair(j, l->h, wrap, &y0, &y1);
        o->o00[p] = y0 * l->w + x0, o->o10[p] = y0 * l->w + x1;
        o->o01[p] = y1 * l->w + x0, o->o11[p] = y1 * l->w + x1;
    }
}

/* Pixel p's bilinear tap from its level's taps. */
static inline __m128 bilinear4(const struct texture_level *l, const struct level_taps *o, int p)
{
    __m128 c00 = texel4(l->texel[o->o00[p]]), c10 = texel4(l->texel[o->o10[p]]);
    __m128 c01 = texel4(l->texel[o->o01[p]]), c11 = texel4(l->texel[o->o11[p]]);
    __m128 va = _mm_set1_ps(o->a[p]), vb = _mm_set1_ps(o->b[p]);
    __m128 top = _mm_add_ps(c00, _mm_mul_ps(va, _mm_sub_ps(c10, c00)));
    __m128 bottom = _mm_add_ps(c01, _mm_mul_ps(va, _mm_sub_ps(c11, c01)));
    return _mm_add_ps(top, _mm_mul_ps(vb, _mm_sub_ps(bottom, top)));
}

/* The texel times the colour (lanes b, g and r, 0), clamped, rounded once. */
static inline uint32_t modulate4(__m128 texel, __m128d bg, __m128d r0)
{
    __m128d lo = _mm_mul_pd(_mm_cvtps_pd(texel), bg);
    __m128d hi = _mm_mul_pd(_mm_cvtps_pd(_mm_movehl_ps(texel, texel)), r0);
    const __m128d zero = _mm_setzero_pd(), top = _mm_set1_pd(255), half = _mm_set1_pd(0.5);
    lo = _mm_add_pd(_mm_min_pd(_mm_max_pd(lo, zero), top), half);    /* a NaN becomes 0 */
    hi = _mm_add_pd(_mm_min_pd(_mm_max_pd(hi, zero), top), half);
    __m128i c = _mm_unpacklo_epi64(_mm_cvttpd_epi32(lo), _mm_cvttpd_epi32(hi));
    c = _mm_packus_epi16(_mm_packs_epi32(c, c), c);
    return 0xff000000u | (uint32_t)_mm_cvtsi128_si32(c);
}

/* pack_rgb of the quad's four pixels, r, g, b a pair of doubles per row:
 * clamped to [0, 1] (a NaN to 0), times 255, rounded half up. */
static inline void pack4(const struct quad2 c[3], uint32_t out[4])
{
    const __m128d zero = _mm_setzero_pd(), one = _mm_set1_pd(1), scale = _mm_set1_pd(255.0),
                  half = _mm_set1_pd(0.5);
    __m128i px = _mm_set1_epi32((int)0xff000000u);
    for (int k = 0; k < 3; k++) {
        __m128d top = _mm_min_pd(_mm_max_pd(c[k].top, zero), one);
        __m128d bottom = _mm_min_pd(_mm_max_pd(c[k].bottom, zero), one);
        __m128i v = _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_add_pd(_mm_mul_pd(top, scale), half)),
                                       _mm_cvttpd_epi32(_mm_add_pd(_mm_mul_pd(bottom, scale), half)));
        px = _mm_or_si128(px, _mm_sll_epi32(v, _mm_cvtsi32_si128(16 - 8 * k)));
    }
    _mm_storeu_si128((__m128i *)out, px);
}

/* Trilinear as the quad's lambda asks: levels k0 and k1 mixed by f (one
 * level when they are the same or f is 0): tex_filter_texel's rule. */
struct trilinear_at {
    int k0, k1;
    float f;
};

static inline struct trilinear_at trilinear_at(const struct texture *tex, const struct tex_deriv *d)
{
    double last = tex->nlevels - 1;
    if (!d->beyond) {   /* tex_lod's rho: magnified (log2 rho <= 0) when rho^2 <= 1, no log2 needed */
        double dudx = d->dsdx * d->w0, dvdx = d->dtdx * d->h0;
        double dudy = d->dsdy * d->w0, dvdy = d->dtdy * d->h0;
        double px2 = dudx * dudx + dvdx * dvdx, py2 = dudy * dudy + dvdy * dvdy;
        if (!((px2 > py2 ? px2 : py2) > 1))     /* (where sqrt rounds to 1, log2 gives 0) */
            return (struct trilinear_at){ 0, 0, 0 };
    }
    double lambda = d->beyond ? last : tex_lod(d);
    if (!(lambda > 0))
        return (struct trilinear_at){ 0, 0, 0 };
    lambda = lambda < last ? lambda : last;
    int k0 = (int)lambda, k1 = k0 + 1 < tex->nlevels ? k0 + 1 : k0;
    return (struct trilinear_at){ k0, k1, (float)(lambda - k0) };
}

/* Pixel p's trilinear texel from the taps of levels k0 and k1. */
static inline __m128 trilinear4(const struct texture *tex, struct trilinear_at at, const struct level_taps *o0,
                                const struct level_taps *o1, int p)
{
    __m128 a = bilinear4(&tex->level[at.k0], o0, p);
    if (at.k1 == at.k0 || at.f == 0)
        return a;
    __m128 b = bilinear4(&tex->level[at.k1], o1, p);
    return _mm_add_ps(a, _mm_mul_ps(_mm_set1_ps(at.f), _mm_sub_ps(b, a)));
}

/* What one triangle's quads share. */
struct twin {
    const struct tri_setup *t;
    const struct raster_params *p;
    struct target *fb;
    struct trace *tr;
    const struct texture *tex;
    enum tex_filter filter;
    int max_aniso;
    struct biased_edges e;
    __m128d area2;
    double s_k[3], t_k[3], ones[3];
    double col[3][3];                   /* r, g, b of A, B and C */
    double iz[3], sq[3], tq[3], cq[3][3];   /* ... over z: 1/z, s/z, t/z, r/z, g/z, b/z */
    double tie[2];                      /* nearest: how close to a texel's edge asks the weights */
    const struct tex_tile *d;           /* the tiled twin's tile, or NULL: the target */
};

/* Would depth z pass at pixel (x, y): in the tile, or on the target. */
static inline bool depth_pass(const struct twin *tw, int x, int y, float z)
{
    const struct tex_tile *d = tw->d;
    if (!d)
        return target_depth_pass(tw->fb, x, y, z);
    return z < d->depth[(size_t)(y - d->y0) * (size_t)d->stride + (size_t)(x - d->x0)];
}

/* A covered pixel written as PLOT writes it (counted, then depth-tested):
 * on the target, or in the tile, narrated there as the write it is. */
static inline void write_pixel(const struct twin *tw, int x, int y, float z, uint32_t rgba)
{
    const struct tex_tile *d = tw->d;
    if (!d) {
        PLOT(tw->fb, tw->tr, L_WRITE, x, y, z, rgba);
        return;
    }
    size_t o = (size_t)(y - d->y0) * (size_t)d->stride + (size_t)(x - d->x0);
    bool pass = z < d->depth[o];
    NARRATE(tw->tr, .kind = TRACE_PIXEL_WRITE, .line = L_WRITE, .x = x, .y = y, .z = z, .rgba = rgba,
            .flags = pass ? TRACE_DEPTH_PASS : 0);
    if (trace_frozen(tw->tr))
        return;
    size_t oc = (size_t)(y - d->y0) * (size_t)d->count_stride + (size_t)(x - d->x0);
    if (d->count && d->count[oc] < 255)
        d->count[oc]++;
    if (pass)
        d->depth[o] = z, d->color[o] = rgba;
}

/* The quad's derivatives in level-0 texels, rho and the lambda of the
 * lesson's level of detail, told as the lesson tells them. */
static inline void narrate_deriv(const struct twin *tw, int qx, int qy, unsigned covered,
                                 const struct tex_deriv *d)
{
    if (!(NARRATING && tw->tr))
        return;
    double dudx = d->dsdx * d->w0, dvdx = d->dtdx * d->h0, dudy = d->dsdy * d->w0, dvdy = d->dtdy * d->h0;
    double rho = fmax(sqrt(dudx * dudx + dvdx * dvdx), sqrt(dudy * dudy + dvdy * dvdy));
    NARRATE(tw->tr, .kind = TRACE_STEP, .line = L_LOD, .span = L_LOD - L_DERIV, .x = qx, .y = qy,
            .mask = { (uint16_t)covered }, .flags = d->beyond ? 0 : TRACE_INSIDE,
            .aux = { (float)dudx, (float)dvdx, (float)dudy, (float)dvdy, (float)rho,
                     d->beyond ? (float)(tw->tex->nlevels - 1) : (float)tex_lod(d) });
}

/* The quad whose top-left pixel is (qx, qy). */
static inline void quad_sse(const struct twin *tw, int qx, int qy)
{
    static const int edge_of[3] = { EDGE_BC, EDGE_CA, EDGE_AB };   /* the edge of weight k */
    const struct tri_setup *t = tw->t;
    const struct texture *tex = tw->tex;
    /* coverage: the biased edge values of the four pixels, exact */
    unsigned covered = 0xF;
    int64_t raw[3];
    for (int k = 0; k < 3; k++) {
        int64_t f = biased_edge_at(&tw->e, k, qx, qy), dx = tw->e.dx[k], dy = tw->e.dy[k];
        covered &= (unsigned)(f >= 0) | (unsigned)(f + dx >= 0) << 1
                 | (unsigned)(f + dy >= 0) << 2 | (unsigned)(f + dx + dy >= 0) << 3;
        raw[k] = f - tw->e.bias[k];
    }
    /* ... and inside the box (a pixel past the target's edge is never covered) */
    if (qx < t->minx) covered &= ~5u;
    if (qx + 1 > t->maxx) covered &= ~10u;
    if (qy < t->miny) covered &= ~3u;
    if (qy + 1 > t->maxy) covered &= ~12u;
    for (int i = 0; NARRATING && tw->tr && i < 4; i++)
        NARRATE(tw->tr, .kind = TRACE_PIXEL_TEST, .line = L_COVER, .x = qx + (i & 1), .y = qy + (i >> 1),
                .e = { raw[0] + (i & 1) * tw->e.dx[0] + (i >> 1) * tw->e.dy[0],
                       raw[1] + (i & 1) * tw->e.dx[1] + (i >> 1) * tw->e.dy[1],
                       raw[2] + (i & 1) * tw->e.dx[2] + (i >> 1) * tw->e.dy[2] },
                .flags = (covered >> i & 1) ? TRACE_INSIDE : 0);
    if (!covered) {
        NARRATE(tw->tr, .kind = TRACE_STEP, .line = L_SKIP, .x = qx, .y = qy);
        return;
    }
    /* the edge values opposite A, B and C at the four centres: exact in
     * doubles, and so are their sums */
    struct quad2 F[3];
    for (int k = 0; k < 3; k++) {
        int j = edge_of[k];
        double f = (double)raw[j], dx = (double)tw->e.dx[j], dy = (double)tw->e.dy[j];
        F[k] = (struct quad2){ _mm_set_pd(f + dx, f), _mm_set_pd((f + dy) + dx, f + dy) };
    }
    struct quad2 vq, depth, rgb[3], vs, vt;
    if (tex) {
        /* textured: q = sum F_k Q_k, one reciprocal r, then s, t, the colour
         * and the depth 2 area r (textures.h) */
        vq = pair_sum3(F, tw->iz);
        struct quad2 rq = pair_div((struct quad2){ _mm_set1_pd(1), _mm_set1_pd(1) }, vq);
        depth = (struct quad2){ _mm_mul_pd(tw->area2, rq.top), _mm_mul_pd(tw->area2, rq.bottom) };
        for (int c = 0; c < 3; c++)
            rgb[c] = pair_mul(pair_sum3(F, tw->cq[c]), rq);
        vs = pair_mul(pair_sum3(F, tw->sq), rq), vt = pair_mul(pair_sum3(F, tw->tq), rq);
    } else {
        /* untextured: the weights of A, B, C over z, then 1/z, the depth
         * 1 / (1/z), the vertex colour sum_k w_k c_k times it, s and t */
        struct quad2 w[3];
        for (int k = 0; k < 3; k++) {
            __m128d z = _mm_set1_pd(t->v[k].z);
            w[k].top = _mm_div_pd(_mm_div_pd(F[k].top, tw->area2), z);
            w[k].bottom = _mm_div_pd(_mm_div_pd(F[k].bottom, tw->area2), z);
        }
        vq = pair_sum3(w, tw->ones);
        depth = pair_div((struct quad2){ _mm_set1_pd(1), _mm_set1_pd(1) }, vq);
        for (int c = 0; c < 3; c++)
            rgb[c] = pair_mul(pair_sum3(w, tw->col[c]), depth);
        if (!(tw->p->checker > 0) && !(NARRATING && tw->tr)) {
            /* no checker: no s and t, the four colours packed at once */
            double zs[4];
            uint32_t rgba[4];
            _mm_storeu_pd(zs, depth.top), _mm_storeu_pd(zs + 2, depth.bottom);
            pack4(rgb, rgba);
            for (int i = 0; i < 4; i++)
                if (covered >> i & 1)
                    write_pixel(tw, qx + (i & 1), qy + (i >> 1), (float)zs[i], rgba[i]);
            return;
        }
        vs = pair_div(pair_sum3(w, tw->s_k), vq), vt = pair_div(pair_sum3(w, tw->t_k), vq);
    }
    double qs[4], zs[4], s[4], tt[4], cb[4], cg[4], cr[4];
    _mm_storeu_pd(zs, depth.top), _mm_storeu_pd(zs + 2, depth.bottom);
    _mm_storeu_pd(qs, vq.top), _mm_storeu_pd(qs + 2, vq.bottom);
    _mm_storeu_pd(s, vs.top), _mm_storeu_pd(s + 2, vs.bottom);
    _mm_storeu_pd(tt, vt.top), _mm_storeu_pd(tt + 2, vt.bottom);
    double *out[3] = { cr, cg, cb };
    for (int c = 0; c < 3; c++)
        _mm_storeu_pd(out[c], rgb[c].top), _mm_storeu_pd(out[c] + 2, rgb[c].bottom);
    double W = tex ? tex->level[0].w : 1, H = tex ? tex->level[0].h : 1;
    for (int i = 0; NARRATING && tw->tr && i < 4; i++)
        NARRATE(tw->tr, .kind = TRACE_STEP, .line = L_EVAL, .x = qx + (i & 1), .y = qy + (i >> 1),
                .flags = (covered >> i & 1) ? TRACE_INSIDE : 0,
                .aux = { (float)(s[i] * W), (float)(tt[i] * H), (float)(tex ? qs[i] / (double)t->area2 : qs[i]) });
    if (!tex) {             /* untextured: the shared shading (and the checker), as the lesson's */
        for (int i = 0; i < 4; i++)
            if (covered >> i & 1)
                write_pixel(tw, qx + (i & 1), qy + (i >> 1), (float)zs[i],
                            shade_pixel(tw->p, tw->tr, cr[i], cg[i], cb[i], s[i], tt[i]));
        return;
    }
    /* the quad's derivatives, and trilinear's levels for all four pixels */
    bool beyond = !(qs[0] > 0) || !(qs[1] > 0) || !(qs[2] > 0) || !(qs[3] > 0);
    struct tex_deriv d = { .dsdx = s[1] - s[0], .dtdx = tt[1] - tt[0], .dsdy = s[2] - s[0],
                           .dtdy = tt[2] - tt[0], .w0 = tex->level[0].w, .h0 = tex->level[0].h,
                           .beyond = beyond };
    narrate_deriv(tw, qx, qy, covered, &d);
    struct trilinear_at at = { 0, 0, 0 };
    struct level_taps taps[2];
    if (tw->filter == FILTER_TRILINEAR) {
        at = trilinear_at(tex, &d);
        level_taps(&tex->level[at.k0], tex->wrap, s, tt, covered, &taps[0]);
        if (at.k1 != at.k0 && at.f != 0)
            level_taps(&tex->level[at.k1], tex->wrap, s, tt, covered, &taps[1]);
    }
    for (int i = 0; i < 4; i++) {
        if (!(covered >> i & 1))
            continue;
        int x = qx + (i & 1), y = qy + (i >> 1);
        float z = (float)zs[i];
        if (!depth_pass(tw, x, y, z)) {
            write_pixel(tw, x, y, z, 0);        /* counted, hidden: no texel needed */
            continue;
        }
        __m128 texel;
        struct tex_used u = { .taps = 1 };
        if (tw->filter == FILTER_TRILINEAR) {
            texel = trilinear4(tex, at, &taps[0], &taps[1], i);
            if (NARRATING && tw->tr)    /* what the texture unit used, told as the lesson tells it */
                tex_filter_texel(tex, tw->filter, tw->max_aniso, s[i], tt[i], &d, &tex_stages_lesson, &u);
        } else {                /* the other filters: the texture unit's own code */
            if (tw->filter == FILTER_NEAREST
                && (tex_near_edge(s[i] * W, tw->tie[0]) || tex_near_edge(tt[i] * H, tw->tie[1]))) {
                /* on a texel's edge, or all but: the weights decide which texel (textures.h) */
                double fk[3];
                for (int k = 0; k < 3; k++) {
                    int j = edge_of[k];
                    fk[k] = (double)(raw[j] + (i & 1) * tw->e.dx[j] + (i >> 1) * tw->e.dy[j]);
                }
                tex_st_by_weights(t, fk, &s[i], &tt[i]);
            }
            struct texel_rgb c = tex_filter_texel(tex, tw->filter, tw->max_aniso, s[i], tt[i], &d,
                                                  &tex_stages_lesson, &u);
            texel = _mm_setr_ps(c.c[2], c.c[1], c.c[0], 0);
        }
        NARRATE(tw->tr, .kind = TRACE_STEP, .line = L_FILTER, .x = x, .y = y,
                .mask = { (uint16_t)covered, (uint16_t)u.taps, (uint16_t)tw->filter },
                .aux = { (float)(s[i] * W), (float)(tt[i] * H), u.lambda, (float)u.level0,
                         (float)u.level1, u.mix });
        write_pixel(tw, x, y, z, modulate4(texel, _mm_set_pd(cg[i], cb[i]), _mm_set_pd(0, cr[i])));
    }
}

/* The twin's state for triangle t (not empty). */
static void twin_init(struct twin *tw, const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr, const struct tex_tile *d)
{
    *tw = (struct twin){ .t = t, .p = p, .fb = fb, .tr = tr, .tex = p->texture, .filter = tex_filter_of(p),
                         .max_aniso = tex_max_aniso_of(p), .area2 = _mm_set1_pd((double)t->area2),
                         .ones = { 1, 1, 1 }, .d = d };
    biased_edges_setup(&tw->e, t, true);
    for (int k = 0; k < 3; k++) {
        tw->s_k[k] = t->v[k].s, tw->t_k[k] = t->v[k].t;
        tw->col[0][k] = t->v[k].r, tw->col[1][k] = t->v[k].g, tw->col[2][k] = t->v[k].b;
        tw->iz[k] = 1 / t->v[k].z;
        tw->sq[k] = t->v[k].s * tw->iz[k], tw->tq[k] = t->v[k].t * tw->iz[k];
        for (int c = 0; c < 3; c++)
            tw->cq[c][k] = tw->col[c][k] * tw->iz[k];
    }
    if (tw->tex)
        tex_tie_bounds(t, tw->tex->level[0].w, tw->tex->level[0].h, tw->tie);
}

/* The lesson's walk over the pixels x0..x1, y0..y1 of the box: its 8 x 8
 * blocks (aligned on the screen), the empty ones skipped, then their quads. */
static void walk(const struct twin *tw, int x0, int y0, int x1, int y1)
{
    for (int by = y0 - y0 % TEX_BLOCK; by <= y1; by += TEX_BLOCK)
        for (int bx = x0 - x0 % TEX_BLOCK; bx <= x1; bx += TEX_BLOCK) {
            int xa = bx < x0 ? x0 : bx, xb = bx + TEX_BLOCK - 1 > x1 ? x1 : bx + TEX_BLOCK - 1;
            int ya = by < y0 ? y0 : by, yb = by + TEX_BLOCK - 1 > y1 ? y1 : by + TEX_BLOCK - 1;
            bool empty = tex_block_empty(&tw->e, xa, ya, xb, yb);
            int line = empty ? L_EMPTY : L_QUADS;
            NARRATE(tw->tr, .kind = TRACE_BLOCK, .line = (uint8_t)line, .span = (uint8_t)(line - L_BLOCKS),
                    .x = xa, .y = ya, .x1 = xb, .y1 = yb,
                    .klass = (uint8_t)(empty ? BLOCK_EMPTY : BLOCK_PARTIAL), .aux = { TEX_BLOCK });
            if (empty)
                continue;
            for (int qy = ya & ~1; qy <= yb && !trace_frozen(tw->tr); qy += 2)
                for (int qx = xa & ~1; qx <= xb && !trace_frozen(tw->tr); qx += 2)
                    quad_sse(tw, qx, qy);
        }
}

void tex_rasterize_sse(const struct tri_setup *t, const struct raster_params *p,
                       struct target *fb, struct trace *tr)
{
    if (p->knob[P_AFFINE]) {    /* the exhibit is the lesson's own loop, not a fast path */
        textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .affine = true });
        return;
    }
    NARRATE_SETUP(tr, t, L_SETUP);
    if (t->empty)
        return;
    struct twin tw;
    twin_init(&tw, t, p, fb, tr, NULL);
    walk(&tw, t->minx, t->miny, t->maxx, t->maxy);
}

void tex_draw_in_tile(const struct tri_setup *t, const struct raster_params *p,
                      const struct tex_tile *d, struct trace *tr)
{
    int x0 = t->minx > d->x0 ? t->minx : d->x0, y0 = t->miny > d->y0 ? t->miny : d->y0;
    int x1 = t->maxx < d->x0 + d->w - 1 ? t->maxx : d->x0 + d->w - 1;
    int y1 = t->maxy < d->y0 + d->h - 1 ? t->maxy : d->y0 + d->h - 1;
    if (t->empty || x0 > x1 || y0 > y1)
        return;
    struct twin tw;
    twin_init(&tw, t, p, NULL, tr, d);
    walk(&tw, x0, y0, x1, y1);
}
