/* test_front.c - the 3-D front end (lessons/CONVENTIONS.md, "3-D scenes"), with
 * random cameras:
 *
 *   - a triangle that needs no clipping covers exactly the pixels of the 2-D
 *     triangle with its projected vertices, projected here by the test's own
 *     reading of the pinned formulas, in every exact lesson variant;
 *   - seen from inside a closed box, every pixel is covered exactly once
 *     (near clipping, guard band and all);
 *   - a closed convex mesh seen from outside covers every pixel 0 or 2 times,
 *     a closed torus an even number of times (cull none);
 *   - a floor reaching far past the guard band has no holes: every pixel
 *     whose centre sees the floor (decided by casting a ray here) is
 *     covered once, every other pixel not at all;
 *   - the stages themselves: canonical new vertices, d on the plane, the
 *     fan from the first vertex, facing and cull.
 *
 * Replay a failure with the seed it prints: TRISTEP_SEED=... --filter 'front/...'.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "explore/replay.h" /* render_scene */
#include "testlib.h"

/* --- the test's own reading of the projection -------------------------------------- */

static const double PI = 3.14159265358979323846;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(double o[3], const double a[3], const double b[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void unit3(double v[3])
{
    double l = sqrt(dot3(v, v));
    v[0] /= l, v[1] /= l, v[2] /= l;
}

/* gluLookAt's basis, written from the convention's text. */
struct basis {
    double f[3], s[3], u[3];
};

static struct basis basis_of(const struct camera *c)
{
    struct basis b;
    for (int i = 0; i < 3; i++)
        b.f[i] = c->target[i] - c->eye[i];
    unit3(b.f);
    cross3(b.s, b.f, c->up);
    unit3(b.s);
    cross3(b.u, b.s, b.f);
    return b;
}

/* x_s = W/2 (1 + g x_v / (a d)), y_s = H/2 (1 - g y_v / d), z = d. */
static struct vertex project_point(const struct camera *c, int w, int h, const double p[3],
                                   const double rgb[3])
{
    struct basis b = basis_of(c);
    double q[3] = { p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2] };
    double xv = dot3(b.s, q), yv = dot3(b.u, q), d = dot3(b.f, q);
    double g = 1.0 / tan(c->fovy * PI / 360.0), a = (double)w / h;
    return (struct vertex){ .x = w / 2.0 * (1 + g * xv / (a * d)), .y = h / 2.0 * (1 - g * yv / d),
                            .z = d, .r = rgb[0], .g = rgb[1], .b = rgb[2] };
}

/* The world point at view coordinates (x_v, y_v, d). */
static void world_at(const struct camera *c, double xv, double yv, double d, double out[3])
{
    struct basis b = basis_of(c);
    for (int i = 0; i < 3; i++)
        out[i] = c->eye[i] + xv * b.s[i] + yv * b.u[i] + d * b.f[i];
}

/* --- random cameras and scenes ---------------------------------------------------------- */

static void random_dir(struct rng *r, double v[3])
{
    do {
        for (int i = 0; i < 3; i++)
            v[i] = rng_range(r, -1, 1);
    } while (dot3(v, v) < 0.01 || dot3(v, v) > 1);
    unit3(v);
}

/* A camera at eye looking along a random direction, with a random up (not
 * parallel to it), field of view and clipping planes. */
static struct camera random_camera(struct rng *r, const double eye[3], double near, double far)
{
    struct camera c = { .near = near, .far = far, .fovy = rng_range(r, 15, 150) };
    double f[3], up[3], x[3];
    random_dir(r, f);
    do {
        random_dir(r, up);
        cross3(x, f, up);
    } while (dot3(x, x) < 0.05);
    double dist = rng_range(r, 0.5, 20);
    for (int i = 0; i < 3; i++) {
        c.eye[i] = eye[i];
        c.target[i] = eye[i] + dist * f[i];
        c.up[i] = up[i] * rng_range(r, 0.5, 3);
    }
    return c;
}

static struct scene scene3_new(int w, int h, const struct camera *c)
{
    struct scene s = { .w = w, .h = h };
    s.world.cam = *c;
    s.world.camera_line = 1;
    return s;
}

static void add_world_tri(struct scene *s, const double a[3], const double b[3], const double c[3],
                          const double rgb[3])
{
    struct world_tri t = { .texture = 0 };
    const double *p[3] = { a, b, c };
    for (int i = 0; i < 3; i++) {
        memcpy(t.p[i], p[i], sizeof t.p[i]);
        memcpy(t.rgb[i], rgb, sizeof t.rgb[i]);
    }
    cr_assert(world_add(&s->world, &t));
}

/* A quad a b c d (in order round it) as two triangles, split on either
 * diagonal, each starting at any corner, in either winding. */
static void add_quad(struct rng *r, struct scene *s, const double *q[4], const double rgb[3])
{
    int k = rng_int(r, 0, 1);
    const double *t[2][3] = { { q[k], q[k + 1], q[(k + 2) % 4] }, { q[k], q[(k + 2) % 4], q[(k + 3) % 4] } };
    for (int i = 0; i < 2; i++) {
        int first = rng_int(r, 0, 2);
        bool flip = rng_chance(r, 0.5);
        const double *v[3];
        for (int j = 0; j < 3; j++)
            v[j] = t[i][(first + (flip ? 3 - j : j)) % 3];
        add_world_tri(s, v[0], v[1], v[2], rgb);
    }
}

/* The 8 corners of a box: centre, half sizes along three orthonormal axes. */
static void box_corners(const double centre[3], const double half[3], double axes[3][3],
                        double corner[8][3])
{
    for (int i = 0; i < 8; i++)
        for (int c = 0; c < 3; c++) {
            corner[i][c] = centre[c];
            for (int a = 0; a < 3; a++)
                corner[i][c] += ((i >> a) & 1 ? half[a] : -half[a]) * axes[a][c];
        }
}

static void random_axes(struct rng *r, double axes[3][3])
{
    double x[3];
    random_dir(r, axes[0]);
    do {
        random_dir(r, x);
        cross3(axes[2], axes[0], x);
    } while (dot3(axes[2], axes[2]) < 0.1);
    unit3(axes[2]);
    cross3(axes[1], axes[2], axes[0]);
}

/* The 6 faces of a box as 12 triangles. */
static void add_box(struct rng *r, struct scene *s, double corner[8][3])
{
    static const int faces[6][4] = {
        { 0, 1, 3, 2 }, { 4, 6, 7, 5 }, { 0, 4, 5, 1 }, { 2, 3, 7, 6 }, { 0, 2, 6, 4 }, { 1, 5, 7, 3 },
    };
    for (int f = 0; f < 6; f++) {
        const double *q[4];
        for (int i = 0; i < 4; i++)
            q[i] = corner[faces[f][i]];
        double rgb[3] = { rng_unit(r), rng_unit(r), rng_unit(r) };
        add_quad(r, s, q, rgb);
    }
}

/* A UV sphere (convex) or a torus (closed, not convex) of `seg` x `rings`
 * quads around centre, radii R (and r for the torus). */
static void add_round(struct rng *r, struct scene *s, const double centre[3], double R, double rr,
                      bool torus, int seg, int rings)
{
    double (*p)[3] = malloc((size_t)(seg * (rings + 1)) * sizeof *p);
    for (int j = 0; j <= rings; j++)
        for (int i = 0; i < seg; i++) {
            double u = 2 * PI * i / seg, v = torus ? 2 * PI * j / rings : PI * j / rings;
            double *q = p[j * seg + i];
            if (torus) {
                q[0] = centre[0] + (R + rr * cos(v)) * cos(u);
                q[1] = centre[1] + rr * sin(v);
                q[2] = centre[2] + (R + rr * cos(v)) * sin(u);
            } else {
                q[0] = centre[0] + R * sin(v) * cos(u);
                q[1] = centre[1] + R * cos(v);
                q[2] = centre[2] + R * sin(v) * sin(u);
            }
        }
    double rgb[3] = { 0.7, 0.5, 0.3 };
    for (int j = 0; j < rings; j++)
        for (int i = 0; i < seg; i++) {
            int j1 = torus ? (j + 1) % rings : j + 1, i1 = (i + 1) % seg;
            const double *q[4] = { p[j * seg + i], p[j * seg + i1], p[j1 * seg + i1], p[j1 * seg + i] };
            if (!torus && j == 0)                   /* the pole: one triangle */
                add_world_tri(s, q[0], q[2], q[3], rgb);
            else if (!torus && j == rings - 1)
                add_world_tri(s, q[0], q[1], q[2], rgb);
            else
                add_quad(r, s, q, rgb);
        }
    free(p);
}

/* --- coverage of a projected scene ---------------------------------------------------- */

/* Pixels next to a fold, kept out of the checks (lessons/CONVENTIONS.md: snapping
 * the new vertices of a clipped polygon whose vertices are nearly in line
 * can fold it). A world triangle's fan folds when its drawn triangles do not
 * all face the same way; every pixel within one pixel of such a fan is
 * marked. Returns how many world triangles folded. */
static int mark_folds(const struct scene *s, uint8_t *skip)
{
    int folds = 0;
    for (int i = 0; i < s->ntris;) {
        int k = i, sign = 0;
        bool folded = false;
        for (; k < s->ntris && s->world.from[k] == s->world.from[i]; k++) {
            int64_t a = facing_area(s->tris[k].v);
            int sk = (a > 0) - (a < 0);
            if (sk && sign && sk != sign)
                folded = true;
            if (sk)
                sign = sk;
        }
        if (folded) {
            folds++;
            for (int j = i; j < k; j++) {
                double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
                for (int v = 0; v < 3; v++) {
                    const double c[2] = { s->tris[j].v[v].x, s->tris[j].v[v].y };
                    for (int a = 0; a < 2; a++)
                        lo[a] = fmin(lo[a], c[a]), hi[a] = fmax(hi[a], c[a]);
                }
                for (int y = (int)fmax(0, floor(lo[1]) - 1); y <= (int)fmin(s->h - 1, hi[1] + 1); y++)
                    for (int x = (int)fmax(0, floor(lo[0]) - 1); x <= (int)fmin(s->w - 1, hi[0] + 1); x++)
                        skip[(size_t)y * s->w + x] = 1;
            }
        }
        i = k;
    }
    return folds;
}

/* Every pixel's count is allowed[] (a bit set of counts); at least one pixel
 * has need (if need >= 0). */
static void expect_counts(const struct scene *s, const uint8_t *mask, const uint8_t *skip,
                          unsigned allowed, int need, const char *what, uint64_t seed, int c)
{
    int have = 0;
    for (int y = 0; y < s->h; y++)
        for (int x = 0; x < s->w; x++) {
            size_t i = (size_t)y * s->w + x;
            if (skip && skip[i])
                continue;
            cr_assert(mask[i] < 32 && (allowed >> mask[i] & 1),
                      "%s: pixel (%d, %d) covered %d times (seed 0x%llx, case %d)", what, x, y,
                      mask[i], (unsigned long long)seed, c);
            have += mask[i] == need;
        }
    if (need >= 0)
        cr_assert_gt(have, 0, "%s: no pixel covered %d times (seed 0x%llx, case %d)", what, need,
                     (unsigned long long)seed, c);
}

/* --- 1. no clipping: exactly the 2-D triangle --------------------------------------- */

Test(front, unclipped_triangles_cover_the_projected_2d_triangle, .timeout = 120)
{
    struct rng r = rng_for(6001);
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    struct raster_params p = default_params();
    for (int c = 0; c < 60; c++) {
        int w = rng_int(&r, 8, 72), h = rng_int(&r, 8, 56);
        double eye[3] = { rng_range(&r, -50, 50), rng_range(&r, -50, 50), rng_range(&r, -50, 50) };
        double near = rng_range(&r, 0.01, 2), far = near * rng_range(&r, 2, 1000);
        struct camera cam = random_camera(&r, eye, near, far);
        struct scene s = scene3_new(w, h, &cam);
        s.world.cull = CULL_NONE;
        double g = 1.0 / tan(cam.fovy * PI / 360.0), a = (double)w / h;
        struct vertex want[40][3];
        int n = rng_int(&r, 1, 40);
        for (int i = 0; i < n; i++) {
            double pts[3][3], rgb[3] = { rng_unit(&r), rng_unit(&r), rng_unit(&r) };
            /* inside the frustum with a margin, or off screen but inside the band */
            double spread = rng_chance(&r, 0.3) ? 3 : 1.1;
            for (int k = 0; k < 3; k++) {
                double d = rng_range(&r, near * 1.01, far * 0.99);
                double nx = rng_range(&r, -spread, spread), ny = rng_range(&r, -spread, spread);
                world_at(&cam, nx * a * d / g, ny * d / g, d, pts[k]);
            }
            add_world_tri(&s, pts[0], pts[1], pts[2], rgb);
            for (int k = 0; k < 3; k++)
                want[i][k] = project_point(&cam, w, h, pts[k], rgb);
        }
        cr_assert(front_scene(&s));
        cr_assert_eq(s.ntris, n, "case %d: %d triangles in, %d out (none needed clipping)", c, n,
                     s.ntris);
        uint8_t *expected = calloc((size_t)w * h, 1);
        for (int i = 0; i < n; i++) {
            cr_assert_eq(s.world.from[i], i);
            for (int k = 0; k < 3; k++) {
                const struct vertex *got = &s.tris[i].v[k];
                cr_assert(fabs(got->x - want[i][k].x) <= 1e-9 && fabs(got->y - want[i][k].y) <= 1e-9
                          && fabs(got->z - want[i][k].z) <= 1e-12 * want[i][k].z,
                          "case %d tri %d vertex %d: (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)",
                          c, i, k, got->x, got->y, got->z, want[i][k].x, want[i][k].y, want[i][k].z);
            }
            struct tri_setup t;
            tri_setup(&t, want[i], w, h);
            reference_mask(&t, expected);
        }
        for (int k = 0; k < nv; k++) {
            struct target fb;
            cr_assert(render_scene(&s, tv[k].variant, &p, &fb));
            char label[128], what[200];
            snprintf(what, sizeof what, "%s, case %d", variant_label(&tv[k], label, sizeof label), c);
            struct case_info info = { what, test_seed(), (uint64_t)c, &want[0][0], 3 * n };
            cr_assert(coverage_equal(expected, fb.count, w, h, &info));
            target_free(&fb);
        }
        free(expected);
        scene_free(&s);
    }
}

/* --- 2. inside a closed box: every pixel once --------------------------------------------- */

Test(front, inside_a_closed_box_every_pixel_is_covered_once, .timeout = 120)
{
    struct rng r = rng_for(6002);
    const struct lesson_variant *l05 = NULL;
    for (int i = 0; all_lessons[i]; i++)
        if (strncmp(all_lessons[i]->id, "05-", 3) == 0)
            l05 = &all_lessons[i]->variants[0];
    cr_assert_not_null(l05);
    struct raster_params p = default_params();
    int folds = 0, guard_clipped = 0, near_clipped = 0;
    for (int c = 0; c < 200; c++) {
        int w = rng_int(&r, 8, 80), h = rng_int(&r, 8, 64);
        double axes[3][3], half[3], centre[3] = { rng_range(&r, -100, 100), rng_range(&r, -100, 100),
                                                  rng_range(&r, -100, 100) };
        random_axes(&r, axes);
        double scale = pow(10, rng_range(&r, -1, 2));
        for (int a = 0; a < 3; a++)
            half[a] = scale * rng_range(&r, 0.3, 3);
        double corner[8][3];
        box_corners(centre, half, axes, corner);
        /* the eye anywhere inside, at least 2 % of the box's size from a wall */
        double eye[3], margin = 1e9;
        memcpy(eye, centre, sizeof eye);
        for (int a = 0; a < 3; a++) {
            double o = rng_range(&r, -0.98, 0.98) * half[a];
            margin = fmin(margin, half[a] - fabs(o));
            for (int k = 0; k < 3; k++)
                eye[k] += o * axes[a][k];
        }
        struct camera cam = random_camera(&r, eye, 1, 30 * scale);
        /* near in front of every wall: a wall point at distance >= margin
         * seen at the frustum's corner has d >= margin cos(corner angle) */
        double tan_y = tan(cam.fovy * PI / 360.0), a = (double)w / h;
        double cos_corner = 1 / sqrt(1 + tan_y * tan_y * (1 + a * a));
        cam.near = margin * cos_corner * pow(10, rng_range(&r, -5, -0.05));
        struct scene s = scene3_new(w, h, &cam);
        add_box(&r, &s, corner);
        cr_assert(front_scene(&s));
        near_clipped += s.ntris > 12;
        /* did any triangle reach past the guard band? */
        struct frustum fr;
        frustum_init(&fr, &cam, w, h);
        for (int i = 0; i < s.world.ntris; i++) {
            struct poly a = { .n = 3 }, b, d;
            for (int k = 0; k < 3; k++)
                a.v[k] = view_vertex(&fr, s.world.tris[i].p[k], s.world.tris[i].rgb[k]);
            struct plane pn = depth_plane(&fr, PLANE_NEAR), pf = depth_plane(&fr, PLANE_FAR);
            clip_polygon(&b, &a, &pn, NULL);
            clip_polygon(&d, &b, &pf, NULL);
            project(&fr, &d);
            guard_clipped += !in_guard_band(&d);
        }
        uint8_t *mask = reference_scene(&s);
        uint8_t *skip = calloc((size_t)w * h, 1);
        folds += mark_folds(&s, skip);
        expect_counts(&s, mask, skip, 1u << 1, 1, "inside a box (reference)", test_seed(), c);
        struct target fb;
        cr_assert(render_scene(&s, l05, &p, &fb));
        expect_counts(&s, fb.count, skip, 1u << 1, 1, "inside a box (lesson 05)", test_seed(), c);
        target_free(&fb);
        free(mask);
        free(skip);
        scene_free(&s);
    }
    cr_log_info("inside a box: 200 cameras, %d near-clipped, %d triangles past the guard band, "
                "%d folds kept out", near_clipped, guard_clipped, folds);
    cr_expect_gt(near_clipped, 100, "the near plane cut the walls in too few cases");
    cr_expect_gt(guard_clipped, 100, "too few triangles reached past the guard band");
    cr_expect_lt(folds, 10, "folds are meant to be rare: %d", folds);
}

/* --- 3. closed meshes from outside: 0 or 2 ------------------------------------------------- */

Test(front, closed_meshes_from_outside_cover_pixels_an_even_number_of_times, .timeout = 120)
{
    struct rng r = rng_for(6003);
    int folds = 0, twos = 0;
    for (int c = 0; c < 150; c++) {
        int w = rng_int(&r, 8, 80), h = rng_int(&r, 8, 64);
        int kind = c % 3;       /* box, UV sphere, torus */
        double scale = pow(10, rng_range(&r, -2, 3));
        double centre[3] = { rng_range(&r, -1, 1) * scale, rng_range(&r, -1, 1) * scale,
                             rng_range(&r, -1, 1) * scale };
        double radius = scale * rng_range(&r, 0.2, 1);
        /* the eye outside the bounding sphere, looking roughly at the mesh;
         * near just in front of it (so that close up, the mesh projects
         * far past the guard band) */
        double dir[3], eye[3];
        random_dir(&r, dir);
        double dist = radius * (rng_chance(&r, 0.5) ? rng_range(&r, 1.02, 1.3) : rng_range(&r, 1.3, 8));
        for (int k = 0; k < 3; k++)
            eye[k] = centre[k] + dist * dir[k];
        double near = (dist - radius) * rng_range(&r, 0.05, 0.99), far = (dist + radius) * 1.5;
        struct camera cam = random_camera(&r, eye, near, far);
        for (int k = 0; k < 3; k++)   /* look towards the mesh, a little off */
            cam.target[k] = centre[k] + radius * rng_range(&r, -0.8, 0.8);
        double x[3], f[3] = { cam.target[0] - eye[0], cam.target[1] - eye[1], cam.target[2] - eye[2] };
        cross3(x, f, cam.up);
        if (dot3(x, x) < 1e-6 * dot3(f, f) * dot3(cam.up, cam.up))
            continue;
        struct scene s = scene3_new(w, h, &cam);
        s.world.camera_line = 1;
        if (kind == 0) {
            double axes[3][3], half[3] = { radius * 0.5, radius * 0.4, radius * 0.55 }, corner[8][3];
            random_axes(&r, axes);
            box_corners(centre, half, axes, corner);
            add_box(&r, &s, corner);
        } else {
            add_round(&r, &s, centre, kind == 1 ? radius : radius * 0.65, radius * 0.3, kind == 2,
                      rng_int(&r, 5, 24), rng_int(&r, 3, 12));
        }
        /* seen from outside means wholly in front of near: move near closer
         * than the nearest vertex */
        struct frustum fr;
        frustum_init(&fr, &cam, w, h);
        double dmin = INFINITY;
        for (int i = 0; i < s.world.ntris; i++)
            for (int k = 0; k < 3; k++)
                dmin = fmin(dmin, view_vertex(&fr, s.world.tris[i].p[k], s.world.tris[i].rgb[k]).pos[2]);
        if (!(dmin > 0)) {
            scene_free(&s);
            continue;
        }
        s.world.cam.near = fmin(cam.near, dmin * 0.999);
        cr_assert(front_scene(&s));
        uint8_t *mask = reference_scene(&s);
        uint8_t *skip = calloc((size_t)w * h, 1);
        folds += mark_folds(&s, skip);
        unsigned allowed = kind == 2 ? 0x55555555u : (1u << 0 | 1u << 2);   /* even, or 0 and 2 */
        expect_counts(&s, mask, skip, allowed, -1, kind == 2 ? "torus" : "convex mesh", test_seed(), c);
        for (size_t i = 0; i < (size_t)w * h; i++)
            twos += mask[i] == 2;
        free(mask);
        free(skip);
        scene_free(&s);
    }
    cr_expect_gt(twos, 10000, "the meshes were hardly seen (%d pixels covered twice)", twos);
    cr_expect_lt(folds, 10, "folds are meant to be rare: %d", folds);
}

/* --- 4. a floor to the horizon, past the guard band: no holes ---------------------------- */

/* Does the ray through the point (sx, sy) of the screen meet the floor
 * y = 0, |x|, |z| <= L, at a view depth in [near, far]? */
static bool sees_floor(const struct camera *c, int w, int h, double sx, double sy, double L)
{
    struct basis b = basis_of(c);
    double g = 1.0 / tan(c->fovy * PI / 360.0), a = (double)w / h;
    double xr = (sx / (w / 2.0) - 1) * a / g, yr = (1 - sy / (h / 2.0)) / g;
    double dir[3];
    for (int i = 0; i < 3; i++)
        dir[i] = b.f[i] + xr * b.s[i] + yr * b.u[i];     /* one unit of depth */
    if (!(dir[1] < 0))
        return false;
    double d = -c->eye[1] / dir[1];
    double hx = c->eye[0] + d * dir[0], hz = c->eye[2] + d * dir[2];
    return d >= c->near && d <= c->far && fabs(hx) <= L && fabs(hz) <= L;
}

Test(front, a_floor_past_the_guard_band_has_no_holes, .timeout = 120)
{
    struct rng r = rng_for(6004);
    int checked = 0, guard_clipped = 0;
    for (int c = 0; c < 60; c++) {
        int w = rng_int(&r, 16, 96), h = rng_int(&r, 12, 72);
        double L = pow(10, rng_range(&r, 3, 5.5)), height = rng_range(&r, 0.02, 3);
        int n = rng_int(&r, 2, 12);
        double eye[3] = { rng_range(&r, -0.5, 0.5) * L, height, rng_range(&r, -0.5, 0.5) * L };
        double yaw = rng_range(&r, 0, 2 * PI), pitch = rng_range(&r, -0.6, 0.15);
        struct camera cam = { .eye = { eye[0], eye[1], eye[2] }, .up = { 0, 1, 0 },
                              .fovy = rng_range(&r, 30, 120), .near = rng_range(&r, 0.001, 0.5),
                              .far = L * rng_range(&r, 0.3, 3) };
        cam.target[0] = eye[0] + cos(yaw) * cos(pitch);
        cam.target[1] = eye[1] + sin(pitch);
        cam.target[2] = eye[2] + sin(yaw) * cos(pitch);
        struct scene s = scene3_new(w, h, &cam);
        double (*grid)[3] = malloc((size_t)((n + 1) * (n + 1)) * sizeof *grid);
        for (int j = 0; j <= n; j++)
            for (int i = 0; i <= n; i++) {
                double *q = grid[j * (n + 1) + i];
                q[0] = -L + 2 * L * i / n, q[1] = 0, q[2] = -L + 2 * L * j / n;
            }
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                const double *q[4] = { grid[j * (n + 1) + i], grid[j * (n + 1) + i + 1],
                                       grid[(j + 1) * (n + 1) + i + 1], grid[(j + 1) * (n + 1) + i] };
                double rgb[3] = { (i + j) % 2 ? 0.9 : 0.3, 0.5, 0.5 };
                add_quad(&r, &s, q, rgb);
            }
        free(grid);
        cr_assert(front_scene(&s));
        for (int i = 0; i < s.ntris; i++)
            for (int k = 0; k < 3; k++)
                guard_clipped += fabs(s.tris[i].v[k].x) >= GUARD_BAND - 1
                                 || fabs(s.tris[i].v[k].y) >= GUARD_BAND - 1;
        uint8_t *mask = reference_scene(&s);
        uint8_t *skip = calloc((size_t)w * h, 1);
        mark_folds(&s, skip);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                size_t i = (size_t)y * w + x;
                cr_assert_leq(mask[i], 1, "floor: pixel (%d, %d) covered %d times (seed 0x%llx, case %d)",
                              x, y, mask[i], (unsigned long long)test_seed(), c);
                /* decided only where the centre is not within 1/64 px of an outline */
                bool in = sees_floor(&cam, w, h, x + 0.5, y + 0.5, L);
                bool sure = true;
                for (int k = 0; k < 4 && sure; k++)
                    sure = sees_floor(&cam, w, h, x + 0.5 + (k == 0) / 64.0 - (k == 1) / 64.0,
                                      y + 0.5 + (k == 2) / 64.0 - (k == 3) / 64.0, L) == in;
                if (!sure || skip[i])
                    continue;
                checked++;
                cr_assert_eq(mask[i], in, "floor: pixel (%d, %d) %s (seed 0x%llx, case %d)", x, y,
                             in ? "is a hole" : "is covered off the floor",
                             (unsigned long long)test_seed(), c);
            }
        free(mask);
        free(skip);
        scene_free(&s);
    }
    cr_expect_gt(checked, 50000);
    cr_expect_gt(guard_clipped, 100, "too few vertices on the guard band (%d)", guard_clipped);
}

