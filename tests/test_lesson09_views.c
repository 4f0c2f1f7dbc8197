/* test_lesson09_views.c - lesson 09's explorer views, held to what they
 * claim, against the independent reference sampler (tests/texref.c) where
 * there is a number to compare:
 *
 *   quads   the pixels shown as helpers are exactly the uncovered pixels of
 *           the 2 x 2 quads that have a covered pixel (coverage by texref);
 *   lod     each pixel's colour is its level's swatch, two levels mixed by
 *           frac(lambda), lambda the reference's (trilinear);
 *   texels  the taps it draws, texel times weight, add up to the colour the
 *           lesson wrote (every filter, both wraps, white vertices);
 *   every view draws the same picture at a step reached forward or back,
 *   and draws at any step of scenes under odd textures (1 x 1, 4 x 1,
 *   1 x 8, clamped, repeated) without reading outside a texture (make test
 *   SANITIZE=1 runs this too). */
#include <cairo.h>
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/paint.h"
#include "draw/painter.h"           /* view_cell, from_rgb */
#include "front/front.h"
#include "testlib.h"
#include "texref.h"
#include "../lessons/09-textures/textures.h"

extern const struct lesson lesson_09;
extern const struct lesson_explorer lesson_09_explorer;
/* textures_explorer.c: the colour the texels view's taps add up to */
bool textures_explorer_taps(const struct raster_params *p, int *x, int *y, double rgb[3]);

/* A random 2-D scene under builtin texture `tex` with white vertices (so a
 * written colour is the filtered texel, rounded), s and t in [-3, 3],
 * depths 0.5..4. */
static void white_scene(struct scene *s, struct rng *r, const char *tex, bool clamp, int n)
{
    static char text[8192];
    size_t at = (size_t)snprintf(text, sizeof text, "size 40 30\ntexture %s %s\n", tex,
                                 clamp ? "clamp" : "repeat");
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        random_tri(r, rng_chance(r, 0.3) ? CAT_TINY : CAT_GENERIC, 40, 30, v);
        at += (size_t)snprintf(text + at, sizeof text - at, "tri");
        for (int k = 0; k < 3; k++)
            at += (size_t)snprintf(text + at, sizeof text - at, "  %.17g %.17g %.3f 1 1 1 %.5f %.5f", v[k].x,
                                   v[k].y, rng_range(r, 0.5, 4), rng_range(r, -3, 3), rng_range(r, -3, 3));
        at += (size_t)snprintf(text + at, sizeof text - at, "\n");
    }
    char err[256];
    cr_assert(scene_parse(s, "views", text, at, err, sizeof err), "%s\n%s", err, text);
}

static void open09(struct explorer *ex, const struct scene *s, enum tex_filter f, const char *view)
{
    struct raster_params p = lesson_params_default(&lesson_09);
    p.knob[P_FILTER] = f;
    struct explorer_desc d = { .lesson = &lesson_09, .scene = s, .scene_name = "test", .params = &p };
    char err[256];
    cr_assert(explorer_init(ex, &d, err, sizeof err), "%s", err);
    cr_assert(explorer_set_view_name(ex, view), "no view %s", view);
}

/* The colour view `view` shows at pixel (x, y) now. */
static uint32_t shown(const struct explorer *ex, int x, int y)
{
    struct view_ctx v;
    view_ctx_init(&v, ex, palette_of(THEME_DARK));
    return view_cell(&v, x, y) & 0xffffff;
}

static uint32_t swatch_rgb(const struct lesson_swatch *s)
{
    return from_rgb(s->rgb[0], s->rgb[1], s->rgb[2]) & 0xffffff;
}

/* The reference's picture of triangle i of s alone (white texels map to
 * its own texture when textured), with lambda kept per pixel. */
