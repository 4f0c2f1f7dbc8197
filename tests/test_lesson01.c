/* test_lesson01.c - lesson 01, scanline gradient filling: the exhibit is
 * real (its count is the one the lesson text states), colour and z agree
 * with the double-precision reference within named tolerances, and the
 * narration tells the truth about rows and spans, the watch panel about the
 * edge crossings it derives from them (scanline_explorer.c).
 * (Coverage against the reference on 100,000 random triangles is
 * test_property.c's job; the named cases here are the geometry the lesson
 * text discusses.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lesson_explorer.h"
#include "testlib.h"
#include "explore/replay.h"

extern const struct lesson lesson_01, lesson_01_fast;
extern const struct lesson_explorer lesson_01_explorer;

/* Colour: every value is built from doubles stepped a few hundred times at
 * most; 1e-9 of the [0, 1] range is far above that drift and far below one
 * 8-bit level. The 8-bit channel written must be the rounding of some value
 * within that tolerance of the reference. */
#define COLOUR_TOLERANCE 1e-9
/* Depth is stored as a float: one float rounding (2^-24 relative) plus the
 * same double drift. */
#define Z_REL_TOLERANCE 1e-6
/* Watch values are printed with 6 significant digits: edge x within 1/1024 px
 * of the exact value. */
#define AUX_X_TOLERANCE (1.0 / 1024)

/* --- the exhibit ------------------------------------------------------------- */

/* README.md, "The exhibit": on offgrid-strip the printed loop differs from
 * the exact coverage on 97 pixels: 33 holes inside the strip, 35 pixels
 * inside drawn twice, 29 pixels outside the strip drawn. */
enum { EXHIBIT_DIFFER = 97, EXHIBIT_HOLES = 33, EXHIBIT_DOUBLED = 35, EXHIBIT_OUTSIDE = 29,
       STRIP_PIXELS = 480 };

struct tally {
    int differ, holes, doubled, outside, covered;
};

/* Compare a scene drawn by a variant with reference_coverage(), triangle by
 * triangle: nothing of the variant's code is used for the expected side. */
static struct tally compare_scene(const char *scene_name, const struct lesson_variant *v)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, scene_name, err, sizeof err), "%s", err);
    size_t n = (size_t)s.w * (size_t)s.h;
    uint8_t *ref = calloc(n, 1);
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        reference_mask(&t, ref);
    }
    struct raster_params p = default_params();
    struct target fb;
    cr_assert(render_scene(&s, v, &p, &fb));
    struct tally c = { 0 };
    for (size_t i = 0; i < n; i++) {
        int r = ref[i], got = fb.count[i];
        c.covered += r;
        c.differ += got != r;
        c.holes += r > 0 && got < r;
        c.doubled += r > 0 && got > r;
        c.outside += r == 0 && got > 0;
    }
    target_free(&fb);
    free(ref);
    scene_free(&s);
    return c;
}

Test(lesson01, exhibit_scene_is_a_watertight_mesh_for_the_exact_walk)
{
    const struct lesson *ls[] = { &lesson_01, &lesson_01_fast };
    for (int k = 0; k < 2; k++) {
        struct tally c = compare_scene(ls[k]->exhibit_scene, &ls[k]->variants[0]);
        cr_expect_eq(c.covered, STRIP_PIXELS, "strip covers %d pixels", c.covered);
        cr_expect_eq(c.differ, 0, "exact walk differs on %d pixels", c.differ);
    }
}

Test(lesson01, source_float_exhibit_differs_by_the_count_the_lesson_states)
{
    const struct lesson *ls[] = { &lesson_01, &lesson_01_fast };
    for (int k = 0; k < 2; k++) {
        const struct lesson_variant *v = lesson_variant(ls[k], "source-float");
        cr_assert_not_null(v);
        cr_expect(variant_against_exact(v));
        struct tally c = compare_scene(ls[k]->exhibit_scene, v);
        cr_expect_eq(c.differ, EXHIBIT_DIFFER, "differ: %d", c.differ);
        cr_expect_eq(c.holes, EXHIBIT_HOLES, "holes: %d", c.holes);
        cr_expect_eq(c.doubled, EXHIBIT_DOUBLED, "doubled: %d", c.doubled);
        cr_expect_eq(c.outside, EXHIBIT_OUTSIDE, "outside: %d", c.outside);
    }
}

/* --- named geometry ---------------------------------------------------------- */

