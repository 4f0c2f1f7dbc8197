/* scenes.c - the scenes of make check (scenes.h): hand-made where a check
 * is about particular cases (ties on pixel centres, both windings,
 * degenerate triangles), seeded random where it is about every case. */
#include "scenes.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* splitmix64: the checks draw the same scenes on every run */
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

static double rng_unit(struct rng *r)
{
    return (double)(rng_next(r) >> 11) * 0x1p-53;
}

static double rng_range(struct rng *r, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(r);
}

/* A coordinate as scenes give them: on the 1/256 grid, or on a pixel centre,
 * or an integer, chosen at random. */
static double grid(struct rng *r, double v)
{
    double u = rng_unit(r);
    if (u < 0.2)
        return floor(v) + 0.5;
    if (u < 0.3)
        return floor(v);
    return floor(v * SUBPIXEL_ONE) / SUBPIXEL_ONE;
}

static struct vertex vtx(double x, double y, double z, double r, double g, double b)
{
    return (struct vertex){ .x = x, .y = y, .z = z, .r = r, .g = g, .b = b };
}

/* A vertex with a random colour and a depth in [zmin, zmax]. */
static struct vertex rvtx(struct rng *r, double x, double y, double zmin, double zmax)
{
    return vtx(x, y, rng_range(r, zmin, zmax), rng_unit(r), rng_unit(r), rng_unit(r));
}

static bool add(struct scene *s, struct vertex a, struct vertex b, struct vertex c)
{
    double lim = COORD_LIMIT - 1.0 / SUBPIXEL_ONE;
    struct vertex v[3] = { a, b, c };
    for (int i = 0; i < 3; i++) {
        v[i].x = fmin(fmax(v[i].x, -COORD_LIMIT), lim);
        v[i].y = fmin(fmax(v[i].y, -COORD_LIMIT), lim);
    }
    return scene_add(s, v);
}

/* The same triangle walked the other way round. */
static bool add_flipped(struct scene *s, struct vertex a, struct vertex b, struct vertex c,
                        bool flip)
{
    return flip ? add(s, a, c, b) : add(s, a, b, c);
}

static void scene_start(struct scene *s, int w, int h)
{
    memset(s, 0, sizeof *s);
    s->w = w;
    s->h = h;
}

bool gen_single(int i, struct scene *s, char *what, size_t n)
{
    /* nothing on a pixel centre: no edge passes exactly through one */
    static const double tris[][6] = {
        { 4.3, 3.2, 35.7, 8.9, 13.1, 26.6 },
        { 20.1, 2.2, 27.9, 27.3, 14.6, 18.35 },
        { 7.7, 5.1, 11.2, 9.9, 3.3, 12.4 },
        { 5.1, 4.2, 30.3, 4.2, 17.9, 25.7 },
        { 36.2, 2.9, 37.1, 26.3, 2.7, 14.1 },
    };
    if (i >= (int)(sizeof tris / sizeof tris[0]))
        return false;
    const double *c = tris[i];
    scene_start(s, 40, 30);
    add(s, vtx(c[0], c[1], 1, 1, 0, 0), vtx(c[2], c[3], 2, 0, 1, 0), vtx(c[4], c[5], 3, 0, 0, 1));
    snprintf(what, n, "one triangle (%g, %g) (%g, %g) (%g, %g)", c[0], c[1], c[2], c[3], c[4], c[5]);
    return true;
}

