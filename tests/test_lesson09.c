/* test_lesson09.c - lesson 09 (texture mapping) against the independent
 * reference sampler (tests/texref.c, written from lessons/CONVENTIONS.md alone):
 * coverage exact and colours within 2 levels on random textured 2-D and
 * 3-D scenes and the built-in 3-D ones, every filter, both wraps; the fast
 * twin draws the narrated lesson's bytes; helper pixels are evaluated and
 * never written; wrap of negative coordinates; the stages an exercise
 * swaps are the ones drawn. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "explore/replay.h"
#include "testlib.h"
#include "texref.h"
#include "../lessons/09-textures/textures.h"

extern const struct lesson lesson_09, lesson_09_fast;

static const char *const textures[] = { "checker-numbers", "bricks", "grid", "rgby" };

/* A random 2-D scene of w x h: n triangles under a builtin texture with
 * the given wrap (s, t in [-3, 3], depths 0.5..4, so that perspective
 * bends them), a few untextured ones, some of them tiny. */
static void random_scene(struct scene *s, struct rng *r, int w, int h, int n, bool clamp)
{
    static char text[16384];
    size_t at = (size_t)snprintf(text, sizeof text, "size %d %d\nbackground 0.1 0.1 0.2\ntexture builtin:%s %s\n",
                                 w, h, textures[rng_int(r, 0, 3)], clamp ? "clamp" : "repeat");
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        random_tri(r, rng_chance(r, 0.2) ? CAT_TINY : rng_chance(r, 0.2) ? CAT_LARGE : CAT_GENERIC,
                   w, h, v);
        bool textured = !rng_chance(r, 0.1);
        at += (size_t)snprintf(text + at, sizeof text - at, "tri");
        for (int k = 0; k < 3; k++) {
            at += (size_t)snprintf(text + at, sizeof text - at, "  %.17g %.17g %.17g  %.3f %.3f %.3f",
                                   v[k].x, v[k].y, rng_range(r, 0.5, 4), rng_range(r, 0.3, 1),
                                   rng_range(r, 0.3, 1), rng_range(r, 0.3, 1));
            if (textured)
                at += (size_t)snprintf(text + at, sizeof text - at, " %.6f %.6f", rng_range(r, -3, 3),
                                       rng_range(r, -3, 3));
        }
        at += (size_t)snprintf(text + at, sizeof text - at, "\n");
        cr_assert_lt(at, sizeof text - 256);
    }
    char err[256];
    cr_assert(scene_parse(s, "random", text, at, err, sizeof err), "%s\n%s", err, text);
}

/* A random 3-D scene: a camera at the origin looking down -z and n
 * textured world triangles in front of it (some reaching behind the near
 * plane, so the front end clips them, s and t with them); its screen
 * triangles made. */
static void random_scene3(struct scene *s, struct rng *r, int n, bool clamp)
{
    static char text[16384];
    size_t at = (size_t)snprintf(text, sizeof text,
                                 "size 64 48\ncamera 0 0 0  0 0 -1  0 1 0  60 0.5 100\ntexture builtin:%s %s\n",
                                 textures[rng_int(r, 0, 3)], clamp ? "clamp" : "repeat");
    for (int i = 0; i < n; i++) {
        at += (size_t)snprintf(text + at, sizeof text - at, "tri3");
        for (int k = 0; k < 3; k++)
            at += (size_t)snprintf(text + at, sizeof text - at, "  %.6f %.6f %.6f  %.3f %.3f %.3f %.6f %.6f",
                                   rng_range(r, -8, 8), rng_range(r, -6, 6), rng_range(r, -40, 1),
                                   rng_range(r, 0.3, 1), rng_range(r, 0.3, 1), rng_range(r, 0.3, 1),
                                   rng_range(r, -4, 4), rng_range(r, -4, 4));
        at += (size_t)snprintf(text + at, sizeof text - at, "\n");
        cr_assert_lt(at, sizeof text - 256);
    }
    char err[256];
    cr_assert(scene_parse(s, "random3", text, at, err, sizeof err), "%s\n%s", err, text);
    cr_assert(front_scene(s));
}

static struct raster_params params_for(enum tex_filter f, int max_aniso)
{
    struct raster_params p = default_params();
    p.knob[P_FILTER] = f;
    p.knob[P_MAX_ANISO] = max_aniso;
    return p;
}

/* Variant v's picture of scene s (its screen triangles made). */
static void draw(struct target *fb, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p)
{
    cr_assert(render_scene(s, v, p, fb));
}

