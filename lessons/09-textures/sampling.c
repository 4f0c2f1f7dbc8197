/* Lesson 09's texture unit: from (s, t) and a quad's derivatives to a
 * filtered texel, in small pieces an exercise can swap (struct tex_stages,
 * textures.h). The rules are lessons/CONVENTIONS.md's "Textures":
 *
 *     texel (i, j) of level k covers [i, i+1) x [j, j+1) in texels,
 *     u = s W_k, v = t H_k; its centre is (i + 1/2, j + 1/2)
 *
 *        bilinear: the four centres around (u, v)
 *
 *          (i0, j0) o-----------o (i0+1, j0)      u - 1/2 = i0 + a
 *                   |     .(u,v)|                 v - 1/2 = j0 + b
 *                   |           |
 *        (i0, j0+1) o-----------o (i0+1, j0+1)    weights (1-a)(1-b), a(1-b),
 *                                                 (1-a)b, ab
 *
 *     level of detail: rho = the longer of (du/dx, dv/dx) and (du/dy,
 *     dv/dy) in level-0 texels, lambda = log2(rho); trilinear mixes the
 *     bilinear values of levels floor(lambda) and floor(lambda) + 1 by
 *     frac(lambda); aniso spreads n trilinear probes along the longer
 *     derivative and takes a finer level, log2(P_max / n).
 *
 * Colours are floats in 0..255 (a texel's 8-bit channels are exact in a
 * float); the weights are floats, the coordinates doubles. */
#include <math.h>

#include "textures.h"

/* Texel (i, j) of level l as three floats (texel_at, textures.h). */
static inline struct texel_rgb texel(const struct texture_level *l, enum texture_wrap wrap, int64_t i,
                                     int64_t j)
{
    uint32_t c = texel_at(l, wrap, i, j);
    return (struct texel_rgb){ { (float)(c >> 16 & 255), (float)(c >> 8 & 255), (float)(c & 255) } };
}

struct texel_rgb tex_nearest(const struct texture *tex, double s, double t)
{
    const struct texture_level *l = &tex->level[0];
    double u = tex_coord_held(s * l->w), v = tex_coord_held(t * l->h);
    return texel(l, tex->wrap, (int64_t)floor(u), (int64_t)floor(v));
}

/* One level's bilinear tap: lerp along u on both rows, then along v. */
struct texel_rgb tex_bilinear(const struct texture *tex, int k, double s, double t)
{
    const struct texture_level *l = &tex->level[k];
    int64_t i, j;
    float a, b;
    bilinear_corner(l, s, t, &i, &j, &a, &b);
    struct texel_rgb c00 = texel(l, tex->wrap, i, j), c10 = texel(l, tex->wrap, i + 1, j);
    struct texel_rgb c01 = texel(l, tex->wrap, i, j + 1), c11 = texel(l, tex->wrap, i + 1, j + 1);
    struct texel_rgb out;
    for (int c = 0; c < 3; c++) {
        float top = c00.c[c] + a * (c10.c[c] - c00.c[c]);
        float bottom = c01.c[c] + a * (c11.c[c] - c01.c[c]);
        out.c[c] = top + b * (bottom - top);
    }
    return out;
}

/* lambda = log2(rho): the derivatives made texels (times W_0, H_0), the
 * longer of the two vectors. */
double tex_lod(const struct tex_deriv *d)
{
    double dudx = d->dsdx * d->w0, dvdx = d->dtdx * d->h0;
    double dudy = d->dsdy * d->w0, dvdy = d->dtdy * d->h0;
    double px2 = dudx * dudx + dvdx * dvdx, py2 = dudy * dudy + dvdy * dvdy;
    return log2(sqrt(px2 > py2 ? px2 : py2));      /* the longer's length: one square root */
}

/* Levels floor(lambda) and the next, mixed by frac(lambda). */
struct texel_rgb tex_trilinear(const struct texture *tex, double lambda, double s, double t,
                               const struct tex_stages *st)
{
    double last = tex->nlevels - 1;
    lambda = lambda > 0 ? (lambda < last ? lambda : last) : 0;     /* NaN: 0 */
    int k0 = (int)lambda, k1 = k0 + 1 < tex->nlevels ? k0 + 1 : k0;
    float f = (float)(lambda - k0);
    struct texel_rgb a = st->bilinear(tex, k0, s, t);
    if (k1 == k0 || f == 0)
        return a;
    struct texel_rgb b = st->bilinear(tex, k1, s, t);
    for (int c = 0; c < 3; c++)
        a.c[c] = a.c[c] + f * (b.c[c] - a.c[c]);
    return a;
}

