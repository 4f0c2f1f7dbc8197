/* scenes.c - the scenes of make check (scenes.h): hand-made where a check
 * is about particular cases (ties on pixel centres, both windings,
 * degenerate triangles), seeded random where it is about every case. */
#include "scenes.h"
#include "gen.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A coordinate as scenes give them: on the 1/256 grid, or on a pixel centre,
 * or an integer, chosen at random. */
double gen_grid(struct rng *r, double v)
{
    double u = rng_unit(r);
    if (u < 0.2)
        return floor(v) + 0.5;
    if (u < 0.3)
        return floor(v);
    return floor(v * SUBPIXEL_ONE) / SUBPIXEL_ONE;
}

struct vertex gen_vtx(double x, double y, double z, double r, double g, double b)
{
    return (struct vertex){ .x = x, .y = y, .z = z, .r = r, .g = g, .b = b };
}

/* A vertex with a random colour and a depth in [zmin, zmax]. */
struct vertex gen_rvtx(struct rng *r, double x, double y, double zmin, double zmax)
{
    return gen_vtx(x, y, rng_range(r, zmin, zmax), rng_unit(r), rng_unit(r), rng_unit(r));
}

bool gen_add(struct scene *s, struct vertex a, struct vertex b, struct vertex c)
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
bool gen_add_flipped(struct scene *s, struct vertex a, struct vertex b, struct vertex c,
                        bool flip)
{
    return flip ? gen_add(s, a, c, b) : gen_add(s, a, b, c);
}

uint64_t check_seed;

void check_scene_start(struct scene *s, int w, int h)
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
    check_scene_start(s, 40, 30);
    gen_add(s, gen_vtx(c[0], c[1], 1, 1, 0, 0), gen_vtx(c[2], c[3], 2, 0, 1, 0), gen_vtx(c[4], c[5], 3, 0, 0, 1));
    snprintf(what, n, "one triangle (%g, %g) (%g, %g) (%g, %g)", c[0], c[1], c[2], c[3], c[4], c[5]);
    return true;
}

/* Two triangles sharing an edge that runs through pixel centres C + t d
 * (t whole) of a 20 x 16 target, its ends and the third vertices off those
 * centres, on the 1/256 grid: far out, up to the coordinate limit (j even),
 * or a few pixels away (j odd). The exact edge function is 0 on those
 * centres and the top-left rule gives each to one triangle; the same
 * function in float rounds products of 20 to 40 significant bits, and its
 * sign there is a coin toss. */
static bool far_ties(int j, bool f1, bool f2, struct scene *s, char *what, size_t n)
{
    static const int dirs[8][2] = { { 7, 3 }, { -5, 11 }, { 13, -2 }, { 1, 9 },
                                    { 3, 4 }, { -9, 5 }, { 11, 1 }, { 2, -7 } };
    const int *d = dirs[j / 2];
    bool far = j % 2 == 0;
    double cx = 9.5 + j % 3, cy = 7.5 + j % 2;
    double len = fmax(abs(d[0]), abs(d[1]));
    /* the ends at t = -ta and t = tb, fractions of 1/256 that are odd */
    double ta = far ? floor(16000 / len) + 37.0 / 256 : 1 + (29 + 8 * j) / 256.0;
    double tb = far ? floor(15000 / len) + 211.0 / 256 : 1 + (157 + 4 * j) / 256.0;
    struct vertex A = gen_vtx(cx - ta * d[0], cy - ta * d[1], 1, 1, 0, 0);
    struct vertex B = gen_vtx(cx + tb * d[0], cy + tb * d[1], 1, 0, 1, 0);
    /* the third vertices either side, along the normal (-d1, d0) */
    double u = far ? floor(9000 / len) + 101.0 / 256 : 3 + 77.0 / 256;
    double fx = far ? 0.25 : 0.5;
    struct vertex P = gen_vtx(cx - u * d[1] + fx * d[0], cy + u * d[0] + fx * d[1], 2, 0, 0, 1);
    struct vertex Q = gen_vtx(cx + u * d[1] - fx * d[0], cy - u * d[0] - fx * d[1], 2, 1, 1, 0);
    gen_add_flipped(s, A, B, P, f1);
    gen_add_flipped(s, B, A, Q, f2);
    snprintf(what, n, "two triangles sharing an edge through the pixel centres (%g, %g) + t (%d, %d), "
             "%s (%s, %s)", cx, cy, d[0], d[1],
             far ? "its ends near the coordinate limit" : "its ends a pixel off, between 1/256 grid points",
             f1 ? "counter-clockwise" : "clockwise", f2 ? "counter-clockwise" : "clockwise");
    return true;
}

