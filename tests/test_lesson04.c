/* test_lesson04.c - lesson 04's SIMD twins agree with each other, and its
 * perspective-correct depth and texture coordinates agree with the analytic
 * answer for a floor seen through a pinhole camera; the affine exhibit does
 * not.
 *
 * The values come from the narration: every covered pixel's TRACE_PIXEL_TEST
 * event carries z and aux = (1/z, w, u, v, s, t), s and t as the lesson
 * computed them for the pixel's colour.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "explore/replay.h"

#define README04 "lessons/04-simd-perspective/README.md"

extern const struct lesson lesson_04, lesson_04_fast;

/* The floor against the analytic answer. Single-precision lanes, stepped:
 * every Cx += I rounds to the nearest float, at most 2^-24 of the lane's
 * size per add; a pixel of the 256 x 160 floor is under 420 adds from the
 * start, and the floor's lanes stay below 1 in size (1/z is 1 to 1/8, and
 * u, v, w stay near [0, 1] on these wide triangles): under 420 * 2^-24 =
 * 2.5e-5, then divided by 1/z >= 1/8 and a few roundings more for (23):
 * 1e-4 bounds it, and a wrong formula misses by far more (affine: 0.1). */
#define LANE_TOL 1e-4

/* The scalar twin performs the SSE function's operations in the same order
 * on the same floats, so on x86-64 (no FMA in the baseline, and GCC does
 * not contract a * b + c in ISO C mode) they agree bit for bit, lanes and
 * z, s, t alike. The bound allows a compiler that fuses a multiply-add in
 * the scalar code: one rounding less, a few ulps of z, s, t. The lanes
 * themselves are only added, never multiplied, and must agree exactly. */
#define TWIN_TOL 1e-5

/* What one run of a scene says about each pixel (last covered test wins). */
struct pixel_values {
    bool covered;
    int count;
    float z, lane[4], s, t;
};

struct collector {
    int w, h;
    struct pixel_values *px;
};

static void collect(void *ctx, const struct trace_event *ev)
{
    struct collector *c = ctx;
    if (ev->kind != TRACE_PIXEL_TEST || !(ev->flags & TRACE_INSIDE))
        return;
    cr_assert(ev->x >= 0 && ev->x < c->w && ev->y >= 0 && ev->y < c->h,
              "covered pixel (%d, %d) outside the %d x %d target", ev->x, ev->y, c->w, c->h);
    struct pixel_values *p = &c->px[(size_t)ev->y * (size_t)c->w + (size_t)ev->x];
    p->covered = true;
    p->count++;
    p->z = ev->z;
    for (int i = 0; i < 4; i++)
        p->lane[i] = ev->aux[i];
    p->s = ev->aux[4];
    p->t = ev->aux[5];
}

/* Run every triangle of a scene through a variant of the narrated build. */
static struct pixel_values *run_scene(const struct scene *s, const char *variant, bool affine)
{
    const struct lesson_variant *v = lesson_variant(&lesson_04, variant);
    cr_assert_not_null(v, "lesson 04 has no variant %s", variant);
    struct collector c = { s->w, s->h, calloc((size_t)s->w * (size_t)s->h, sizeof *c.px) };
    cr_assert_not_null(c.px);
    struct raster_params p = default_params();
    p.checker = s->checker;
    cr_assert(lesson_param_set(&lesson_04, &p, "affine", affine));
    struct target fb;
    cr_assert(target_init(&fb, s->w, s->h, 0));
    struct trace tr = { .sink = collect, .ctx = &c };
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        v->rasterize(&t, &p, &fb, &tr);
    }
    target_free(&fb);
    return c.px;
}

/* --- the SIMD twins ---------------------------------------------------------------- */

/* How far a stepped float lane may be from the exact value. Each Cx += I or
 * Cy += J rounds once, by at most 2^-24 of the result, and the result is
 * never larger than the largest value the lane takes on the walk (`scale`,
 * at a corner of the walked box, as every lane is linear). Rounding the start
 * value and the step adds at most a few such errors more: after `steps` adds
 * a lane is within (steps + 4) * 2^-24 * scale of the exact value. Note the
 * scale is the box's, not the pixel's: a sliver's u, v, w reach hundreds
 * outside it, and the rounding of those large values is what a small weight
 * inside the sliver carries. */
