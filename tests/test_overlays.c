/* test_overlays.c - the lessons' own drawings and watch constants.
 *
 * Lesson 01's TRIANGLE constants are checked against the tutorial's formulas
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
extern const struct lesson_explorer lesson_01_explorer, lesson_03_explorer, lesson_05_explorer;

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
 * that order), so 1, 2, 3 of the tutorial are A, B, C. */
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
    lesson_01_explorer.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
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
    lesson_01_explorer.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "= flat"), "%s", buf);
    /* a short buffer is cut, never overrun */
    char small[12];
    lesson_01_explorer.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, small, sizeof small);
    cr_assert_lt(strlen(small), sizeof small);
}

Test(overlays, lesson03_constants_are_the_edge_coefficients)
{
    struct vertex v[3] = { test_vertex(2.5, 1.25), test_vertex(17, 6), test_vertex(6.75, 12.5) };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 20, 14));
    cr_assert(!t.swapped);
    char buf[1024];
    lesson_03_explorer.constants(&t, &(struct raster_params){ .subpixel_bits = 8 }, buf, sizeof buf);
    /* I01 = Ay - By, J01 = Bx - Ax, in 1/256 px (the edge-function notes, (6)-(8)) */
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

/* It also draws one scene pixel, (2, 3), through the canvas's verbs. */
static void record_overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                           const struct raster_params *p, const struct trace_event *last)
{
    (void)p;
    seen.calls++;
    seen.area2 = t->area2;
    snprintf(seen.view, sizeof seen.view, "%s", c->view);
    seen.last_kind = last ? last->kind : -1;
    seen.unit = c->unit;
    c->polygon(c, (const double[][2]){ { 2, 3 }, { 3, 3 }, { 3, 4 }, { 2, 4 } }, 4,
               (struct pen){ .fill = INK_MARK });
}

static int constants_calls;
static void record_constants(const struct tri_setup *t, const struct raster_params *p, char *buf,
                             size_t n)
{
    (void)t, (void)p;
    constants_calls++;
    snprintf(buf, n, "marker = 1\n");
}

static cairo_surface_t *paint(const struct lesson *l, const struct lesson_explorer *side,
                              const char *view, uint64_t step, struct explorer_layout *L)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, l->builtin_scene, err, sizeof err), "%s", err);
    struct explorer ex;
    struct explorer_desc d = { .lesson = l, .side = side, .scene = &s, .scene_name = "test",
                               .step = step };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    cr_assert(!view || explorer_set_view_name(&ex, view), "%s: no view %s", l->id, view);
    scene_free(&s);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 960, 600);
    cairo_t *cr = cairo_create(img);
    explorer_paint(&ex, cr, 960, 600);
    if (L)
        explorer_layout(&ex, 960, 600, L);
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
    char why[512];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    struct lesson_explorer side = { .lesson = &lesson_01, .overlay = record_overlay,
                                    .constants = record_constants };
    memset(&seen, 0, sizeof seen);
    constants_calls = 0;
    cairo_surface_destroy(paint(&lesson_01, &side, "spans", 0, NULL));
    cr_assert_eq(seen.calls, 1);
    cr_assert_eq(seen.last_kind, -1, "no event has happened at step 0");
    cr_assert_str_eq(seen.view, "spans");
    cr_assert_eq(constants_calls, 1);

    struct explorer_layout L;
    cairo_surface_t *img = paint(&lesson_01, &side, "coverage", 1, &L);
    cr_assert_eq(seen.calls, 2);
    cr_assert_eq(seen.last_kind, TRACE_SETUP);
    cr_assert_str_eq(seen.view, "coverage");
    cr_assert_gt(seen.area2, 0);
    cr_assert_float_eq(seen.unit, 1 / L.zoom, 1e-12, "one screen pixel is `unit` scene pixels");
    /* the canvas is in scene pixels: the square drawn over pixel (2, 3) is
     * white on the screen where that pixel is, and only there */
    const uint8_t *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    for (int k = 0; k < 2; k++) {
        int sx = (int)(L.ox + (2.5 + 2 * k) * L.zoom), sy = (int)(L.oy + 3.5 * L.zoom);
        uint32_t px = *(const uint32_t *)(data + (size_t)sy * (size_t)stride + 4 * (size_t)sx);
        if (k == 0)
            cr_assert_eq(px & 0xffffff, 0xffffff, "pixel (2, 3) on the screen: %06x", px & 0xffffff);
        else
            cr_assert_neq(px & 0xffffff, 0xffffff, "pixel (4, 3) is not drawn over");
    }
    cairo_surface_destroy(img);
}

/* Each lesson's overlay draws something where it says it does: the picture
 * with the overlay differs from the one without. */
static void assert_overlay_draws(const struct lesson_explorer *real, const char *view,
                                 uint64_t step)
{
    char why[512];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    const struct lesson *l = real->lesson;
    struct lesson_explorer bare = { .lesson = l };
    struct lesson_explorer only_constants = { .lesson = l, .constants = real->constants };
    cairo_surface_t *a = paint(l, real, view, step, NULL),
                    *b = paint(l, &only_constants, view, step, NULL),
                    *c = paint(l, &bare, view, step, NULL);
    cr_assert(!same(a, b), "%s: the overlay drew nothing in the %s view at step %llu", l->id,
              view, (unsigned long long)step);
    if (real->constants)
        cr_assert(!same(b, c), "%s: no TRIANGLE constants in the panel", l->id);
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    cairo_surface_destroy(c);
}

Test(overlays, lesson01_draws) { assert_overlay_draws(&lesson_01_explorer, "spans", 200); }
Test(overlays, lesson03_draws) { assert_overlay_draws(&lesson_03_explorer, "edges", 60); }
Test(overlays, lesson05_draws) { assert_overlay_draws(&lesson_05_explorer, "blocks", 2); }

/* Every lesson's explorer side names its lesson, and the explorer finds it. */
Test(overlays, every_explorer_side_pairs_with_its_lesson)
{
    int found = 0;
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson_explorer *x = lesson_explorer_of(all_lessons[i]);
        if (!x)
            continue;
        cr_assert_eq(x->lesson, all_lessons[i], "%s: paired with %s", all_lessons[i]->id,
                     x->lesson->id);
        found++;
    }
    int listed = 0;
    while (all_lesson_explorers[listed])
        listed++;
    cr_assert_eq(found, listed, "every explorer side belongs to a lesson");
    cr_assert_geq(found, 4);
}