/* Two triangles sharing a long edge that misses a pixel centre C by the
 * least an edge can miss it, F = +-1 (1/65536 of a pixel squared): one
 * triangle covers C, the other does not. The edge's ends lie thousands of
 * pixels away on the 1/256 grid, so that the products of any float form of
 * F, (x - xa)(ya - yb) and the like, are rounded by a thousand times F:
 * only exact integers tell the two triangles apart. */
static bool near_ties(int j, bool f1, bool f2, struct scene *s, char *what, size_t n)
{
    static const int64_t dirs[8][2] = { { 1795, 769 }, { -1283, 2819 }, { 3331, -515 }, { 257, 2305 },
                                        { 771, 1025 }, { -2305, 1283 }, { 2819, 259 }, { 517, -1793 } };
    int64_t dx = dirs[j][0], dy = dirs[j][1];
    /* e with dx ey - dy ex = 1 (extended Euclid on dx and -dy, coprime) */
    int64_t r0 = dx, r1 = -dy, s0 = 1, s1 = 0, t0 = 0, t1 = 1;
    while (r1 != 0) {
        int64_t q = r0 / r1, r = r0 - q * r1, ss = s0 - q * s1, tt = t0 - q * t1;
        r0 = r1, r1 = r, s0 = s1, s1 = ss, t0 = t1, t1 = tt;
    }
    /* dx s0 - dy t0 = r0 = +-1: e = (ex, ey) = (t0, s0) * r0 */
    int64_t ex = t0 * r0, ey = s0 * r0;
    int64_t len = llabs(dx) > llabs(dy) ? llabs(dx) : llabs(dy);
    int64_t m = (int64_t)14000 * SUBPIXEL_ONE / len, k = (int64_t)27000 * SUBPIXEL_ONE / len;
    double cx = 9.5 + j % 3, cy = 7.5 + j % 2;
    int64_t X = (int64_t)(cx * SUBPIXEL_ONE), Y = (int64_t)(cy * SUBPIXEL_ONE);
    int64_t ax = X - m * dx + ex, ay = Y - m * dy + ey;
    struct vertex A = gen_vtx((double)ax / SUBPIXEL_ONE, (double)ay / SUBPIXEL_ONE, 1, 1, 0, 0);
    struct vertex B = gen_vtx((double)(ax + k * dx) / SUBPIXEL_ONE, (double)(ay + k * dy) / SUBPIXEL_ONE, 1, 0, 1, 0);
    double u = 3000.0 / ((double)len / SUBPIXEL_ONE);
    struct vertex P = gen_vtx(cx - u * (double)dy / SUBPIXEL_ONE, cy + u * (double)dx / SUBPIXEL_ONE, 2, 0, 0, 1);
    struct vertex Q = gen_vtx(cx + u * (double)dy / SUBPIXEL_ONE, cy - u * (double)dx / SUBPIXEL_ONE, 2, 1, 1, 0);
    gen_add_flipped(s, A, B, P, f1);
    gen_add_flipped(s, B, A, Q, f2);
    snprintf(what, n, "two triangles sharing an edge from (%g, %g) to (%g, %g) that misses the pixel centre "
             "(%g, %g) by 1/65536 of a pixel squared (%s, %s)", A.x, A.y, B.x, B.y, cx, cy,
             f1 ? "counter-clockwise" : "clockwise", f2 ? "counter-clockwise" : "clockwise");
    return true;
}