static void reference_tri(const struct scene *s, int i, enum texref_filter f, struct texref_target *fb,
                          struct texref *ref)
{
    cr_assert(texref_target_init(fb, s->w, s->h, 0xff000000u));
    fb->lambda = malloc((size_t)s->w * (size_t)s->h * sizeof *fb->lambda);
    cr_assert_not_null(fb->lambda);
    const struct texture *t = scene_texture(s, s->tris[i].texture);
    if (t)
        cr_assert(texref_init(ref, t->level[0].w, t->level[0].h, t->level[0].texel,
                              t->wrap == TEXTURE_CLAMP ? TEXREF_CLAMP : TEXREF_REPEAT));
    texref_draw_tri(fb, s->tris[i].v, t ? ref : NULL, f, 16);
}

/* --- quads: helpers --------------------------------------------------------------- */

Test(lesson09_views, quads_view_shows_the_references_helpers)
{
    struct rng r = rng_for(0x9a7d5u);
    for (int round = 0; round < 2; round++) {
        struct scene s;
        white_scene(&s, &r, "builtin:grid", round, 6);
        struct explorer ex;
        open09(&ex, &s, FILTER_TRILINEAR, "quads");
        const struct lesson_view *lv = &lesson_09_explorer.views[ex.view - VIEW_BUILTIN_COUNT];
        cr_assert_str_eq(lv->name, "quads");
        struct lesson_swatch sw[VIEW_LEGEND_MAX];
        cr_assert_eq(lesson_09_explorer.swatches("quads", &ex.params, sw, VIEW_LEGEND_MAX), 4);
        cr_assert(strstr(sw[0].label, "covered") && strstr(sw[1].label, "helper"));
        long helpers = 0;
        for (int i = 0; i < s.ntris; i++) {
            cr_assert(explorer_set_step(&ex, ex.replay.start[i + 1]));   /* triangle i done */
            struct texref_target fb;
            struct texref ref = { 0 };
            reference_tri(&s, i, TEXREF_TRILINEAR, &fb, &ref);
            for (int y = 0; y < s.h; y++)
                for (int x = 0; x < s.w; x++) {
                    bool quad = false;
                    for (int k = 0; k < 4; k++) {
                        int qx = (x & ~1) + (k & 1), qy = (y & ~1) + (k >> 1);
                        quad = quad || (qx < s.w && qy < s.h && fb.covered[qy * s.w + qx]);
                    }
                    bool covered = fb.covered[y * s.w + x], helper = quad && !covered;
                    uint32_t c = shown(&ex, x, y);
                    helpers += helper;
                    cr_assert_eq(c == swatch_rgb(&sw[1]), helper,
                                 "triangle %d, pixel (%d, %d): %s by the reference, %s in the view", i, x,
                                 y, helper ? "a helper" : "no helper", helper ? "not shown so" : "shown so");
                    cr_assert_eq(c == swatch_rgb(&sw[0]), covered, "triangle %d, pixel (%d, %d)", i, x, y);
                }
            texref_target_free(&fb);
            texref_free(&ref);
        }
        cr_assert_gt(helpers, 0, "the scene has no helper pixels to show");
        explorer_free(&ex);
        scene_free(&s);
    }
}

/* --- lod: the level of each pixel ------------------------------------------------- */

Test(lesson09_views, lod_view_colours_the_references_levels)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "texture-floor", err, sizeof err) && front_scene(&s), "%s", err);
    struct explorer ex;
    open09(&ex, &s, FILTER_TRILINEAR, "lod");
    cr_assert(explorer_set_step(&ex, ex.replay.start[1]));      /* the floor's big triangle done */
    struct lesson_swatch sw[VIEW_LEGEND_MAX];
    int levels = lesson_09_explorer.swatches("lod", &ex.params, sw, VIEW_LEGEND_MAX);
    const struct texture *tex = scene_texture(&s, s.tris[0].texture);
    cr_assert_not_null(tex);
    cr_assert_eq(levels, tex->nlevels, "a swatch per level");
    struct texref_target fb;
    struct texref ref;
    reference_tri(&s, 0, TEXREF_TRILINEAR, &fb, &ref);
    long checked = 0, mixed = 0;
    for (int y = 0; y < s.h; y++)
        for (int x = 0; x < s.w; x++) {
            size_t i = (size_t)y * (size_t)s.w + (size_t)x;
            if (!fb.covered[i])
                continue;
            double last = tex->nlevels - 1, l = fb.lambda[i];
            l = l > 0 ? (l < last ? l : last) : 0;
            int k0 = (int)l, k1 = k0 + 1 < tex->nlevels ? k0 + 1 : k0;
            double f = l - k0, want[3];
            for (int c = 0; c < 3; c++)
                want[c] = (1 - f) * sw[k0].rgb[c] + f * sw[k1].rgb[c];
            uint32_t got = shown(&ex, x, y);
            for (int c = 0; c < 3; c++) {
                int g = (int)(got >> (16 - 8 * c) & 255), w = (int)lround(want[c] * 255);
                cr_assert(abs(g - w) <= 3, "pixel (%d, %d), lambda %.5f: channel %d is %d, want %d", x, y,
                          fb.lambda[i], c, g, w);
            }
            checked++;
            mixed += f > 0.1 && f < 0.9;
        }
    cr_assert_gt(checked, 1000);
    cr_assert_gt(mixed, 100, "few pixels between two levels: the mix is not tried");
    texref_target_free(&fb);
    texref_free(&ref);
    explorer_free(&ex);
    scene_free(&s);
}