static void expect_exact(const char *what, struct vertex v[3], int w, int h)
{
    const struct lesson *ls[] = { &lesson_01, &lesson_01_fast };
    for (int k = 0; k < 2; k++) {
        for (int wind = 0; wind < 2; wind++) {
            struct vertex tv[3] = { v[0], wind ? v[2] : v[1], wind ? v[1] : v[2] };
            struct tri_setup t;
            tri_setup(&t, tv, w, h);
            uint8_t *ref = calloc((size_t)w * h, 1);
            reference_mask(&t, ref);
            struct target fb;
            cr_assert(target_init(&fb, w, h, 0));
            rasterize_one(&ls[k]->variants[0], NULL, &t, &fb, NULL);
            struct case_info info = { .what = what, .v = tv, .nv = 3 };
            cr_expect(coverage_equal(ref, fb.count, w, h, &info), "%s", what);
            target_free(&fb);
            free(ref);
        }
    }
}

/* The middle vertex exactly on a pixel centre: both short edges meet there,
 * on the left (case [A], the centre is in) and on the right ([B], out). */
Test(lesson01, middle_vertex_on_a_pixel_centre_cases_a_and_b)
{
    struct vertex a[3] = { test_vertex(8.25, 1.3), test_vertex(3.5, 6.5), test_vertex(9.7, 13.9) };
    expect_exact("case [A], middle vertex (3.5, 6.5)", a, 16, 16);
    struct vertex b[3] = { test_vertex(4.25, 1.3), test_vertex(12.5, 6.5), test_vertex(3.7, 13.9) };
    expect_exact("case [B], middle vertex (12.5, 6.5)", b, 16, 16);
}

/* Flat top and flat bottom on pixel-centre rows: the top row is in, the
 * bottom row out; the slanted sides pass through centres too. */
Test(lesson01, flat_top_and_flat_bottom_on_centre_rows)
{
    struct vertex top[3] = { test_vertex(2.5, 2.5), test_vertex(12.5, 2.5), test_vertex(7.5, 12.5) };
    expect_exact("flat top on row 2", top, 16, 16);
    struct vertex bottom[3] = { test_vertex(7.5, 2.5), test_vertex(12.5, 12.5), test_vertex(2.5, 12.5) };
    expect_exact("flat bottom on row 12", bottom, 16, 16);
    struct vertex vertical[3] = { test_vertex(4.5, 1.5), test_vertex(4.5, 13.5), test_vertex(11.5, 7.5) };
    expect_exact("vertical left edge on column 4", vertical, 16, 16);
}

/* A tiny triangle between centres covers nothing; one around a centre covers it. */
Test(lesson01, sub_pixel_triangles)
{
    struct vertex miss[3] = { test_vertex(3.55, 3.55), test_vertex(3.95, 3.6), test_vertex(3.7, 3.95) };
    expect_exact("tiny, no centre inside", miss, 8, 8);
    struct vertex hit[3] = { test_vertex(3.3, 3.3), test_vertex(3.9, 3.45), test_vertex(3.45, 3.9) };
    expect_exact("tiny, around the centre (3.5, 3.5)", hit, 8, 8);
}

/* --- interpolation ------------------------------------------------------------ */

static bool channel_ok(uint32_t rgba, int shift, double ref)
{
    int got = (int)((rgba >> shift) & 0xff);
    for (int s = -1; s <= 1; s += 2) {
        double v = ref + s * COLOUR_TOLERANCE;
        v = v < 0 ? 0 : v > 1 ? 1 : v;
        if (got == (int)(v * 255.0 + 0.5))
            return true;
    }
    return false;
}

/* Every covered pixel's colour and depth, in both builds, against
 * reference_shade() (linear in screen space, as the 1994 tutorial interpolates). */