bool gen_ties(int i, struct scene *s, char *what, size_t n)
{
    check_scene_start(s, 20, 16);
    bool f1 = i & 1, f2 = (i >> 1) & 1;     /* the windings of the two triangles */
    const char *w1 = f1 ? "counter-clockwise" : "clockwise", *w2 = f2 ? "counter-clockwise" : "clockwise";
    struct vertex P = gen_vtx(0, 0, 1, 0.9, 0.5, 0.1);
    switch (i >> 2) {
    case 0:     /* a vertical edge x = 10.5 through pixel centres */
        gen_add_flipped(s, gen_vtx(10.5, 2.5, 1, 1, 0, 0), gen_vtx(10.5, 14.5, 1, 0, 1, 0), gen_vtx(3.2, 8.1, 1, 0, 0, 1), f1);
        gen_add_flipped(s, gen_vtx(10.5, 2.5, 2, 1, 1, 0), gen_vtx(17.7, 9.3, 2, 0, 1, 1), gen_vtx(10.5, 14.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the vertical edge x = 10.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 1:     /* a horizontal edge y = 8.5 */
        gen_add_flipped(s, gen_vtx(2.5, 8.5, 1, 1, 0, 0), gen_vtx(17.5, 8.5, 1, 0, 1, 0), gen_vtx(9.2, 1.3, 1, 0, 0, 1), f1);
        gen_add_flipped(s, gen_vtx(2.5, 8.5, 2, 1, 1, 0), gen_vtx(11.7, 15.6, 2, 0, 1, 1), gen_vtx(17.5, 8.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the horizontal edge y = 8.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 2:     /* a diagonal through a centre every 3 pixels */
        gen_add_flipped(s, gen_vtx(2.5, 2.5, 1, 1, 0, 0), gen_vtx(17.5, 12.5, 1, 0, 1, 0), gen_vtx(4.1, 13.7, 1, 0, 0, 1), f1);
        gen_add_flipped(s, gen_vtx(2.5, 2.5, 2, 1, 1, 0), gen_vtx(16.2, 3.1, 2, 0, 1, 1), gen_vtx(17.5, 12.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the edge (2.5, 2.5)-(17.5, 12.5) through pixel centres (%s, %s)", w1, w2);
        return true;
    case 3:     /* a square of two triangles, every vertex on a pixel centre */
        gen_add_flipped(s, gen_vtx(3.5, 2.5, 1, 1, 0, 0), gen_vtx(15.5, 2.5, 1, 0, 1, 0), gen_vtx(3.5, 13.5, 1, 0, 0, 1), f1);
        gen_add_flipped(s, gen_vtx(15.5, 2.5, 2, 1, 1, 0), gen_vtx(15.5, 13.5, 2, 0, 1, 1), gen_vtx(3.5, 13.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "a square of two triangles, vertices on pixel centres (%s, %s)", w1, w2);
        return true;
    case 4: {   /* a fan of eight around a centre, every vertex on a pixel centre */
        static const double ring[8][2] = { { 10.5, 1.5 }, { 16.5, 3.5 }, { 18.5, 8.5 }, { 15.5, 13.5 },
                                           { 10.5, 14.5 }, { 4.5, 12.5 }, { 1.5, 7.5 }, { 5.5, 2.5 } };
        for (int k = 0; k < 8; k++) {
            const double *a = ring[k], *b = ring[(k + 1) % 8];
            P.x = 10.5, P.y = 8.5;
            gen_add_flipped(s, P, gen_vtx(a[0], a[1], 1, k & 1, 0.5, 1), gen_vtx(b[0], b[1], 1, 1, k & 1, 0.3),
                        (k & 1) ? f1 : f2);
        }
        snprintf(what, n, "a fan of eight triangles around the pixel centre (10.5, 8.5), windings mixed");
        return true;
    }
    case 5: case 6: case 7: case 8: case 9: case 10: case 11: case 12:
    case 13: case 14: case 15: case 16: case 17: case 18: case 19: case 20:
        return far_ties((i >> 2) - 5, f1, f2, s, what, n);
    case 21: case 22: case 23: case 24: case 25: case 26: case 27: case 28:
        return near_ties((i >> 2) - 21, f1, f2, s, what, n);
    case 29:    /* degenerate: they cover nothing (the last scenes) */
        if (f2)
            return false;
        if (!f1) {
            gen_add(s, gen_vtx(2.5, 2.5, 1, 1, 1, 1), gen_vtx(8.5, 6.5, 1, 1, 1, 1), gen_vtx(14.5, 10.5, 1, 1, 1, 1));
            gen_add(s, gen_vtx(3.5, 12.5, 1, 1, 1, 1), gen_vtx(15.5, 12.5, 1, 1, 1, 1), gen_vtx(9.5, 12.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: three vertices in line through pixel centres (cover nothing)");
        } else {
            gen_add(s, gen_vtx(4.5, 3.5, 1, 1, 1, 1), gen_vtx(12.3, 9.7, 1, 1, 1, 1), gen_vtx(4.5, 3.5, 1, 1, 1, 1));
            gen_add(s, gen_vtx(7.5, 7.5, 1, 1, 1, 1), gen_vtx(7.5, 7.5, 1, 1, 1, 1), gen_vtx(7.5, 7.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: a repeated vertex, a triangle that is a point (cover nothing)");
        }
        return true;
    }
    return false;
}

/* A jittered grid of nx x ny cells over [x0, x1] x [y0, y1], each cell cut
 * along a random diagonal into two triangles of random winding. */
void gen_grid_mesh(struct scene *s, struct rng *r, int nx, int ny, double x0, double y0,
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
                x = gen_grid(r, x + rng_range(r, -jitter, jitter) * cw);
            if (j > 0 && j < ny)
                y = gen_grid(r, y + rng_range(r, -jitter, jitter) * ch);
            v[j * (nx + 1) + i] = gen_rvtx(r, x, y, 1, 4);
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            struct vertex a = v[j * (nx + 1) + i], b = v[j * (nx + 1) + i + 1];
            struct vertex c = v[(j + 1) * (nx + 1) + i + 1], d = v[(j + 1) * (nx + 1) + i];
            if (rng_unit(r) < 0.5) {
                gen_add_flipped(s, a, b, c, rng_unit(r) < 0.5);
                gen_add_flipped(s, a, c, d, rng_unit(r) < 0.5);
            } else {
                gen_add_flipped(s, a, b, d, rng_unit(r) < 0.5);
                gen_add_flipped(s, b, c, d, rng_unit(r) < 0.5);
            }
        }
    free(v);
}

bool gen_meshes(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = rng_start(0x3e5a11u + (uint64_t)i);
    switch (i) {
    case 0:
        check_scene_start(s, 48, 36);
        gen_grid_mesh(s, &r, 6, 4, 2.5, 2.5, 45.5, 33.5, 0.3);
        snprintf(what, n, "a jittered 6 x 4 grid of 48 triangles, corners on pixel centres");
        return true;
    case 1:
        check_scene_start(s, 48, 36);
        gen_grid_mesh(s, &r, 16, 12, 1.3, 1.7, 46.2, 34.1, 0.35);
        snprintf(what, n, "a jittered 16 x 12 grid of 384 small triangles");
        return true;
    case 2:
        check_scene_start(s, 40, 30);
        gen_grid_mesh(s, &r, 7, 5, -20.25, -15.75, 61.5, 47.25, 0.3);
        snprintf(what, n, "a jittered 7 x 5 grid reaching past every side of the target");
        return true;
    case 3:
        check_scene_start(s, 48, 36);
        gen_grid_mesh(s, &r, 2, 24, 1.5, 0.5, 46.5, 35.5, 0.45);
        snprintf(what, n, "a 2 x 24 grid of long thin triangles");
        return true;
    case 4:
        check_scene_start(s, 48, 36);
        gen_grid_mesh(s, &r, 12, 9, 0, 0, 48, 36, 0);
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
    struct rng r = rng_start(0x7a11d0u * 31 + (uint64_t)i);
    int w = 64, h = 48;
    double cx = rng_range(&r, 0, w), cy = rng_range(&r, 0, h);
    struct vertex v[3];
    const char *kind;
    switch (i % 8) {
    case 0:
        kind = "generic";
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 1, 24);
            v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -d, d)), gen_grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 1:
        kind = "sliver";
        v[0] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, 0, w)), gen_grid(&r, rng_range(&r, 0, h)), 1, 4);
        v[1] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, 0, w)), gen_grid(&r, rng_range(&r, 0, h)), 1, 4);
        {
            double t = rng_unit(&r), d = rng_range(&r, -0.7, 0.7);
            v[2] = gen_rvtx(&r, gen_grid(&r, v[0].x + t * (v[1].x - v[0].x) + d),
                        gen_grid(&r, v[0].y + t * (v[1].y - v[0].y) - d), 1, 4);
        }
        break;
    case 2:
        kind = "smaller than a pixel";
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -0.7, 0.7)), gen_grid(&r, cy + rng_range(&r, -0.7, 0.7)), 1, 4);
        break;
    case 3:
        kind = "larger than the target";
        w = 256, h = 192;
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -2.0 * w, 3.0 * w)), gen_grid(&r, rng_range(&r, -2.0 * h, 3.0 * h)), 1, 4);
        break;
    case 4:
        kind = "partly off-screen";
        if (rng_unit(&r) < 0.5)
            cx = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : w + rng_range(&r, -4, 4);
        else
            cy = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : h + rng_range(&r, -4, 4);
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 2, 40);
            v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -d, d)), gen_grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 5:
        kind = "vertices on pixel centres";
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, floor(cx + rng_range(&r, -16, 16)) + 0.5, floor(cy + rng_range(&r, -16, 16)) + 0.5, 1, 4);
        break;
    case 6:
        kind = "a horizontal or vertical edge";
        {
            double a = gen_grid(&r, rng_range(&r, 0, w)), b = gen_grid(&r, rng_range(&r, 0, w));
            double c = gen_grid(&r, rng_range(&r, 0, h)), d = gen_grid(&r, rng_range(&r, 0, h));
            v[0] = gen_rvtx(&r, a, c, 1, 4);
            if (rng_unit(&r) < 0.5)
                v[1] = gen_rvtx(&r, b, c, 1, 4), v[2] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, 0, w)), d, 1, 4);
            else
                v[1] = gen_rvtx(&r, a, d, 1, 4), v[2] = gen_rvtx(&r, b, gen_grid(&r, rng_range(&r, 0, h)), 1, 4);
        }
        break;
    default:
        kind = "with far vertices (up to 16384 px away)";
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -16000, 16000)), gen_grid(&r, rng_range(&r, -16000, 16000)), 1, 4);
        if (rng_unit(&r) < 0.7)
            v[0] = gen_rvtx(&r, gen_grid(&r, cx), gen_grid(&r, cy), 1, 4);
        break;
    }
    check_scene_start(s, w, h);
    gen_add(s, v[0], v[1], v[2]);
    snprintf(what, n, "random triangle %d of %d: %s", i + 1, RANDOM_SCENES, kind);
    return true;
}

