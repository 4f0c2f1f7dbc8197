/* test_overlays.c - the lessons' own drawings and watch constants.
 *
 * Lesson 01's TRIANGLE constants are checked against the seed's formulas
 * worked out here from the literal vertices (never from the lesson's code);
 * the explorer is checked to call both hooks with the focus triangle, the
 * view shown and the last event, and each overlay to change the picture. */
#include <cairo.h>
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/paint.h"
#include "testlib.h"

extern const struct lesson lesson_01, lesson_03, lesson_05;

/* The number after "name = " in the constants text. */
static double value_of(const char *text, const char *name)
{
    char key[32];
    snprintf(key, sizeof key, "%s = ", name);
    const char *at = strstr(text, key);
    cr_assert_not_null(at, "no \"%s\" in:\n%s", key, text);
    char *end;
    double v = strtod(at + strlen(key), &end);
    cr_assert_neq(end, at + strlen(key), "\"%s\" is not followed by a number:\n%s", key, text);
    return v;
}

static void assert_close(double got, double want, const char *what)
{
    cr_assert(fabs(got - want) <= 1e-3 * fabs(want) + 1e-9, "%s: %.9g, want %.9g", what, got, want);
}

/* One triangle given with 1 on top and clockwise on screen (tri_setup keeps
 * that order), so 1, 2, 3 of the seed are A, B, C. */
struct case01 {
    double x[3], y[3];
    const char *kase;
};

static void check01(const struct case01 *c)
{
    struct vertex v[3];
    for (int i = 0; i < 3; i++) {
        v[i] = test_vertex(c->x[i], c->y[i]);
        v[i].r = i == 0, v[i].g = i == 1, v[i].b = i == 2;
        v[i].z = 1 + i;
    }
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 64, 48));
    cr_assert(!t.swapped, "the triangle is meant to be clockwise already");
    cr_assert(c->y[0] < c->y[1] && c->y[0] < c->y[2], "vertex 1 is meant to be on top");
    char buf[1024];
    memset(buf, 'x', sizeof buf);
    lesson_01.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
    cr_assert(memchr(buf, '\0', sizeof buf), "constants left the text unterminated");

    const double *x = c->x, *y = c->y;
    assert_close(value_of(buf, "Dc12"), (x[1] - x[0]) / (y[1] - y[0]), "Dc12");
    assert_close(value_of(buf, "Dc13"), (x[2] - x[0]) / (y[2] - y[0]), "Dc13");
    assert_close(value_of(buf, "Dc23"), (x[2] - x[1]) / (y[2] - y[1]), "Dc23");
    /* formula (1) for red (1 at vertex 1), green (at 2), blue (at 3), z = 1, 2, 3 */
    double den = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    double c1[3] = { 1, 0, 0 }, c2[3] = { 0, 1, 0 }, c3[3] = { 0, 0, 1 };
    const char *names[3] = { "Dc r", "g", "b" };
    for (int i = 0; i < 3; i++)
        assert_close(value_of(buf, names[i]),
                     ((c2[i] - c1[i]) * (y[2] - y[0]) - (c3[i] - c1[i]) * (y[1] - y[0])) / den,
                     names[i]);
    assert_close(value_of(buf, "z"), ((2.0 - 1) * (y[2] - y[0]) - (3.0 - 1) * (y[1] - y[0])) / den, "z");
    char want[16];
    snprintf(want, sizeof want, "case = %s", c->kase);
    cr_assert_not_null(strstr(buf, want), "want \"%s\" in:\n%s", want, buf);
}

Test(overlays, lesson01_constants_case_b)
{
    check01(&(struct case01){ { 10.5, 50, 20 }, { 4, 20.25, 40 }, "[B]" });
}

Test(overlays, lesson01_constants_case_a)
{
    check01(&(struct case01){ { 10, 30, 4 }, { 4, 40, 20 }, "[A]" });
}

Test(overlays, lesson01_flat_edge_named_flat)
{
    /* a flat top: 1 -> 2 horizontal has no x per row */
    struct vertex v[3] = { test_vertex(4, 4), test_vertex(30, 4), test_vertex(10, 30) };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 64, 48));
    char buf[1024];
    lesson_01.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "= flat"), "%s", buf);
    /* a short buffer is cut, never overrun */
    char small[12];
    lesson_01.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, small, sizeof small);
    cr_assert_lt(strlen(small), sizeof small);
}

