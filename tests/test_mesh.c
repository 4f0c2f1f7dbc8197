/* test_mesh.c - watertightness: triangles that share edges cover every pixel
 * centre inside their union exactly once and nothing outside it.
 *
 * "Inside" is decided from the outline alone, never from the triangles:
 * a jittered grid mesh fills the rectangle [X0, X1) x [Y0, Y1) (the top-left
 * rule makes a rectangle half-open: its top and left sides are in, its
 * bottom and right sides out); a fan around a shared vertex fills a convex
 * polygon, whose own edges are top, left or neither by their shape.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

#define MESH_W 64
#define MESH_H 56

/* A coordinate near v: off the 1/256 grid, on it, or on a pixel centre. */
static double jitter_place(struct rng *r, double v)
{
    switch (rng_int(r, 0, 3)) {
    case 0: return v;
    case 1: return round(v * 256) / 256;
    case 2: return floor(v) + 0.5;
    default: return round(v * 4) / 4;
    }
}

/* A coordinate for an outline: on the 1/256 grid, often on a centre or corner. */
static double outline_coord(struct rng *r, double lo, double hi)
{
    double v = rng_range(r, lo, hi);
    switch (rng_int(r, 0, 2)) {
    case 0: return floor(v) + 0.5;
    case 1: return round(v);
    default: return round(v * 256) / 256;
    }
}

struct mesh {
    int ntris;
    struct vertex v[3 * 512];
};

static void add_tri(struct rng *r, struct mesh *m, struct vertex a, struct vertex b, struct vertex c)
{
    struct vertex t[3] = { a, b, c };
    int first = rng_int(r, 0, 2);           /* any vertex first, either winding */
    bool flip = rng_chance(r, 0.5);
    for (int k = 0; k < 3; k++) {
        int i = (first + (flip ? 3 - k : k)) % 3;
        m->v[3 * m->ntris + k] = t[i];
    }
    m->ntris++;
}

/* The same test for every exact variant: draw all triangles, compare. */
static void check_mesh(const struct mesh *m, const uint8_t *expected, const char *what,
                       uint64_t index)
{
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    /* the oracle first: the reference agrees with the outline */
    uint8_t ref[MESH_W * MESH_H] = { 0 };
    for (int i = 0; i < m->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, &m->v[3 * i], MESH_W, MESH_H);
        reference_mask(&t, ref);
    }
    char msg[256];
    snprintf(msg, sizeof msg, "reference_coverage, %s (%d triangles)", what, m->ntris);
    struct case_info rinfo = { msg, test_seed(), index, m->v, 3 * m->ntris };
    cr_assert(coverage_equal(expected, ref, MESH_W, MESH_H, &rinfo));

    struct target fb;
    cr_assert(target_init(&fb, MESH_W, MESH_H, 0));
    for (int k = 0; k < nv; k++) {
        target_clear(&fb);
        for (int i = 0; i < m->ntris; i++) {
            struct tri_setup t;
            tri_setup(&t, &m->v[3 * i], MESH_W, MESH_H);
            rasterize_one(tv[k].variant, NULL, &t, &fb, NULL);
        }
        char label[128];
        snprintf(msg, sizeof msg, "%s, %s (%d triangles; vertices listed per triangle)",
                 variant_label(&tv[k], label, sizeof label), what, m->ntris);
        struct case_info info = { msg, test_seed(), index, m->v, 3 * m->ntris };
        cr_assert(coverage_equal(expected, fb.count, MESH_W, MESH_H, &info));
    }
    target_free(&fb);
}

/* --- jittered grid meshes --------------------------------------------------------- */

/* Counter-clockwise on screen (y down): listed as a grid cell's corners are. */
static bool positive(const struct vertex *a, const struct vertex *b, const struct vertex *c)
{
    /* snapped as lessons/CONVENTIONS.md says: to nearest 1/256, ties to even */
    double ax = nearbyint(a->x * 256), ay = nearbyint(a->y * 256);
    double bx = nearbyint(b->x * 256), by = nearbyint(b->y * 256);
    double cx = nearbyint(c->x * 256), cy = nearbyint(c->y * 256);
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) > 0;
}

