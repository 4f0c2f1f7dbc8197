/* test_lesson03.c - lesson 03's claims: no multiplication per pixel, the
 * float exhibit is real and as large as the text says, its errors stay within
 * the rounding bound, colour and z agree with lesson 02, and the overflow
 * budget the text tabulates is what the arithmetic allows.
 * (Exact coverage on random triangles and meshes: test_property.c.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson_explorer.h"
#include "testlib.h"
#include "explore/replay.h"

extern const struct lesson lesson_02, lesson_03, lesson_03_fast;

#define README "lessons/03-edge-stepping/README.md"

static const char *readme(void)
{
    static char text[1 << 17];
    FILE *f = fopen(README, "rb");
    cr_assert_not_null(f, README " not found (run the tests from the project's top folder)");
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    return text;
}

/* --- events of one run ------------------------------------------------------------ */

/* Run one triangle through a variant with narration, keeping every event. */
static void run_traced(const struct lesson_variant *v, const struct tri_setup *t,
                       struct target *fb, struct test_events *out)
{
    struct raster_params p = default_params();
    struct trace tr = { .sink = test_collect, .ctx = out };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    v->rasterize(t, &p, fb, &tr);
}

static void setup_tri(struct tri_setup *t, double ax, double ay, double bx, double by,
                      double cx, double cy, int w, int h)
{
    struct vertex v[3] = { test_vertex(ax, ay), test_vertex(bx, by), test_vertex(cx, cy) };
    v[0].z = 1, v[1].z = 3, v[2].z = 2;
    v[0].r = 1, v[1].g = 1, v[2].b = 1;
    tri_setup(t, v, w, h);
}

/* --- the operation counters -------------------------------------------------------- */

/* Between two pixel tests of one row the lesson does its additions and no
 * multiplication at all, shading included; lesson 02 multiplies at every
 * pixel. The counters are the ones the lesson COUNTs, read from the events. */
Test(lesson03, zero_multiplications_per_pixel_inside_the_loop)
{
    struct rng r = rng_for(0x103);
    int rows_checked = 0;
    for (int n = 0; n < 200; n++) {
        struct vertex v[3];
        random_tri(&r, CAT_GENERIC, 48, 32, v);
        struct tri_setup t;
        tri_setup(&t, v, 48, 32);
        struct target fb;
        cr_assert(target_init(&fb, 48, 32, 0));
        struct test_events e03 = { 0 }, e02 = { 0 };
        run_traced(&lesson_03.variants[0], &t, &fb, &e03);
        run_traced(&lesson_02.variants[0], &t, &fb, &e02);

        uint64_t adds_per_pixel = 0;
        const struct trace_event *prev = NULL;
        for (size_t i = 0; i < e03.n; i++) {
            const struct trace_event *ev = &e03.ev[i];
            if (ev->kind == TRACE_ROW)
                prev = NULL, rows_checked++;
            if (ev->kind != TRACE_PIXEL_TEST)
                continue;
            if (prev) {
                cr_assert_eq(ev->mul, prev->mul, "triangle %d: %llu multiplications between "
                             "pixels (%d,%d) and (%d,%d)", n, (unsigned long long)(ev->mul - prev->mul),
                             prev->x, prev->y, ev->x, ev->y);
                uint64_t adds = ev->add - prev->add;
                cr_assert_gt(adds, 0);
                if (prev->flags & TRACE_INSIDE)     /* the previous pixel was shaded too */
                    continue;
                if (!adds_per_pixel)
                    adds_per_pixel = adds;
                cr_assert_eq(adds, adds_per_pixel, "the additions per tested pixel are a constant");
            }
            prev = ev;
        }
        /* lesson 02, for comparison: its counter grows at every pixel */
        prev = NULL;
        for (size_t i = 0; i < e02.n; i++) {
            const struct trace_event *ev = &e02.ev[i];
            if (ev->kind == TRACE_ROW)
                prev = NULL;
            if (ev->kind != TRACE_PIXEL_TEST)
                continue;
            if (prev)
                cr_assert_geq(ev->mul - prev->mul, 6, "lesson 02 evaluates F01, F02, F03 anew");
            prev = ev;
        }
        free(e03.ev);
        free(e02.ev);
        target_free(&fb);
    }
    cr_expect_gt(rows_checked, 1000);
}

