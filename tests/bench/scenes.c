/* scenes.c - the bench's three scenes, generated from a seed.
 *
 *   large  random triangles of about the screen's size, their vertices up
 *          to 1.6 half-diagonals from a point of the screen, added until
 *          they cover the screen 16 times (vertices stay inside the range
 *          llvmpipe draws without clipping, see peer.c);
 *   small  200,000 triangles of about 10 pixels each;
 *   mixed  100,000 triangles: 95% of about 10 pixels, 4% of 100, 0.9% of
 *          1,000 and 0.1% of 20,000.
 *
 * Every triangle has its own colour per vertex (Gouraud) and depths in
 * [1.5, 99.5]; half of them are wound the other way. Small and mixed
 * triangles lie wholly on the screen, a quarter of them with vertices on
 * the half-pixel grid so that edges pass through pixel centres. The quick mode makes the same kinds
 * of scene at 320 x 176 with fewer triangles.
 *
 * The textured scenes, each under a builtin texture of 256 x 256 texels:
 *
 *   floor      a floor to the horizon and a wall along it, seen at a
 *              grazing angle, in 48 large triangles, white (make_floor);
 *   small-tex  100,000 triangles of about 10 pixels (clamp),
 *   mixed-tex  50,000 of the mixed sizes (repeat), each with (s, t) of its
 *              own: 1/4 to 4 texels a pixel, turned by a random angle.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#define SCREEN_W 1920
#define SCREEN_H 1080
#define QUICK_W 320
#define QUICK_H 176
#define LARGE_OVERDRAW 16
#define Z_MIN 1.5
#define Z_MAX 99.5
#define TAU 6.283185307179586

/* splitmix64: small, seedable, the same numbers on every machine */
struct rng {
    uint64_t s;
};