static bool grid_mesh(struct rng *r, struct mesh *m, uint8_t *expected, enum fill_convention rule)
{
    /* the outline: a rectangle on the 1/256 grid, sometimes past the target */
    double x0 = outline_coord(r, -6, 20), y0 = outline_coord(r, -6, 16);
    double x1 = outline_coord(r, x0 + 12, MESH_W + 6), y1 = outline_coord(r, y0 + 12, MESH_H + 6);
    int nx = rng_int(r, 1, (int)((x1 - x0) / 3)), ny = rng_int(r, 1, (int)((y1 - y0) / 3));
    if (nx > 12) nx = 12;
    if (ny > 12) ny = 12;
    double cw = (x1 - x0) / nx, ch = (y1 - y0) / ny;

    struct vertex g[13][13];
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double x = i == nx ? x1 : x0 + i * cw, y = j == ny ? y1 : y0 + j * ch;
            bool edge_x = i == 0 || i == nx, edge_y = j == 0 || j == ny;
            /* inner vertices move freely; outline vertices only along the outline */
            if (!edge_x)
                x = jitter_place(r, x + rng_range(r, -0.3, 0.3) * cw);
            if (!edge_y)
                y = jitter_place(r, y + rng_range(r, -0.3, 0.3) * ch);
            g[j][i] = test_vertex(x, y);
            g[j][i].z = rng_range(r, 0.5, 4);
        }
    /* Split each quad along a diagonal that leaves both halves the right way
     * round (a jittered quad may be concave): with every triangle positively
     * oriented and the outline fixed, the triangles tile the rectangle with
     * no fold. A quad neither diagonal can split makes the caller try again. */
    m->ntris = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            struct vertex a = g[j][i], b = g[j][i + 1], c = g[j + 1][i + 1], d = g[j + 1][i];
            bool ac = positive(&a, &b, &c) && positive(&a, &c, &d);
            bool bd = positive(&a, &b, &d) && positive(&b, &c, &d);
            if (!ac && !bd)
                return false;
            if (ac && (!bd || rng_chance(r, 0.5))) {
                add_tri(r, m, a, b, c);
                add_tri(r, m, a, c, d);
            } else {
                add_tri(r, m, a, b, d);
                add_tri(r, m, b, c, d);
            }
        }

    /* inside: X0 <= centre < X1 and Y0 <= centre < Y1 (all on the grid,
     * exact); under the bottom-right rule X0 < centre <= X1, Y0 < centre <= Y1 */
    for (int y = 0; y < MESH_H; y++)
        for (int x = 0; x < MESH_W; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            expected[y * MESH_W + x] = rule == FILL_BOTTOM_RIGHT
                ? cx > x0 && cx <= x1 && cy > y0 && cy <= y1
                : cx >= x0 && cx < x1 && cy >= y0 && cy < y1;
        }
    return true;
}

Test(mesh, jittered_grids_cover_every_inner_centre_once)
{
    struct rng r = rng_for(3000);
    static struct mesh m;
    uint8_t expected[MESH_W * MESH_H];
    int redrawn = 0;
    for (int i = 0; i < 150; i++) {
        if (!grid_mesh(&r, &m, expected, FILL_TOP_LEFT)) {
            redrawn++;
            i--;
            continue;
        }
        check_mesh(&m, expected, "jittered grid", (uint64_t)i);
    }
    cr_assert_lt(redrawn, 150, "the jitter folds most meshes: %d redrawn", redrawn);
}

/* --- the bottom-right rule ---------------------------------------------------------- */

/* The bottom-right rule (raster.h: lesson 02's graded variant) keeps meshes
 * watertight too. No lesson draws by it; the reference decides alone, the
 * rule its parameter. */
static void count_pixel(void *ctx, int x, int y)
{
    uint8_t *n = ctx;
    n[y * MESH_W + x]++;
}

static void reference_count(const struct vertex *v, int ntris, enum fill_convention rule, uint8_t *n)
{
    memset(n, 0, MESH_W * MESH_H);
    for (int i = 0; i < ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, &v[3 * i], MESH_W, MESH_H);
        reference_coverage_rule(&t, rule, count_pixel, n);
    }
}

Test(mesh, jittered_grids_cover_every_inner_centre_once_under_the_bottom_right_rule)
{
    struct rng r = rng_for(3001);
    static struct mesh m;
    uint8_t expected[MESH_W * MESH_H], got[MESH_W * MESH_H];
    int redrawn = 0;
    for (int i = 0; i < 150; i++) {
        if (!grid_mesh(&r, &m, expected, FILL_BOTTOM_RIGHT)) {
            redrawn++;
            i--;
            continue;
        }
        reference_count(m.v, m.ntris, FILL_BOTTOM_RIGHT, got);
        struct case_info info = { "reference_coverage_rule, bottom-right, jittered grid", test_seed(),
                                  (uint64_t)i, m.v, 3 * m.ntris };
        cr_assert(coverage_equal(expected, got, MESH_W, MESH_H, &info));
    }
    cr_assert_lt(redrawn, 150, "the jitter folds most meshes: %d redrawn", redrawn);
}