const struct tex_stages tex_stages_lesson = {
    .bilinear = tex_bilinear,
    .lod = tex_lod,
    .trilinear = tex_trilinear,
};

/* The levels and weight trilinear uses at lambda, for the narration. */
static void trilinear_used(const struct texture *tex, double lambda, struct tex_used *u)
{
    double last = tex->nlevels - 1;
    lambda = lambda > 0 ? (lambda < last ? lambda : last) : 0;
    u->lambda = (float)lambda;
    u->level0 = (int)lambda;
    u->level1 = u->level0 + 1 < tex->nlevels ? u->level0 + 1 : u->level0;
    u->mix = (float)(lambda - u->level0);
}

/* Anisotropic: n trilinear probes along the longer derivative, averaged. */
static struct texel_rgb aniso(const struct texture *tex, int max_aniso, double s, double t,
                              const struct tex_deriv *d, const struct tex_stages *st,
                              struct tex_used *used)
{
    double dudx = d->dsdx * d->w0, dvdx = d->dtdx * d->h0;
    double dudy = d->dsdy * d->w0, dvdy = d->dtdy * d->h0;
    double px = sqrt(dudx * dudx + dvdx * dvdx), py = sqrt(dudy * dudy + dvdy * dvdy);
    bool along_x = px >= py;
    double pmax = along_x ? px : py, pmin = along_x ? py : px;
    double ds = along_x ? d->dsdx : d->dsdy, dt = along_x ? d->dtdx : d->dtdy;
    int n = max_aniso;
    if (pmax == 0)
        n = 1;
    else if (pmin > 0 && ceil(pmax / pmin) < max_aniso)
        n = (int)ceil(pmax / pmin);
    double lambda = log2(pmax / n);
    struct texel_rgb sum = { { 0, 0, 0 } };
    for (int i = 0; i < n; i++) {
        double o = (i + 0.5) / n - 0.5;
        struct texel_rgb tap = st->trilinear(tex, lambda, s + o * ds, t + o * dt, st);
        for (int c = 0; c < 3; c++)
            sum.c[c] += tap.c[c];
    }
    for (int c = 0; c < 3; c++)
        sum.c[c] /= (float)n;
    trilinear_used(tex, lambda, used);
    used->taps = n;
    return sum;
}

struct texel_rgb tex_filter_texel(const struct texture *tex, enum tex_filter f, int max_aniso,
                                  double s, double t, const struct tex_deriv *d,
                                  const struct tex_stages *st, struct tex_used *used)
{
    struct tex_used scratch;
    struct tex_used *u = used ? used : &scratch;
    *u = (struct tex_used){ .taps = 1 };
    if (f == FILTER_NEAREST)
        return tex_nearest(tex, s, t);
    double last = tex->nlevels - 1;
    double lambda = d->beyond ? last : st->lod(d);
    if (f == FILTER_BILINEAR || !(lambda > 0)) {
        /* lambda <= 0 magnifies: level 0, bilinear (for aniso too: rho is its P_max) */
        u->lambda = f == FILTER_BILINEAR ? 0 : (float)lambda;
        return st->bilinear(tex, 0, s, t);
    }
    if (f == FILTER_MIP_BILINEAR) {
        lambda = lambda < last ? lambda : last;
        int k = lambda <= 0.5 ? 0 : (int)ceil(lambda + 0.5) - 1;   /* the nearest, ties to the finer */
        *u = (struct tex_used){ .lambda = (float)lambda, .level0 = k, .level1 = k, .taps = 1 };
        return st->bilinear(tex, k, s, t);
    }
    if (f == FILTER_TRILINEAR || d->beyond) {
        trilinear_used(tex, lambda, u);
        return st->trilinear(tex, lambda, s, t, st);
    }
    return aniso(tex, max_aniso, s, t, d, st, u);
}

uint32_t tex_modulate(struct texel_rgb texel, double r, double g, double b)
{
    double c[3] = { texel.c[0] * r, texel.c[1] * g, texel.c[2] * b };
    uint32_t out = 0xff000000u;
    for (int i = 0; i < 3; i++) {
        double v = c[i] > 0 ? (c[i] < 255 ? c[i] : 255) : 0;      /* a NaN becomes 0 */
        out |= (uint32_t)(v + 0.5) << (16 - 8 * i);
    }
    return out;
}