static uint64_t rng_next(struct rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* uniform in [lo, hi) */
static double rng_range(struct rng *r, double lo, double hi)
{
    return lo + (hi - lo) * (double)(rng_next(r) >> 11) * 0x1p-53;
}

static void random_colour(struct rng *r, struct vertex *v)
{
    v->r = rng_range(r, 0, 1);
    v->g = rng_range(r, 0, 1);
    v->b = rng_range(r, 0, 1);
}

static bool add_random_winding(struct rng *r, struct scene *s, struct vertex v[3], int texture)
{
    if (rng_next(r) & 1) {
        struct vertex tmp = v[1];
        v[1] = v[2];
        v[2] = tmp;
    }
    return scene_add_textured(s, v, texture);
}

/* A triangle of about `area` square pixels, wholly on the screen: three
 * points around a centre, roughly 120 degrees apart, scaled to the area.
 * Under image texture `texture` (0: none) it gets (s, t): the screen turned
 * by a random angle, 1/4 to 4 texels of the 256-texel level 0 a pixel
 * (magnified to minified), around a random point of [st_lo, st_hi)^2. */
static bool add_sized(struct rng *r, struct scene *s, double area, int texture,
                      double st_lo, double st_hi)
{
    double a[3], rad[3];
    a[0] = rng_range(r, 0, TAU);
    for (int k = 1; k < 3; k++)
        a[k] = a[k - 1] + TAU / 3 + rng_range(r, -0.6, 0.6);
    for (int k = 0; k < 3; k++)
        rad[k] = rng_range(r, 0.7, 1.3);
    double ux[3], uy[3];
    for (int k = 0; k < 3; k++) {
        ux[k] = rad[k] * cos(a[k]);
        uy[k] = rad[k] * sin(a[k]);
    }
    double unit = fabs((ux[1] - ux[0]) * (uy[2] - uy[0]) - (ux[2] - ux[0]) * (uy[1] - uy[0])) / 2;
    double scale = sqrt(area * rng_range(r, 0.7, 1.3) / unit);
    double margin = 1.3 * scale + 1;
    double cx = 2 * margin < s->w ? rng_range(r, margin, s->w - margin) : s->w / 2.0;
    double cy = 2 * margin < s->h ? rng_range(r, margin, s->h - margin) : s->h / 2.0;
    double z = rng_range(r, Z_MIN + 0.5, Z_MAX - 0.5);
    struct vertex v[3];
    memset(v, 0, sizeof v);
    /* a quarter of them on the half-pixel grid: edges through pixel
     * centres, where only the fill rule decides */
    double grid = rng_next(r) % 4 == 0 ? 2 : SUBPIXEL_ONE * 64;
    for (int k = 0; k < 3; k++) {
        v[k].x = round((cx + scale * ux[k]) * grid) / grid;
        v[k].y = round((cy + scale * uy[k]) * grid) / grid;
        v[k].z = z + rng_range(r, -0.5, 0.5);
        random_colour(r, &v[k]);
    }
    if (texture) {      /* drawn after the rest: the untextured scenes stay as they were */
        double turn = rng_range(r, 0, TAU), per_pixel = exp2(rng_range(r, -2, 2)) / 256;
        double s0 = rng_range(r, st_lo, st_hi), t0 = rng_range(r, st_lo, st_hi);
        for (int k = 0; k < 3; k++) {
            double dx = v[k].x - cx, dy = v[k].y - cy;
            v[k].s = s0 + per_pixel * (cos(turn) * dx - sin(turn) * dy);
            v[k].t = t0 + per_pixel * (sin(turn) * dx + cos(turn) * dy);
        }
    }
    return add_random_winding(r, s, v, texture);
}

struct counting {
    uint8_t *cov;
    int w;
    uint64_t n;
};

static void count_pixel(void *ctx, int x, int y)
{
    struct counting *c = ctx;
    uint8_t *p = &c->cov[(size_t)y * (size_t)c->w + (size_t)x];
    if (*p < 255)
        (*p)++;
    c->n++;
}

/* Coverage of one triangle, by the reference rasterizer. */
static void count_triangle(const struct scene *s, int i, struct counting *c)
{
    struct tri_setup t;
    tri_setup(&t, s->tris[i].v, s->w, s->h);
    reference_coverage(&t, count_pixel, c);
}

/* Large: a triangle around a point of the screen, its vertices 0.6 to 1.6
 * half-diagonals away, roughly 120 degrees apart; each covers a good part
 * of the screen and crosses it with its edges. */
static bool make_large(struct rng *r, struct bench_scene *b, struct counting *c)
{
    struct scene *s = &b->s;
    uint64_t goal = (uint64_t)LARGE_OVERDRAW * (uint64_t)s->w * (uint64_t)s->h;
    double half_diag = sqrt((double)s->w * s->w + (double)s->h * s->h) / 2;
    while (c->n < goal) {
        double cx = rng_range(r, 0, s->w), cy = rng_range(r, 0, s->h);
        double a = rng_range(r, 0, TAU);
        struct vertex v[3];
        memset(v, 0, sizeof v);
        for (int k = 0; k < 3; k++, a += TAU / 3 + rng_range(r, -0.5, 0.5)) {
            double rad = half_diag * rng_range(r, 0.6, 1.6);
            v[k].x = cx + rad * cos(a);
            v[k].y = cy + rad * sin(a);
            v[k].z = rng_range(r, Z_MIN, Z_MAX);
            random_colour(r, &v[k]);
        }
        if (!add_random_winding(r, s, v, 0))
            return false;
        count_triangle(s, s->ntris - 1, c);
    }
    return true;
}

static bool make_sized(struct rng *r, struct bench_scene *b, int n, const double *area,
                       const double *share, int nsizes, int texture, double st_lo, double st_hi)
{
    for (int i = 0; i < n; i++) {
        double u = rng_range(r, 0, 1);
        int k = 0;
        while (k < nsizes - 1 && u >= share[k]) {
            u -= share[k];
            k++;
        }
        if (!add_sized(r, &b->s, area[k], texture, st_lo, st_hi))
            return false;
    }
    return true;
}

/* --- the textured scenes -------------------------------------------------- */

/* A quadrilateral of the floor or the wall, p[0..3] in order around it, as
 * two triangles: each corner in pixels (a pinhole of focal length f at the
 * screen's centre, looking along +Z, y down), its depth Z, its (s, t). */
static bool add_quad(struct scene *s, const double p[4][3], const double st[4][2], double f,
                     int texture)
{
    struct vertex v[4];
    memset(v, 0, sizeof v);
    for (int k = 0; k < 4; k++) {
        v[k].x = s->w / 2.0 + f * p[k][0] / p[k][2];
        v[k].y = s->h / 2.0 - f * p[k][1] / p[k][2];
        v[k].z = p[k][2];
        v[k].r = v[k].g = v[k].b = 1;
        v[k].s = st[k][0];
        v[k].t = st[k][1];
    }
    struct vertex a[3] = { v[0], v[1], v[2] }, b[3] = { v[0], v[2], v[3] };
    return scene_add_textured(s, a, texture) && scene_add_textured(s, b, texture);
}

/* The floor to the horizon: the eye 1 above a floor (texture 1) that runs
 * from just below the screen's bottom edge to 4,000 ahead, less than a pixel
 * under the horizon, and a wall (texture 2) on the right seen at a grazing
 * angle; both in bands of depth growing geometrically, with shared edges
 * (every pixel of them covered once). Near the eye a texel spans several
 * pixels (magnified), far away a pixel spans thousands (minified, up to the
 * last level; a quad at the horizon has helper pixels beyond it). A 90
 * degree field of view across; white vertices; the seed moves (s, t). */
static bool make_floor(struct rng *r, struct bench_scene *b, int bands)
{
    struct scene *s = &b->s;
    double f = s->w / 2.0, eye = 1, left = -6, right = 2.5, top = 3;
    double z_near = f * eye / (s->h / 2.0 + 100 * s->h / 1080.0), z_far = 4000;
    double s0 = rng_range(r, 0, 1), t0 = rng_range(r, 0, 1);
    double unit = s->w / (2 * 1920.0);  /* (s, t) a world unit: texels as many pixels at any size */
    for (int k = 0; k < bands; k++) {
        double z0 = z_near * pow(z_far / z_near, (double)k / bands);
        double z1 = z_near * pow(z_far / z_near, (double)(k + 1) / bands);
        const double floor_p[4][3] = { { left, -eye, z0 }, { right, -eye, z0 },
                                       { right, -eye, z1 }, { left, -eye, z1 } };
        double sl = s0 + unit * left, sr = s0 + unit * right, t_0 = t0 - unit * z0, t_1 = t0 - unit * z1;
        const double floor_st[4][2] = { { sl, t_0 }, { sr, t_0 }, { sr, t_1 }, { sl, t_1 } };
        const double wall_p[4][3] = { { right, top, z0 }, { right, top, z1 },
                                      { right, -eye, z1 }, { right, -eye, z0 } };
        double tb = unit * (top + eye);
        const double wall_st[4][2] = { { unit * z0, 0 }, { unit * z1, 0 }, { unit * z1, tb }, { unit * z0, tb } };
        if (!add_quad(s, floor_p, floor_st, f, 1) || !add_quad(s, wall_p, wall_st, f, 2))
            return false;
    }
    return true;
}

/* The three scenes, plain (Gouraud) or textured (image textures, other
 * streams of the same seed). */
static bool make_scenes(struct bench_scene sc[3], uint64_t seed, bool quick, bool textured)
{
    static const double small_area[] = { 10 };
    static const double small_share[] = { 1 };
    static const double mixed_area[] = { 10, 100, 1000, 20000 };
    static const double mixed_area_quick[] = { 10, 100, 1000, 4000 };
    static const double mixed_share[] = { 0.95, 0.04, 0.009, 0.001 };
    static const char *const textures[3] = {
        "texture builtin:checker-numbers repeat\ntexture builtin:bricks repeat\n",
        "texture builtin:grid clamp\n",
        "texture builtin:checker-numbers repeat\n",
    };
    static const char *const names[2][3] = {
        { "large", "small", "mixed" }, { "floor", "small-tex", "mixed-tex" },
    };
    static const char *const what[2][3] = { {
        "a few large triangles covering the screen 16 times",
        "triangles of about 10 pixels",
        "mostly 10 pixels, some 100, 1,000 and 20,000",
    }, {
        "a floor to the horizon and a wall at a grazing angle, 256 x 256 textures (repeat), "
        "magnified near the eye, minified far away",
        "triangles of about 10 pixels, a 256 x 256 texture (clamp), 1/4 to 4 texels a pixel",
        "mostly 10 pixels, some 100, 1,000 and 20,000, a 256 x 256 texture (repeat), "
        "1/4 to 4 texels a pixel",
    } };
    int w = quick ? QUICK_W : SCREEN_W, h = quick ? QUICK_H : SCREEN_H;
    int tex = textured ? 1 : 0;         /* the image texture of the sized triangles */

    memset(sc, 0, 3 * sizeof *sc);
    for (int i = 0; i < 3; i++) {
        struct rng r = { seed * 3 + (textured ? 1000 : 0) + (uint64_t)i };
        sc[i].name = names[tex][i];
        sc[i].what = what[tex][i];
        sc[i].s.w = w;
        sc[i].s.h = h;
        if (textured) {     /* the textures, through the scene's own reader */
            char text[256], err[256];
            snprintf(text, sizeof text, "size %d %d\n%s", w, h, textures[i]);
            if (!scene_parse(&sc[i].s, names[tex][i], text, strlen(text), err, sizeof err))
                return false;
            sc[i].s.has_st = true;
        }
        sc[i].coverage = calloc((size_t)w * (size_t)h, 1);
        if (!sc[i].coverage)
            return false;
        struct counting c = { sc[i].coverage, w, 0 };
        bool ok = i == 0 ? (textured ? make_floor(&r, &sc[i], 12) : make_large(&r, &sc[i], &c))
                : i == 1 ? make_sized(&r, &sc[i], quick ? 2000 : textured ? 100000 : 200000,
                                      small_area, small_share, 1, tex, -0.25, 1.25)
                : make_sized(&r, &sc[i], quick ? 2000 : textured ? 50000 : 100000,
                             quick ? mixed_area_quick : mixed_area, mixed_share, 4, tex, -4, 4);
        if (!ok)
            return false;
        if (i > 0 || textured)  /* make_large counts as it goes */
            for (int t = 0; t < sc[i].s.ntris; t++)
                count_triangle(&sc[i].s, t, &c);
        sc[i].pixels = c.n;
    }
    return true;
}

bool bench_scenes_make(struct bench_scene sc[3], uint64_t seed, bool quick)
{
    return make_scenes(sc, seed, quick, false);
}

bool bench_tex_scenes_make(struct bench_scene sc[3], uint64_t seed, bool quick)
{
    return make_scenes(sc, seed, quick, true);
}

void bench_scenes_free(struct bench_scene sc[3])
{
    for (int i = 0; i < 3; i++) {
        scene_free(&sc[i].s);
        free(sc[i].coverage);
    }
}
