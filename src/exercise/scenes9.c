/* scenes9.c - the textured scenes of make check for lesson 09's sampler
 * (scenes.h), simplest first: texels magnified, minified ones at chosen
 * levels of detail, both wraps and negative s and t, a texture that is not
 * square, grazing floors and tiny triangles; then 3-D scenes (an OBJ's
 * own texture coordinates, a floor cut by near).
 *
 * Each scene is written as a scene file's text and read by scene_parse, so
 * that its textures are the built-in ones a counterexample names again
 * (builtin:rgby, checker-numbers, bricks, grid, plaid). Every level of
 * detail and weight is chosen so that a classic mistake moves a colour by
 * far more than the check's 2 levels: texels of high contrast, mixes far
 * from one half, levels that differ from their neighbours. */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */

#include "scenes.h"
#include "gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool gen_text_start(struct gen_text *x, int w, int h, const char *texture)
{
    x->buf = NULL;
    x->len = 0;
    x->f = open_memstream(&x->buf, &x->len);
    if (!x->f)
        return false;
    fprintf(x->f, "size %d %d\nbackground 0.1 0.1 0.12\n", w, h);
    if (texture)
        fprintf(x->f, "texture %s\n", texture);
    return true;
}

void gen_tri(struct gen_text *x, struct tv a, struct tv b, struct tv c)
{
    const struct tv *v[3] = { &a, &b, &c };
    fputs("tri", x->f);
    for (int k = 0; k < 3; k++)
        fprintf(x->f, "  %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", v[k]->x, v[k]->y, v[k]->z,
                v[k]->r, v[k]->g, v[k]->b, v[k]->s, v[k]->t);
    fputc('\n', x->f);
}

/* The text read as a scene; a scene of no triangles if it were wrong (it
 * is not: the tests check every scene of every check). */
bool gen_text_end(struct gen_text *x, struct scene *s)
{
    fclose(x->f);
    char err[256];
    bool ok = x->buf && scene_parse(s, "make-check.scene", x->buf, x->len, err, sizeof err);
    free(x->buf);
    if (!ok) {
        fprintf(stderr, "make check: a scene of its own does not read: %s\n", err);
        check_scene_start(s, 8, 8);
    }
    return true;
}

static struct tv V(double x, double y, double z, double s, double t)
{
    return (struct tv){ x, y, z, 1, 1, 1, s, t };
}

static struct tv Vc(double x, double y, double z, double r, double g, double b, double s, double t)
{
    return (struct tv){ x, y, z, r, g, b, s, t };
}

/* A triangle of about 44 x 30 pixels on a 48 x 36 target, its texture
 * coordinates (s0, t0) + (ds, dt) spread over it: the level of detail of
 * a w-texel-wide texture is about log2(w ds / 44) along x. `turn` lays the
 * spread along y instead (rho from the y derivatives). */
static void spread(struct gen_text *x, double s0, double t0, double ds, double dt, double z0, double z1, bool turn,
                   bool coloured)
{
    struct tv a = V(2.3, 2.6, z0, s0, t0), b = V(46.1, 3.9, z0, s0 + ds, t0), c = V(4.7, 33.2, z1, s0, t0 + dt);
    if (turn)
        b = V(45.4, 4.2, z0, s0, t0 + dt), c = V(3.6, 33.7, z1, s0 + ds, t0);
    if (coloured) {
        a.g = 0.6, b.b = 0.5, c.r = 0.7;
    }
    gen_tri(x, a, b, c);
}

/* --- texels magnified: the bilinear tap at level 0 ------------------------------- */

