/* scenes3.c - the 3-D scenes of make check for lesson 06's clipper
 * (scenes.h): hand-made cuts by near and far first, then closed boxes,
 * floors past the guard band and random cameras. */
#include "scenes.h"
#include "gen.h"

#include <math.h>
#include <stdio.h>

/* --- 3-D scenes for lesson 06's clipper (lessons/CONVENTIONS.md, "3-D scenes") ------- */

static void world_start(struct scene *s, int w, int h, struct camera cam, enum cull cull)
{
    check_scene_start(s, w, h);
    s->world.camera_line = 1;
    s->world.cam = cam;
    s->world.cull = cull;
}

static void tri3(struct scene *s, struct rng *r, const double a[3], const double b[3], const double c[3])
{
    struct world_tri t = { .texture = 0 };   /* no texture, s = t = 0 */
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
    struct rng r = rng_start(0x6c1e0u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e1u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e2u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e3u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e4u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e5u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e6u + (uint64_t)i);
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
    struct rng r = rng_start(0x6c1e7u + (uint64_t)i);
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