Test(overlays, lesson03_constants_are_the_edge_coefficients)
{
    struct vertex v[3] = { test_vertex(2.5, 1.25), test_vertex(17, 6), test_vertex(6.75, 12.5) };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 20, 14));
    cr_assert(!t.swapped);
    char buf[1024];
    lesson_03.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
    /* I01 = Ay - By, J01 = Bx - Ax, in 1/256 px (seed 001, (6)-(8)) */
    double X[3] = { 2.5, 17, 6.75 }, Y[3] = { 1.25, 6, 12.5 };
    for (int k = 0; k < 3; k++) {
        int b = (k + 1) % 3;
        char name[8];
        snprintf(name, sizeof name, "I0%d", k + 1);
        assert_close(value_of(buf, name), (Y[k] - Y[b]) * 256, name);
        snprintf(name, sizeof name, "J0%d", k + 1);
        assert_close(value_of(buf, name), (X[b] - X[k]) * 256, name);
    }
}

/* --- the explorer calls the hooks --------------------------------------------------- */

static struct {
    int calls;
    int64_t area2;
    char view[32];
    int last_kind;              /* -1: NULL */
    double unit;
} seen;

static void record_overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                           const struct raster_params *p, const struct trace_event *last)
{
    (void)p;
    seen.calls++;
    seen.area2 = t->area2;
    snprintf(seen.view, sizeof seen.view, "%s", c->view);
    seen.last_kind = last ? last->kind : -1;
    seen.unit = c->unit;
    /* user space is scene pixels: one scene pixel is 1 / unit screen pixels */
    double dx = 1, dy = 0;
    cairo_user_to_device_distance(c->cr, &dx, &dy);
    cr_assert_float_eq(dx * c->unit, 1.0, 1e-9);
}

static int constants_calls;
static void record_constants(const struct tri_setup *t, const struct raster_params *p, char *buf,
                             size_t n)
{
    (void)t, (void)p;
    constants_calls++;
    snprintf(buf, n, "marker = 1\n");
}

static cairo_surface_t *paint(const struct lesson *l, const char *view, uint64_t step)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, l->builtin_scene, err, sizeof err), "%s", err);
    struct explorer ex;
    struct explorer_desc d = { .lesson = l, .scene = &s, .scene_name = "test", .step = step };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    cr_assert(!view || explorer_set_view_name(&ex, view), "%s: no view %s", l->id, view);
    scene_free(&s);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 960, 600);
    cairo_t *cr = cairo_create(img);
    explorer_paint(&ex, cr, 960, 600);
    cairo_destroy(cr);
    explorer_free(&ex);
    cairo_surface_flush(img);
    return img;
}

static bool same(cairo_surface_t *a, cairo_surface_t *b)
{
    int h = cairo_image_surface_get_height(a), stride = cairo_image_surface_get_stride(a);
    return memcmp(cairo_image_surface_get_data(a), cairo_image_surface_get_data(b),
                  (size_t)h * (size_t)stride) == 0;
}

Test(overlays, explorer_calls_both_hooks)
{
    explorer_fonts();
    struct lesson l = lesson_01;
    l.overlay = record_overlay;
    l.constants = record_constants;
    memset(&seen, 0, sizeof seen);
    constants_calls = 0;
    cairo_surface_destroy(paint(&l, "spans", 0));
    cr_assert_eq(seen.calls, 1);
    cr_assert_eq(seen.last_kind, -1, "no event has happened at step 0");
    cr_assert_str_eq(seen.view, "spans");
    cr_assert_eq(constants_calls, 1);

    cairo_surface_destroy(paint(&l, "coverage", 1));
    cr_assert_eq(seen.calls, 2);
    cr_assert_eq(seen.last_kind, TRACE_SETUP);
    cr_assert_str_eq(seen.view, "coverage");
    cr_assert_gt(seen.area2, 0);
    cr_assert_gt(seen.unit, 0);
}

/* Each lesson's overlay draws something where it says it does: the picture
 * with the overlay differs from the one without. */
static void assert_overlay_draws(const struct lesson *real, const char *view, uint64_t step)
{
    explorer_fonts();
    struct lesson bare = *real;
    bare.overlay = NULL;
    bare.constants = NULL;
    struct lesson only_constants = *real;
    only_constants.overlay = NULL;
    cairo_surface_t *a = paint(real, view, step), *b = paint(&only_constants, view, step),
                    *c = paint(&bare, view, step);
    cr_assert(!same(a, b), "%s: the overlay drew nothing in the %s view at step %llu", real->id,
              view, (unsigned long long)step);
    if (real->constants)
        cr_assert(!same(b, c), "%s: no TRIANGLE constants in the panel", real->id);
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    cairo_surface_destroy(c);
}

Test(overlays, lesson01_draws) { assert_overlay_draws(&lesson_01, "spans", 200); }
Test(overlays, lesson03_draws) { assert_overlay_draws(&lesson_03, "edges", 60); }
Test(overlays, lesson05_draws) { assert_overlay_draws(&lesson_05, "blocks", 2); }