static double lane_bound(int steps, double scale)
{
    return (steps + 4) * ldexp(1.0, -24) * scale;
}

/* The largest |lane| over the box the row4 layout walks (it reaches up to
 * three pixels past maxX). */
static void lane_scales(const struct tri_setup *t, double scale[4])
{
    int xs[2] = { t->minx, t->maxx + 3 }, ys[2] = { t->miny, t->maxy };
    const struct vertex *v = t->v;
    for (int i = 0; i < 4; i++)
        scale[i] = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double f[3];
            for (int k = 0; k < 3; k++)
                f[k] = (double)edge_value(t, k, xs[i], ys[j]) / (double)t->area2;
            double lane[4] = { f[EDGE_BC] / v[0].z + f[EDGE_CA] / v[1].z + f[EDGE_AB] / v[2].z,
                               f[EDGE_AB], f[EDGE_BC], f[EDGE_CA] };
            for (int k = 0; k < 4; k++)
                scale[k] = fmax(scale[k], fabs(lane[k]));
        }
}

/* Pixels covered differently, and the largest lane difference in units of
 * the bound both runs must meet (<= 1 passes). */
static int coverage_diffs(const struct pixel_values *a, const struct pixel_values *b, int n)
{
    int diffs = 0;
    for (int i = 0; i < n; i++)
        diffs += a[i].covered != b[i].covered || a[i].count != b[i].count;
    return diffs;
}

static double lane_diff(const struct tri_setup *t, const struct pixel_values *a,
                        const struct pixel_values *b, int w, int h)
{
    double scale[4], worst = 0;
    lane_scales(t, scale);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const struct pixel_values *pa = &a[y * w + x], *pb = &b[y * w + x];
            if (!pa->covered || !pb->covered)
                continue;
            int steps = (x - t->minx) + (y - t->miny);
            for (int k = 0; k < 4; k++) {
                double d = fabs((double)pa->lane[k] - pb->lane[k]);
                worst = fmax(worst, d / (2 * lane_bound(steps, scale[k])));
            }
        }
    return worst;
}

/* Largest difference in z, s, t, relative to the values' size (at least 1). */
static double value_diff(const struct pixel_values *a, const struct pixel_values *b, int n)
{
    double worst = 0;
    for (int i = 0; i < n; i++) {
        if (!a[i].covered || !b[i].covered)
            continue;
        float va[3] = { a[i].z, a[i].s, a[i].t }, vb[3] = { b[i].z, b[i].s, b[i].t };
        for (int k = 0; k < 3; k++) {
            double scale = fmax(1, fmax(fabs(va[k]), fabs(vb[k])));
            worst = fmax(worst, fabs((double)va[k] - vb[k]) / scale);
        }
    }
    return worst;
}

/* Random textured triangles of every category on a 96 x 64 target. */
Test(lesson04, sse_scalar_and_row4_twins_agree)
{
    enum { W = 96, H = 64, PER_CATEGORY = 150 };
    struct rng r = rng_for(0x104);
    double worst_twin = 0, worst_row4 = 0;
    for (int c = 0; c < CAT_COUNT; c++) {
        for (int i = 0; i < PER_CATEGORY; i++) {
            struct scene s = { .w = W, .h = H, .checker = 4 };
            struct vertex v[3];
            random_tri(&r, (enum tri_category)c, W, H, v);
            for (int k = 0; k < 3; k++) {
                v[k].s = rng_unit(&r);
                v[k].t = rng_unit(&r);
            }
            cr_assert(scene_add(&s, v));
            struct tri_setup t;
            tri_setup(&t, v, W, H);
            struct pixel_values *sse = run_scene(&s, "sse", false);
            struct pixel_values *scalar = run_scene(&s, "scalar", false);
            struct pixel_values *row4 = run_scene(&s, "row4", false);
            int diffs_twin = coverage_diffs(sse, scalar, W * H);
            int diffs_row4 = coverage_diffs(row4, scalar, W * H);
            double twin = value_diff(sse, scalar, W * H);
            double twin_lanes = lane_diff(&t, sse, scalar, W, H);
            double quad = lane_diff(&t, row4, scalar, W, H);
            struct case_info info = { "lesson 04 twins", test_seed(),
                                      (uint64_t)(c * PER_CATEGORY + i), v, 3 };
            if (diffs_twin || diffs_row4 || twin > TWIN_TOL || twin_lanes > 0 || quad > 1)
                print_case(&info);
            cr_assert_eq(diffs_twin, 0, "sse and scalar cover different pixels (%s)", tri_category_name(c));
            cr_assert_eq(diffs_row4, 0, "row4 and scalar cover different pixels (%s)", tri_category_name(c));
            cr_assert_leq(twin, TWIN_TOL, "sse and scalar z, s, t differ by %g", twin);
            cr_assert_eq(twin_lanes, 0, "sse and scalar lanes differ (%g of the bound)", twin_lanes);
            cr_assert_leq(quad, 1.0, "row4 and scalar lanes differ by %g times the bound", quad);
            worst_twin = fmax(worst_twin, twin);
            worst_row4 = fmax(worst_row4, quad);
            free(sse);
            free(scalar);
            free(row4);
            scene_free(&s);
        }
    }
    cr_log_info("sse/scalar: largest z, s, t difference %g; row4/scalar: largest lane "
                "difference %.3g of the rounding bound", worst_twin, worst_row4);
}