bool gen_ties(int i, struct scene *s, char *what, size_t n)
{
    scene_start(s, 20, 16);
    bool f1 = i & 1, f2 = (i >> 1) & 1;     /* the windings of the two triangles */
    const char *w1 = f1 ? "counter-clockwise" : "clockwise", *w2 = f2 ? "counter-clockwise" : "clockwise";
    struct vertex P = vtx(0, 0, 1, 0.9, 0.5, 0.1);
    switch (i >> 2) {
    case 0:     /* a vertical edge x = 10.5 through pixel centres */
        add_flipped(s, vtx(10.5, 2.5, 1, 1, 0, 0), vtx(10.5, 14.5, 1, 0, 1, 0), vtx(3.2, 8.1, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(10.5, 2.5, 2, 1, 1, 0), vtx(17.7, 9.3, 2, 0, 1, 1), vtx(10.5, 14.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the vertical edge x = 10.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 1:     /* a horizontal edge y = 8.5 */
        add_flipped(s, vtx(2.5, 8.5, 1, 1, 0, 0), vtx(17.5, 8.5, 1, 0, 1, 0), vtx(9.2, 1.3, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(2.5, 8.5, 2, 1, 1, 0), vtx(11.7, 15.6, 2, 0, 1, 1), vtx(17.5, 8.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the horizontal edge y = 8.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 2:     /* a diagonal through a centre every 3 pixels */
        add_flipped(s, vtx(2.5, 2.5, 1, 1, 0, 0), vtx(17.5, 12.5, 1, 0, 1, 0), vtx(4.1, 13.7, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(2.5, 2.5, 2, 1, 1, 0), vtx(16.2, 3.1, 2, 0, 1, 1), vtx(17.5, 12.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the edge (2.5, 2.5)-(17.5, 12.5) through pixel centres (%s, %s)", w1, w2);
        return true;
    case 3:     /* a square of two triangles, every vertex on a pixel centre */
        add_flipped(s, vtx(3.5, 2.5, 1, 1, 0, 0), vtx(15.5, 2.5, 1, 0, 1, 0), vtx(3.5, 13.5, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(15.5, 2.5, 2, 1, 1, 0), vtx(15.5, 13.5, 2, 0, 1, 1), vtx(3.5, 13.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "a square of two triangles, vertices on pixel centres (%s, %s)", w1, w2);
        return true;
    case 4: {   /* a fan of eight around a centre, every vertex on a pixel centre */
        static const double ring[8][2] = { { 10.5, 1.5 }, { 16.5, 3.5 }, { 18.5, 8.5 }, { 15.5, 13.5 },
                                           { 10.5, 14.5 }, { 4.5, 12.5 }, { 1.5, 7.5 }, { 5.5, 2.5 } };
        for (int k = 0; k < 8; k++) {
            const double *a = ring[k], *b = ring[(k + 1) % 8];
            P.x = 10.5, P.y = 8.5;
            add_flipped(s, P, vtx(a[0], a[1], 1, k & 1, 0.5, 1), vtx(b[0], b[1], 1, 1, k & 1, 0.3),
                        (k & 1) ? f1 : f2);
        }
        snprintf(what, n, "a fan of eight triangles around the pixel centre (10.5, 8.5), windings mixed");
        return true;
    }
    case 5:     /* degenerate: they cover nothing */
        if (f2)
            return false;
        if (!f1) {
            add(s, vtx(2.5, 2.5, 1, 1, 1, 1), vtx(8.5, 6.5, 1, 1, 1, 1), vtx(14.5, 10.5, 1, 1, 1, 1));
            add(s, vtx(3.5, 12.5, 1, 1, 1, 1), vtx(15.5, 12.5, 1, 1, 1, 1), vtx(9.5, 12.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: three vertices in line through pixel centres (cover nothing)");
        } else {
            add(s, vtx(4.5, 3.5, 1, 1, 1, 1), vtx(12.3, 9.7, 1, 1, 1, 1), vtx(4.5, 3.5, 1, 1, 1, 1));
            add(s, vtx(7.5, 7.5, 1, 1, 1, 1), vtx(7.5, 7.5, 1, 1, 1, 1), vtx(7.5, 7.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: a repeated vertex, a triangle that is a point (cover nothing)");
        }
        return true;
    }
    return false;
}

/* A jittered grid of nx x ny cells over [x0, x1] x [y0, y1], each cell cut
 * along a random diagonal into two triangles of random winding. */
static void grid_mesh(struct scene *s, struct rng *r, int nx, int ny, double x0, double y0,
                      double x1, double y1, double jitter)
{
    struct vertex *v = malloc(sizeof *v * (size_t)(nx + 1) * (size_t)(ny + 1));
    if (!v)
        return;
    double cw = (x1 - x0) / nx, ch = (y1 - y0) / ny;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double x = x0 + i * cw, y = y0 + j * ch;
            if (i > 0 && i < nx)
                x = grid(r, x + rng_range(r, -jitter, jitter) * cw);
            if (j > 0 && j < ny)
                y = grid(r, y + rng_range(r, -jitter, jitter) * ch);
            v[j * (nx + 1) + i] = rvtx(r, x, y, 1, 4);
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            struct vertex a = v[j * (nx + 1) + i], b = v[j * (nx + 1) + i + 1];
            struct vertex c = v[(j + 1) * (nx + 1) + i + 1], d = v[(j + 1) * (nx + 1) + i];
            if (rng_unit(r) < 0.5) {
                add_flipped(s, a, b, c, rng_unit(r) < 0.5);
                add_flipped(s, a, c, d, rng_unit(r) < 0.5);
            } else {
                add_flipped(s, a, b, d, rng_unit(r) < 0.5);
                add_flipped(s, b, c, d, rng_unit(r) < 0.5);
            }
        }
    free(v);
}

bool gen_meshes(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0x3e5a11u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 6, 4, 2.5, 2.5, 45.5, 33.5, 0.3);
        snprintf(what, n, "a jittered 6 x 4 grid of 48 triangles, corners on pixel centres");
        return true;
    case 1:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 16, 12, 1.3, 1.7, 46.2, 34.1, 0.35);
        snprintf(what, n, "a jittered 16 x 12 grid of 384 small triangles");
        return true;
    case 2:
        scene_start(s, 40, 30);
        grid_mesh(s, &r, 7, 5, -20.25, -15.75, 61.5, 47.25, 0.3);
        snprintf(what, n, "a jittered 7 x 5 grid reaching past every side of the target");
        return true;
    case 3:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 2, 24, 1.5, 0.5, 46.5, 35.5, 0.45);
        snprintf(what, n, "a 2 x 24 grid of long thin triangles");
        return true;
    case 4:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 12, 9, 0, 0, 48, 36, 0);
        snprintf(what, n, "a regular 12 x 9 grid on whole pixels: every edge through pixel corners");
        return true;
    }
    return false;
}

/* Random triangles by kind, one per scene. */
#define RANDOM_SCENES 1600
bool gen_random(int i, struct scene *s, char *what, size_t n)
{
    if (i >= RANDOM_SCENES)
        return false;
    struct rng r = { 0x7a11d0u * 31 + (uint64_t)i };
    int w = 64, h = 48;
    double cx = rng_range(&r, 0, w), cy = rng_range(&r, 0, h);
    struct vertex v[3];
    const char *kind;
    switch (i % 8) {
    case 0:
        kind = "generic";
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 1, 24);
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -d, d)), grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 1:
        kind = "sliver";
        v[0] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), grid(&r, rng_range(&r, 0, h)), 1, 4);
        v[1] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), grid(&r, rng_range(&r, 0, h)), 1, 4);
        {
            double t = rng_unit(&r), d = rng_range(&r, -0.7, 0.7);
            v[2] = rvtx(&r, grid(&r, v[0].x + t * (v[1].x - v[0].x) + d),
                        grid(&r, v[0].y + t * (v[1].y - v[0].y) - d), 1, 4);
        }
        break;
    case 2:
        kind = "smaller than a pixel";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -0.7, 0.7)), grid(&r, cy + rng_range(&r, -0.7, 0.7)), 1, 4);
        break;
    case 3:
        kind = "larger than the target";
        w = 256, h = 192;
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, rng_range(&r, -2.0 * w, 3.0 * w)), grid(&r, rng_range(&r, -2.0 * h, 3.0 * h)), 1, 4);
        break;
    case 4:
        kind = "partly off-screen";
        if (rng_unit(&r) < 0.5)
            cx = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : w + rng_range(&r, -4, 4);
        else
            cy = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : h + rng_range(&r, -4, 4);
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 2, 40);
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -d, d)), grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 5:
        kind = "vertices on pixel centres";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, floor(cx + rng_range(&r, -16, 16)) + 0.5, floor(cy + rng_range(&r, -16, 16)) + 0.5, 1, 4);
        break;
    case 6:
        kind = "a horizontal or vertical edge";
        {
            double a = grid(&r, rng_range(&r, 0, w)), b = grid(&r, rng_range(&r, 0, w));
            double c = grid(&r, rng_range(&r, 0, h)), d = grid(&r, rng_range(&r, 0, h));
            v[0] = rvtx(&r, a, c, 1, 4);
            if (rng_unit(&r) < 0.5)
                v[1] = rvtx(&r, b, c, 1, 4), v[2] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), d, 1, 4);
            else
                v[1] = rvtx(&r, a, d, 1, 4), v[2] = rvtx(&r, b, grid(&r, rng_range(&r, 0, h)), 1, 4);
        }
        break;
    default:
        kind = "with far vertices (up to 16384 px away)";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, rng_range(&r, -16000, 16000)), grid(&r, rng_range(&r, -16000, 16000)), 1, 4);
        if (rng_unit(&r) < 0.7)
            v[0] = rvtx(&r, grid(&r, cx), grid(&r, cy), 1, 4);
        break;
    }
    scene_start(s, w, h);
    add(s, v[0], v[1], v[2]);
    snprintf(what, n, "random triangle %d of %d: %s", i + 1, RANDOM_SCENES, kind);
    return true;
}