bool gen_colour(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = rng_start(0xc0107u + (uint64_t)i);
    switch (i) {
    case 0:
        check_scene_start(s, 40, 30);
        gen_add(s, gen_vtx(4.3, 3.2, 1, 1, 0, 0), gen_vtx(35.7, 8.9, 2, 0, 1, 0), gen_vtx(13.1, 26.6, 3, 0, 0, 1));
        snprintf(what, n, "one triangle, red, green and blue corners at depths 1, 2, 3");
        return true;
    case 1:
        check_scene_start(s, 64, 48);
        gen_add(s, gen_vtx(2.2, 45.1, 1, 1, 1, 0.2), gen_vtx(61.7, 44.3, 1.2, 0.1, 0.9, 1), gen_vtx(30.4, 2.6, 12, 0.9, 0.1, 0.6));
        snprintf(what, n, "a triangle receding from depth 1 to depth 12");
        return true;
    case 2:
        check_scene_start(s, 48, 36);
        gen_add(s, gen_vtx(3.5, 3.5, 1, 1, 0, 0), gen_vtx(44.5, 5.5, 6, 0, 1, 0), gen_vtx(40.5, 32.5, 2, 0, 0, 1));
        gen_add(s, gen_vtx(3.5, 3.5, 1, 1, 0, 0), gen_vtx(40.5, 32.5, 2, 0, 0, 1), gen_vtx(5.5, 30.5, 9, 1, 1, 1));
        snprintf(what, n, "a quad of two triangles sharing an edge, depths 1 to 9");
        return true;
    case 3:
    case 4: {   /* the nearer triangle must win, whichever is drawn first */
        check_scene_start(s, 40, 30);
        struct vertex n0 = gen_vtx(3.3, 4.1, 1, 1, 0.2, 0.2), n1 = gen_vtx(30.2, 9.9, 1.5, 1, 0.6, 0.2),
                      n2 = gen_vtx(9.7, 27.4, 1.2, 0.9, 0.1, 0.3);
        struct vertex f0 = gen_vtx(36.1, 2.2, 4, 0.2, 0.3, 1), f1 = gen_vtx(35.3, 28.8, 6, 0.2, 1, 0.6),
                      f2 = gen_vtx(5.2, 15.6, 5, 0.1, 0.6, 1);
        if (i == 3) {
            gen_add(s, n0, n1, n2);
            gen_add(s, f0, f1, f2);
            snprintf(what, n, "depth test: a near triangle, then a far one over it (the near one stays)");
        } else {
            gen_add(s, f0, f1, f2);
            gen_add(s, n0, n1, n2);
            snprintf(what, n, "depth test: a far triangle, then a near one over it");
        }
        return true;
    }
    case 5:
        check_scene_start(s, 200, 150);
        gen_add(s, gen_vtx(3.1, 2.7, 1, 1, 0.5, 0), gen_vtx(197.2, 40.3, 3, 0, 0.5, 1), gen_vtx(60.6, 148.1, 8, 0.5, 1, 0.5));
        snprintf(what, n, "a large triangle, 200 x 150 pixels, depths 1 to 8");
        return true;
    default:
        if (i >= 6 + 24)
            return false;
        check_scene_start(s, 48, 36);
        {
            double cx = rng_range(&r, 8, 40), cy = rng_range(&r, 8, 28);
            struct vertex v[3];
            for (int k = 0; k < 3; k++)
                v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -20, 20)), gen_grid(&r, cy + rng_range(&r, -20, 20)), 1, 10);
            gen_add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "random coloured triangle %d of 24, depths 1 to 10", i - 5);
        return true;
    }
}