bool gen_tex_magnify(int i, struct scene *s, char *what, size_t n)
{
    struct gen_text x;
    switch (i) {
    case 0:
        gen_text_start(&x, 40, 30, "builtin:rgby");
        gen_tri(&x, V(2.3, 2.1, 1, 0, 0), V(37.6, 3.4, 1, 1, 0), V(5.2, 27.8, 1, 0, 1));
        snprintf(what, n, "builtin:rgby (2 x 2 texels) magnified, a texel some 18 pixels wide");
        break;
    case 1:
        gen_text_start(&x, 40, 30, "builtin:rgby");
        gen_tri(&x, Vc(1.7, 28.4, 1, 1, 0.8, 0.6, 0.1, 1.9), Vc(38.2, 26.9, 3, 0.5, 1, 1, 1.9, 1.7),
            Vc(20.6, 1.3, 2, 1, 1, 0.4, 0.8, 0.05));
        snprintf(what, n, "builtin:rgby magnified under coloured vertices, depths 1 to 3 (perspective)");
        break;
    case 2:
        gen_text_start(&x, 48, 36, "builtin:checker-numbers");
        gen_tri(&x, V(1.5, 1.5, 1, 0.30, 0.40), V(46.3, 3.2, 1, 0.344, 0.40), V(3.1, 34.6, 1, 0.30, 0.4515));
        snprintf(what, n, "builtin:checker-numbers magnified, a texel some 4 pixels wide, on the digits of a cell");
        break;
    case 3:
        gen_text_start(&x, 48, 36, "builtin:bricks");
        gen_tri(&x, V(2.5, 2.5, 1, 0.10, 0.05), V(45.5, 3.5, 4, 0.13, 0.05), V(43.5, 33.5, 2, 0.13, 0.08));
        gen_tri(&x, V(2.5, 2.5, 1, 0.10, 0.05), V(43.5, 33.5, 2, 0.13, 0.08), V(3.5, 32.5, 1.5, 0.10, 0.08));
        snprintf(what, n, "builtin:bricks magnified on two triangles sharing an edge, depths 1 to 4");
        break;
    default:
        return false;
    }
    return gen_text_end(&x, s);
}

/* --- minified: levels of detail chosen one by one ---------------------------------- */

bool gen_tex_minify(int i, struct scene *s, char *what, size_t n)
{
    /* lambda about log2(256 ds / 44) along x: 1.2, 2.85, 4.1, 5.7, 7.3, and
     * 9.6 beyond the last level (8 of builtin:checker-numbers); the mixes
     * frac(lambda) far from one half */
    static const struct {
        const char *texture;
        double ds, dt, z1;
        bool turn, coloured;
    } m[] = {
        { "builtin:checker-numbers", 0.39, 0.2, 1, false, false },
        { "builtin:checker-numbers", 1.1, 0.5, 1, true, false },
        { "builtin:checker-numbers", 2.95, 1.1, 1, false, true },
        { "builtin:grid", 9.0, 2.0, 1, true, false },
        { "builtin:checker-numbers", 27.0, 5.0, 1, false, false },
        { "builtin:bricks", 12.2, 8.0, 1.3, false, true },
        { "builtin:checker-numbers", 28.0, 40.0, 1, true, false },
        { "builtin:checker-numbers", 1400.0, 900.0, 1, false, false },
    };
    if (i >= (int)(sizeof m / sizeof m[0]))
        return false;
    struct gen_text x;
    gen_text_start(&x, 48, 36, m[i].texture);
    struct rng r = rng_start(0x70d5u + (uint64_t)i);
    spread(&x, rng_range(&r, -2, 2), rng_range(&r, -2, 2), m[i].ds, m[i].dt, 1, m[i].z1, m[i].turn, m[i].coloured);
    snprintf(what, n, "%s minified: s spans %g, t %g over some 44 pixels%s", m[i].texture, m[i].ds, m[i].dt,
             i == 7 ? " (lambda beyond the last level)" : "");
    return gen_text_end(&x, s);
}

/* --- repeat and clamp, s and t below 0 and beyond 1 ------------------------------- */

