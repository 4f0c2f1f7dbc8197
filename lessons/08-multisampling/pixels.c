/* Lesson 08's tiled twin, its pixels in the fast build: msaa's per-sample
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
 * The pixel is marked for the resolve at the tile's store (tiled.c). Runs
 * where the CPU has AVX2, at 4 or 8 samples; elsewhere msaa's own loops. */
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

AVX2 static void pixels_avx2(const struct run *r, int x0, int y0, int x1, int y1, bool full)
{
    const struct planes *pl = &r->pl;
    const struct biased_edges *e = &r->e.b;
    int regs = r->pt.n / 4;
    bool st = r->nplanes > PL_S;
    /* per register h: samples 4h .. 4h + 3, their offsets on each edge and
     * on the plane of 1/z; the lanes of each register as mask bits */
    __m256i off[2][3];
    __m256d inv_off[2];
    for (int h = 0; h < regs; h++) {
        for (int k = 0; k < 3; k++)
            off[h][k] = _mm256_setr_epi64x(r->e.off[4 * h][k], r->e.off[4 * h + 1][k],
                                           r->e.off[4 * h + 2][k], r->e.off[4 * h + 3][k]);
        inv_off[h] = _mm256_setr_pd(r->plane_off[4 * h][PL_INV_Z], r->plane_off[4 * h + 1][PL_INV_Z],
                                    r->plane_off[4 * h + 2][PL_INV_Z], r->plane_off[4 * h + 3][PL_INV_Z]);
    }
    __m256d p0 = _mm256_loadu_pd(pl->p0), px = _mm256_loadu_pd(pl->px), py = _mm256_loadu_pd(pl->py);
    __m256d p0_st = _mm256_setr_pd(pl->p0[PL_S], pl->p0[PL_T], 0, 0);
    __m256d px_st = _mm256_setr_pd(pl->px[PL_S], pl->px[PL_T], 0, 0);
    __m256d py_st = _mm256_setr_pd(pl->py[PL_S], pl->py[PL_T], 0, 0);
    __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
    unsigned all = (1u << r->pt.n) - 1;
    __m256i minus_one = _mm256_set1_epi64x(-1);
    int64_t cy[3] = { biased_edge_at(e, 0, x0, y0), biased_edge_at(e, 1, x0, y0),
                      biased_edge_at(e, 2, x0, y0) };
    for (int y = y0; y <= y1; y++) {
        int64_t cx[3] = { cy[0], cy[1], cy[2] };
        __m256d dy = _mm256_set1_pd((double)(y - pl->y0));
        uint8_t *count = r->fb->count ? r->fb->count + (size_t)y * (size_t)r->fb->w : NULL;
        for (int x = x0; x <= x1; x++) {
            unsigned mask = all;
            if (!full) {
                mask = 0;
                for (int h = 0; h < regs; h++) {
                    __m256i in = _mm256_and_si256(
                        _mm256_and_si256(
                            _mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(cx[0]), off[h][0]), minus_one),
                            _mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(cx[1]), off[h][1]), minus_one)),
                        _mm256_cmpgt_epi64(_mm256_add_epi64(_mm256_set1_epi64x(cx[2]), off[h][2]), minus_one));
                    mask |= (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(in)) << 4 * h;
                }
                for (int k = 0; k < 3; k++)
                    cx[k] += e->dx[k];
            }
            if (!mask)
                continue;
            /* msaa's shade: the planes at the centre, (P0 + Px dx) + Py dy */
            __m256d dx = _mm256_set1_pd((double)(x - pl->x0));
            __m256d v = _mm256_add_pd(_mm256_add_pd(p0, _mm256_mul_pd(px, dx)), _mm256_mul_pd(py, dy));
            __m256d inv_z = _mm256_permute4x64_pd(v, 0);
            size_t at = ((size_t)(y - r->sy) * r->srow + (size_t)(x - r->sx)) * (size_t)r->pt.n;
            float *sd = r->sdepth + at;
            uint32_t *sc = r->scolor + at;
            bool shaded = false;
            __m128i colour = _mm_setzero_si128();
            for (int h = 0; h < regs; h++) {
                __m128 z = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), _mm256_add_pd(inv_z, inv_off[h])));
                __m128 old = _mm_loadu_ps(sd + 4 * h);
                __m128i want = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)(mask >> 4 * h & 0xF)), bits), bits);
                __m128 pass = _mm_and_ps(_mm_cmplt_ps(z, old), _mm_castsi128_ps(want));
                if (!_mm_movemask_ps(pass))
                    continue;
                if (!shaded) {
                    double vs[PL_COUNT];
                    _mm256_storeu_pd(vs, v);
                    if (st) {
                        __m256d w = _mm256_add_pd(_mm256_add_pd(p0_st, _mm256_mul_pd(px_st, dx)),
                                                  _mm256_mul_pd(py_st, dy));
                        _mm_storeu_pd(vs + PL_S, _mm256_castpd256_pd128(w));
                    } else
                        vs[PL_S] = vs[PL_T] = 0;
                    colour = _mm_set1_epi32((int)colour_at(r, vs));
                    shaded = true;
                }
                _mm_storeu_ps(sd + 4 * h, _mm_blendv_ps(old, z, pass));
                __m128i c = _mm_loadu_si128((const __m128i *)(sc + 4 * h));
                _mm_storeu_si128((__m128i *)(sc + 4 * h),
                                 _mm_castps_si128(_mm_blendv_ps(_mm_castsi128_ps(c), _mm_castsi128_ps(colour), pass)));
            }
            r->touched[y - r->sy] |= (uint64_t)1 << (x - r->sx);
            if (count) {
                unsigned c = count[x] + (unsigned)__builtin_popcount(mask);
                count[x] = (uint8_t)(c > 255 ? 255 : c);
            }
        }
        for (int k = 0; k < 3; k++)
            cy[k] += e->dy[k];
    }
}

ms_pixels_fn ms_pixels(const struct run *r)
{
    bool fits = (r->pt.n == 4 || r->pt.n == 8) && r->touched && !r->tr;
    return fits && __builtin_cpu_supports("avx2") ? pixels_avx2 : NULL;
}
#else
ms_pixels_fn ms_pixels(const struct run *r)
{
    (void)r;
    return NULL;
}
#endif
