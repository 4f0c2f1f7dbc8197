/* Lesson 07, stage 3b: the pixels of one triangle in one tile, 8 a register,
 * in three twins: plain C, SSE2, AVX2 (draw.c picks one per run).
 *
 * A twin draws a strip: the columns i .. i + 7 of rows y0 .. y1 of the tile
 * (a block, a small triangle's box, a column of a FULL tile), the lanes of
 * `mask` only. Down the strip, what depends on the column alone is computed
 * once: the column terms Px (x - minx) of every plane, and (E) of each edge
 * at the strip's first row, which then steps by J_k a row (exact: integers).
 * At each row, each pixel:
 *
 *   cover: (E) >= 0 for all three edges (when the strip is tested);
 *   shade: 1/z = row term + column term, z = 1 / (1/z), nearer than the
 *          buffer -> colour = (255 a / z) z, the same for r, g, b.
 *
 * Same float operations in the same order in all three: same bytes. */
#include "tiles.h"
#if TILES_AVX2
#include <immintrin.h>          /* AVX2: eight lanes a register, where the CPU has it */
#endif

/* Saturating coverage counts of the lanes in `mask` (bit l = column i + l). */
static void count_lanes(const struct dst *d, int i, int j, unsigned mask)
{
    if (!d->count)
        return;
    uint8_t *c = d->count + (size_t)j * (size_t)d->count_stride + (size_t)i;
    for (int l = 0; l < LANES; l++)
        if (mask >> l & 1 && c[l] < 255)
            c[l]++;
}

/* The conversions of the SIMD instructions, written out for the scalar twin:
 * cvtps2dq rounds to nearest even, cvttps2dq truncates, and both give
 * INT32_MIN for anything out of range (NaN included). */
static int32_t cvt_round(float f)
{
    float r = f + 0.0f;
    if (!(r >= -2147483648.0f && r < 2147483648.0f))
        return INT32_MIN;
    /* round half to even, as the default rounding mode does */
    float fl = (float)(int64_t)r;
    if (fl > r)
        fl -= 1.0f;
    float frac = r - fl;
    int64_t i = (int64_t)fl;
    if (frac > 0.5f || (frac == 0.5f && (i & 1)))
        i++;
    return (int32_t)i;
}

static int32_t cvt_trunc(float f)
{
    if (!(f >= -2147483648.0f && f < 2147483648.0f))
        return INT32_MIN;
    return (int32_t)f;
}

/* floor(), as int32, the way the SSE twin computes it. */
static int32_t floor_i32(float f)
{
    int32_t i = cvt_trunc(f);
    if ((float)i > f)
        i = (int32_t)((uint32_t)i - 1u);
    return i;
}