/* --- 5. the stages ----------------------------------------------------------------------- */

static struct pvert pv(double x, double y, double d)
{
    return (struct pvert){ .pos = { x, y, d }, .rgb = { 0.25, 0.5, 1 } };
}

Test(front, a_shared_edge_gets_the_same_new_vertex_from_both_sides)
{
    struct rng r = rng_for(6005);
    struct frustum fr = { .near = 1, .far = 10 };
    for (int c = 0; c < 2000; c++) {
        struct pvert a = pv(rng_range(&r, -5, 5), rng_range(&r, -5, 5), rng_range(&r, -1, 0.99));
        struct pvert b = pv(rng_range(&r, -5, 5), rng_range(&r, -5, 5), rng_range(&r, 1.01, 20));
        struct pvert o1 = pv(rng_range(&r, -5, 5), rng_range(&r, -5, 5), rng_range(&r, 1, 9));
        struct pvert o2 = pv(rng_range(&r, -5, 5), rng_range(&r, -5, 5), rng_range(&r, -3, 9));
        a.rgb[0] = rng_unit(&r), b.rgb[2] = rng_unit(&r);
        /* two triangles sharing a-b, walked a -> b in one and b -> a in the other */
        struct poly t1 = { 3, { a, b, o1 } }, t2 = { 3, { b, a, o2 } }, c1, c2;
        struct plane pn = depth_plane(&fr, PLANE_NEAR);
        clip_polygon(&c1, &t1, &pn, NULL);
        clip_polygon(&c2, &t2, &pn, NULL);
        /* the new vertex on a-b: the one with d = near that lies on the segment */
        int found = 0;
        for (int i = 0; i < c1.n; i++)
            for (int j = 0; j < c2.n; j++)
                if (memcmp(&c1.v[i], &c2.v[j], sizeof c1.v[i]) == 0 && c1.v[i].pos[2] == 1.0)
                    found++;
        cr_assert_geq(found, 1, "case %d: the two sides made different vertices on the shared edge", c);
        for (int i = 0; i < c1.n; i++)
            cr_assert_geq(c1.v[i].pos[2], 1.0, "case %d: a vertex in front of near", c);
    }
}