/* --- texels: the taps --------------------------------------------------------------- */

/* At sampled steps of every triangle, where the last event is a filter:
 * the taps' colour, rounded, is the colour the next step writes. */
static void check_taps(const struct scene *s, enum tex_filter f, int per_tri, struct rng *r)
{
    struct explorer ex;
    open09(&ex, s, f, "texels");
    int filters = 0;
    for (int i = 0; i < ex.replay.ntris; i++) {
        uint64_t a = ex.replay.start[i], b = ex.replay.start[i + 1];
        for (int k = 0, tries = 0; k < per_tri && b > a + 1 && tries < 40 * per_tri; tries++) {
            uint64_t step = a + 1 + (uint64_t)rng_int(r, 0, (int)(b - a - 2));
            cr_assert(explorer_set_step(&ex, step));
            if (!(ex.last.kind == TRACE_STEP && ex.last.line == L_FILTER))
                continue;
            k++;
            struct run_place at;
            struct raster_params p = replay_params(&ex.replay, ex.cur, &at);
            at.told = ex.told;
            int x, y;
            double rgb[3];
            cr_assert(textures_explorer_taps(&p, &x, &y, rgb), "step %llu: no taps", (unsigned long long)step);
            cr_assert(x == ex.last.x && y == ex.last.y);
            cr_assert(explorer_set_step(&ex, step + 1));
            cr_assert(ex.last.kind == TRACE_PIXEL_WRITE && ex.last.x == x && ex.last.y == y);
            for (int c = 0; c < 3; c++) {
                int got = (int)(ex.last.rgba >> (16 - 8 * c) & 255);
                cr_assert(fabs(got - rgb[c]) <= 1.0, "%s, step %llu, pixel (%d, %d): taps give %.3f, written %d",
                          texref_filter_name((enum texref_filter)(f - 1)), (unsigned long long)step, x, y,
                          rgb[c], got);
            }
            filters++;
        }
    }
    cr_assert_gt(filters, 5, "%s: too few filter steps sampled", texref_filter_name((enum texref_filter)(f - 1)));
    explorer_free(&ex);
}

Test(lesson09_views, texels_taps_add_up_to_the_written_colour)
{
    struct rng r = rng_for(0x7a95u);
    for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++)
        for (int clamp = 0; clamp < 2; clamp++) {
            struct scene s;
            white_scene(&s, &r, f % 2 ? "builtin:checker-numbers" : "builtin:bricks", clamp, 4);
            check_taps(&s, (enum tex_filter)f, 12, &r);
            scene_free(&s);
        }
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "texture-wall", err, sizeof err) && front_scene(&s), "%s", err);
    check_taps(&s, FILTER_ANISO, 30, &r);      /* long footprints: many probes */
    scene_free(&s);
}

/* --- following the step, any texture ------------------------------------------------ */