bool gen_property(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = rng_start(0x9409e7u + (uint64_t)i);
    switch (i) {
    case 0:
        check_scene_start(s, 160, 120);
        gen_add(s, gen_vtx(5.3, 4.7, 1, 1, 0, 0), gen_vtx(154.1, 30.2, 2, 0, 1, 0), gen_vtx(40.8, 116.6, 3, 0, 0, 1));
        snprintf(what, n, "a large triangle, 150 pixels across");
        return true;
    case 1:
        check_scene_start(s, 160, 120);
        gen_add(s, gen_vtx(80.5, 2.5, 1, 1, 1, 0), gen_vtx(157.5, 117.5, 1, 0, 1, 1), gen_vtx(2.5, 117.5, 1, 1, 0, 1));
        gen_add(s, gen_vtx(20.5, 10.5, 2, 1, 1, 0), gen_vtx(60.5, 10.5, 2, 0, 1, 1), gen_vtx(20.5, 50.5, 2, 1, 0, 1));
        snprintf(what, n, "two large triangles, vertices on pixel centres");
        return true;
    case 2:
        check_scene_start(s, 96, 72);
        gen_grid_mesh(s, &r, 4, 3, -5.5, -3.25, 101.5, 75.5, 0.25);
        snprintf(what, n, "a jittered 4 x 3 grid of large triangles over the target");
        return true;
    case 3:
        check_scene_start(s, 128, 96);
        gen_add(s, gen_vtx(-300.2, -200.6, 1, 1, 0, 0), gen_vtx(900.3, 40.1, 1, 0, 1, 0), gen_vtx(60.7, 700.9, 1, 0, 0, 1));
        snprintf(what, n, "a triangle larger than the target");
        return true;
    }
    return false;
}