bool gen_colour(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0xc0107u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 40, 30);
        add(s, vtx(4.3, 3.2, 1, 1, 0, 0), vtx(35.7, 8.9, 2, 0, 1, 0), vtx(13.1, 26.6, 3, 0, 0, 1));
        snprintf(what, n, "one triangle, red, green and blue corners at depths 1, 2, 3");
        return true;
    case 1:
        scene_start(s, 64, 48);
        add(s, vtx(2.2, 45.1, 1, 1, 1, 0.2), vtx(61.7, 44.3, 1.2, 0.1, 0.9, 1), vtx(30.4, 2.6, 12, 0.9, 0.1, 0.6));
        snprintf(what, n, "a triangle receding from depth 1 to depth 12");
        return true;
    case 2:
        scene_start(s, 48, 36);
        add(s, vtx(3.5, 3.5, 1, 1, 0, 0), vtx(44.5, 5.5, 6, 0, 1, 0), vtx(40.5, 32.5, 2, 0, 0, 1));
        add(s, vtx(3.5, 3.5, 1, 1, 0, 0), vtx(40.5, 32.5, 2, 0, 0, 1), vtx(5.5, 30.5, 9, 1, 1, 1));
        snprintf(what, n, "a quad of two triangles sharing an edge, depths 1 to 9");
        return true;
    case 3:
    case 4: {   /* the nearer triangle must win, whichever is drawn first */
        scene_start(s, 40, 30);
        struct vertex n0 = vtx(3.3, 4.1, 1, 1, 0.2, 0.2), n1 = vtx(30.2, 9.9, 1.5, 1, 0.6, 0.2),
                      n2 = vtx(9.7, 27.4, 1.2, 0.9, 0.1, 0.3);
        struct vertex f0 = vtx(36.1, 2.2, 4, 0.2, 0.3, 1), f1 = vtx(35.3, 28.8, 6, 0.2, 1, 0.6),
                      f2 = vtx(5.2, 15.6, 5, 0.1, 0.6, 1);
        if (i == 3) {
            add(s, n0, n1, n2);
            add(s, f0, f1, f2);
            snprintf(what, n, "depth test: a near triangle, then a far one over it (the near one stays)");
        } else {
            add(s, f0, f1, f2);
            add(s, n0, n1, n2);
            snprintf(what, n, "depth test: a far triangle, then a near one over it");
        }
        return true;
    }
    case 5:
        scene_start(s, 200, 150);
        add(s, vtx(3.1, 2.7, 1, 1, 0.5, 0), vtx(197.2, 40.3, 3, 0, 0.5, 1), vtx(60.6, 148.1, 8, 0.5, 1, 0.5));
        snprintf(what, n, "a large triangle, 200 x 150 pixels, depths 1 to 8");
        return true;
    default:
        if (i >= 6 + 24)
            return false;
        scene_start(s, 48, 36);
        {
            double cx = rng_range(&r, 8, 40), cy = rng_range(&r, 8, 28);
            struct vertex v[3];
            for (int k = 0; k < 3; k++)
                v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -20, 20)), grid(&r, cy + rng_range(&r, -20, 20)), 1, 10);
            add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "random coloured triangle %d of 24, depths 1 to 10", i - 5);
        return true;
    }
}