/* The fast build (what the bench times) draws the same picture as the narrated one. */
Test(lesson04, fast_build_draws_what_the_narrated_build_draws)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "floor", err, sizeof err), "%s", err);
    struct raster_params p = default_params();
    p.checker = s.checker;
    for (int i = 0; i < lesson_04.nvariants; i++) {
        struct target a, b;
        cr_assert(render_scene(&s, &lesson_04.variants[i], &p, &a));
        cr_assert(render_scene(&s, &lesson_04_fast.variants[i], &p, &b));
        size_t n = (size_t)s.w * (size_t)s.h;
        cr_expect(memcmp(a.color, b.color, n * sizeof *a.color) == 0, "%s: colours differ",
                  lesson_04.variants[i].name);
        cr_expect(memcmp(a.depth, b.depth, n * sizeof *a.depth) == 0, "%s: depths differ",
                  lesson_04.variants[i].name);
        target_free(&a);
        target_free(&b);
    }
    scene_free(&s);
}

/* --- perspective-correct against the analytic answer -------------------------------
 *
 * A pinhole camera at height H_CAM above a floor, looking along +Z, focal
 * length F_PX pixels, horizon on row HORIZON, centre column CX. The floor
 * point (X, Z) appears at
 *
 *     x = CX + F_PX * X / Z,      y = HORIZON + F_PX * H_CAM / Z
 *
 * and the ray through the pixel centre (x, y) meets the floor at
 *
 *     Z = F_PX * H_CAM / (y - HORIZON),      X = (x - CX) * Z / F_PX.
 *
 * The corners (X = +-1, Z = 1 and 8) land on whole pixels, so snapping to
 * 1/256 px moves nothing: the triangles the lesson draws are exactly the
 * projected floor and the analytic answer is exact at every pixel centre. */
enum { FLOOR_W = 256, FLOOR_H = 160 };
#define F_PX 128.0
#define H_CAM 1.0
#define HORIZON 8.0
#define CX 128.0
#define Z_NEAR 1.0
#define Z_FAR 8.0

static struct vertex floor_vertex(double X, double Z)
{
    return (struct vertex){ .x = CX + F_PX * X / Z, .y = HORIZON + F_PX * H_CAM / Z, .z = Z,
                            .r = 0.5, .g = 0.5, .b = 0.5,
                            .s = (X + 1) / 2, .t = (Z - Z_NEAR) / (Z_FAR - Z_NEAR) };
}

static void floor_scene(struct scene *s)
{
    *s = (struct scene){ .w = FLOOR_W, .h = FLOOR_H, .checker = 8 };
    struct vertex nl = floor_vertex(-1, Z_NEAR), nr = floor_vertex(1, Z_NEAR);
    struct vertex fl = floor_vertex(-1, Z_FAR), fr = floor_vertex(1, Z_FAR);
    cr_assert(scene_add(s, (struct vertex[3]){ nl, nr, fr }));
    cr_assert(scene_add(s, (struct vertex[3]){ nl, fr, fl }));
}

struct floor_errors {
    int covered;
    double z, s, t;     /* largest |lesson - analytic|, z relative */
};

