/* Lesson 09's fast twin: the quads of textures.c with a quad in SSE lanes.
 *
 * The same pixels, the same bytes: every value a pixel's colour depends on
 * is computed by the same IEEE operations in the same order, only four
 * pixels at a time (two pairs of doubles for the weights and the divides).
 * What is different is the walk: the box's quads row by row, with no block
 * classification, coverage from the edge values of the quad's four pixels
 * at once, and a pixel's texel sampled only once it passes the depth test.
 *
 *      lanes:   [ TL | TR ]  the quad's top row     (x0, x0 + 1) at y0
 *               [ BL | BR ]  its bottom row         (x0, x0 + 1) at y0 + 1
 *
 * The edge values are exact integers below 2^47, so they and their sums
 * are exact in doubles too: coverage tested on doubles is the integer
 * test, and the weights F_k / (2 area) are the narrated ones, bit for bit.
 */
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

/* One level's bilinear taps for the quad's four pixels: the wrapped
 * columns and rows of each pixel's four texels and its weights, as
 * bilinear_corner finds them. The quad's u and v at once: u = s W - 1/2,
 * floor(u) from the truncation (exact below 2^31 texels), a = u - floor(u)
 * as a float; a lane out of that range (or a NaN) is found by
 * bilinear_corner itself. Pixels not in `lanes` are left alone. */
struct level_taps {
    int x0[4], x1[4], y0[4], y1[4];
    float a[4], b[4];
};

static inline __m128d floor2(__m128d u, __m128i *i)
{
    __m128i t = _mm_cvttpd_epi32(u);
    __m128d f = _mm_cvtepi32_pd(t);
    __m128d above = _mm_cmpgt_pd(f, u);         /* negative and not whole: one less */
    *i = _mm_add_epi32(t, _mm_shuffle_epi32(_mm_castpd_si128(above), _MM_SHUFFLE(3, 3, 2, 0)));
    return _mm_sub_pd(f, _mm_and_pd(above, _mm_set1_pd(1)));
}

static inline void level_taps(const struct texture_level *l, enum texture_wrap wrap, const double s[4],
                              const double t[4], unsigned lanes, struct level_taps *o)
{
    const __m128d w = _mm_set1_pd(l->w), h = _mm_set1_pd(l->h), half = _mm_set1_pd(0.5);
    const __m128d limit = _mm_set1_pd(0x1p30), sign = _mm_set1_pd(-0.0);
    int64_t ii[4], jj[4];
    bool wide = false;
    for (int p = 0; p < 4; p += 2) {
        __m128d u = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(s + p), w), half);
        __m128d v = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(t + p), h), half);
        __m128d in = _mm_and_pd(_mm_cmplt_pd(_mm_andnot_pd(sign, u), limit),
                                _mm_cmplt_pd(_mm_andnot_pd(sign, v), limit));
        int ok = _mm_movemask_pd(in), want = (int)(lanes >> p & 3);
        if ((ok & want) != want) {
            wide = true;
            break;
        }
        __m128i iu, iv;
        __m128 a = _mm_cvtpd_ps(_mm_sub_pd(u, floor2(u, &iu)));
        __m128 b = _mm_cvtpd_ps(_mm_sub_pd(v, floor2(v, &iv)));
        int32_t i32[4], j32[4];
        _mm_storeu_si128((__m128i *)i32, iu);
        _mm_storeu_si128((__m128i *)j32, iv);
        float af[4], bf[4];
        _mm_storeu_ps(af, a), _mm_storeu_ps(bf, b);
        for (int k = 0; k < 2; k++)
            ii[p + k] = i32[k], jj[p + k] = j32[k], o->a[p + k] = af[k], o->b[p + k] = bf[k];
    }
    for (int p = 0; p < 4; p++) {
        if (!(lanes >> p & 1))
            continue;
        if (wide)
            bilinear_corner(l, s[p], t[p], &ii[p], &jj[p], &o->a[p], &o->b[p]);
        wrap_pair(ii[p], l->w, wrap, &o->x0[p], &o->x1[p]);
        wrap_pair(jj[p], l->h, wrap, &o->y0[p], &o->y1[p]);
    }
}