bool gen_property(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0x9409e7u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 160, 120);
        add(s, vtx(5.3, 4.7, 1, 1, 0, 0), vtx(154.1, 30.2, 2, 0, 1, 0), vtx(40.8, 116.6, 3, 0, 0, 1));
        snprintf(what, n, "a large triangle, 150 pixels across");
        return true;
    case 1:
        scene_start(s, 160, 120);
        add(s, vtx(80.5, 2.5, 1, 1, 1, 0), vtx(157.5, 117.5, 1, 0, 1, 1), vtx(2.5, 117.5, 1, 1, 0, 1));
        add(s, vtx(20.5, 10.5, 2, 1, 1, 0), vtx(60.5, 10.5, 2, 0, 1, 1), vtx(20.5, 50.5, 2, 1, 0, 1));
        snprintf(what, n, "two large triangles, vertices on pixel centres");
        return true;
    case 2:
        scene_start(s, 96, 72);
        grid_mesh(s, &r, 4, 3, -5.5, -3.25, 101.5, 75.5, 0.25);
        snprintf(what, n, "a jittered 4 x 3 grid of large triangles over the target");
        return true;
    case 3:
        scene_start(s, 128, 96);
        add(s, vtx(-300.2, -200.6, 1, 1, 0, 0), vtx(900.3, 40.1, 1, 0, 1, 0), vtx(60.7, 700.9, 1, 0, 0, 1));
        snprintf(what, n, "a triangle larger than the target");
        return true;
    }
    return false;
}