static uint32_t byte_of(int32_t v)
{
    return (uint32_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* The lanes of `mask` whose pixel (i + l, j) passes (E) for all three edges. */
static unsigned cover8_c(const struct tri_in_tile *c, int i, int j, unsigned mask)
{
    unsigned in = 0;
    for (int l = 0; l < LANES; l++) {
        bool inside = mask >> l & 1;
        for (int k = 0; k < 3; k++)
            inside = inside && c->e0[k] + c->t->di[k] * (i + l) + c->t->dj[k] * j >= 0;
        in |= (unsigned)inside << l;
    }
    return in;
}

/* One pixel, column i, of the scalar twin, in two steps: its depth z, and
 * (only where z is nearer than the buffer) its colour. */
static float depth1_c(const struct tri_in_tile *c, const struct rows *rw, int i)
{
    const struct tri *t = c->t;
    float dxf = (float)(c->tx + i - t->minx);
    return 1.0f / (rw->p[PL_INV_Z] + t->px[PL_INV_Z] * dxf);
}

static uint32_t colour1_c(const struct tri_in_tile *c, const struct rows *rw, int i, float z)
{
    const struct tri *t = c->t;
    const float *row = rw->p, *st_row = rw->st;
    float dxf = (float)(c->tx + i - t->minx);
    float r = (row[PL_R] + t->px[PL_R] * dxf) * z;
    float g = (row[PL_G] + t->px[PL_G] * dxf) * z;
    float b = (row[PL_B] + t->px[PL_B] * dxf) * z;
    if (c->st) {
        int32_t square = (int32_t)((uint32_t)floor_i32((st_row[ST_S] + c->st[1] * dxf) * z)
                                   + (uint32_t)floor_i32((st_row[ST_T] + c->st[4] * dxf) * z));
        if (square & 1) {
            r *= (float)CHECKER_DARK;
            g *= (float)CHECKER_DARK;
            b *= (float)CHECKER_DARK;
        }
    }
    return 0xff000000u | byte_of(cvt_round(r)) << 16 | byte_of(cvt_round(g)) << 8
         | byte_of(cvt_round(b));
}

/* Both steps for one pixel, whether it passes or not: what the narration
 * shows (a hidden pixel's colour too). */
bool shade1_c(const struct tri_in_tile *c, const struct dst *d, const struct rows *rw, int i, int j,
              float *z_out, uint32_t *rgba_out)
{
    float z = depth1_c(c, rw, i);
    *z_out = z;
    *rgba_out = colour1_c(c, rw, i, z);
    return z < d->depth[(size_t)j * (size_t)d->stride + (size_t)i];
}

/* The lanes of `mask`: depth test, then colour and write where it passes.
 * A hidden pixel is not coloured (the SIMD twins skip a register whose
 * lanes are all hidden): on a scene covered many times over, many are. */
static void shade8_c(const struct tri_in_tile *c, const struct dst *d, const struct rows *rw, int i, int j,
                     unsigned mask)
{
    count_lanes(d, i, j, mask);
    for (int l = 0; l < LANES; l++) {
        if (!(mask >> l & 1))
            continue;
        size_t o = (size_t)j * (size_t)d->stride + (size_t)(i + l);
        float z = depth1_c(c, rw, i + l);
        if (z < d->depth[o]) {
            d->depth[o] = z;
            d->color[o] = colour1_c(c, rw, i + l, z);
        }
    }
}

/* Plain C: row by row, pixel by pixel, straight from the formulas. */
void strip_c(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1, unsigned mask,
                    bool test)
{
    for (int j = y0; j <= y1; j++) {
        struct rows rw;
        plane_rows(c, j, &rw);
        unsigned m = test ? cover8_c(c, i, j, mask) : mask;
        if (m)
            shade8_c(c, d, &rw, i, j, m);
    }
}

/* SSE2: two registers of four lanes. */
static __m128i clamp_byte_sse2(__m128i v)
{
    v = _mm_and_si128(v, _mm_cmpgt_epi32(v, _mm_setzero_si128()));     /* max(v, 0) */
    __m128i big = _mm_cmpgt_epi32(v, _mm_set1_epi32(255));
    return _mm_or_si128(_mm_andnot_si128(big, v), _mm_and_si128(big, _mm_set1_epi32(255)));
}

/* The four pixels at o (rows of the planes `row`, columns `col`, `dxf`) whose
 * lanes `in` has: depth test, shade, write. */
static void shade4_sse2(const struct tri_in_tile *c, const struct dst *d, const struct rows *rw,
                        const __m128 col[QUAD_PLANES], __m128 dxf, __m128 in, size_t o)
{
    const float *row = rw->p, *st_row = rw->st;
    __m128 z = _mm_div_ps(_mm_set1_ps(1.0f), _mm_add_ps(_mm_set1_ps(row[PL_INV_Z]), col[PL_INV_Z]));
    __m128 old_z = _mm_loadu_ps(d->depth + o);
    __m128 pass = _mm_and_ps(_mm_cmplt_ps(z, old_z), in);
    if (!_mm_movemask_ps(pass))
        return;
    __m128 r = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_R]), col[PL_R]), z);
    __m128 g = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_G]), col[PL_G]), z);
    __m128 b = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_B]), col[PL_B]), z);
    if (c->st) {
        __m128 s_coord = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(st_row[ST_S]), _mm_mul_ps(_mm_set1_ps(c->st[1]), dxf)), z);
        __m128 t_coord = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(st_row[ST_T]), _mm_mul_ps(_mm_set1_ps(c->st[4]), dxf)), z);
        __m128 scale = checker_scale(s_coord, t_coord);
        r = _mm_mul_ps(r, scale);
        g = _mm_mul_ps(g, scale);
        b = _mm_mul_ps(b, scale);
    }
    __m128i rgba = _mm_or_si128(_mm_set1_epi32((int)0xff000000u),
                   _mm_or_si128(_mm_slli_epi32(clamp_byte_sse2(_mm_cvtps_epi32(r)), 16),
                   _mm_or_si128(_mm_slli_epi32(clamp_byte_sse2(_mm_cvtps_epi32(g)), 8),
                                clamp_byte_sse2(_mm_cvtps_epi32(b)))));
    __m128i pass_i = _mm_castps_si128(pass);
    __m128i old_c = _mm_loadu_si128((const __m128i *)(d->color + o));
    _mm_storeu_ps(d->depth + o, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, old_z)));
    _mm_storeu_si128((__m128i *)(d->color + o),
                     _mm_or_si128(_mm_and_si128(pass_i, rgba), _mm_andnot_si128(pass_i, old_c)));
}

