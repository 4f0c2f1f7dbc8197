/* Lesson 08's tiled twin, its pixels: msaa's per-sample
 * rule (multisampling.c: sample_mask, shade, resolve, store), four samples a
 * register (AVX2), in the same double arithmetic, so the same bytes:
 *
 *   cover: F0k + O_sk >= 0 for k = 1, 2, 3, the four samples' 64-bit edge
 *          values at once (a FULL block: every sample, no test);
 *   depth: 1/z at the centre (the four planes 1/z, r, g, b in one register:
 *          P0 + Px dx + Py dy), plus each sample's offset, z = 1 / (1/z) for
 *          four samples in one division, rounded to float as msaa rounds;
 *   write: a sample nearer than the tile's takes the pixel's colour, which
 *          is shaded (msaa's colour_of) only when some sample passes.
 *
 * Under overdraw most samples are hidden: a float estimate that proves it
 * (sure_hidden) skips the division, for four pixels of a FULL block at once
 * where it can. The pixel is marked for the resolve at the tile's store
 * (tiled.c). Runs where the CPU has AVX2, at 4 or 8 samples (elsewhere
 * msaa's own loops), in both builds: narrated, a partial block's pixel
 * tells its mask and its write as msaa's partial_block does (the write with
 * the pixel's resolved colour, its new samples held back until the step
 * has happened), so the explorer steps this very code. */
#include <string.h>

#include "multisampling.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TRISTEP_SIMDE)
#include <immintrin.h>
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF    /* no fused multiply-add: msaa's roundings */
#endif
#define AVX2 __attribute__((target("avx2")))

/* The colour msaa gives the pixel whose plane values are v[]. */
static uint32_t colour_at(const struct run *r, const double v[PL_COUNT])
{
    double z = 1.0 / v[PL_INV_Z];
    return shade_scaled(r->p, NULL, v[PL_R] * z, v[PL_G] * z, v[PL_B] * z, v[PL_S] * z, v[PL_T] * z);
}

/* The mask of pixel (x, y)'s covered samples, from its centre values cx[]
 * (bias folded in): each register's four samples, 64-bit edge values. */
AVX2 static unsigned mask_avx2(__m256i (*off)[3], int regs, int64_t c0, int64_t c1, int64_t c2)
{
    __m256i minus_one = _mm256_set1_epi64x(-1);
    unsigned mask = 0;
    for (int h = 0; h < regs; h++) {
        __m256i in = _mm256_and_si256(
            _mm256_and_si256(_mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(c0), off[h][0]), minus_one),
                             _mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(c1), off[h][1]), minus_one)),
            _mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(c2), off[h][2]), minus_one));
        mask |= (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(in)) << 4 * h;
    }
    return mask;
}

/* Hidden for sure, no division: z > the sample's depth d when 1/z in float
 * and its reciprocal estimate (relative error under 2^-11 in all) put it
 * beyond d with room to spare; then msaa's z, rounded, is >= d: no pass. */
AVX2 static __m128 sure_hidden(__m128 inv_z, __m128 d)
{
    return _mm_and_ps(_mm_and_ps(_mm_cmpgt_ps(inv_z, _mm_set1_ps(1e-30f)), _mm_cmplt_ps(inv_z, _mm_set1_ps(1e30f))),
                      _mm_cmpge_ps(_mm_mul_ps(_mm_rcp_ps(inv_z), _mm_set1_ps(0.998f)), d));
}

/* Whether every sample of the four pixels at sd (n samples each, a FULL
 * block's) is hidden for sure; inv_z: 1/z at their centres, off: at the
 * samples. Sample by sample, the four pixels a register. */
AVX2 static bool hidden4_avx2(const float *sd, int n, __m256d inv_z, const double off[SAMPLES_MAX])
{
    for (int h = 0; h < n; h += 4) {
        __m128 d0 = _mm_loadu_ps(sd + h), d1 = _mm_loadu_ps(sd + n + h);
        __m128 d2 = _mm_loadu_ps(sd + 2 * n + h), d3 = _mm_loadu_ps(sd + 3 * n + h);
        _MM_TRANSPOSE4_PS(d0, d1, d2, d3);      /* d_s: sample h + s of the four */
        __m128 d[4] = { d0, d1, d2, d3 }, sure = _mm_castsi128_ps(_mm_set1_epi32(-1));
        for (int s = 0; s < 4; s++)
            sure = _mm_and_ps(sure, sure_hidden(_mm256_cvtpd_ps(_mm256_add_pd(
                                  inv_z, _mm256_set1_pd(off[h + s]))), d[s]));
        if (_mm_movemask_ps(sure) != 0xF)
            return false;
    }
    return true;
}

