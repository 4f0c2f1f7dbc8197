/* Exercise 09: write lesson 09's texture unit: the bilinear tap, the level
 * of detail and the trilinear mix.
 *
 * The rest is the lesson's own rasterizer, textures_rasterize (textures.h):
 * lesson 05's blocks, the 2 x 2 quads inside them with their helper
 * pixels, (s, t) perspective-correct at the four centres, the quad's
 * coarse derivatives, and the modulate and write. It runs your three
 * stages for every textured pixel it writes:
 *
 *     quad -> derivatives -> YOUR lod -> lambda -> YOUR trilinear
 *          -> YOUR bilinear at two levels -> x vertex colour -> write
 *
 * As given, the level of detail is always 0, the trilinear mix takes
 * level 0 alone, and the bilinear tap is grey: untextured triangles are
 * right (the checks of the rasterizer pass), textured ones are grey.
 *
 *     make exercise LESSON=09        the explorer on this file
 *                                    (builtin:texture-floor)
 *     make check LESSON=09           the checks: the rasterizer's first
 *                                    (given, they pass), then yours on
 *                                    textured scenes, from texels
 *                                    magnified to textured 3-D scenes
 */
#include <math.h>

#include "lesson.h"
#include "textures.h"       /* struct tex_stages, textures_rasterize */

/* --- given: a level's size and one texel --------------------------------------- */

/* The size of level k, W_k x H_k; 1 x 1 for a level the texture does not
 * have (level 0 .. tex->nlevels - 1), which make check reports when read. */
static void level_size(const struct texture *tex, int k, int *w, int *h)
{
    bool have = k >= 0 && k < tex->nlevels;
    *w = have ? tex->level[k].w : 1;
    *h = have ? tex->level[k].h : 1;
}

/* Texel (i, j) of level k, channels 0..255. i and j must lie in the level,
 * 0 .. W_k - 1 and 0 .. H_k - 1: wrap them first. One outside is reported
 * by make check (and read as black, never out of bounds). */
static struct texel_rgb texel(const struct texture *tex, int k, int64_t i, int64_t j)
{
    uint32_t c = exercise_texel(tex, k, i, j);
    return (struct texel_rgb){ { (float)(c >> 16 & 255u), (float)(c >> 8 & 255u), (float)(c & 255u) } };
}

/* TODO 1, README section 1, "Texels and wrap": texel index i, any integer, into
 * 0 .. n - 1. repeat: i mod n, the mathematical mod (never negative:
 * -1 mod 4 is 3); clamp: the nearest of 0 .. n - 1. */
static int64_t wrap(int64_t i, int n, enum texture_wrap how)
{
    (void)n, (void)how;
    return i;
}

/* TODO 2, README section 2, "Nearest and bilinear": the bilinear tap at level k.
 *
 *     u = s W_k - 1/2,  v = t H_k - 1/2      (texel centres at i + 1/2)
 *     i0 = floor(u), a = u - i0;  j0 = floor(v), b = v - j0
 *
 * and the texels (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1),
 * each index wrapped, weighted (1-a)(1-b), a(1-b), (1-a)b, ab. */
static struct texel_rgb bilinear(const struct texture *tex, int k, double s, double t)
{
    (void)tex, (void)k, (void)s, (void)t, (void)level_size, (void)texel, (void)wrap;
    return (struct texel_rgb){ { 128, 128, 128 } };
}

/* TODO 3, README section 6, "The level of detail": lambda = log2(rho) from the
 * quad's derivatives. d gives them in texture coordinates per pixel
 * (ds/dx, dt/dx, ds/dy, dt/dy) and the size of level 0, W_0 x H_0:
 *
 *     du/dx = ds/dx W_0,  dv/dx = dt/dx H_0   (the same for y)
 *     rho = max(sqrt(du/dx^2 + dv/dx^2), sqrt(du/dy^2 + dv/dy^2))
 *
 * (log2 of rho squared is twice lambda.) Not clamped here. d->beyond (a
 * helper pixel of the quad beyond the horizon, 1/z <= 0) has no
 * derivatives: the rasterizer then takes the last level itself and does not
 * call lod(). */
static double lod(const struct tex_deriv *d)
{
    (void)d;
    return 0;
}

/* TODO 4, README section 7, "Trilinear": lambda clamped to [0, last level] (lambda
 * <= 0 magnifies: level 0), then the bilinear taps st->bilinear at levels
 * k = floor(lambda) and k + 1 (the last level twice at the end), mixed by
 * f = lambda - k: (1 - f) of level k, f of level k + 1. Where f is 0 (the
 * last level, or lambda a whole number) level k + 1 weighs nothing: you may
 * skip its tap, but a level the texture does not have is never read.
 * make check counts the texels read for each pixel (exercise_texel): two
 * taps of 4 at most, at two adjacent levels (or one level twice). */
static struct texel_rgb trilinear(const struct texture *tex, double lambda, double s, double t,
                                  const struct tex_stages *st)
{
    (void)lambda;
    return st->bilinear(tex, 0, s, t);
}

/* --- given: the lesson's rasterizer, with your stages ------------------------- */

static const struct tex_stages yours = { .bilinear = bilinear, .lod = lod, .trilinear = trilinear };

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &yours, (struct tex_options){ .lod = LOD_COARSE });
}