/* The multiplications of a whole triangle depend on its rows, not on its
 * width: stretching a triangle eight times wider leaves them unchanged. */
Test(lesson03, multiplications_do_not_grow_with_the_width)
{
    uint64_t mul[2][2];
    for (int wide = 0; wide < 2; wide++) {
        double s = wide ? 8 : 1;
        struct tri_setup t;
        setup_tri(&t, 2.3 * s, 1.6, 18.6 * s, 5.2, 6.4 * s, 12.7, 160, 16);
        const struct lesson *ls[2] = { &lesson_03, &lesson_02 };
        for (int k = 0; k < 2; k++) {
            struct target fb;
            cr_assert(target_init(&fb, 160, 16, 0));
            struct raster_params p = default_params();
            struct trace tr = { 0 };
            trace_begin(&tr, 0, TRACE_UNLIMITED);
            ls[k]->variants[0].rasterize(&t, &p, &fb, &tr);
            mul[k][wide] = tr.c.mul;
            target_free(&fb);
        }
    }
    cr_expect_eq(mul[0][0], mul[0][1], "lesson 03: %llu vs %llu multiplications",
                 (unsigned long long)mul[0][0], (unsigned long long)mul[0][1]);
    cr_expect_gt(mul[1][1], 4 * mul[1][0], "lesson 02 pays per pixel: %llu vs %llu",
                 (unsigned long long)mul[1][0], (unsigned long long)mul[1][1]);
}

/* --- the float exhibit --------------------------------------------------------------- */

struct float_errors {
    long extra, missing;       /* per triangle, against the exact reference */
    long on_dropped_edge;      /* extra pixels whose centre is exactly on an edge
                                * the top-left rule leaves out (F == 0, bias -1) */
    long beyond_bound;         /* wrong pixels no edge value explains (must be 0) */
};

/* How far can the float sum of one edge be from the exact value at pixel
 * (x, y)? It is reached from the first centre by (y - miny) + (x - minx)
 * additions after one rounding of the start; each rounds by at most half a
 * unit in the last place of its result, 2^-24 relative, and no result
 * exceeds the largest |F + bias| over the box, one step past it included
 * (F is linear: the largest is at a corner). */
static double float_error_bound(const struct tri_setup *t, int k, int x, int y)
{
    double fmax = 0;
    for (int cy = 0; cy < 2; cy++)
        for (int cx = 0; cx < 2; cx++) {
            int px = cx ? t->maxx + 1 : t->minx, py = cy ? t->maxy + 1 : t->miny;
            double f = fabs((double)(edge_value(t, k, px, py) + t->bias[k]));
            fmax = f > fmax ? f : fmax;
        }
    double steps = (double)(y - t->miny) + (double)(x - t->minx) + 1;
    return steps * ldexp(fmax, -24);
}

/* Every wrong pixel of the float loop on triangle t, compared with the
 * exact reference, added to *e. */
static void float_errors_of(const struct tri_setup *t, struct float_errors *e)
{
    int w = t->target_w, h = t->target_h;
    const struct lesson_variant *fl = lesson_variant(&lesson_03, "float");
    cr_assert_not_null(fl, "lesson 03 has no float exhibit");
    cr_assert(variant_against_exact(fl));
    struct target fb, exact;
    cr_assert(target_init(&fb, w, h, 0));
    cr_assert(target_init(&exact, w, h, 0));
    struct raster_params p = default_params();
    fl->rasterize(t, &p, &fb, NULL);
    lesson_03_fast.variants[0].rasterize(t, &p, &exact, NULL);
    uint8_t *ref = calloc((size_t)w * (size_t)h, 1);
    cr_assert_not_null(ref);
    reference_mask(t, ref);
    cr_assert_eq(memcmp(exact.count, ref, (size_t)w * (size_t)h), 0,
                 "the exact loop differs from the reference");

    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (fb.count[i] == ref[i])
                continue;
            bool explained = false, dropped = false;
            for (int k = 0; k < 3; k++) {
                int64_t f = edge_value(t, k, x, y);
                dropped |= f == 0 && t->bias[k] == -1;
                explained |= fabs((double)(f + t->bias[k])) <= float_error_bound(t, k, x, y);
            }
            if (fb.count[i] > ref[i]) {
                e->extra++;
                e->on_dropped_edge += dropped;
            } else {
                e->missing++;
            }
            e->beyond_bound += !explained;
        }
    free(ref);
    target_free(&fb);
    target_free(&exact);
}