struct steps {
    int n, news;
    float t[16];
    float made[16][3];
};

/* The clipper's narration: the plane, then each vertex kept, dropped or made. */
static void record(void *ctx, const struct trace_event *ev)
{
    struct steps *st = ctx;
    if (ev->kind != TRACE_FRONT || ev->klass == FRONT_PLANE)
        return;
    st->n++;
    if (ev->klass == FRONT_NEW) {
        st->t[st->news] = ev->aux[3];
        memcpy(st->made[st->news++], ev->aux, sizeof st->made[0]);
    }
}

/* Where v lies on the edge a -> b, as a fraction of it along x. */
static double edge_t(const struct pvert *v, const struct pvert *a, const struct pvert *b)
{
    return (v->pos[0] - a->pos[0]) / (b->pos[0] - a->pos[0]);
}

Test(front, a_new_vertex_lies_on_the_plane_exactly_at_its_t)
{
    struct frustum fr = { .near = 0.1, .far = 100 };
    /* A behind the eye, B and C in front: the edges AB and CA are cut */
    struct poly in = { 3, { pv(0, 0, -1), pv(3, 0, 3.1), pv(0, 6, 1.1) } }, out;
    in.v[0].rgb[0] = 0, in.v[1].rgb[0] = 1, in.v[2].rgb[0] = 0.5;
    struct steps st = { 0 };
    struct trace tr = { .sink = record, .ctx = &st };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    struct plane pn = depth_plane(&fr, PLANE_NEAR);
    clip_polygon(&out, &in, &pn, &tr);
    cr_assert_eq(out.n, 4);
    cr_assert_eq(st.news, 2);
    cr_assert_eq(st.n, 5, "3 vertices kept or dropped, 2 made");
    /* walked from the first vertex: A dropped, new on AB, B, C, new on CA */
    cr_expect_eq(memcmp(&out.v[1], &in.v[1], sizeof in.v[1]), 0, "B kept as it was");
    cr_expect_eq(memcmp(&out.v[2], &in.v[2], sizeof in.v[2]), 0, "C kept as it was");
    double t = 1.1 / 4.1;      /* (near - d_A) / (d_B - d_A) */
    cr_expect(fabs(edge_t(&out.v[0], &in.v[0], &in.v[1]) - t) < 1e-15, "t = %.17g",
              edge_t(&out.v[0], &in.v[0], &in.v[1]));
    cr_expect_eq(st.t[0], (float)t, "the narration told t = %.9g", st.t[0]);
    cr_expect(fabs(out.v[0].pos[0] - 3 * t) < 1e-15, "A + t (B - A)");
    cr_expect_eq(out.v[0].pos[2], 0.1, "d set to near exactly");
    cr_expect_eq(out.v[3].pos[2], 0.1);
    cr_expect(fabs(out.v[0].rgb[0] - t) < 1e-15, "colour interpolated with t");
    for (int k = 0; k < 3; k++)
        cr_expect_eq(st.made[0][k], (float)out.v[0].pos[k], "the narration told it");
    /* a vertex on the plane is kept and makes no second vertex */
    struct poly on = { 3, { pv(0, 0, 0.1), pv(1, 0, -1), pv(0, 1, 2) } };
    clip_polygon(&out, &on, &pn, NULL);
    cr_expect_eq(out.n, 3, "the vertex on the plane, one new vertex, the vertex in front");
}