/* Lesson 07's scenes: 64 x 64 tiles and their 8 x 8 blocks, on targets
 * whose last column and row of tiles the screen cuts (200 x 150: tiles 8
 * pixels wide and 22 tall there, blocks 6 tall), simplest first. */
#define TILE_SCENES_RANDOM 48
#define TILE_SCENES_EDGES 16
bool gen_tiles(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = rng_start(0x7113u + (uint64_t)i);
    check_scene_start(s, 200, 150);
    switch (i) {
    case 0:
        gen_add(s, gen_vtx(65.3, 66.2, 1, 1, 0, 0), gen_vtx(71.1, 67.9, 2, 0, 1, 0), gen_vtx(66.8, 70.7, 3, 0, 0, 1));
        snprintf(what, n, "a triangle inside one 8 x 8 block of tile (1, 1)");
        return true;
    case 1:
        gen_add(s, gen_vtx(70.2, 68.9, 1, 1, 0, 0), gen_vtx(121.7, 80.3, 2, 0, 1, 0), gen_vtx(83.4, 122.6, 3, 0, 0, 1));
        snprintf(what, n, "a triangle inside tile (1, 1), across its blocks");
        return true;
    case 2:
        gen_add(s, gen_vtx(40.3, 20.7, 1, 1, 0, 0), gen_vtx(100.6, 35.2, 2, 0, 1, 0), gen_vtx(55.9, 58.1, 3, 0, 0, 1));
        snprintf(what, n, "a triangle across the border of two tiles");
        return true;
    case 3:
        gen_add(s, gen_vtx(-30.2, -20.7, 1, 1, 0, 0), gen_vtx(260.4, 30.1, 2, 0, 1, 0), gen_vtx(40.8, 230.3, 3, 0, 0, 1));
        snprintf(what, n, "a large triangle over many tiles, some of them inside it in full");
        return true;
    case 4:     /* F = 0 exactly at corners of tiles: the fill rule decides them */
        gen_add(s, gen_vtx(0.5, 0.5, 1, 1, 0, 0), gen_vtx(128.5, 0.5, 2, 0, 1, 0), gen_vtx(128.5, 128.5, 3, 0, 0, 1));
        gen_add(s, gen_vtx(0.5, 0.5, 2, 1, 1, 0), gen_vtx(128.5, 128.5, 3, 0, 1, 1), gen_vtx(0.5, 128.5, 1, 1, 0, 1));
        snprintf(what, n, "two triangles sharing the diagonal through the corner pixel centres of "
                 "tiles (0, 0) and (1, 1), edges along the first row and column of tiles");
        return true;
    case 5:     /* a left and a top edge on the first centres of tile (1, 0): inside, the tile full */
        gen_add(s, gen_vtx(64.5, 0.5, 1, 1, 0, 0), gen_vtx(400.5, 0.5, 2, 0, 1, 0), gen_vtx(64.5, 400.5, 3, 0, 0, 1));
        /* a right and a bottom edge on the last centres of tile (1, 1): outside */
        gen_add(s, gen_vtx(127.5, 64.5, 1, 1, 1, 0), gen_vtx(127.5, 127.5, 2, 0, 1, 1), gen_vtx(64.5, 127.5, 3, 1, 0, 1));
        snprintf(what, n, "edges exactly on the corner pixel centres of tiles: left and top edges "
                 "(those centres inside), right and bottom ones (outside)");
        return true;
    case 6:
        gen_add(s, gen_vtx(-300, -300, 1, 1, 0, 0), gen_vtx(900, -300, 2, 0, 1, 0), gen_vtx(-300, 900, 3, 0, 0, 1));
        snprintf(what, n, "a triangle over the whole screen: every tile inside it, the cut ones too");
        return true;
    case 7:     /* the tiles of the last column and row lie inside; the tiles' full 64 x 64 do not */
        gen_add(s, gen_vtx(200.25, 10.3, 1, 1, 0, 0), gen_vtx(200.25, 150.25, 2, 0, 1, 0), gen_vtx(60.1, 150.25, 3, 0, 0, 1));
        snprintf(what, n, "a triangle whose edges run just past the screen's right and bottom edges "
                 "(the tiles cut by the screen inside it)");
        return true;
    case 8:
        gen_grid_mesh(s, &r, 10, 8, -3.5, -2.5, 203.5, 152.5, 0.3);
        snprintf(what, n, "a jittered 10 x 8 grid of 160 triangles over 4 x 3 tiles");
        return true;
    }
    if (i >= 9 + TILE_SCENES_RANDOM + TILE_SCENES_EDGES)
        return false;
    if (i >= 9 + TILE_SCENES_RANDOM) {
        /* triangles mostly off-screen, poking in across one side: the
         * tiles and blocks that the screen's side and the box cut */
        static const char *const sides[4] = { "left", "top", "right", "bottom" };
        static const int sizes[][2] = { { 200, 150 }, { 130, 70 } };
        int e = (i - 9 - TILE_SCENES_RANDOM) % 4;
        check_scene_start(s, sizes[(i / 4) % 2][0], sizes[(i / 4) % 2][1]);
        for (int tri = 0; tri < 8; tri++) {
            double along = rng_range(&r, -20, (e % 2 ? s->w : s->h) + 20), in = rng_range(&r, 0.2, 6);
            double out1 = rng_range(&r, 4, 160), out2 = rng_range(&r, 4, 160);
            double a1 = along + rng_range(&r, -90, 90), a2 = along + rng_range(&r, -90, 90);
            double lim = e % 2 ? s->h : s->w;   /* the side's coordinate: 0 or the size */
            double d[3][2] = { { along, e < 2 ? in : lim - in }, { a1, e < 2 ? -out1 : lim + out1 },
                               { a2, e < 2 ? -out2 : lim + out2 } };
            struct vertex v[3];
            for (int q = 0; q < 3; q++) {
                double x = e % 2 ? d[q][0] : d[q][1], y = e % 2 ? d[q][1] : d[q][0];
                v[q] = gen_rvtx(&r, gen_grid(&r, x), gen_grid(&r, y), 1, 6);
            }
            gen_add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "8 triangles mostly off-screen, each poking in across the %s side of %d x %d pixels",
                 sides[e], s->w, s->h);
        return true;
    }
    /* random scenes: targets of 1 to 4 x 3 tiles, triangles small and large,
     * vertices drawn towards the borders of tiles and blocks */
    static const int sizes[][2] = { { 200, 150 }, { 130, 70 }, { 64, 64 }, { 129, 65 } };
    int k = (i - 9) % 4;
    check_scene_start(s, sizes[k][0], sizes[k][1]);
    for (int tri = 0; tri < 6; tri++) {
        struct vertex v[3];
        double scale = tri % 3 == 0 ? 160 : tri % 3 == 1 ? 24 : 5;
        double cx = rng_range(&r, -10, s->w + 10), cy = rng_range(&r, -10, s->h + 10);
        for (int q = 0; q < 3; q++) {
            double x = cx + rng_range(&r, -scale, scale), y = cy + rng_range(&r, -scale, scale);
            /* a third of them onto a border of blocks: the centre on either side */
            x = rng_unit(&r) < 0.3 ? 8 * floor(x / 8 + 0.5) + (rng_unit(&r) < 0.5 ? -0.5 : 0.5) : gen_grid(&r, x);
            y = rng_unit(&r) < 0.3 ? 8 * floor(y / 8 + 0.5) + (rng_unit(&r) < 0.5 ? -0.5 : 0.5) : gen_grid(&r, y);
            v[q] = gen_rvtx(&r, x, y, 1, 6);
        }
        gen_add(s, v[0], v[1], v[2]);
    }
    snprintf(what, n, "random scene %d of %d: 6 triangles on %d x %d pixels", i - 8, TILE_SCENES_RANDOM,
             s->w, s->h);
    return true;
}