bool gen_tex_wrap(int i, struct scene *s, char *what, size_t n)
{
    struct gen_text x;
    switch (i) {
    case 0:
        gen_text_start(&x, 40, 30, "builtin:rgby repeat");
        gen_tri(&x, V(1.5, 1.5, 1, -2.25, -1.75), V(38.5, 2.5, 1, 0.75, -1.75), V(2.5, 28.5, 1, -2.25, 0.75));
        snprintf(what, n, "builtin:rgby repeated, s from -2.25 to 0.75, t from -1.75 to 0.75");
        break;
    case 1:
        gen_text_start(&x, 40, 30, "builtin:rgby clamp");
        gen_tri(&x, V(1.5, 1.5, 1, -0.75, -0.6), V(38.5, 2.5, 1, 1.75, -0.6), V(2.5, 28.5, 1, -0.75, 1.6));
        snprintf(what, n, "builtin:rgby clamped, s from -0.75 to 1.75, t from -0.6 to 1.6");
        break;
    case 2:
        gen_text_start(&x, 48, 36, "builtin:checker-numbers repeat");
        gen_tri(&x, V(2.5, 1.5, 1, -1.03, -2.02), V(45.5, 2.5, 1, -0.97, -2.02), V(3.5, 34.5, 1, -1.03, -1.975));
        snprintf(what, n, "builtin:checker-numbers repeated, magnified where s = -1 and t = -2 (the corner of four copies)");
        break;
    case 3:
        gen_text_start(&x, 48, 36, "builtin:checker-numbers clamp");
        gen_tri(&x, V(2.5, 1.5, 1, 0.96, -0.04), V(45.5, 2.5, 1, 1.04, -0.04), V(3.5, 34.5, 1, 0.96, 0.035));
        snprintf(what, n, "builtin:checker-numbers clamped, magnified across s = 1 and t = 0");
        break;
    case 4:
        gen_text_start(&x, 48, 36, "builtin:bricks repeat");
        gen_tri(&x, V(1.5, 2.5, 1, -700.6, -300.2), V(46.5, 1.5, 2, -700.3, -300.2), V(4.5, 34.5, 1, -700.6, -299.9));
        snprintf(what, n, "builtin:bricks repeated, s near -700 and t near -300");
        break;
    case 5:
        gen_text_start(&x, 48, 36, "builtin:checker-numbers repeat");
        spread(&x, -6.3, -3.2, 4.2, 1.9, 1, 1, false, false);
        snprintf(what, n, "builtin:checker-numbers repeated and minified (lambda about 4.6), s and t below 0");
        break;
    case 6:
        gen_text_start(&x, 48, 36, "builtin:grid clamp");
        spread(&x, -1.6, -1.1, 3.3, 2.9, 1, 1, true, true);
        snprintf(what, n, "builtin:grid clamped and minified, s from -1.6 to 1.7, t from -1.1 to 1.8");
        break;
    default:
        return false;
    }
    return gen_text_end(&x, s);
}

/* --- a texture that is not square ------------------------------------------------- */

bool gen_tex_nonsquare(int i, struct scene *s, char *what, size_t n)
{
    struct gen_text x;
    switch (i) {
    case 0:
        gen_text_start(&x, 40, 30, "builtin:plaid");
        gen_tri(&x, V(1.5, 1.5, 1, 0, 0), V(38.5, 2.5, 1, 0.9, 0), V(2.5, 28.5, 1, 0, 3.1));
        snprintf(what, n, "builtin:plaid (32 x 8 texels) magnified: a texel 1.3 pixels wide and 1.2 tall");
        break;
    case 1:
        gen_text_start(&x, 48, 36, "builtin:plaid");
        spread(&x, 0.1, 0.2, 5.1, 1.3, 1, 1, false, false);
        snprintf(what, n, "builtin:plaid minified along s (lambda about 1.9)");
        break;
    case 2:
        gen_text_start(&x, 48, 36, "builtin:plaid");
        spread(&x, 0.05, -3.4, 0.7, 9.3, 1, 1, true, true);
        snprintf(what, n, "builtin:plaid minified along t (lambda about 1.1), t below 0");
        break;
    case 3:
        gen_text_start(&x, 48, 36, "builtin:plaid clamp");
        gen_tri(&x, V(1.5, 1.5, 1, -0.2, -0.3), V(46.5, 2.5, 3, 1.25, -0.3), V(2.5, 34.5, 1, -0.2, 1.4));
        snprintf(what, n, "builtin:plaid clamped, s from -0.2 to 1.25, t from -0.3 to 1.4, depths 1 to 3");
        break;
    default:
        return false;
    }
    return gen_text_end(&x, s);
}

/* --- grazing floors: the level of detail changes across the triangle ------------- */

bool gen_tex_floor(int i, struct scene *s, char *what, size_t n)
{
    static const char *const textures[] = { "builtin:checker-numbers", "builtin:bricks clamp", "builtin:plaid",
                                            "builtin:grid" };
    if (i >= 4)
        return false;
    struct gen_text x;
    gen_text_start(&x, 64, 48, textures[i]);
    if (i % 2 == 0) {
        /* a floor: far (depth 40) along the top, near (1) along the bottom */
        struct tv a = V(-30.3, 5.2, 40, 0, 0), b = V(94.6, 5.7, 40, 8, 0), c = V(62.1, 47.6, 1, 8, 24),
                  d = V(1.4, 47.3, 1, 0, 24);
        if (i == 2)
            b.s = c.s = 3, c.t = d.t = 40;
        gen_tri(&x, a, b, c);
        gen_tri(&x, a, c, d);
        snprintf(what, n, "%s on a floor receding from depth 1 to 40: the level of detail from 0 to 8", textures[i]);
    } else {
        /* a wall: near on the left, far (depth 60) on the right */
        struct tv a = V(0.6, -2.4, 1, 0, 0), b = V(63.2, 21.3, 60, 30, 0), c = V(63.4, 25.1, 60, 30, 1.5),
                  d = V(0.3, 47.8, 1, 0, 1.5);
        if (i == 1)
            b.s = c.s = 1.4, c.t = d.t = 1.3;
        gen_tri(&x, a, b, c);
        gen_tri(&x, a, c, d);
        snprintf(what, n, "%s on a wall seen at a grazing angle, depths 1 to 60", textures[i]);
    }
    return gen_text_end(&x, s);
}