Test(front, guard_band_clipping_keeps_colours_perspective_correct)
{
    /* an edge from x = 0 (d = 1) to x = 40000 (d = 4): cut at x = 16383 */
    struct poly p = { 3, { pv(0, 0, 1), pv(40000, 0, 4), pv(0, 100, 1) } };
    p.v[0].rgb[0] = 0, p.v[1].rgb[0] = 1;
    cr_assert(!in_guard_band(&p));
    clip_guard_band(&p, NULL);
    cr_assert_eq(p.n, 4);
    int k = -1;
    for (int i = 0; i < p.n; i++)
        if (p.v[i].pos[1] == 0 && p.v[i].pos[0] == 16383)
            k = i;
    cr_assert_geq(k, 0, "a vertex at x = 16383 exactly on the cut edge");
    double t = 16383.0 / 40000, w = 1 + t * (0.25 - 1);        /* 1/d is linear on screen */
    cr_expect(fabs(p.v[k].pos[2] - 1 / w) < 1e-12, "d = %.17g, expected %.17g", p.v[k].pos[2], 1 / w);
    cr_expect(fabs(p.v[k].rgb[0] - t * 0.25 / w) < 1e-12, "r/d is linear on screen");
    cr_assert(in_guard_band(&p));
    /* [-16384, 16384) is used as it is */
    struct poly edge = { 3, { pv(-16384, -16384, 1), pv(16383.99, 0, 1), pv(0, 16383.99, 1) } };
    cr_expect(in_guard_band(&edge));
    edge.v[1].pos[0] = 16384;
    cr_expect(!in_guard_band(&edge));
}