/* A random triangle cut into three at a point inside it, on the 1/256
 * grid: the three cover every centre the whole one covers exactly once,
 * and nothing else, under either rule (each outer edge keeps its
 * direction, so its owner; each inner edge is shared by two of them). */
Test(mesh, random_triangles_cut_at_an_inner_point_cover_each_centre_once_under_either_rule)
{
    struct rng r = rng_for(3002);
    int cut = 0;
    for (int i = 0; i < 4000; i++) {
        enum tri_category cat = (enum tri_category)(i % CAT_COUNT);
        if (cat == CAT_DEGENERATE)
            continue;
        struct vertex v[3];
        random_tri(&r, cat, MESH_W, MESH_H, v);
        struct tri_setup t;
        tri_setup(&t, v, MESH_W, MESH_H);
        if (t.area2 == 0)
            continue;
        /* barycentric weights on a grid of 1/64, strictly inside */
        int a = rng_int(&r, 1, 62), b = rng_int(&r, 1, 63 - a), c = 64 - a - b;
        double px = (a * t.x[0] + b * t.x[1] + c * t.x[2]) / 64.0, py = (a * t.y[0] + b * t.y[1] + c * t.y[2]) / 64.0;
        struct vertex p = test_vertex(round(px) / SUBPIXEL_ONE, round(py) / SUBPIXEL_ONE);
        struct vertex S[3];     /* the vertices as snapped, in setup's order (the right way round) */
        for (int k = 0; k < 3; k++)
            S[k] = test_vertex(t.x[k] / (double)SUBPIXEL_ONE, t.y[k] / (double)SUBPIXEL_ONE);
        struct vertex three[9] = { S[0], S[1], p, S[1], S[2], p, S[2], S[0], p };
        /* the point must leave all three the triangle's way round, inside it */
        bool inside = true;
        for (int k = 0; k < 3; k++) {
            struct tri_setup u;
            tri_setup(&u, &three[3 * k], MESH_W, MESH_H);
            inside = inside && u.area2 > 0 && !u.swapped;
        }
        if (!inside)
            continue;
        cut++;
        for (int rule = FILL_TOP_LEFT; rule <= FILL_BOTTOM_RIGHT; rule++) {
            uint8_t whole[MESH_W * MESH_H], parts[MESH_W * MESH_H];
            reference_count(S, 1, (enum fill_convention)rule, whole);
            reference_count(three, 3, (enum fill_convention)rule, parts);
            char what[96];
            snprintf(what, sizeof what, "%s triangle cut in three, the %s rule", tri_category_name(cat),
                     rule == FILL_BOTTOM_RIGHT ? "bottom-right" : "top-left");
            struct case_info info = { what, test_seed(), (uint64_t)i, three, 9 };
            cr_assert(coverage_equal(whole, parts, MESH_W, MESH_H, &info));
        }
    }
    cr_assert_gt(cut, 1000, "only %d triangles cut", cut);
}

/* --- fans around a shared vertex ------------------------------------------------- */

/* The rule's definition for the outline edge P -> Q of a convex polygon with
 * an inner point O: top = horizontal with the polygon below; left = not
 * horizontal with the interior on its +x side. Coordinates in 1/256 px. */
static bool outline_top_left(int64_t px, int64_t py, int64_t qx, int64_t qy, int64_t ox, int64_t oy)
{
    if (py == qy)
        return oy > py;
    int64_t d = (ox - px) * (qy - py) - (oy - py) * (qx - px);
    return (qy - py > 0) == (d > 0);
}

static int64_t cross(int64_t px, int64_t py, int64_t qx, int64_t qy, int64_t x, int64_t y)
{
    return (qx - px) * (y - py) - (qy - py) * (x - px);
}

/* A convex polygon around o with n vertices (1/256 grid); false if rounding
 * broke convexity (the caller draws another). */