static const enum texref_filter as_texref[] = {
    [FILTER_NEAREST] = TEXREF_NEAREST, [FILTER_BILINEAR] = TEXREF_BILINEAR,
    [FILTER_MIP_BILINEAR] = TEXREF_MIP_BILINEAR, [FILTER_TRILINEAR] = TEXREF_TRILINEAR,
    [FILTER_ANISO] = TEXREF_ANISO,
};

/* Lesson 09's picture of s against the reference's: coverage exact, every
 * covered pixel within 2 levels. */
static void expect_reference(const struct scene *s, const struct lesson_variant *v, enum tex_filter f,
                             int max_aniso, const char *what)
{
    struct raster_params p = params_for(f, max_aniso);
    struct target fb;
    draw(&fb, s, v, &p);
    struct texref_target ref;
    cr_assert(texref_target_init(&ref, s->w, s->h, scene_background(s)));
    cr_assert(texref_draw_scene(&ref, s, as_texref[f], max_aniso));
    struct texref_diff d = texref_compare(&ref, &fb, 2);
    cr_expect(d.coverage == 0 && d.colour == 0,
              "%s, %s, filter %s: %ld pixels covered otherwise, %ld colours off by more than 2 "
              "(first at %d, %d: %06x, the reference %06x)", what, v->name, texref_filter_name(as_texref[f]),
              d.coverage, d.colour, d.x, d.y, d.x < 0 ? 0 : fb.color[d.y * fb.w + d.x] & 0xffffff,
              d.x < 0 ? 0 : ref.color[d.y * ref.w + d.x] & 0xffffff);
    texref_target_free(&ref);
    target_free(&fb);
}

Test(lesson09, random_2d_scenes_match_the_reference_every_filter_both_wraps, .timeout = 60)
{
    struct rng r = rng_for(0x0909);
    for (int c = 0; c < 12; c++) {
        struct scene s;
        random_scene(&s, &r, 48, 40, 10, c & 1);
        char what[64];
        snprintf(what, sizeof what, "random scene %d (seed %#llx, %s)", c, (unsigned long long)test_seed(),
                 c & 1 ? "clamp" : "repeat");
        for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++) {
            expect_reference(&s, &lesson_09.variants[0], f, f == FILTER_ANISO ? rng_int(&r, 1, 16) : 16,
                             what);
            expect_reference(&s, &lesson_09_fast.variants[1], f, 16, what);
        }
        scene_free(&s);
    }
}

Test(lesson09, random_3d_scenes_match_the_reference_every_filter_both_wraps, .timeout = 60)
{
    struct rng r = rng_for(0x0903);
    int drawn = 0;
    for (int c = 0; c < 8; c++) {
        struct scene s;
        random_scene3(&s, &r, 8, c & 1);
        drawn += s.ntris;
        char what[64];
        snprintf(what, sizeof what, "random 3-D scene %d (seed %#llx, %s)", c,
                 (unsigned long long)test_seed(), c & 1 ? "clamp" : "repeat");
        for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++) {
            expect_reference(&s, &lesson_09.variants[0], f, 16, what);
            expect_reference(&s, &lesson_09_fast.variants[1], f, f == FILTER_ANISO ? 1 + c : 16, what);
        }
        scene_free(&s);
    }
    cr_expect_gt(drawn, 40, "%d screen triangles", drawn);
}

Test(lesson09, builtin_3d_scenes_match_the_reference_every_filter, .timeout = 60)
{
    static const char *const names[] = { "texture-floor", "texture-model", "texture-wall", "texture-tiny" };
    for (int i = 0; i < 4; i++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, names[i], err, sizeof err), "%s", err);
        cr_assert(front_scene(&s));
        for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++) {
            expect_reference(&s, &lesson_09_fast.variants[1], f, 16, names[i]);
            expect_reference(&s, &lesson_09.variants[0], f, 16, names[i]);
        }
        scene_free(&s);
    }
}