Test(front, the_fan_starts_at_the_first_vertex_and_cull_follows_opengl)
{
    struct poly p = { 5, { pv(10, 10, 1), pv(20, 10, 1), pv(25, 20, 1), pv(15, 28, 1), pv(5, 20, 1) } };
    struct vertex out[POLY_MAX - 2][3];
    cr_assert_eq(fan(&p, CULL_NONE, out, NULL), 3);
    for (int i = 0; i < 3; i++) {
        cr_expect_eq(out[i][0].x, 10.0);
        cr_expect_eq(out[i][1].x, p.v[i + 1].pos[0]);
        cr_expect_eq(out[i][2].x, p.v[i + 2].pos[0]);
    }
    /* (10,10) (20,10) (25,20): x right, y down, clockwise on screen: a back face */
    cr_expect_gt(facing_area(out[0]), 0);
    cr_expect_eq(fan(&p, CULL_BACK, out, NULL), 0, "clockwise as seen: every one is a back face");
    cr_expect_eq(fan(&p, CULL_FRONT, out, NULL), 3);
    /* through the whole pipeline: a triangle counter-clockwise as the
     * viewer sees it (OpenGL's front face) survives cull back */
    struct camera cam = { .eye = { 0, 0, 5 }, .target = { 0, 0, 0 }, .up = { 0, 1, 0 },
                          .fovy = 60, .near = 0.1, .far = 100 };
    struct frustum fr;
    frustum_init(&fr, &cam, 64, 48);
    struct world_tri ccw = { .p = { { -1, -1, 0 }, { 1, -1, 0 }, { 0, 1, 0 } } };
    struct vertex tris[POLY_MAX - 2][3];
    cr_expect_eq(front_triangle(&fr, CULL_BACK, &ccw, tris), 1);
    cr_expect_eq(front_triangle(&fr, CULL_FRONT, &ccw, tris), 0);
    struct world_tri cw = { .p = { { -1, -1, 0 }, { 0, 1, 0 }, { 1, -1, 0 } } };
    cr_expect_eq(front_triangle(&fr, CULL_BACK, &cw, tris), 0);
    cr_expect_eq(front_triangle(&fr, CULL_FRONT, &cw, tris), 1);
    cr_expect_eq(front_triangle(&fr, CULL_NONE, &cw, tris), 1);
}