/* --- 3-D scenes for lesson 06's clipper (CONVENTIONS.md, "3-D scenes") ------- */

static void world_start(struct scene *s, int w, int h, struct camera cam, enum cull cull)
{
    scene_start(s, w, h);
    s->world.camera_line = 1;
    s->world.cam = cam;
    s->world.cull = cull;
}

static void tri3(struct scene *s, struct rng *r, const double a[3], const double b[3], const double c[3])
{
    struct world_tri t;
    const double *p[3] = { a, b, c };
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) {
            t.p[k][i] = p[k][i];
            t.rgb[k][i] = rng_unit(r);
        }
    world_add(&s->world, &t);
}

/* The camera of the simple checks: at the origin looking down -z, so that
 * a point at view depth d is at z = -d. */
static const struct camera look_down_z = { { 0, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 }, 60, 1, 10 };
#define LOOK_G 1.7320508075688772   /* 1 / tan(30 degrees) */

/* A world point at view depth d, at (u, v) of the screen (-1..1 across, a
 * little beyond), for the camera above on a w x h target. Behind the eye
 * (d <= 0) u and v are taken at depth 1. */
static void at_depth(double out[3], double u, double v, double d, double aspect)
{
    double k = d > 0 ? d : 1;
    out[0] = u * k * aspect / LOOK_G;
    out[1] = v * k / LOOK_G;
    out[2] = -d;
}