/* The twin, fast build, is the narrated algorithm's bytes: colour and depth. */
Test(lesson09, fast_twin_draws_the_narrated_bytes, .timeout = 60)
{
    struct rng r = rng_for(0x0910);
    for (int c = 0; c < 6; c++) {
        struct scene s;
        if (c < 2) {
            char err[256];
            cr_assert(scene_builtin(&s, c ? "texture-wall" : "texture-floor", err, sizeof err), "%s", err);
            cr_assert(front_scene(&s));
        } else if (c == 2) {    /* untextured under the checker: the shared shading */
            char err[256];
            const char *text = "size 40 30\ntexture checker 6\n"
                               "tri 2 2 1 1 0.5 0.2 0 0  38 4 2 0.2 1 0.5 4 0  6 28 1.5 0.3 0.4 1 0 4\n"
                               "tri 20 10 1 0.9 0.9 0.9 0 0  39 29 3 0.9 0.9 0.9 1 1  10 29 1 0.9 0.9 0.9 0 1\n";
            cr_assert(scene_parse(&s, "checker", text, strlen(text), err, sizeof err), "%s", err);
            cr_assert_eq(s.checker, 6);
        } else {
            random_scene(&s, &r, 64, 48, 12, c & 1);
        }
        for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++) {
            struct raster_params p = params_for(f, 16);
            p.checker = s.checker;
            struct target a, b;
            draw(&a, &s, &lesson_09.variants[0], &p);
            draw(&b, &s, &lesson_09_fast.variants[1], &p);
            size_t n = (size_t)s.w * s.h;
            cr_expect(memcmp(a.color, b.color, n * sizeof *a.color) == 0
                      && memcmp(a.depth, b.depth, n * sizeof *a.depth) == 0
                      && memcmp(a.count, b.count, n) == 0,
                      "scene %d, filter %d: the twin's bytes differ from the narrated algorithm's", c, f);
            target_free(&a);
            target_free(&b);
        }
        scene_free(&s);
    }
}

/* Helper pixels: every quad with a covered pixel evaluates all four, the
 * uncovered ones are never written, and every write is a covered pixel
 * that the reference covers. */
Test(lesson09, helper_pixels_are_evaluated_never_written, .timeout = 60)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "texture-tiny", err, sizeof err), "%s", err);
    cr_assert(front_scene(&s));
    struct raster_params p = params_for(FILTER_TRILINEAR, 16);
    long helpers = 0, covered = 0, writes = 0;
    size_t n = (size_t)s.w * s.h;
    uint8_t *ref = malloc(n);
    cr_assert(ref);
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        memset(ref, 0, n);
        reference_mask(&t, ref);
        struct target fb;
        cr_assert(target_init(&fb, s.w, s.h, 0));
        struct test_events ev = { 0 };
        struct trace tr = { .sink = test_collect, .ctx = &ev };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        p.texture = scene_texture(&s, s.tris[i].texture);
        lesson_09.variants[0].rasterize(&t, &p, &fb, &tr);
        int evals = 0;
        for (size_t k = 0; k < ev.n; k++) {
            const struct trace_event *e = &ev.ev[k];
            if (e->kind == TRACE_STEP && e->line == L_EVAL) {
                bool in = e->flags & TRACE_INSIDE;
                cr_assert(e->x >= 0 && e->y >= 0);
                cr_expect_eq(in, e->x < s.w && e->y < s.h && ref[(size_t)e->y * s.w + (size_t)e->x],
                             "triangle %d: pixel (%d, %d) evaluated as %s", i, e->x, e->y,
                             in ? "covered" : "a helper");
                helpers += !in, covered += in, evals++;
            }
            if (e->kind == TRACE_PIXEL_WRITE) {
                cr_expect(ref[(size_t)e->y * s.w + (size_t)e->x], "triangle %d wrote (%d, %d), not covered",
                          i, e->x, e->y);
                writes++;
            }
        }
        cr_expect_eq(evals % 4, 0, "a quad evaluates its four pixels");
        for (size_t k = 0; k < n; k++)
            cr_expect_eq(fb.count[k], ref[k], "triangle %d: pixel %zu written %d times, covered %d", i, k,
                         fb.count[k], ref[k]);
        free(ev.ev);
        target_free(&fb);
    }
    cr_expect_eq(writes, covered, "every covered pixel written once");
    cr_expect_geq(2 * helpers, covered, "small triangles: %ld helpers for %ld covered pixels", helpers, covered);
    /* the reference counts the same helpers */
    struct texref_target rt;
    cr_assert(texref_target_init(&rt, s.w, s.h, 0));
    cr_assert(texref_draw_scene(&rt, &s, TEXREF_TRILINEAR, 16));
    cr_expect_eq(rt.helpers, helpers);
    cr_expect_eq(rt.shaded, covered);
    texref_target_free(&rt);
    free(ref);
    scene_free(&s);
}