/* --- tiny triangles: quads with helper pixels -------------------------------------- */

bool gen_tex_tiny(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 3)
        return false;
    struct rng r = rng_start(0x717e9u + (uint64_t)i);
    struct gen_text x;
    gen_text_start(&x, 48, 36, i == 1 ? "builtin:grid" : "builtin:checker-numbers");
    if (i == 0) {
        /* a grid of 4 x 4 pixel cells, two triangles each, the texture
         * spread over it at lambda about 2.5 */
        for (int cy = 0; cy < 6; cy++)
            for (int cx = 0; cx < 8; cx++) {
                double x0 = 4.25 + 4 * cx, y0 = 4.75 + 4 * cy, k = 0.09;
                struct tv a = V(x0, y0, 1, k * cx, k * cy), b = V(x0 + 4, y0, 1, k * cx + k, k * cy),
                          c = V(x0 + 4, y0 + 4, 1, k * cx + k, k * cy + k), d = V(x0, y0 + 4, 1, k * cx, k * cy + k);
                gen_tri(&x, a, b, c);
                gen_tri(&x, a, c, d);
            }
        snprintf(what, n, "96 triangles of 8 pixels, a sheet of 4 x 4 pixel squares, minified");
    } else {
        /* triangles of a pixel or three, each its own scale of texture */
        int count = i == 1 ? 40 : 60;
        double size = i == 1 ? 2.5 : 1.1;
        for (int k = 0; k < count; k++) {
            double cx = rng_range(&r, 2, 46), cy = rng_range(&r, 2, 34), sc = rng_range(&r, 0.01, 0.6);
            double s0 = rng_range(&r, -3, 3), t0 = rng_range(&r, -3, 3);
            struct tv v[3];
            for (int q = 0; q < 3; q++) {
                double dx = rng_range(&r, -size, size), dy = rng_range(&r, -size, size);
                v[q] = V(floor((cx + dx) * 256) / 256, floor((cy + dy) * 256) / 256, rng_range(&r, 1, 3),
                         s0 + sc * dx, t0 + sc * dy);
            }
            gen_tri(&x, v[0], v[1], v[2]);
        }
        snprintf(what, n, "%d textured triangles %s a pixel across, each minified its own way", count,
                 i == 1 ? "of some 2 to 5 pixels" : "smaller than");
    }
    return gen_text_end(&x, s);
}

/* --- 3-D: an OBJ's own texture coordinates, clipping that carries s and t ------ */

bool gen_tex_world(int i, struct scene *s, char *what, size_t n)
{
    char err[256];
    if (i == 0) {
        /* the torus's vt lines, t = 1 - v (OBJ's v points up) */
        snprintf(what, n, "builtin:texture-model, the torus under bricks by its own vt (t flipped)");
        if (scene_builtin(s, "texture-model", err, sizeof err))
            return true;
        fprintf(stderr, "make check: %s\n", err);
        check_scene_start(s, 8, 8);
        return true;
    }
    if (i > 1)
        return false;
    /* a floor from under the eye to far away, cut by near: the new
     * vertices carry s and t, interpolated as positions are */
    struct gen_text x;
    gen_text_start(&x, 64, 48, NULL);
    fprintf(x.f, "camera  0 1 0   0 0.4 -4   0 1 0   60  0.5 60\ntexture builtin:checker-numbers\n"
                 "tri3 -6 0 2 1 1 1 0 0   6 0 2 1 1 1 3 0   6 0 -40 1 1 1 3 10.5\n"
                 "tri3 -6 0 2 1 1 1 0 0   6 0 -40 1 1 1 3 10.5   -6 0 -40 1 1 1 0 10.5\n");
    snprintf(what, n, "a 3-D floor under builtin:checker-numbers from behind the eye to depth 40, cut by near");
    return gen_text_end(&x, s);
}