/* A triangle with `behind` vertices at depths in [lo_b, hi_b] and the
 * others in [lo, hi]; the vertex order rotated by i and the winding
 * flipped by i / 3, so that every position of the cut is walked both ways. */
static void cut_triangle(struct scene *s, struct rng *r, int i, int behind, double lo_b, double hi_b,
                         double lo, double hi)
{
    double p[3][3], aspect = (double)s->w / s->h;
    for (int k = 0; k < 3; k++) {
        bool b = k < behind;
        at_depth(p[k], rng_range(r, -1.2, 1.2), rng_range(r, -1.2, 1.2),
                 b ? rng_range(r, lo_b, hi_b) : rng_range(r, lo, hi), aspect);
    }
    int o = i % 3;
    if ((i / 3) % 2)
        tri3(s, r, p[o], p[(o + 2) % 3], p[(o + 1) % 3]);
    else
        tri3(s, r, p[o], p[(o + 1) % 3], p[(o + 2) % 3]);
}

/* The vertex of t with the k-th smallest view depth (the largest z) for
 * the camera above. */
static int nearest(const struct world_tri *t, int k)
{
    int order[3] = { 0, 1, 2 };
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            if (t->p[order[b]][2] > t->p[order[a]][2]) {
                int tmp = order[a];
                order[a] = order[b], order[b] = tmp;
            }
    return order[k];
}

bool gen_no_clip(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 8)
        return false;
    struct rng r = { 0x6c1e0u + (uint64_t)i };
    world_start(s, 48, 36, look_down_z, CULL_NONE);
    for (int k = 0; k <= i % 3; k++)
        cut_triangle(s, &r, i + k, 0, 0, 0, 1.2, 9.5);
    snprintf(what, n, "%d triangle%s between near and far (scene %d of 8)", i % 3 + 1, i % 3 ? "s" : "", i + 1);
    return true;
}

bool gen_behind_one(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 24)
        return false;
    struct rng r = { 0x6c1e1u + (uint64_t)i };
    world_start(s, 48, 36, look_down_z, CULL_NONE);
    cut_triangle(s, &r, i, 1, i < 6 ? -4 : 0.2, i < 6 ? -0.5 : 0.95, 1.5, 8);
    if (i % 8 == 7)             /* the vertex behind exactly at the eye's depth */
        s->world.tris[0].p[nearest(&s->world.tris[0], 0)][2] = 0;
    snprintf(what, n, "a triangle with one vertex %s the near plane (%d of 24)", i < 6 ? "behind the eye and" : "behind",
             i + 1);
    return true;
}

bool gen_behind_two(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 24)
        return false;
    struct rng r = { 0x6c1e2u + (uint64_t)i };
    world_start(s, 48, 36, look_down_z, CULL_NONE);
    cut_triangle(s, &r, i, 2, i < 12 ? -3 : 0.3, 0.9, 1.5, 8);
    if (i >= 18)                /* one of them exactly on the near plane: kept, no new vertex */
        s->world.tris[0].p[nearest(&s->world.tris[0], 1)][2] = -1;
    snprintf(what, n, "a triangle with two vertices behind the near plane%s (%d of 24)",
             i >= 18 ? ", or one on it" : "", i + 1);
    return true;
}

bool gen_crossing_far(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 24)
        return false;
    struct rng r = { 0x6c1e3u + (uint64_t)i };
    world_start(s, 48, 36, look_down_z, CULL_NONE);
    if (i < 16) {
        /* one or two vertices beyond far (cut_triangle's "behind" vertices) */
        cut_triangle(s, &r, i, 1 + i / 8, 10.5, 30, 2, 9.5);
        snprintf(what, n, "a triangle with %d vertex%s beyond the far plane (%d of 24)", 1 + i / 8,
                 i / 8 ? "es" : "", i + 1);
    } else {
        /* through both planes: a vertex behind near, one beyond far (a pentagon) */
        double p[3][3], aspect = (double)s->w / s->h;
        at_depth(p[0], rng_range(&r, -1, 1), rng_range(&r, -1, 1), rng_range(&r, -2, 0.8), aspect);
        at_depth(p[1], rng_range(&r, -1, 1), rng_range(&r, -1, 1), rng_range(&r, 11, 25), aspect);
        at_depth(p[2], rng_range(&r, -1, 1), rng_range(&r, -1, 1), rng_range(&r, 2, 9), aspect);
        int o = i % 3;
        tri3(s, &r, p[o], p[(o + 1) % 3], p[(o + 2) % 3]);
        snprintf(what, n, "a triangle through the near and the far plane (%d of 24)", i + 1);
    }
    return true;
}