Test(front, a_triangle_wholly_behind_the_eye_or_beyond_far_draws_nothing)
{
    struct camera cam = { .eye = { 0, 0, 0 }, .target = { 0, 0, -1 }, .up = { 0, 1, 0 },
                          .fovy = 90, .near = 1, .far = 10 };
    struct frustum fr;
    frustum_init(&fr, &cam, 32, 32);
    struct vertex tris[POLY_MAX - 2][3];
    struct world_tri behind = { .p = { { -1, 0, 1 }, { 1, 0, 1 }, { 0, 1, 3 } } };
    struct world_tri beyond = { .p = { { -1, 0, -11 }, { 1, 0, -11 }, { 0, 1, -30 } } };
    struct world_tri across = { .p = { { -1, 0, 5 }, { 1, 0, -5 }, { 0, 1, -20 } } };
    cr_expect_eq(front_triangle(&fr, CULL_NONE, &behind, tris), 0);
    cr_expect_eq(front_triangle(&fr, CULL_NONE, &beyond, tris), 0);
    int n = front_triangle(&fr, CULL_NONE, &across, tris);
    cr_expect_geq(n, 1);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            cr_expect(tris[i][k].z >= 1 && tris[i][k].z <= 10, "z = %.17g", tris[i][k].z);
}