static cairo_surface_t *paint_now(struct explorer *ex)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 800, 500);
    cairo_t *cr = cairo_create(img);
    explorer_paint(ex, cr, 800, 500);
    cr_assert_eq(cairo_status(cr), CAIRO_STATUS_SUCCESS);
    cairo_destroy(cr);
    cairo_surface_flush(img);
    return img;
}

static bool same(cairo_surface_t *a, cairo_surface_t *b)
{
    int h = cairo_image_surface_get_height(a), stride = cairo_image_surface_get_stride(a);
    return memcmp(cairo_image_surface_get_data(a), cairo_image_surface_get_data(b), (size_t)h * (size_t)stride) == 0;
}

Test(lesson09_views, views_follow_the_step_back_and_forth)
{
    char why[512];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "texture-floor", err, sizeof err) && front_scene(&s), "%s", err);
    static const char *const views[] = { "texels", "lod", "quads" };
    for (int v = 0; v < 3; v++) {
        struct explorer ex;
        open09(&ex, &s, FILTER_TRILINEAR, views[v]);
        uint64_t a = 12000, b = 12400;
        cr_assert(explorer_set_step(&ex, a));
        cairo_surface_t *first = paint_now(&ex);
        cr_assert(explorer_set_step(&ex, b));
        cairo_surface_t *later = paint_now(&ex);
        cr_assert(explorer_set_step(&ex, a));
        cairo_surface_t *again = paint_now(&ex);
        cr_assert(same(first, again), "%s: step %llu drawn again differs", views[v], (unsigned long long)a);
        cr_assert(!same(first, later), "%s: steps %llu and %llu look alike", views[v], (unsigned long long)a,
                  (unsigned long long)b);
        cairo_surface_destroy(first), cairo_surface_destroy(later), cairo_surface_destroy(again);
        explorer_free(&ex);
    }
    scene_free(&s);
}

/* A w x h PNG of a little pattern in the scratch folder. */
static void put_png(const char *name, int w, int h)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    uint32_t *px = (uint32_t *)cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img) / 4;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            px[y * stride + x] = 0xff000000u | (uint32_t)(x * 255 / (w > 1 ? w - 1 : 1)) << 16
                                 | (uint32_t)(y * 255 / (h > 1 ? h - 1 : 1)) << 8 | 0x40u;
    cairo_surface_mark_dirty(img);
    cr_assert_eq(cairo_surface_write_to_png(img, test_scratch_path(name)), CAIRO_STATUS_SUCCESS);
    cairo_surface_destroy(img);
}

Test(lesson09_views, every_view_draws_any_texture_at_any_step, .init = test_scratch_make,
     .fini = test_scratch_remove)
{
    char why[512];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    put_png("one.png", 1, 1), put_png("row.png", 4, 1), put_png("column.png", 1, 8);
    static const char *const textures[] = { "one.png clamp", "row.png repeat", "column.png clamp",
                                            "builtin:rgby repeat" };
    char text[2048];
    size_t at = (size_t)snprintf(text, sizeof text, "size 32 24\n");
    for (int k = 0; k < 4; k++)        /* a triangle under each, far outside [0, 1] and magnified */
        at += (size_t)snprintf(text + at, sizeof text - at,
                               "texture %s\ntri %d 1 1 1 1 1 -40.5 7   %d 22 2 1 1 1 3.25 -9   %d 12 0.5 1 1 1 0.5 0.5\n",
                               textures[k], 8 * k, 8 * k + 7, 8 * k + 3);
    test_scratch_text("odd.scene", text);
    struct scene s;
    char err[256];
    cr_assert(scene_load(&s, test_scratch_path("odd.scene"), err, sizeof err), "%s", err);
    static const char *const views[] = { "texels", "lod", "quads" };
    for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f += 2)
        for (int v = 0; v < 3; v++) {
            struct explorer ex;
            open09(&ex, &s, (enum tex_filter)f, views[v]);
            uint64_t total = ex.replay.total;
            for (int k = 0; k <= 12; k++) {
                cr_assert(explorer_set_step(&ex, total * (uint64_t)k / 12));
                cairo_surface_destroy(paint_now(&ex));
            }
            explorer_free(&ex);
        }
    scene_free(&s);
}