bool gen_shared_edge(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 16)
        return false;
    struct rng r = { 0x6c1e4u + (uint64_t)i };
    world_start(s, 64, 48, look_down_z, CULL_NONE);
    double aspect = (double)s->w / s->h;
    if (i < 12) {
        /* two triangles sharing the edge a - b, which the near (or far) plane cuts */
        bool far = i >= 8;
        double a[3], b[3], c[3], d[3];
        at_depth(a, rng_range(&r, -0.8, 0.8), rng_range(&r, -0.8, 0.8), far ? rng_range(&r, 12, 20) : rng_range(&r, -2, 0.9), aspect);
        at_depth(b, rng_range(&r, -0.8, 0.8), rng_range(&r, -0.8, 0.8), rng_range(&r, 2, 8), aspect);
        at_depth(c, rng_range(&r, 0.5, 1.2), rng_range(&r, -1, 1), rng_range(&r, far ? 3 : 0.5, 8), aspect);
        at_depth(d, rng_range(&r, -1.2, -0.5), rng_range(&r, -1, 1), rng_range(&r, far ? 3 : 0.5, 8), aspect);
        if (i % 2)
            tri3(s, &r, a, b, c), tri3(s, &r, b, a, d);   /* the shared edge walked both ways */
        else
            tri3(s, &r, b, c, a), tri3(s, &r, d, b, a);
        snprintf(what, n, "two triangles sharing an edge the %s plane cuts (%d of 16)", far ? "far" : "near", i + 1);
    } else {
        /* a fan of six around a vertex behind the eye: every spoke cut */
        double centre[3], ring[6][3];
        at_depth(centre, 0, 0, -1 - (i - 12), aspect);
        for (int k = 0; k < 6; k++) {
            double ang = k * 1.0471975511965976 + 0.3 * (i - 12);
            at_depth(ring[k], 1.1 * cos(ang), 1.1 * sin(ang), rng_range(&r, 2, 6), aspect);
        }
        for (int k = 0; k < 6; k++)
            tri3(s, &r, centre, ring[k], ring[(k + 1) % 6]);
        snprintf(what, n, "a fan of six triangles around a vertex behind the eye (%d of 16)", i + 1);
    }
    return true;
}

/* The six faces of the box [-h, h]^3, each a k x k grid of quads cut in
 * two: a closed mesh. */