/* regression (found by make fuzz): clipping against the guard band
 * interpolates 1/d, and the rounded result could land one ulp past the
 * edge's ends: a depth below near (0.054999999999999993 with near = 0.055),
 * which a scene written from the screen triangles could not read back at
 * near = 10^-6. A point on an edge now stays between the edge's ends. */
Test(front, guard_band_clip_depth_below_near)
{
    static const char text[] = "size 4 836\n"     /* so narrow that x leaves the guard band */
                               "camera 0 1 1e-6  0 0 1  0 1 0  70 .055 1\n"
                               "obj builtin:torus.obj 0 0 0\n";
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "t.scene", text, sizeof text - 1, err, sizeof err), "%s", err);
    cr_assert(front_scene(&s));
    cr_assert_gt(s.ntris, 100, "the torus is drawn");
    for (int i = 0; i < s.ntris; i++)
        for (int k = 0; k < 3; k++) {
            const struct vertex *v = &s.tris[i].v[k];
            cr_assert(v->z >= 0.055 && v->z <= 1, "triangle %d: z = %.17g", i, v->z);
            cr_assert(v->r >= 0 && v->r <= 1 && v->g >= 0 && v->g <= 1 && v->b >= 0 && v->b <= 1,
                      "triangle %d: colour %.17g %.17g %.17g", i, v->r, v->g, v->b);
        }
    scene_free(&s);
}