/* The lanes of `mask` (bit l: lane l) as a register of all-ones lanes. */
static __m128 lanes_sse2(unsigned mask)
{
    __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
    return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)mask), bits), bits));
}

void strip_sse2(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
                       unsigned mask, bool test)
{
    if (i + LANES > d->wide) {      /* no room for whole registers: lane by lane */
        strip_c(c, d, i, y0, y1, mask, test);
        return;
    }
    /* down the strip: the column terms of each plane and (E) at row y0,
     * each edge stepping by J_k a row; lanes 0-3, then 4-7 */
    const struct tri *t = c->t;
    __m128 dx[2], cols[2][QUAD_PLANES], want[2];
    __m128i edge[2][3], step[3];
    for (int h = 0; h < 2; h++) {
        dx[h] = _mm_cvtepi32_ps(_mm_add_epi32(_mm_set1_epi32(c->tx + i + 4 * h - t->minx),
                                              _mm_setr_epi32(0, 1, 2, 3)));
        for (int q = 0; q < QUAD_PLANES; q++)
            cols[h][q] = _mm_mul_ps(_mm_set1_ps(t->px[q]), dx[h]);
        want[h] = lanes_sse2(mask >> 4 * h & 0xF);
    }
    for (int k = 0; k < 3; k++) {
        int32_t base = c->e0[k] + t->di[k] * i + t->dj[k] * y0, di = t->di[k];
        edge[0][k] = _mm_add_epi32(_mm_set1_epi32(base), _mm_setr_epi32(0, di, 2 * di, 3 * di));
        edge[1][k] = _mm_add_epi32(edge[0][k], _mm_set1_epi32(4 * di));
        step[k] = _mm_set1_epi32(t->dj[k]);
    }
    size_t o = (size_t)y0 * (size_t)d->stride + (size_t)i;
    for (int j = y0; j <= y1; j++, o += (size_t)d->stride) {
        __m128 in[2] = { want[0], want[1] };
        for (int h = 0; test && h < 2; h++) {
            /* a lane is outside when some edge's (E) is negative: its sign
             * bit, spread over the lane */
            __m128i out = _mm_or_si128(_mm_or_si128(edge[h][0], edge[h][1]), edge[h][2]);
            in[h] = _mm_andnot_ps(_mm_castsi128_ps(_mm_srai_epi32(out, 31)), want[h]);
            for (int k = 0; k < 3; k++)
                edge[h][k] = _mm_add_epi32(edge[h][k], step[k]);
        }
        unsigned m = (unsigned)_mm_movemask_ps(in[0]) | (unsigned)_mm_movemask_ps(in[1]) << 4;
        if (!m)
            continue;
        count_lanes(d, i, j, m);
        struct rows rw;
        plane_rows(c, j, &rw);
        for (int h = 0; h < 2; h++)
            if (m >> 4 * h & 0xF)
                shade4_sse2(c, d, &rw, cols[h], dx[h], in[h], o + (size_t)(4 * h));
    }
}

#if TILES_AVX2
#define AVX2 __attribute__((target("avx2")))

AVX2 static __m256i floor_avx2(__m256 v)
{
    __m256i i = _mm256_cvttps_epi32(v);
    __m256 too_big = _mm256_cmp_ps(_mm256_cvtepi32_ps(i), v, _CMP_GT_OQ);
    return _mm256_add_epi32(i, _mm256_castps_si256(too_big));
}

AVX2 static __m256i byte_avx2(__m256 v)
{
    return _mm256_min_epi32(_mm256_max_epi32(_mm256_cvtps_epi32(v), _mm256_setzero_si256()),
                            _mm256_set1_epi32(255));
}

