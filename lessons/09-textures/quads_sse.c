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
    double s_k[3], t_k[3], ones[3] = { 1, 1, 1 }, col[3][3];
    for (int k = 0; k < 3; k++) {
        s_k[k] = t->v[k].s, t_k[k] = t->v[k].t;
        col[k][0] = t->v[k].r, col[k][1] = t->v[k].g, col[k][2] = t->v[k].b;
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
            for (int i = 0; i < 4; i++) {
                if (!(covered >> i & 1))
                    continue;
                int x = qx + (i & 1), y = qy + (i >> 1);
                float z = (float)(1 / qs[i]);
                if (!target_depth_pass(fb, x, y, z)) {
                    target_write(fb, x, y, z, 0);   /* counted, hidden: no texel needed */
                    continue;
                }
                double rgb[3] = { 0, 0, 0 };
                for (int k = 0; k < 3; k++)
                    for (int c = 0; c < 3; c++)
                        rgb[c] += wl[k][i] * col[k][c];
                for (int c = 0; c < 3; c++)
                    rgb[c] /= qs[i];
                struct texel_rgb texel = tex_filter_texel(tex, filter, max_aniso, s[i], tt[i], &d,
                                                          &tex_stages_lesson, NULL);
                PLOT(fb, tr, L_WRITE, x, y, z, tex_modulate(texel, rgb[0], rgb[1], rgb[2]));
            }
        }
    }
}