/* Pixel p's bilinear tap from its level's taps. */
static inline __m128 bilinear4(const struct texture_level *l, const struct level_taps *o, int p)
{
    const uint32_t *row0 = l->texel + (size_t)o->y0[p] * (size_t)l->w;
    const uint32_t *row1 = l->texel + (size_t)o->y1[p] * (size_t)l->w;
    __m128 c00 = texel4(row0[o->x0[p]]), c10 = texel4(row0[o->x1[p]]);
    __m128 c01 = texel4(row1[o->x0[p]]), c11 = texel4(row1[o->x1[p]]);
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

/* Trilinear as the quad's lambda asks: levels k0 and k1 mixed by f (one
 * level when they are the same or f is 0): tex_filter_texel's rule. */
struct trilinear_at {
    int k0, k1;
    float f;
};

static inline struct trilinear_at trilinear_at(const struct texture *tex, const struct tex_deriv *d)
{
    double last = tex->nlevels - 1;
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

void tex_rasterize_sse(const struct tri_setup *t, const struct raster_params *p,
                       struct target *fb, struct trace *tr)
{
    const struct texture *tex = p->texture;
    if (!tex) {     /* untextured: the shared shading, as the lesson draws it */
        textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .lod = LOD_COARSE });
        return;
    }
    NARRATE_SETUP(tr, t, L_SETUP);
    if (t->empty)
        return;
    enum tex_filter filter = tex_filter_of(p);
    int max_aniso = tex_max_aniso_of(p);
    struct biased_edges e;
    biased_edges_setup(&e, t, true);
    double s_k[3], t_k[3], ones[3] = { 1, 1, 1 };
    __m128d col_bg[3], col_r0[3];       /* the vertex colours, lanes (b, g) and (r, 0) */
    for (int k = 0; k < 3; k++) {
        s_k[k] = t->v[k].s, t_k[k] = t->v[k].t;
        col_bg[k] = _mm_set_pd(t->v[k].g, t->v[k].b);
        col_r0[k] = _mm_set_pd(0, t->v[k].r);
    }
    const __m128d area2 = _mm_set1_pd((double)t->area2);
    static const int edge_of[3] = { EDGE_BC, EDGE_CA, EDGE_AB };   /* the edge of weight k */
    const int W = tex->level[0].w, H = tex->level[0].h;
    for (int qy = t->miny & ~1; qy <= t->maxy; qy += 2) {
        for (int qx = t->minx & ~1; qx <= t->maxx; qx += 2) {
            /* coverage: the biased edge values of the four pixels, exact */
            unsigned covered = 0xF;
            int64_t raw[3];
            for (int k = 0; k < 3; k++) {
                int64_t f = biased_edge_at(&e, k, qx, qy), dx = e.dx[k], dy = e.dy[k];
                covered &= (unsigned)(f >= 0) | (unsigned)(f + dx >= 0) << 1
                         | (unsigned)(f + dy >= 0) << 2 | (unsigned)(f + dx + dy >= 0) << 3;
                raw[k] = f - e.bias[k];
            }
            /* ... and inside the box (a pixel past the target's edge is never covered) */
            if (qx < t->minx) covered &= ~5u;
            if (qx + 1 > t->maxx) covered &= ~10u;
            if (qy < t->miny) covered &= ~3u;
            if (qy + 1 > t->maxy) covered &= ~12u;
            if (!covered)
                continue;
            /* the weights of A, B, C over z at the four centres, then the planes */
            struct quad2 w[3];
            for (int k = 0; k < 3; k++) {
                int j = edge_of[k];
                double f = (double)raw[j], dx = (double)e.dx[j], dy = (double)e.dy[j];
                __m128d z = _mm_set1_pd(t->v[k].z);
                w[k].top = _mm_div_pd(_mm_div_pd(_mm_set_pd(f + dx, f), area2), z);
                w[k].bottom = _mm_div_pd(_mm_div_pd(_mm_set_pd((f + dy) + dx, f + dy), area2), z);
            }
            struct quad2 vq = pair_sum3(w, ones);
            struct quad2 vs = pair_div(pair_sum3(w, s_k), vq), vt = pair_div(pair_sum3(w, t_k), vq);
            double qs[4], s[4], tt[4], wl[3][4];
            _mm_storeu_pd(qs, vq.top), _mm_storeu_pd(qs + 2, vq.bottom);
            _mm_storeu_pd(s, vs.top), _mm_storeu_pd(s + 2, vs.bottom);
            _mm_storeu_pd(tt, vt.top), _mm_storeu_pd(tt + 2, vt.bottom);
            for (int k = 0; k < 3; k++)
                _mm_storeu_pd(wl[k], w[k].top), _mm_storeu_pd(wl[k] + 2, w[k].bottom);
            bool beyond = !(qs[0] > 0) || !(qs[1] > 0) || !(qs[2] > 0) || !(qs[3] > 0);
            struct tex_deriv d = { .dsdx = s[1] - s[0], .dtdx = tt[1] - tt[0], .dsdy = s[2] - s[0],
                                   .dtdy = tt[2] - tt[0], .w0 = W, .h0 = H, .beyond = beyond };
            struct trilinear_at at = { 0, 0, 0 };
            struct level_taps taps[2];
            if (filter == FILTER_TRILINEAR) {
                at = trilinear_at(tex, &d);         /* one lambda for the quad */
                level_taps(&tex->level[at.k0], tex->wrap, s, tt, covered, &taps[0]);
                if (at.k1 != at.k0 && at.f != 0)
                    level_taps(&tex->level[at.k1], tex->wrap, s, tt, covered, &taps[1]);
            }
            for (int i = 0; i < 4; i++) {
                if (!(covered >> i & 1))
                    continue;
                int x = qx + (i & 1), y = qy + (i >> 1);
                float z = (float)(1 / qs[i]);
                if (!target_depth_pass(fb, x, y, z)) {
                    target_write(fb, x, y, z, 0);   /* counted, hidden: no texel needed */
                    continue;
                }
                /* the vertex colour: sum_k w_k c_k from 0, over 1/z, as the narrated sum */
                __m128d bg = _mm_setzero_pd(), r0 = _mm_setzero_pd(), q = _mm_set1_pd(qs[i]);
                for (int k = 0; k < 3; k++) {
                    __m128d wk = _mm_set1_pd(wl[k][i]);
                    bg = _mm_add_pd(bg, _mm_mul_pd(wk, col_bg[k]));
                    r0 = _mm_add_pd(r0, _mm_mul_pd(wk, col_r0[k]));
                }
                bg = _mm_div_pd(bg, q), r0 = _mm_div_pd(r0, q);
                __m128 texel;
                if (filter == FILTER_TRILINEAR) {
                    texel = trilinear4(tex, at, &taps[0], &taps[1], i);
                } else {
                    struct texel_rgb c = tex_filter_texel(tex, filter, max_aniso, s[i], tt[i], &d,
                                                          &tex_stages_lesson, NULL);
                    texel = _mm_setr_ps(c.c[2], c.c[1], c.c[0], 0);
                }
                PLOT(fb, tr, L_WRITE, x, y, z, modulate4(texel, bg, r0));
            }
        }
    }
}