static void box(struct scene *s, struct rng *r, double h, int k)
{
    for (int f = 0; f < 6; f++) {
        int axis = f / 2;
        double side = f % 2 ? h : -h;
        for (int a = 0; a < k; a++)
            for (int b = 0; b < k; b++) {
                double q[4][3];
                static const int corner[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
                for (int c = 0; c < 4; c++) {
                    double u = -h + 2 * h * (a + corner[c][0]) / k, v = -h + 2 * h * (b + corner[c][1]) / k;
                    q[c][axis] = side;
                    q[c][(axis + 1) % 3] = f % 2 ? u : v;
                    q[c][(axis + 2) % 3] = f % 2 ? v : u;
                }
                tri3(s, r, q[0], q[1], q[2]);
                tri3(s, r, q[0], q[2], q[3]);
            }
    }
}

/* A random camera: eye, a target at least 1 away, an up not parallel. */
static struct camera random_camera(struct rng *r, double spread, double fovy_lo, double fovy_hi)
{
    struct camera c;
    for (int k = 0; k < 3; k++) {
        c.eye[k] = rng_range(r, -spread, spread);
        c.target[k] = rng_range(r, -1, 1);
        c.up[k] = rng_range(r, -1, 1);
    }
    double f[3], len = 0, dot = 0, up = 0;
    for (int k = 0; k < 3; k++)
        f[k] = c.target[k] - c.eye[k], len += f[k] * f[k];
    if (len < 1) {
        c.target[0] = c.eye[0] + 1, f[0] += 1;
        len = 0;
        for (int k = 0; k < 3; k++)
            len += f[k] * f[k];
    }
    for (int k = 0; k < 3; k++)
        dot += f[k] * c.up[k], up += c.up[k] * c.up[k];
    if (up < 0.01 || dot * dot > 0.9 * len * up)        /* too near parallel: another up */
        c.up[0] = -f[1], c.up[1] = f[0], c.up[2] = f[2] + 1;
    c.fovy = rng_range(r, fovy_lo, fovy_hi);
    c.near = 1, c.far = 100;
    return c;
}

bool gen_box_inside(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 8)
        return false;
    struct rng r = { 0x6c1e5u + (uint64_t)i };
    struct camera c = random_camera(&r, 1.5, 50, 110);
    c.near = rng_range(&r, 0.02, 0.4);
    c.far = 20;
    world_start(s, 64, 48, c, CULL_NONE);
    int k = 1 + i % 3;
    box(s, &r, 2, k);
    snprintf(what, n, "a closed box of %d triangles seen from inside (%d of 8)", 12 * k * k, i + 1);
    return true;
}

bool gen_floor(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 6)
        return false;
    struct rng r = { 0x6c1e6u + (uint64_t)i };
    double height = rng_range(&r, 0.05, 1.5), yaw = rng_range(&r, 0, 6.283185307179586);
    struct camera c = { { 0, height, 0 }, { sin(yaw) * 10, height - rng_range(&r, 0.5, 3), cos(yaw) * 10 },
                        { 0, 1, 0 }, rng_range(&r, 45, 90), rng_range(&r, 0.005, 0.05), rng_range(&r, 30, 200) };
    world_start(s, 64, 48, c, i % 2 ? CULL_BACK : CULL_NONE);
    const int k = 6;
    const double half = 120;
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++) {
            double x0 = -half + 2 * half * a / k, x1 = -half + 2 * half * (a + 1) / k;
            double z0 = -half + 2 * half * b / k, z1 = -half + 2 * half * (b + 1) / k;
            double p[4][3] = { { x0, 0, z0 }, { x0, 0, z1 }, { x1, 0, z1 }, { x1, 0, z0 } };
            tri3(s, &r, p[0], p[1], p[2]);
            tri3(s, &r, p[0], p[2], p[3]);
        }
    snprintf(what, n, "a floor of %d triangles seen from %.2f above it, reaching past the guard band (%d of 6)",
             2 * k * k, height, i + 1);
    return true;
}

bool gen_random_cameras(int i, struct scene *s, char *what, size_t n)
{
    if (i >= 40)
        return false;
    struct rng r = { 0x6c1e7u + (uint64_t)i };
    struct camera c = random_camera(&r, 5, 30, 120);
    c.near = rng_range(&r, 0.05, 2.5);
    c.far = c.near + rng_range(&r, 1, 8);
    static const int sizes[][2] = { { 48, 36 }, { 64, 48 }, { 40, 40 } };
    world_start(s, sizes[i % 3][0], sizes[i % 3][1], c, (enum cull)(i % 3));
    box(s, &r, rng_range(&r, 0.8, 2.5), 1 + i % 2);
    static const char *const culls[] = { "none", "back", "front" };
    snprintf(what, n, "a closed box from a random camera, near %.3g, far %.3g, cull %s (%d of 40)", c.near, c.far,
             culls[i % 3], i + 1);
    return true;
}