/* A number the lesson text states, by its marker (testlib.h). */
static long stated(const char *key)
{
    return (long)text_number(README, key, NULL);
}

/* builtin:float-drift: two triangles sharing an edge, two of whose edges run
 * through pixel centres. Float stepping rounds the fill rule's -1 away, so
 * centres on the right and bottom edges are drawn although the rule leaves
 * them to the neighbour. */
Test(lesson03, float_exhibit_is_wrong_on_its_scene_by_the_count_the_text_states)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_03.exhibit_scene, err, sizeof err), "%s", err);
    struct float_errors e = { 0 };
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        float_errors_of(&t, &e);
    }
    cr_expect_gt(e.extra + e.missing, 0, "the exhibit is not wrong anywhere");
    cr_expect_eq(e.extra + e.missing, stated("l03.float.wrong"),
                 "%ld extra + %ld missing", e.extra, e.missing);
    cr_expect_eq(e.on_dropped_edge, e.extra, "every extra pixel is a centre on a right or bottom edge");
    cr_expect_eq(e.beyond_bound, 0);

    /* the whole scene: those centres are covered by both triangles */
    struct raster_params p = default_params();
    struct target fb;
    cr_assert(render_scene(&s, lesson_variant(&lesson_03, "float"), &p, &fb));
    long twice = 0;
    for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++)
        twice += fb.count[i] > 1;
    cr_expect_gt(twice, 0);
    cr_expect_eq(twice, stated("l03.float.twice"), "%ld drawn twice", twice);
    target_free(&fb);
    scene_free(&s);
}

/* Off the grid, on a triangle 2,000 pixels across, the drift itself moves
 * centres to the wrong side, both ways, and always within the bound. */
Test(lesson03, float_drift_on_a_large_triangle_stays_within_the_rounding_bound)
{
    struct tri_setup t;
    setup_tri(&t, 10.3, 20.7, 2000.1, 100.4, 150.6, 2030.2, 2048, 2048);
    struct float_errors e = { 0 };
    float_errors_of(&t, &e);
    cr_expect_eq(e.beyond_bound, 0, "a wrong pixel farther from every edge than rounding explains");
    cr_expect_gt(e.missing, 0, "drift drops centres inside the triangle");
    cr_expect_eq(e.extra, stated("l03.large.extra"));
    cr_expect_eq(e.missing, stated("l03.large.missing"));
}

/* --- interpolation ----------------------------------------------------------------- */

/* Colour and z are stepped by additions in double precision and restarted at
 * each row from the exact integer edge values. Against lesson 02, which
 * evaluates u, v, w at every pixel, they may differ by the drift of one row
 * (far below 1e-9) and by how that moves an 8-bit or float rounding. */
#define INTERP_TOLERANCE 1e-6  /* relative, the watch values: float rounding (2^-24) plus drift */
#define COLOR_TOLERANCE 1      /* 8-bit steps: a value within the drift of a .5 boundary */
#define Z_TOLERANCE 2e-7       /* relative: z stored as float, one unit in the last place */

struct written { bool set; float z; uint32_t rgba; };