static struct floor_errors floor_errors(const char *variant, bool affine)
{
    struct scene s;
    floor_scene(&s);
    struct pixel_values *px = run_scene(&s, variant, affine);
    struct floor_errors e = { 0 };
    for (int y = 0; y < FLOOR_H; y++)
        for (int x = 0; x < FLOOR_W; x++) {
            const struct pixel_values *p = &px[y * FLOOR_W + x];
            if (!p->covered)
                continue;
            cr_assert_eq(p->count, 1, "pixel (%d, %d) covered %d times", x, y, p->count);
            double Z = F_PX * H_CAM / (y + 0.5 - HORIZON);
            double X = (x + 0.5 - CX) * Z / F_PX;
            double s_exact = (X + 1) / 2, t_exact = (Z - Z_NEAR) / (Z_FAR - Z_NEAR);
            e.covered++;
            e.z = fmax(e.z, fabs(p->z - Z) / Z);
            e.s = fmax(e.s, fabs(p->s - s_exact));
            e.t = fmax(e.t, fabs(p->t - t_exact));
        }
    free(px);
    scene_free(&s);
    return e;
}

Test(lesson04, depth_and_texture_match_the_ray_floor_intersection)
{
    for (int i = 0; i < lesson_04.nvariants; i++) {
        const char *name = lesson_04.variants[i].name;
        struct floor_errors e = floor_errors(name, false);
        cr_assert_gt(e.covered, 10000, "%s: the floor covers %d pixels", name, e.covered);
        cr_expect_leq(e.z, LANE_TOL, "%s: depth off by %g (relative)", name, e.z);
        cr_expect_leq(e.s, LANE_TOL, "%s: s off by %g", name, e.s);
        cr_expect_leq(e.t, LANE_TOL, "%s: t off by %g", name, e.t);
        cr_log_info("%s: %d pixels, worst z %.3g (relative), s %.3g, t %.3g",
                    name, e.covered, e.z, e.s, e.t);
        double tol, quoted = text_number(README04, "l04.perspective.worst", &tol);
        cr_expect_leq(fabs(fmax(e.s, e.t) - quoted), tol, "%s: the text quotes %g, the "
                      "floor's worst is %g", name, quoted, fmax(e.s, e.t));
    }
}

/* The affine exhibit keeps the depth right (it still divides by lane 0) but
 * interpolates s and t linearly on the screen: on this floor t is wrong by
 * more than a tenth of the whole texture somewhere, s by more than a twentieth. */
Test(lesson04, affine_texturing_measurably_misses_the_floor)
{
    for (int i = 0; i < lesson_04.nvariants; i++) {
        const char *name = lesson_04.variants[i].name;
        struct floor_errors e = floor_errors(name, true);
        cr_expect_leq(e.z, LANE_TOL, "%s (affine): depth off by %g", name, e.z);
        cr_expect_gt(e.t, 0.1, "%s (affine): t is off by only %g", name, e.t);
        cr_expect_gt(e.s, 0.05, "%s (affine): s is off by only %g", name, e.s);
        cr_log_info("%s affine: worst s %.3g, t %.3g", name, e.s, e.t);
        /* the lesson text quotes the worst, rounded as it prints it */
        double tol, quoted = text_number(README04, "l04.affine.worst", &tol);
        cr_expect_leq(fabs(fmax(e.s, e.t) - quoted), tol, "%s: the text quotes %g, the "
                      "floor's worst is %g", name, quoted, fmax(e.s, e.t));
    }
}

/* --- against the double-precision reference on random triangles ---------------------
 *
 * How far z, s, t may be from reference_shade(): the lane errors of
 * lane_bound() carried through z = 1 / lane0 and (23), s = N / lane0 with
 * N = u sA/ZA + v sB/ZB + w sC/ZC. To first order
 *
 *     |dz| <= z * d0 / (lane0 - d0)
 *     |ds| <= (du |sA/ZA| + dv |sB/ZB| + dw |sC/ZC| + |s| d0) / (lane0 - d0)
 *
 * plus a few roundings of the products themselves (FINAL_ROUNDING, relative).
 * VALUE_MARGIN = 2 covers the second-order terms. A formula slip (a missing
 * 1/Z, swapped weights) misses by far more: see the affine test above. */
#define FINAL_ROUNDING (8 * 0x1p-24)
#define VALUE_MARGIN 2.0