/* --- dragging a vertex of a 3-D scene (the explorer) --------------------------------- */

/* A box in front of random cameras: a screen vertex dragged to (x, y)
 * moves the model's vertex at its own view depth so that it projects there
 * (checked with this file's own projection), every copy of it moves (the
 * box stays closed: counts stay even), and nothing else moves. */
Test(front, dragging_a_screen_vertex_moves_the_model_vertex_at_its_depth, .timeout = 60)
{
    struct rng r = rng_for(6011);
    int moved = 0;
    for (int c = 0; c < 60; c++) {
        int w = rng_int(&r, 16, 80), h = rng_int(&r, 16, 64);
        double centre[3] = { rng_range(&r, -5, 5), rng_range(&r, -5, 5), rng_range(&r, -5, 5) };
        double dir[3], eye[3];
        random_dir(&r, dir);
        for (int k = 0; k < 3; k++)
            eye[k] = centre[k] + rng_range(&r, 4, 9) * dir[k];
        struct camera cam = random_camera(&r, eye, 0.01, 100);
        for (int k = 0; k < 3; k++)
            cam.target[k] = centre[k];
        double x3[3], f[3] = { centre[0] - eye[0], centre[1] - eye[1], centre[2] - eye[2] };
        cross3(x3, f, cam.up);
        if (dot3(x3, x3) < 1e-3 * dot3(f, f) * dot3(cam.up, cam.up))
            continue;
        struct scene s = scene3_new(w, h, &cam);
        double axes[3][3], half[3] = { 1, 1.2, 0.9 }, corner[8][3];
        random_axes(&r, axes);
        box_corners(centre, half, axes, corner);
        add_box(&r, &s, corner);
        cr_assert(front_scene(&s));
        if (s.ntris == 0) {
            scene_free(&s);
            continue;
        }
        int i = rng_int(&r, 0, s.ntris - 1), k = rng_int(&r, 0, 2);
        struct vertex old = s.tris[i].v[k];
        double x = old.x + rng_range(&r, -4, 4), y = old.y + rng_range(&r, -4, 4);
        struct world before = s.world;
        struct world_tri *copy = malloc((size_t)before.ntris * sizeof *copy);
        memcpy(copy, s.world.tris, (size_t)before.ntris * sizeof *copy);
        cr_assert(front_move_vertex(&s, i, old.x, old.y, x, y), "case %d: no model vertex at (%g, %g)",
                  c, old.x, old.y);
        moved++;
        /* the world vertex that projected to the old place now projects to the new one */
        int changed = 0;
        for (int t = 0; t < s.world.ntris; t++)
            for (int v = 0; v < 3; v++) {
                const double *p = s.world.tris[t].p[v], *q = copy[t].p[v];
                if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])
                    continue;
                changed++;
                struct vertex was = project_point(&cam, w, h, q, copy[t].rgb[v]);
                struct vertex now = project_point(&cam, w, h, p, copy[t].rgb[v]);
                cr_assert(fabs(was.x - old.x) < 1e-6 && fabs(was.y - old.y) < 1e-6,
                          "case %d: a vertex that was elsewhere moved", c);
                cr_assert(fabs(now.x - x) < 1e-6 && fabs(now.y - y) < 1e-6,
                          "case %d: moved to (%g, %g), not (%g, %g)", c, now.x, now.y, x, y);
                cr_assert(fabs(now.z - was.z) < 1e-9 * was.z, "case %d: depth %g became %g", c,
                          was.z, now.z);
            }
        /* a box corner is shared by 3 to 6 of its 12 triangles */
        cr_assert(changed >= 3 && changed <= 6, "case %d: %d copies of the corner moved", c, changed);
        cr_assert(front_scene(&s));
        uint8_t *mask = reference_scene(&s);
        uint8_t *skip = calloc((size_t)w * h, 1);
        mark_folds(&s, skip);
        expect_counts(&s, mask, skip, 0x55555555u, -1, "dragged box", test_seed(), c);
        free(mask);
        free(skip);
        free(copy);
        scene_free(&s);
    }
    cr_expect_gt(moved, 30, "only %d boxes were dragged", moved);
}

/* A vertex the near plane made is not the model's: it stays, and so does
 * the model. */
Test(front, a_vertex_made_by_clipping_cannot_be_dragged)
{
    struct camera cam = { .eye = { 0, 0, 0 }, .target = { 0, 0, -1 }, .up = { 0, 1, 0 },
                          .fovy = 60, .near = 1, .far = 100 };
    struct scene s = scene3_new(64, 48, &cam);
    const double a[3] = { -1, -1, -4 }, b[3] = { 1, -1, -4 }, c[3] = { 0, 1, 2 }, rgb[3] = { 1, 1, 1 };
    add_world_tri(&s, a, b, c, rgb);            /* c is behind the eye: near cuts two edges */
    cr_assert(front_scene(&s));
    cr_assert_gt(s.ntris, 0);
    struct world_tri before = s.world.tris[0];
    int made = 0;
    for (int i = 0; i < s.ntris; i++)
        for (int k = 0; k < 3; k++) {
            struct vertex v = s.tris[i].v[k];
            if (fabs(v.z - cam.near) > 1e-9)
                continue;               /* a vertex of the model, at d = 4 */
            made++;
            cr_assert(!front_move_vertex(&s, i, v.x, v.y, v.x + 3, v.y + 2));
            cr_assert(memcmp(&before, &s.world.tris[0], sizeof before) == 0);
        }
    /* near makes two vertices; the fan of the clipped quad uses one of them twice */
    cr_assert_eq(made, 3, "%d vertices at d = near in the fan", made);
    scene_free(&s);
}