/* (E) of edge k at the pixels (i .. i + 7, j) of the tile. */
AVX2 static inline __m256i edge8_avx2(const struct tri_in_tile *c, int k, int i, int j)
{
    const struct tri *t = c->t;
    return _mm256_add_epi32(_mm256_set1_epi32(c->e0[k] + t->di[k] * i + t->dj[k] * j),
                            _mm256_mullo_epi32(_mm256_set1_epi32(t->di[k]),
                                               _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
}

/* AVX2: one register of eight lanes, the same steps as the SSE2 twin. */
AVX2 void strip_avx2(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
                            unsigned mask, bool test)
{
    if (i + LANES > d->wide) {
        strip_c(c, d, i, y0, y1, mask, test);
        return;
    }
    const struct tri *t = c->t;
    /* down the strip: the column terms of each plane and (E) at row y0,
     * each edge stepping by J_k a row */
    __m256 dx = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(c->tx + i - t->minx),
                                                    _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
    __m256 col_inv_z = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_INV_Z]), dx);
    __m256 col_r = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_R]), dx);
    __m256 col_g = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_G]), dx);
    __m256 col_b = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_B]), dx);
    __m256i e0 = edge8_avx2(c, 0, i, y0), e1 = edge8_avx2(c, 1, i, y0), e2 = edge8_avx2(c, 2, i, y0);
    __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    __m256 want = _mm256_castsi256_ps(_mm256_cmpeq_epi32(
        _mm256_and_si256(_mm256_set1_epi32((int)mask), bits), bits));
    float *depth = d->depth + (size_t)y0 * (size_t)d->stride + (size_t)i;
    uint32_t *color = d->color + (size_t)y0 * (size_t)d->stride + (size_t)i;
    for (int j = y0; j <= y1; j++, depth += d->stride, color += d->stride) {
        __m256 in = want;
        if (test) {
            /* a lane is outside when some edge's (E) is negative: its sign
             * bit, spread over the lane */
            __m256i out = _mm256_or_si256(_mm256_or_si256(e0, e1), e2);
            in = _mm256_andnot_ps(_mm256_castsi256_ps(_mm256_srai_epi32(out, 31)), want);
            e0 = _mm256_add_epi32(e0, _mm256_set1_epi32(t->dj[0]));
            e1 = _mm256_add_epi32(e1, _mm256_set1_epi32(t->dj[1]));
            e2 = _mm256_add_epi32(e2, _mm256_set1_epi32(t->dj[2]));
        }
        unsigned m = (unsigned)_mm256_movemask_ps(in);
        if (!m)
            continue;
        count_lanes(d, i, j, m);
        struct rows rw;
        plane_rows(c, j, &rw);
        const float *row = rw.p, *st_row = rw.st;
        __m256 z = _mm256_div_ps(_mm256_set1_ps(1.0f),
                                 _mm256_add_ps(_mm256_set1_ps(row[PL_INV_Z]), col_inv_z));
        __m256 old_z = _mm256_loadu_ps(depth);
        __m256 pass = _mm256_and_ps(_mm256_cmp_ps(z, old_z, _CMP_LT_OQ), in);
        if (!_mm256_movemask_ps(pass))
            continue;
        __m256 r = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_R]), col_r), z);
        __m256 g = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_G]), col_g), z);
        __m256 b = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_B]), col_b), z);
        if (c->st) {
            __m256 s_coord = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(st_row[ST_S]),
                                                   _mm256_mul_ps(_mm256_set1_ps(c->st[1]), dx)), z);
            __m256 t_coord = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(st_row[ST_T]),
                                                    _mm256_mul_ps(_mm256_set1_ps(c->st[4]), dx)), z);
            __m256i square = _mm256_add_epi32(floor_avx2(s_coord), floor_avx2(t_coord));
            __m256 dark = _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                _mm256_and_si256(square, _mm256_set1_epi32(1)), _mm256_set1_epi32(1)));
            __m256 scale = _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_set1_ps((float)CHECKER_DARK), dark);
            r = _mm256_mul_ps(r, scale);
            g = _mm256_mul_ps(g, scale);
            b = _mm256_mul_ps(b, scale);
        }
        __m256i rgba = _mm256_or_si256(_mm256_set1_epi32((int)0xff000000u),
                       _mm256_or_si256(_mm256_slli_epi32(byte_avx2(r), 16),
                       _mm256_or_si256(_mm256_slli_epi32(byte_avx2(g), 8), byte_avx2(b))));
        __m256i old_c = _mm256_loadu_si256((const __m256i *)color);
        _mm256_storeu_ps(depth, _mm256_blendv_ps(old_z, z, pass));
        _mm256_storeu_si256((__m256i *)color,
                            _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(old_c),
                                                                 _mm256_castsi256_ps(rgba), pass)));
    }
}
#endif