Test(lesson01, colour_and_z_within_tolerance_of_the_reference)
{
    const int w = 53, h = 37;
    const enum tri_category cats[] = { CAT_GENERIC, CAT_SLIVER, CAT_LARGE, CAT_OFFSCREEN, CAT_CENTRES };
    const struct lesson *ls[] = { &lesson_01, &lesson_01_fast };
    struct rng r = rng_for(0x1e550101);
    struct target fb;
    cr_assert(target_init(&fb, w, h, 0));
    long checked = 0;
    for (int i = 0; i < 2000; i++) {
        struct vertex v[3];
        random_tri(&r, cats[i % 5], w, h, v);
        for (int k = 0; k < 3; k++)
            v[k].z = rng_range(&r, 0.5, 50);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        for (int k = 0; k < 2; k++) {
            target_clear(&fb);
            rasterize_one(&ls[k]->variants[0], NULL, &t, &fb, NULL);
            double zmax = fmax(v[0].z, fmax(v[1].z, v[2].z));
            for (int y = 0; y < h; y++) {
                for (int x = 0; x < w; x++) {
                    size_t j = (size_t)y * w + x;
                    if (!fb.count[j])
                        continue;
                    double z, rgb[3], st[2];
                    reference_shade(&t, x, y, false, &z, rgb, st);
                    bool ok = fabs(fb.depth[j] - z) <= Z_REL_TOLERANCE * zmax
                           && channel_ok(fb.color[j], 16, rgb[0])
                           && channel_ok(fb.color[j], 8, rgb[1])
                           && channel_ok(fb.color[j], 0, rgb[2]);
                    if (!ok) {
                        struct case_info info = { .what = "colour/z", .seed = test_seed(),
                                                  .index = (uint64_t)i, .v = v, .nv = 3 };
                        print_case(&info);
                        cr_assert_fail("pixel (%d, %d): z %.9g vs %.9g, rgba %08x vs (%.9f %.9f %.9f)",
                                x, y, fb.depth[j], z, fb.color[j], rgb[0], rgb[1], rgb[2]);
                    }
                    checked++;
                }
            }
        }
    }
    cr_expect_gt(checked, 100000, "only %ld pixels checked", checked);
    target_free(&fb);
}

/* --- narration ------------------------------------------------------------------ */

struct story {
    const struct tri_setup *t;
    int rows, spans, writes, bad;
    char why[256];
    int last_row;
};

/* Where edge (p, q) crosses the horizontal line y, in pixels (double). */
static double crossing(double px, double py, double qx, double qy, double y)
{
    return px + (qx - px) * (y - py) / (qy - py);
}

/* The exact left and right crossings of row y's centre line, from the snapped
 * vertices: the smallest and largest x of the slanted edges spanning it. */
static bool row_crossings(const struct tri_setup *t, int row, double *xl, double *xr)
{
    double yc = row + 0.5, lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < 3; k++) {
        double ax = t->x[k] / 256.0, ay = t->y[k] / 256.0;
        double bx = t->x[(k + 1) % 3] / 256.0, by = t->y[(k + 1) % 3] / 256.0;
        if (ay == by || yc < fmin(ay, by) || yc > fmax(ay, by))
            continue;
        double x = crossing(ax, ay, bx, by, yc);
        lo = fmin(lo, x);
        hi = fmax(hi, x);
    }
    *xl = lo;
    *xr = hi;
    return lo <= hi;
}

/* What the watch panel shows about a row or span event: x_left, x_right and
 * (for a span) the prestep; returns how many of the three it found. */
static int watch_values(const struct tri_setup *t, const struct trace_event *ev, double v[3])
{
    char buf[256];
    lesson_01_explorer.watch(t, &(struct raster_params){ .subpixel_bits = 8 }, ev, buf, sizeof buf);
    return sscanf(buf, "x_left %lf, x_right %lf, prestep %lf", &v[0], &v[1], &v[2]);
}

static void listen(void *ctx, const struct trace_event *ev)
{
    struct story *s = ctx;
    const struct tri_setup *t = s->t;
    if (s->bad)
        return;
    switch (ev->kind) {
    case TRACE_ROW: {
        s->rows++;
        double xl, xr, w[3] = { 0, 0, 0 };
        if (s->last_row >= 0 && ev->y != s->last_row + 1) {
            snprintf(s->why, sizeof s->why, "row %d after row %d", ev->y, s->last_row);
            s->bad = 1;
        }
        s->last_row = ev->y;
        if (s->bad) {
            break;
        } else if (!row_crossings(t, ev->y, &xl, &xr)) {
            snprintf(s->why, sizeof s->why, "row %d: no edge crosses its centre", ev->y);
            s->bad = 1;
        } else if (watch_values(t, ev, w) != 2 || fabs(w[0] - xl) > AUX_X_TOLERANCE
                   || fabs(w[1] - xr) > AUX_X_TOLERANCE) {
            snprintf(s->why, sizeof s->why, "row %d: x_left %.6f x_right %.6f, exact %.6f %.6f",
                     ev->y, w[0], w[1], xl, xr);
            s->bad = 1;
        }
        break;
    }
    case TRACE_SPAN: {
        s->spans++;
        /* the span is the reference's run of covered centres on that row */
        int first = -1, last = -2;
        for (int x = 0; x < t->target_w; x++) {
            int64_t f[3] = { edge_value(t, 0, x, ev->y), edge_value(t, 1, x, ev->y),
                             edge_value(t, 2, x, ev->y) };
            if (edge_inside(t, 0, f[0]) && edge_inside(t, 1, f[1]) && edge_inside(t, 2, f[2])) {
                if (first < 0)
                    first = x;
                last = x;
            }
        }
        double w[3] = { 0, 0, 0 };
        int got = watch_values(t, ev, w);
        double xl, xr;      /* the prestep from the exact left crossing, worked out here */
        double prestep = row_crossings(t, ev->y, &xl, &xr) ? ev->x + 0.5 - xl : -1;
        if (ev->x != first || ev->x1 != last) {
            snprintf(s->why, sizeof s->why, "row %d: span %d..%d, reference %d..%d",
                     ev->y, ev->x, ev->x1, first, last);
            s->bad = 1;
        } else if (got != 3 || (ev->x > 0 && (w[2] < 0 || w[2] >= 1
                                               || fabs(w[2] - prestep) > AUX_X_TOLERANCE))) {
            snprintf(s->why, sizeof s->why, "row %d: prestep %.6f, expected %.6f",
                     ev->y, w[2], prestep);
            s->bad = 1;
        }
        break;
    }
    case TRACE_PIXEL_WRITE:
        s->writes++;
        break;
    default:
        break;
    }
}