static void check_against_lesson02(const struct tri_setup *t, int n)
{
    int w = t->target_w, h = t->target_h;
    struct target fb;
    cr_assert(target_init(&fb, w, h, 0));
    struct test_events e03 = { 0 }, e02 = { 0 };
    run_traced(&lesson_03.variants[0], t, &fb, &e03);
    run_traced(&lesson_02.variants[0], t, &fb, &e02);
    struct written *by02 = calloc((size_t)w * (size_t)h, sizeof *by02);
    cr_assert_not_null(by02);
    for (size_t i = 0; i < e02.n; i++)
        if (e02.ev[i].kind == TRACE_PIXEL_WRITE)
            by02[(size_t)e02.ev[i].y * (size_t)w + (size_t)e02.ev[i].x]
                = (struct written){ true, e02.ev[i].z, e02.ev[i].rgba };

    for (size_t i = 0; i < e03.n; i++) {
        const struct trace_event *ev = &e03.ev[i];
        if (ev->kind == TRACE_PIXEL_TEST && (ev->flags & TRACE_INSIDE)) {
            /* the stepped values in the watch panel against the reference */
            double z, rgb[3], st[2];
            reference_shade(t, ev->x, ev->y, false, &z, rgb, st);
            /* stepped as the pixel writes them: colour times 255, s and t times
             * the checker's N (1 without a checker) */
            double want[6] = { z, 255 * rgb[0], 255 * rgb[1], 255 * rgb[2], st[0], st[1] };
            for (int k = 0; k < 6; k++)
                cr_assert(fabs(ev->aux[k] - want[k]) <= INTERP_TOLERANCE * fmax(1, fabs(want[k])),
                          "triangle %d, %s at (%d,%d): %.9g stepped, %.9g exact", n,
                          lesson_03.aux_names[k], ev->x, ev->y, ev->aux[k], want[k]);
        }
        if (ev->kind != TRACE_PIXEL_WRITE)
            continue;
        const struct written *o = &by02[(size_t)ev->y * (size_t)w + (size_t)ev->x];
        cr_assert(o->set, "triangle %d: (%d,%d) written by lesson 03 only", n, ev->x, ev->y);
        cr_assert(fabsf(ev->z - o->z) <= Z_TOLERANCE * fabsf(o->z), "triangle %d, z at (%d,%d): "
                  "%.9g vs %.9g", n, ev->x, ev->y, ev->z, o->z);
        for (int c = 0; c < 3; c++) {
            int a = (int)(ev->rgba >> (16 - 8 * c) & 0xff), b = (int)(o->rgba >> (16 - 8 * c) & 0xff);
            cr_assert(abs(a - b) <= COLOR_TOLERANCE, "triangle %d, channel %d at (%d,%d): %d vs %d",
                      n, c, ev->x, ev->y, a, b);
        }
    }
    free(by02);
    free(e03.ev);
    free(e02.ev);
    target_free(&fb);
}

Test(lesson03, colour_and_z_agree_with_lesson02_within_the_named_tolerance)
{
    struct rng r = rng_for(0x303);
    for (int n = 0; n < 300; n++) {
        struct vertex v[3];
        random_tri(&r, n % 3 ? CAT_GENERIC : CAT_SLIVER, 64, 48, v);
        struct tri_setup t;
        tri_setup(&t, v, 64, 48);
        check_against_lesson02(&t, n);
    }
}

/* The longest rows: 1,900 steps of the double sums on a full-HD triangle. */
Test(lesson03, stepped_colour_does_not_drift_along_long_rows)
{
    struct tri_setup t;
    setup_tri(&t, 3.3, 7.7, 1910.1, 60.4, 90.6, 1070.2, 1920, 1080);
    check_against_lesson02(&t, 0);
}

/* --- the overflow budget ---------------------------------------------------------------- */

/* With coordinates |x|, |y| <= R (in units of 1/2^b pixel), every edge
 * coefficient is |I|, |J| <= 2R and every difference |Px - Ax| <= 2R, so
 * |F| = |I (Px - Ax) + J (Py - Ay)| <= 8 R^2. The largest R whose budget
 * fits a signed integer of the given maximum: */