AVX2 static void pixels_avx2(const struct run *r, int x0, int y0, int x1, int y1, bool full)
{
    const struct planes *pl = &r->pl;
    const struct biased_edges *e = &r->e.b;
    int n = r->pt.n, regs = n / 4;
    /* per register h: samples 4h .. 4h + 3, their offsets on each edge and
     * on the plane of 1/z; what a mask's four bits select, as lanes */
    __m256i off[2][3];
    __m256d inv_off[2];
    for (int h = 0; h < regs; h++) {
        for (int k = 0; k < 3; k++)
            off[h][k] = _mm256_setr_epi64x(r->e.off[4 * h][k], r->e.off[4 * h + 1][k],
                                           r->e.off[4 * h + 2][k], r->e.off[4 * h + 3][k]);
        inv_off[h] = _mm256_setr_pd(r->plane_off[4 * h][PL_INV_Z], r->plane_off[4 * h + 1][PL_INV_Z],
                                    r->plane_off[4 * h + 2][PL_INV_Z], r->plane_off[4 * h + 3][PL_INV_Z]);
    }
    double offz[SAMPLES_MAX];
    for (int i = 0; i < n; i++)
        offz[i] = r->plane_off[i][PL_INV_Z];
    __m256d p0z = _mm256_set1_pd(pl->p0[PL_INV_Z]), pxz = _mm256_set1_pd(pl->px[PL_INV_Z]);
    __m256d pyz = _mm256_set1_pd(pl->py[PL_INV_Z]);
    __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
    __m256d p0 = _mm256_loadu_pd(pl->p0), px = _mm256_loadu_pd(pl->px), py = _mm256_loadu_pd(pl->py);
    __m256d p0_st = _mm256_setr_pd(pl->p0[PL_S], pl->p0[PL_T], 0, 0);
    __m256d px_st = _mm256_setr_pd(pl->px[PL_S], pl->px[PL_T], 0, 0);
    __m256d py_st = _mm256_setr_pd(pl->py[PL_S], pl->py[PL_T], 0, 0);
    bool st = r->nplanes > PL_S;
    unsigned all = (1u << n) - 1;
    /* what the loops read, in locals: a byte stored (a count) may alias any
     * field of *r, which the compiler would then read again */
    int sx = r->sx, sy = r->sy, plx = pl->x0, ply = pl->y0;
    size_t srow = r->srow, w = (size_t)r->fb->w;
    float *sdepth = r->sdepth;
    uint32_t *scolor = r->scolor;
    uint64_t *touched = r->touched;
    uint8_t *counts = r->fb->count;
    int64_t dx0 = e->dx[0], dx1 = e->dx[1], dx2 = e->dx[2];
    int64_t cy[3] = { biased_edge_at(e, 0, x0, y0), biased_edge_at(e, 1, x0, y0),
                      biased_edge_at(e, 2, x0, y0) };
    for (int y = y0; y <= y1; y++) {
        int64_t c0 = cy[0], c1 = cy[1], c2 = cy[2];
        __m256d dy = _mm256_set1_pd((double)(y - ply));
        uint8_t *count = counts ? counts + (size_t)y * w : NULL;
        uint64_t row = 0;       /* the pixels written, for the resolve */
        size_t at = ((size_t)(y - sy) * srow + (size_t)(x0 - sx)) * (size_t)n;
        for (int x = x0; x <= x1; x++, at += (size_t)n) {
            if (full && x + 3 <= x1) {  /* four pixels behind what the tile holds: skipped */
                __m256d dx4 = _mm256_add_pd(_mm256_set1_pd((double)(x - plx)), _mm256_setr_pd(0, 1, 2, 3));
                __m256d inv_z4 = _mm256_add_pd(_mm256_add_pd(p0z, _mm256_mul_pd(pxz, dx4)), _mm256_mul_pd(pyz, dy));
                if (hidden4_avx2(sdepth + at, n, inv_z4, offz)) {
                    for (int i = 0; i < 4; i++) {
                        row |= (uint64_t)1 << (x + i - sx);
                        if (count)
                            count[x + i] = (uint8_t)(count[x + i] + n < 255 ? count[x + i] + n : 255);
                    }
                    x += 3, at += 3 * (size_t)n;
                    continue;
                }
            }
            unsigned mask = all;
            if (!full) {
                mask = mask_avx2(off, regs, c0, c1, c2);
                NARRATE(r->tr, .kind = TRACE_PIXEL_TEST, .line = MS_LINE_MASK, .x = x, .y = y,
                        .e = { c0 - e->bias[0], c1 - e->bias[1], c2 - e->bias[2] },
                        .flags = mask ? TRACE_INSIDE : 0, .mask = { (uint16_t)mask },
                        .aux = { (float)n, (float)__builtin_popcount(mask), (float)mask, r->grid });
                c0 += dx0, c1 += dx1, c2 += dx2;
                if (!mask)
                    continue;
            }
            /* narrated: the new samples in `held` until the write is told */
            bool narrated = NARRATING && r->tr && !full;
            float held_z[SAMPLES_MAX];
            uint32_t held_c[SAMPLES_MAX];
            if (narrated) {
                memcpy(held_z, sdepth + at, (size_t)n * sizeof *held_z);
                memcpy(held_c, scolor + at, (size_t)n * sizeof *held_c);
            }
            bool passed = false;
            /* msaa's shade: the planes 1/z, r, g, b at the centre, (P0 + Px dx) + Py dy */
            __m256d dx = _mm256_set1_pd((double)(x - plx));
            __m256d v = _mm256_add_pd(_mm256_add_pd(p0, _mm256_mul_pd(px, dx)), _mm256_mul_pd(py, dy));
            __m256d inv_z = _mm256_permute4x64_pd(v, 0);
            bool shaded = false;
            __m128i colour = _mm_setzero_si128();
            for (int h = 0; h < regs; h++) {
                float *sd = narrated ? held_z + 4 * h : sdepth + at + 4 * h;
                uint32_t *sc = narrated ? held_c + 4 * h : scolor + at + 4 * h;
                __m256d at_s = _mm256_add_pd(inv_z, inv_off[h]);       /* 1/z at the samples */
                __m128 old = _mm_loadu_ps(sd);
                __m128 want = full ? _mm_castsi128_ps(_mm_set1_epi32(-1)) : _mm_castsi128_ps(_mm_cmpeq_epi32(
                    _mm_and_si128(_mm_set1_epi32((int)(mask >> 4 * h)), bits), bits));
                __m128 sure = sure_hidden(_mm256_cvtpd_ps(at_s), old);
                if (!_mm_movemask_ps(_mm_andnot_ps(sure, want)))
                    continue;
                __m128 z = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), at_s));
                __m128 pass = _mm_and_ps(_mm_cmplt_ps(z, old), want);
                if (!_mm_movemask_ps(pass))
                    continue;
                passed = true;
                if (!shaded) {      /* msaa's colour_of, once */
                    double vs[PL_COUNT];
                    _mm256_storeu_pd(vs, v);
                    __m256d w2 = _mm256_add_pd(_mm256_add_pd(p0_st, _mm256_mul_pd(px_st, dx)),
                                               _mm256_mul_pd(py_st, dy));
                    _mm_storeu_pd(vs + PL_S, st ? _mm256_castpd256_pd128(w2) : _mm_setzero_pd());
                    colour = _mm_set1_epi32((int)colour_at(r, vs));
                    shaded = true;
                }
                _mm_storeu_ps(sd, _mm_blendv_ps(old, z, pass));
                __m128i c = _mm_loadu_si128((const __m128i *)sc);
                _mm_storeu_si128((__m128i *)sc, _mm_castps_si128(_mm_blendv_ps(
                    _mm_castsi128_ps(c), _mm_castsi128_ps(colour), pass)));
            }
            if (narrated) {     /* msaa's write, the pixel resolved as it is shown */
                uint32_t rgba;
                float nearest;
                ms_resolve(n, held_c, held_z, &rgba, &nearest);
                NARRATE(r->tr, .kind = TRACE_PIXEL_WRITE, .line = MS_LINE_WRITE, .x = x, .y = y,
                        .z = nearest, .rgba = rgba, .flags = passed ? TRACE_DEPTH_PASS : 0,
                        .mask = { (uint16_t)mask },
                        .aux = { (float)n, (float)__builtin_popcount(mask), (float)mask, r->grid });
                if (trace_frozen(r->tr))
                    continue;
                memcpy(sdepth + at, held_z, (size_t)n * sizeof *held_z);
                memcpy(scolor + at, held_c, (size_t)n * sizeof *held_c);
            }
            (void)passed;
            row |= (uint64_t)1 << (x - sx);
            if (count) {    /* saturating, as msaa's store */
                unsigned c = count[x] + (unsigned)__builtin_popcount(mask);
                count[x] = (uint8_t)(c > 255 ? 255 : c);
            }
        }
        touched[y - sy] |= row;
        for (int k = 0; k < 3; k++)
            cy[k] += e->dy[k];
    }
}

ms_pixels_fn ms_pixels(const struct run *r)
{
    bool fits = (r->pt.n == 4 || r->pt.n == 8) && r->touched;
    return fits && __builtin_cpu_supports("avx2") ? pixels_avx2 : NULL;
}
#else
ms_pixels_fn ms_pixels(const struct run *r)
{
    (void)r;
    return NULL;
}
#endif