Test(lesson01, rows_spans_and_edge_crossings_are_told_truly)
{
    const int w = 41, h = 29;
    struct rng r = rng_for(0x1e550102);
    for (int i = 0; i < 1500; i++) {
        struct vertex v[3];
        random_tri(&r, i % 3 == 0 ? CAT_CENTRES : i % 3 == 1 ? CAT_GENERIC : CAT_SLIVER, w, h, v);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        uint8_t *ref = calloc((size_t)w * h, 1);
        reference_mask(&t, ref);
        int covered = 0;
        for (int j = 0; j < w * h; j++)
            covered += ref[j];
        struct target fb;
        cr_assert(target_init(&fb, w, h, 0));
        struct story s = { .t = &t, .last_row = -1 };
        struct trace tr = { .sink = listen, .ctx = &s };
        trace_begin(&tr, 0, TRACE_UNLIMITED);
        lesson_01.variants[0].rasterize(&t, &(struct raster_params){ .subpixel_bits = 8 }, &fb, &tr);

        /* rows: every row whose centre is in [y_top, y_bottom), clipped */
        int rows = 0;
        if (!t.empty) {
            int64_t ymin = t.y[0], ymax = t.y[0];
            for (int k = 1; k < 3; k++) {
                ymin = t.y[k] < ymin ? t.y[k] : ymin;
                ymax = t.y[k] > ymax ? t.y[k] : ymax;
            }
            for (int y = 0; y < h; y++)
                rows += pixel_centre(y) >= ymin && pixel_centre(y) < ymax;
        }
        struct case_info info = { .what = "narration", .seed = test_seed(), .index = (uint64_t)i,
                                  .v = v, .nv = 3 };
        if (s.bad || s.rows != rows || s.writes != covered || (int)tr.c.covered != covered)
            print_case(&info);
        cr_assert(!s.bad, "%s", s.why);
        cr_assert_eq(s.rows, rows, "%d ROW events for %d rows", s.rows, rows);
        cr_assert_eq(s.writes, covered, "%d writes for %d covered pixels", s.writes, covered);
        cr_assert_eq((int)tr.c.covered, covered, "spans count %d covered, reference %d",
                     (int)tr.c.covered, covered);
        target_free(&fb);
        free(ref);
    }
}

Test(lesson01, setup_is_the_first_event_even_for_an_empty_triangle)
{
    struct vertex v[3] = { test_vertex(1, 1), test_vertex(5, 5), test_vertex(9, 9) };
    struct tri_setup t;
    tri_setup(&t, v, 16, 16);
    struct target fb;
    cr_assert(target_init(&fb, 16, 16, 0));
    struct trace tr = { 0 };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    for (int k = 0; k < lesson_01.nvariants; k++) {
        trace_begin(&tr, 0, TRACE_UNLIMITED);
        lesson_01.variants[k].rasterize(&t, &(struct raster_params){ .subpixel_bits = 8 }, &fb, &tr);
        cr_expect_eq(tr.c.events, 1, "%s: %llu events for a degenerate triangle",
                     lesson_01.variants[k].name, (unsigned long long)tr.c.events);
    }
    target_free(&fb);
}