Test(lesson04, perspective_values_match_the_reference_shade)
{
    enum { W = 128, H = 96, CASES = 400 };
    struct rng r = rng_for(0x404);
    double worst = 0;
    for (int n = 0; n < CASES; n++) {
        struct scene s = { .w = W, .h = H };
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(n % CAT_COUNT), W, H, v);
        for (int k = 0; k < 3; k++) {
            v[k].z = rng_range(&r, 0.5, 20);   /* depth ratios up to 40 */
            v[k].s = rng_unit(&r);
            v[k].t = rng_unit(&r);
        }
        cr_assert(scene_add(&s, v));
        struct tri_setup t;
        tri_setup(&t, v, W, H);
        double scale[4];
        lane_scales(&t, scale);
        const struct vertex *tv = t.v;     /* A, B, C after setup's normalisation */
        struct pixel_values *px = run_scene(&s, lesson_04.variants[0].name, false);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const struct pixel_values *p = &px[y * W + x];
                if (!p->covered)
                    continue;
                double z, rgb[3], st[2];
                reference_shade(&t, x, y, true, &z, rgb, st);
                int steps = (x - t.minx) + (y - t.miny);
                double d[4];
                for (int k = 0; k < 4; k++)
                    d[k] = lane_bound(steps, scale[k]);
                double lane0 = 1 / z, den = lane0 - d[0];
                cr_assert_gt(den, 0, "1/z is lost in the rounding at (%d, %d)", x, y);
                double zb = z * d[0] / den + FINAL_ROUNDING * z;
                double sb = (d[2] * fabs(tv[0].s / tv[0].z) + d[3] * fabs(tv[1].s / tv[1].z)
                             + d[1] * fabs(tv[2].s / tv[2].z) + fabs(st[0]) * d[0]) / den
                          + FINAL_ROUNDING * fmax(fabs(st[0]), 1);
                double tb = (d[2] * fabs(tv[0].t / tv[0].z) + d[3] * fabs(tv[1].t / tv[1].z)
                             + d[1] * fabs(tv[2].t / tv[2].z) + fabs(st[1]) * d[0]) / den
                          + FINAL_ROUNDING * fmax(fabs(st[1]), 1);
                double ez = fabs(p->z - z) / zb, es = fabs(p->s - st[0]) / sb;
                double et = fabs(p->t - st[1]) / tb;
                worst = fmax(worst, fmax(ez, fmax(es, et)));
                bool ok = ez <= VALUE_MARGIN && es <= VALUE_MARGIN && et <= VALUE_MARGIN;
                if (!ok) {
                    struct case_info info = { "lesson 04 vs reference_shade", test_seed(), (uint64_t)n, v, 3 };
                    print_case(&info);
                }
                cr_assert(ok, "pixel (%d, %d): z %g vs %g (bound %g), s %g vs %g (%g), t %g vs %g (%g)",
                          x, y, p->z, z, zb, p->s, st[0], sb, p->t, st[1], tb);
            }
        free(px);
        scene_free(&s);
    }
    cr_log_info("largest error against reference_shade: %.3g of the propagated bound", worst);
}

/* The depth test keeps the nearer surface whatever the drawing order. */
Test(lesson04, nearer_surface_wins_in_either_order)
{
    struct vertex near[3] = { { 2, 2, 1, 1, 0, 0, 0, 0 }, { 30, 4, 1, 1, 0, 0, 0, 0 },
                              { 10, 28, 1, 1, 0, 0, 0, 0 } };
    struct vertex far[3] = { { 1, 30, 5, 0, 0, 1, 0, 0 }, { 4, 1, 5, 0, 0, 1, 0, 0 },
                             { 31, 20, 5, 0, 0, 1, 0, 0 } };
    uint32_t first[32 * 32];
    for (int order = 0; order < 2; order++) {
        struct scene s = { .w = 32, .h = 32 };
        cr_assert(scene_add(&s, order ? far : near));
        cr_assert(scene_add(&s, order ? near : far));
        struct target fb;
        struct raster_params p = default_params();
        cr_assert(render_scene(&s, &lesson_04.variants[0], &p, &fb));
        if (order == 0)
            memcpy(first, fb.color, sizeof first);
        else
            cr_expect(memcmp(first, fb.color, sizeof first) == 0,
                      "the picture depends on the drawing order");
        cr_expect_eq(fb.color[10 * 32 + 10], 0xffff0000u, "the nearer red triangle is on top");
        target_free(&fb);
        scene_free(&s);
    }
}