/* Negative texel indices wrap by the mathematical mod (repeat) or clamp. */
Test(lesson09, negative_coordinates_wrap)
{
    struct scene s;
    char err[256];
    const char *text = "size 8 8\ntexture builtin:rgby\n"
                       "tri 0 0 1 1 1 1 0 0  8 0 1 1 1 1 1 0  0 8 1 1 1 1 0 1\n";
    cr_assert(scene_parse(&s, "t", text, strlen(text), err, sizeof err), "%s", err);
    const struct texture *tex = scene_texture(&s, 1);
    cr_assert(tex && tex->level[0].w == 2);
    /* s = -0.25: u = -0.5, texel -1, which is texel 1 (green) under repeat */
    struct texel_rgb c = tex_nearest(tex, -0.25, 0.25);
    cr_expect(c.c[0] == 0 && c.c[1] == 255 && c.c[2] == 0, "repeat: -1 mod 2 is 1 (%g %g %g)", c.c[0],
              c.c[1], c.c[2]);
    c = tex_nearest(tex, -3.25, -1.75);       /* u = -6.5, v = -3.5: texel (-7, -4) = (1, 0) */
    cr_expect(c.c[0] == 0 && c.c[1] == 255 && c.c[2] == 0);
    /* bilinear at the centre of texel (-1, -1) = (1, 1), yellow, exactly */
    c = tex_bilinear(tex, 0, -0.25, -0.25);
    cr_expect(c.c[0] == 255 && c.c[1] == 255 && c.c[2] == 0, "(%g %g %g)", c.c[0], c.c[1], c.c[2]);
    scene_free(&s);
    text = "size 8 8\ntexture builtin:rgby clamp\ntri 0 0 1 1 1 1 0 0  8 0 1 1 1 1 1 0  0 8 1 1 1 1 0 1\n";
    cr_assert(scene_parse(&s, "t", text, strlen(text), err, sizeof err), "%s", err);
    tex = scene_texture(&s, 1);
    c = tex_bilinear(tex, 0, -3.25, 0.25);     /* clamped to column 0: red */
    cr_expect(c.c[0] == 255 && c.c[1] == 0 && c.c[2] == 0, "clamp (%g %g %g)", c.c[0], c.c[1], c.c[2]);
    scene_free(&s);
}

/* The stages an exercise swaps are the ones drawn: a bilinear tap that
 * returns grey makes every textured pixel grey times its vertex colour. */
static struct texel_rgb grey_tap(const struct texture *tex, int k, double s, double t)
{
    (void)tex, (void)k, (void)s, (void)t;
    return (struct texel_rgb){ { 128, 128, 128 } };
}

Test(lesson09, swapped_stages_are_the_ones_drawn)
{
    struct scene s;
    char err[256];
    const char *text = "size 16 16\ntexture builtin:bricks\n"
                       "tri 0 0 1 1 1 1 0 0  16 0 1 1 1 1 1 0  0 16 1 1 1 1 0 1\n";
    cr_assert(scene_parse(&s, "t", text, strlen(text), err, sizeof err), "%s", err);
    struct tex_stages st = tex_stages_lesson;
    st.bilinear = grey_tap;
    struct raster_params p = params_for(FILTER_TRILINEAR, 16);
    p.texture = scene_texture(&s, 1);
    struct target fb;
    cr_assert(target_init(&fb, 16, 16, 0));
    struct tri_setup t;
    tri_setup(&t, s.tris[0].v, 16, 16);
    textures_rasterize(&t, &p, &fb, NULL, &st, (struct tex_options){ .lod = LOD_COARSE });
    int grey = 0, covered = 0;
    for (int i = 0; i < 256; i++) {
        grey += fb.count[i] && fb.color[i] == 0xff808080u;
        covered += fb.count[i] > 0;
    }
    cr_expect_eq(grey, covered, "every covered pixel grey: %d of %d", grey, covered);
    cr_expect_gt(covered, 100);
    target_free(&fb);
    scene_free(&s);
}

/* --affine (lesson 04's option) textures lesson 09 affinely too: every
 * variant, the fast twin included, draws the affine exhibit's bytes, which
 * differ from the perspective-correct picture. */
Test(lesson09, affine_option_draws_the_affine_exhibit, .timeout = 60)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "texture-floor", err, sizeof err), "%s", err);
    cr_assert(front_scene(&s));
    struct raster_params p = params_for(FILTER_TRILINEAR, 16);
    struct target exhibit, plain;
    draw(&exhibit, &s, lesson_variant(&lesson_09, "affine"), &p);
    draw(&plain, &s, &lesson_09.variants[0], &p);
    size_t n = (size_t)s.w * s.h;
    cr_expect(memcmp(exhibit.color, plain.color, n * sizeof *plain.color) != 0,
              "the affine exhibit draws the perspective-correct picture");
    p.knob[P_AFFINE] = 1;
    const struct lesson_variant *with[] = { &lesson_09.variants[0], lesson_variant(&lesson_09, "quads-sse"),
                                            &lesson_09_fast.variants[1] };
    for (size_t i = 0; i < sizeof with / sizeof with[0]; i++) {
        struct target a;
        draw(&a, &s, with[i], &p);
        cr_expect(memcmp(a.color, exhibit.color, n * sizeof *a.color) == 0,
                  "--affine with variant %s is not the affine exhibit", with[i]->name);
        target_free(&a);
    }
    target_free(&exhibit);
    target_free(&plain);
    scene_free(&s);
}