static int64_t largest_r(int64_t max)
{
    int64_t lo = 0, hi = (int64_t)1 << 31;      /* 8 hi^2 > INT64_MAX */
    while (lo < hi) {
        int64_t mid = lo + (hi - lo + 1) / 2;
        if ((uint64_t)mid * (uint64_t)mid <= (uint64_t)max / 8)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* The largest magnitude any step of the constant-form evaluation
 * I Px + J Py + K takes (products, partial sums, K's products, F), over
 * triangles and points on the corners of the square [-R, R]^2: every such
 * term is affine in each point separately, so corners give its maximum. */
static double largest_term(double R)
{
    const double c[2] = { -R, R };
    double m = 0;
    for (int i = 0; i < 64; i++) {
        double ax = c[i & 1], ay = c[i >> 1 & 1], bx = c[i >> 2 & 1], by = c[i >> 3 & 1];
        double px = c[i >> 4 & 1], py = c[i >> 5 & 1];
        double I = ay - by, J = bx - ax, K = ax * by - ay * bx;
        double terms[] = { I * px, J * py, I * px + J * py, ax * by, ay * bx, K,
                           I * px + J * py + K };
        for (size_t k = 0; k < sizeof terms / sizeof terms[0]; k++)
            m = fmax(m, fabs(terms[k]));
    }
    return m;
}

static void thousands(char *buf, size_t len, int64_t v)
{
    char digits[32];
    int n = snprintf(digits, sizeof digits, "%lld", (long long)v), o = 0;
    for (int i = 0; i < n && o + 2 < (int)len; i++) {
        if (i && (n - i) % 3 == 0)
            buf[o++] = ',';
        buf[o++] = digits[i];
    }
    buf[o] = '\0';
}

Test(lesson03, overflow_budget_table_is_what_the_arithmetic_allows)
{
    int64_t r32 = largest_r(INT32_MAX), r64 = largest_r(INT64_MAX);
    cr_assert_eq(r32, ((int64_t)1 << 14) - 1);
    cr_assert_eq(r64, ((int64_t)1 << 30) - 1);

    /* the budget is safe: nothing overflows 32 bits at R = r32 ... */
    cr_expect_leq(largest_term((double)r32), 8.0 * (double)r32 * (double)r32);
    cr_expect_leq(largest_term((double)r32), (double)INT32_MAX);
    /* ... and not wasteful beyond a factor of two: at 2 R something does */
    cr_expect_gt(largest_term(2.0 * (double)(r32 + 1)), (double)INT32_MAX);
    cr_expect_gt(largest_term(2.0 * (double)(r64 + 1)), (double)INT64_MAX);

    /* the table of the lesson text, one row per choice of sub-pixel bits:
     * every coordinate below (r + 1) / 2^b pixels */
    const char *text = readme();
    for (int b = 0; b <= SUBPIXEL_BITS; b++) {
        char px32[32], px64[32], row[160];
        thousands(px32, sizeof px32, (r32 + 1) >> b);
        thousands(px64, sizeof px64, (r64 + 1) >> b);
        snprintf(row, sizeof row, "| %d | 1/%d px | %s px | %s px |", b, 1 << b, px32, px64);
        cr_expect(strstr(text, row) != NULL, README " lacks the table row\n%s", row);
    }
}

/* The watch panel states the overflow budget of the bits in use, as the
 * README's table does: 32-bit edges keep |F| <= 8 R^2 below 2^31, so R < 2^14
 * units; at 2 bits a unit is 1/4 px, so 4,096 px. */
extern const struct lesson_explorer lesson_03_explorer;

Test(lesson03, watch_panel_states_the_range_of_the_bits_in_use)
{
    struct vertex v[3] = { { .x = 2, .y = 2, .z = 1 }, { .x = 12, .y = 3, .z = 1 },
                           { .x = 5, .y = 11, .z = 1 } };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 16, 16));
    char buf[1024];
    struct raster_params p = { .subpixel_bits = 2 };
    lesson_03_explorer.constants(&t, &p, buf, sizeof buf);
    cr_expect(strstr(buf, "< 4096 px in 32-bit, 268435456 px in 64-bit") != NULL, "%s", buf);
    p.subpixel_bits = 8;
    lesson_03_explorer.constants(&t, &p, buf, sizeof buf);
    cr_expect(strstr(buf, "< 64 px in 32-bit, 4194304 px in 64-bit") != NULL, "%s", buf);
}