static bool fan_outline(struct rng *r, double ox, double oy, int n, int64_t (*p)[2])
{
    double rx = rng_range(r, 1.5, 22), ry = rng_range(r, 1.5, 22);
    double start = rng_range(r, 0, 6.283185307179586);
    double ang[16];
    double total = 0;
    for (int i = 0; i < n; i++) {
        ang[i] = rng_range(r, 0.4, 1.0);
        total += ang[i];
    }
    double a = start;
    for (int i = 0; i < n; i++) {
        double x = ox + rx * cos(a), y = oy + ry * sin(a);
        if (rng_chance(r, 0.3)) {           /* on a pixel centre */
            x = floor(x) + 0.5;
            y = floor(y) + 0.5;
        }
        p[i][0] = llround(x * 256);
        p[i][1] = llround(y * 256);
        a += ang[i] / total * 6.283185307179586;
    }
    /* strictly convex, one orientation, the shared vertex strictly inside */
    int64_t sox = llround(ox * 256), soy = llround(oy * 256);
    int sign = 0;
    for (int i = 0; i < n; i++) {
        const int64_t *u = p[i], *v = p[(i + 1) % n], *w = p[(i + 2) % n];
        int64_t turn = cross(u[0], u[1], v[0], v[1], w[0], w[1]);
        int64_t side = cross(u[0], u[1], v[0], v[1], sox, soy);
        int s = turn > 0 ? 1 : turn < 0 ? -1 : 0;
        if (s == 0 || (sign && s != sign) || side == 0 || (side > 0) != (s > 0))
            return false;
        sign = s;
    }
    return true;
}

Test(mesh, fans_around_a_shared_vertex_cover_every_inner_centre_once)
{
    struct rng r = rng_for(3001);
    static struct mesh m;
    uint8_t expected[MESH_W * MESH_H];
    int on_centre = 0;
    for (int i = 0; i < 300; i++) {
        /* the shared vertex: on a pixel centre half of the time */
        double ox = rng_range(&r, 4, MESH_W - 4), oy = rng_range(&r, 4, MESH_H - 4);
        if (i % 2 == 0) {
            ox = floor(ox) + 0.5;
            oy = floor(oy) + 0.5;
            on_centre++;
        } else if (i % 4 == 1) {
            ox = round(ox * 256) / 256;
            oy = round(oy * 256) / 256;
        } else {
            ox = round(ox * 256) / 256 + 1.0 / 1024;   /* off the grid */
        }
        int n = rng_int(&r, 3, 12);
        int64_t p[16][2];
        if (!fan_outline(&r, ox, oy, n, p)) {
            i--;
            continue;
        }
        struct vertex o = test_vertex(ox, oy);
        m.ntris = 0;
        for (int k = 0; k < n; k++) {
            const int64_t *a = p[k], *b = p[(k + 1) % n];
            add_tri(&r, &m, o, test_vertex(a[0] / 256.0, a[1] / 256.0),
                    test_vertex(b[0] / 256.0, b[1] / 256.0));
        }
        /* inside the outline, by the rule applied to the outline's edges */
        int64_t sox = (int64_t)llround(ox * 256), soy = (int64_t)llround(oy * 256);
        for (int y = 0; y < MESH_H; y++)
            for (int x = 0; x < MESH_W; x++) {
                int64_t cx = (int64_t)x * 256 + 128, cy = (int64_t)y * 256 + 128;
                bool in = true;
                for (int k = 0; k < n && in; k++) {
                    const int64_t *a = p[k], *b = p[(k + 1) % n];
                    int64_t s = cross(a[0], a[1], b[0], b[1], cx, cy);
                    int64_t so = cross(a[0], a[1], b[0], b[1], sox, soy);
                    in = s == 0 ? outline_top_left(a[0], a[1], b[0], b[1], sox, soy)
                                : (s > 0) == (so > 0);
                }
                expected[y * MESH_W + x] = in;
            }
        char what[128];
        snprintf(what, sizeof what, "fan of %d around (%.17g, %.17g)", n, ox, oy);
        check_mesh(&m, expected, what, (uint64_t)i);
    }
    cr_assert_gt(on_centre, 100);
}

/* The built-in scenes that claim to be watertight are (by the reference). */
Test(mesh, builtin_shared_edge_fan_and_mesh_cover_each_centre_at_most_once)
{
    const char *names[] = { "shared-edge", "fan", "mesh" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, names[i], err, sizeof err), "%s", err);
        uint8_t *mask = calloc((size_t)s.w * (size_t)s.h, 1);
        for (int k = 0; k < s.ntris; k++) {
            struct tri_setup t;
            tri_setup(&t, s.tris[k].v, s.w, s.h);
            reference_mask(&t, mask);
        }
        for (int p = 0; p < s.w * s.h; p++)
            cr_assert_leq(mask[p], 1, "builtin:%s pixel (%d, %d) covered %d times", names[i],
                          p % s.w, p / s.w, mask[p]);
        free(mask);
        scene_free(&s);
    }
}
