/* test_texture.c - image textures (lessons/CONVENTIONS.md, "Textures"): the pyramid
 * against a hand-computed example and against the independent reference's
 * (texref.c), texel addressing, the texture lines of 2-D and 3-D scenes,
 * OBJ texture coordinates, (s, t) through the front end's clipping, and
 * every input error with its FILE:LINE message. The programs reading
 * textured scenes: test_texture_cli.c. */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */

#include <cairo.h>
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "texref.h"
#include "testlib.h"

/* A w x h PNG of `format` (CAIRO_FORMAT_RGB24 or ARGB32), texel (x, y)
 * coloured by x and y, one texel translucent when alpha_below < 255. */
static void put_png(const char *name, int w, int h, cairo_format_t format, int alpha_below)
{
    cairo_surface_t *s = cairo_image_surface_create(format, w, h);
    cr_assert_eq(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t a = x == w - 1 && y == h - 1 && alpha_below < 255 ? (uint32_t)alpha_below : 255;
            uint32_t c = a << 24 | (uint32_t)(x * 37 % 256 * a / 255) << 16
                       | (uint32_t)(y * 91 % 256 * a / 255) << 8 | (uint32_t)((x + y) % 256 * a / 255);
            ((uint32_t *)(void *)(data + (size_t)y * stride))[x] = c;
        }
    cairo_surface_mark_dirty(s);
    cr_assert_eq(cairo_surface_write_to_png(s, test_scratch_path(name)), CAIRO_STATUS_SUCCESS);
    cairo_surface_destroy(s);
}

static struct scene load_ok(const char *text)
{
    test_scratch_text("ok.scene", text);
    struct scene s;
    char err[512] = "";
    cr_assert(scene_load(&s, test_scratch_path("ok.scene"), err, sizeof err), "rejected: %s\n%s", err, text);
    return s;
}

/* --- the pyramid ------------------------------------------------------------------- */

#define RGB(r, g, b) (0xff000000u | (uint32_t)(r) << 16 | (uint32_t)(g) << 8 | (uint32_t)(b))

/* A 4 x 2 image whose means fall on halves and quarters:
 *
 *   level 0 (r, g, b)                          level 1 (2 x 1)           level 2 (1 x 1)
 *   (0,0,255) (1,0,255) | (2,1,0) (3,1,0)      r (0+1+4+5+2)/4 = 3       r (3+5+1)/2 = 4
 *   (4,0,255) (5,4,254) | (6,2,0) (8,3,1)      r (2+3+6+8+2)/4 = 5       g (1+2+1)/2 = 2
 *                                              g (0+0+0+4+2)/4 = 1       b (255+0+1)/2 = 128
 *                                              g (1+1+2+3+2)/4 = 2
 *                                              b (255*3+254+2)/4 = 255
 *                                              b (0+0+0+1+2)/4 = 0
 */
static const uint32_t hand_image[8] = {
    RGB(0, 0, 255), RGB(1, 0, 255), RGB(2, 1, 0), RGB(3, 1, 0),
    RGB(4, 0, 255), RGB(5, 4, 254), RGB(6, 2, 0), RGB(8, 3, 1),
};
static const uint32_t hand_level1[2] = { RGB(3, 1, 255), RGB(5, 2, 0) };
static const uint32_t hand_level2 = RGB(4, 2, 128);

Test(texture, pyramid_of_a_hand_computed_example)
{
    struct texture t;
    cr_assert(texture_make(&t, "hand", TEXTURE_REPEAT, 4, 2, hand_image));
    cr_assert_eq(t.nlevels, 3);
    cr_expect(t.level[1].w == 2 && t.level[1].h == 1 && t.level[2].w == 1 && t.level[2].h == 1);
    for (int i = 0; i < 8; i++)
        cr_expect_eq(t.level[0].texel[i], hand_image[i]);
    for (int i = 0; i < 2; i++)
        cr_expect_eq(t.level[1].texel[i], hand_level1[i], "level 1 texel %d: %08x, expected %08x",
                     i, t.level[1].texel[i], hand_level1[i]);
    cr_expect_eq(t.level[2].texel[0], hand_level2, "level 2: %08x", t.level[2].texel[0]);
    texture_free(&t);

    /* the reference builds the same levels on its own */
    struct texref r;
    cr_assert(texref_init(&r, 4, 2, hand_image, TEXREF_REPEAT));
    cr_assert_eq(r.nlevels, 3);
    double c[3];
    texref_texel(&r, 2, 0, 0, c);
    cr_expect(c[0] == 4 && c[1] == 2 && c[2] == 128, "reference level 2: %g %g %g", c[0], c[1], c[2]);
    texref_texel(&r, 1, 1, 0, c);
    cr_expect(c[0] == 5 && c[1] == 2 && c[2] == 0);
    texref_free(&r);
}

Test(texture, a_one_texel_wide_image_halves_its_height_only)
{
    /* 1 x 4: pairs (10, 11) -> 11 (10.5 rounded up), (20, 21) -> 21, then (11 + 21 + 1) / 2 = 16 */
    const uint32_t im[4] = { RGB(10, 0, 0), RGB(11, 0, 0), RGB(20, 0, 0), RGB(21, 0, 0) };
    struct texture t;
    cr_assert(texture_make(&t, "column", TEXTURE_CLAMP, 1, 4, im));
    cr_assert_eq(t.nlevels, 3);
    cr_expect(t.level[1].w == 1 && t.level[1].h == 2);
    cr_expect_eq(t.level[1].texel[0], RGB(11, 0, 0));
    cr_expect_eq(t.level[1].texel[1], RGB(21, 0, 0));
    cr_expect_eq(t.level[2].texel[0], RGB(16, 0, 0));
    texture_free(&t);
}

Test(texture, pyramid_equals_the_reference_on_random_images)
{
    struct rng r = rng_for(0x7e47);
    for (int n = 0; n < 60; n++) {
        int w = 1 << rng_int(&r, 0, 6), h = 1 << rng_int(&r, 0, 6);
        uint32_t *im = malloc((size_t)w * h * sizeof *im);
        cr_assert_not_null(im);
        bool constant = n % 5 == 0;
        for (int i = 0; i < w * h; i++)
            im[i] = constant ? 0x00a1b2c3u : (uint32_t)rng_next(&r);   /* alpha byte ignored */
        struct texture t;
        struct texref ref;
        cr_assert(texture_make(&t, "random", TEXTURE_REPEAT, w, h, im));
        cr_assert(texref_init(&ref, w, h, im, TEXREF_REPEAT));
        int logw = 0, logh = 0;
        while ((1 << logw) < w)
            logw++;
        while ((1 << logh) < h)
            logh++;
        cr_assert_eq(t.nlevels, (logw > logh ? logw : logh) + 1, "%d x %d", w, h);
        cr_assert_eq(t.nlevels, ref.nlevels);
        for (int k = 0; k < t.nlevels; k++) {
            cr_assert(t.level[k].w == ref.w[k] && t.level[k].h == ref.h[k]);
            for (int j = 0; j < t.level[k].h; j++)
                for (int i = 0; i < t.level[k].w; i++) {
                    uint32_t c = texture_fetch(&t, k, i, j);
                    double want[3];
                    texref_texel(&ref, k, i, j, want);
                    cr_assert(c >> 24 == 255 && (double)(c >> 16 & 255) == want[0]
                              && (double)(c >> 8 & 255) == want[1] && (double)(c & 255) == want[2],
                              "%d x %d, level %d texel (%d, %d): %08x", w, h, k, i, j, c);
                    if (constant)
                        cr_assert_eq(c, 0xffa1b2c3u, "a constant image stays constant");
                }
        }
        cr_expect(t.level[t.nlevels - 1].w == 1 && t.level[t.nlevels - 1].h == 1);
        texture_free(&t);
        texref_free(&ref);
        free(im);
    }
}

Test(texture, repeat_is_the_mathematical_mod_and_clamp_clamps)
{
    cr_expect_eq(texture_wrap_index(-1, 4, TEXTURE_REPEAT), 3, "-1 mod 4 is 3 (C's %% says -1)");
    cr_expect_eq(texture_wrap_index(-5, 4, TEXTURE_REPEAT), 3);
    cr_expect_eq(texture_wrap_index(-4, 4, TEXTURE_REPEAT), 0);
    cr_expect_eq(texture_wrap_index(4, 4, TEXTURE_REPEAT), 0);
    cr_expect_eq(texture_wrap_index(4100000000LL, 4096, TEXTURE_REPEAT), (int)(4100000000LL % 4096));
    cr_expect_eq(texture_wrap_index(-3, 4, TEXTURE_CLAMP), 0);
    cr_expect_eq(texture_wrap_index(9, 4, TEXTURE_CLAMP), 3);
    cr_expect_eq(texture_wrap_index(2, 4, TEXTURE_CLAMP), 2);
    cr_expect_eq(texture_wrap_index(-7, 1, TEXTURE_REPEAT), 0);
    /* texel fetch against the reference, both wraps, far from the image */
    struct rng r = rng_for(0x3a9);
    uint32_t im[8 * 4];
    for (int i = 0; i < 32; i++)
        im[i] = (uint32_t)rng_next(&r) | 0xff000000u;
    for (int wrap = 0; wrap < 2; wrap++) {
        struct texture t;
        struct texref ref;
        cr_assert(texture_make(&t, "w", wrap ? TEXTURE_CLAMP : TEXTURE_REPEAT, 8, 4, im));
        cr_assert(texref_init(&ref, 8, 4, im, wrap ? TEXREF_CLAMP : TEXREF_REPEAT));
        for (int n = 0; n < 2000; n++) {
            long long i = rng_int(&r, -1000, 1000), j = rng_int(&r, -1000, 1000);
            int k = rng_int(&r, 0, t.nlevels - 1);
            uint32_t c = texture_fetch(&t, k, i, j);
            double want[3];
            texref_texel(&ref, k, i, j, want);
            cr_assert((double)(c >> 16 & 255) == want[0] && (double)(c & 255) == want[2],
                      "wrap %d level %d (%lld, %lld)", wrap, k, i, j);
        }
        texture_free(&t);
        texref_free(&ref);
    }
}

Test(texture, builtin_textures_are_opaque_powers_of_two)
{
    for (int i = 0; builtin_textures[i].name; i++) {
        int w, h;
        uint32_t *im;
        char why[256];
        cr_assert(texture_builtin(builtin_textures[i].name, &w, &h, &im, why, sizeof why), "%s", why);
        cr_expect(texture_size_ok(w) && texture_size_ok(h), "%s: %d x %d", builtin_textures[i].name, w, h);
        bool varied = false;
        for (int k = 0; k < w * h; k++) {
            cr_assert_eq(im[k] >> 24, 255u, "%s: texel %d not opaque", builtin_textures[i].name, k);
            varied |= im[k] != im[0];
        }
        cr_expect(varied, "%s is not one colour", builtin_textures[i].name);
        free(im);
    }
    int w, h;
    uint32_t *im;
    char why[256];
    cr_expect(!texture_builtin("marble", &w, &h, &im, why, sizeof why));
    cr_expect(strstr(why, "builtin:bricks") != NULL, "the message lists them: %s", why);
}

/* noise-WxH: any shape the format allows, neighbours far apart; other
 * sizes and spellings are no texture */
Test(texture, builtin_noise_is_every_shape_the_format_allows)
{
    static const int sizes[][2] = { { 1, 1 }, { 1, 64 }, { 64, 1 }, { 4096, 2 }, { 2, 4096 }, { 32, 8 } };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        char name[40], why[256];
        snprintf(name, sizeof name, "noise-%dx%d", sizes[i][0], sizes[i][1]);
        int w, h;
        uint32_t *im;
        cr_assert(texture_builtin(name, &w, &h, &im, why, sizeof why), "%s: %s", name, why);
        cr_expect(w == sizes[i][0] && h == sizes[i][1], "%s: %d x %d", name, w, h);
        for (int y = 0; y < h; y++)
            for (int x = 0; x + 1 < w; x++) {
                uint32_t a = im[(size_t)y * (size_t)w + (size_t)x], b = im[(size_t)y * (size_t)w + (size_t)x + 1];
                int dr = (int)(a >> 16 & 255) - (int)(b >> 16 & 255);
                cr_assert(a >> 24 == 255u && (dr >= 96 || dr <= -96), "%s: texels (%d, %d) and (%d, %d) %06x %06x",
                          name, x, y, x + 1, y, a & 0xffffffu, b & 0xffffffu);
            }
        free(im);
    }
    static const char *const bad[] = { "noise-3x4", "noise-8192x1", "noise-0x1", "noise-4x4x", "noise-04x4", "noise-4" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int w, h;
        uint32_t *im;
        char why[256];
        cr_expect(!texture_builtin(bad[i], &w, &h, &im, why, sizeof why), "%s read", bad[i]);
    }
}

/* --- scenes -------------------------------------------------------------------------- */

#define TRI24 "tri 1 1 1 1 1 1 0 0  30 2 1 1 1 1 1 0  3 20 1 1 1 1 0 1\n"
#define TRI18 "tri 1 1 1 1 1 1  30 2 1 1 1 1  3 20 1 1 1 1\n"

Test(texture, a_texture_line_applies_to_the_textured_tris_that_follow, .init = test_scratch_make, .fini = test_scratch_remove)
{
    put_png("wall.png", 8, 4, CAIRO_FORMAT_RGB24, 255);
    struct scene s = load_ok("size 32 24\n" TRI24
                             "texture wall.png\n" TRI24 TRI18
                             "texture builtin:rgby clamp\n" TRI24
                             "texture wall.png   # again: the same texture\n" TRI24
                             "texture wall.png clamp\n" TRI24
                             "texture checker 4\n" TRI24);
    const int want[7] = { 0, 1, 0, 2, 1, 3, 0 };
    cr_assert_eq(s.ntris, 7);
    for (int i = 0; i < 7; i++)
        cr_expect_eq(s.tris[i].texture, want[i], "triangle %d: texture %d", i, s.tris[i].texture);
    cr_assert_eq(scene_texture_count(&s), 3);
    cr_expect_eq(s.checker, 4, "the checker is every lesson's, as ever");
    const struct texture *wall = scene_texture(&s, 1), *rgby = scene_texture(&s, 2);
    cr_expect(wall->level[0].w == 8 && wall->level[0].h == 4 && wall->wrap == TEXTURE_REPEAT);
    cr_expect(wall->name[0] == '/' && strstr(wall->name, "/wall.png"), "a full path: %s", wall->name);
    cr_expect(rgby->wrap == TEXTURE_CLAMP && strcmp(rgby->name, "builtin:rgby") == 0);
    cr_expect_eq(rgby->level[0].texel[3], RGB(255, 255, 0));
    cr_expect(scene_texture(&s, 0) == NULL && scene_texture(&s, 4) == NULL);
    /* the PNG as cairo read it: texel (x, y) = (37 x, 91 y, x + y) */
    cr_expect_eq(texture_fetch(wall, 0, 5, 3), RGB(185, 273 % 256, 8));

    struct scene c;     /* a copy shares the textures; both free without trouble */
    cr_assert(scene_copy(&c, &s));
    cr_expect(scene_texture(&c, 3) == scene_texture(&s, 3));
    scene_free(&s);
    cr_expect_eq(c.tris[3].texture, 2);
    cr_expect_eq(scene_texture(&c, 1)->level[0].w, 8);
    scene_free(&c);
}

static void write_read(const struct scene *s, struct scene *back)
{
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    cr_assert(scene_write(s, out));
    fclose(out);
    char err[512];
    cr_assert(scene_parse(back, "written", text, len, err, sizeof err), "%s\n%s", err, text);
    free(text);
}

Test(texture, written_and_read_back_with_the_same_textures, .init = test_scratch_make, .fini = test_scratch_remove)
{
    put_png("a.png", 4, 4, CAIRO_FORMAT_ARGB32, 255);
    struct scene s = load_ok("size 32 24\ntexture builtin:grid clamp\ntexture a.png\n" TRI24
                             "texture builtin:grid clamp\n" TRI24 TRI18 "texture checker 2\n" TRI24);
    struct scene b;
    write_read(&s, &b);
    cr_assert_eq(scene_texture_count(&b), 2);
    cr_assert_eq(b.ntris, s.ntris);
    for (int k = 1; k <= 2; k++)
        cr_expect(strcmp(scene_texture(&b, k)->name, scene_texture(&s, k)->name) == 0
                  && scene_texture(&b, k)->wrap == scene_texture(&s, k)->wrap);
    for (int i = 0; i < s.ntris; i++)
        cr_expect_eq(b.tris[i].texture, s.tris[i].texture, "triangle %d", i);
    cr_expect_eq(memcmp(b.tris, s.tris, (size_t)s.ntris * sizeof *s.tris), 0);
    scene_free(&b);
    scene_free(&s);
}

#define CAM "camera 0 1 5  0 0 0  0 1 0  60 0.5 100\n"

Test(texture, obj_vt_flips_t_and_faces_carry_it, .init = test_scratch_make, .fini = test_scratch_remove)
{
    test_scratch_text("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                    "vt 0 0\nvt 1 0\nvt 1 1 0.5\nvt 0.25\n"
                    "f 1/1 2/2 3/3 4/4\nf 1/-4/1 3/-2/1 4//1\n");
    struct scene s = load_ok("size 32 24\n" CAM "obj quad.obj 1 1 1\ntexture builtin:bricks\n"
                             "obj quad.obj 0.5 0.5 0.5\n"
                             "tri3 0 0 0 1 1 1 0.5 2  1 0 0 1 1 1 -3 0  0 1 0 1 1 1 0 0\n"
                             "tri3 0 0 0 1 1 1  1 0 0 1 1 1  0 1 0 1 1 1\n");
    const struct world *w = &s.world;
    cr_assert_eq(w->ntris, 8);
    /* f 1/1 2/2 3/3 4/4 fans into (1 2 3) (1 3 4): s = u, t = 1 - v */
    const double st[2][3][2] = { { { 0, 1 }, { 1, 1 }, { 1, 0 } }, { { 0, 1 }, { 1, 0 }, { 0.25, 1 } } };
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 3; k++)
            cr_expect(w->tris[i].st[k][0] == st[i][k][0] && w->tris[i].st[k][1] == st[i][k][1],
                      "triangle %d corner %d: (%g, %g)", i, k, w->tris[i].st[k][0], w->tris[i].st[k][1]);
    /* f 1/-4/1 3/-2/1 4//1: vt counted back from the last; no t is (0, 0) */
    cr_expect(w->tris[2].st[0][0] == 0 && w->tris[2].st[0][1] == 1);
    cr_expect(w->tris[2].st[1][0] == 1 && w->tris[2].st[1][1] == 0);
    cr_expect(w->tris[2].st[2][0] == 0 && w->tris[2].st[2][1] == 0);
    for (int i = 0; i < 3; i++)
        cr_expect_eq(w->tris[i].texture, 0, "before the texture line");
    for (int i = 3; i < 7; i++)
        cr_expect_eq(w->tris[i].texture, 1, "obj and textured tri3 after it");
    cr_expect_eq(w->tris[6].st[1][0], -3);
    cr_expect_eq(w->tris[7].texture, 0, "a tri3 of 18 numbers has no texture coordinates");
    cr_expect(s.has_st);
    struct scene b;
    write_read(&s, &b);
    cr_assert_eq(b.world.ntris, 8);
    for (int i = 0; i < 8; i++)
        cr_expect(b.world.tris[i].texture == w->tris[i].texture
                  && (w->tris[i].texture == 0 || memcmp(b.world.tris[i].st, w->tris[i].st, sizeof w->tris[i].st) == 0),
                  "world triangle %d written and read back", i);
    scene_free(&b);
    scene_free(&s);
}

/* (s, t) go through the front end as the colour does: with s = r and t = g
 * at every world vertex, every screen vertex keeps s == r and t == g, after
 * near and far clipping and the guard band alike. */
Test(texture, the_front_end_clips_s_and_t_as_it_clips_colour, .init = test_scratch_make, .fini = test_scratch_remove)
{
    struct rng r = rng_for(0xc11f);
    struct scene s = load_ok("size 64 48\n" CAM "texture builtin:grid\n");
    for (int n = 0; n < 300; n++) {
        struct world_tri t = { .texture = 1 };
        for (int k = 0; k < 3; k++) {
            for (int a = 0; a < 3; a++)
                t.p[k][a] = rng_range(&r, -30, 30);
            for (int c = 0; c < 3; c++)
                t.rgb[k][c] = rng_unit(&r);
            t.st[k][0] = t.rgb[k][0], t.st[k][1] = t.rgb[k][1];
        }
        cr_assert(world_add(&s.world, &t));
    }
    cr_assert(front_scene(&s));
    cr_assert_gt(s.ntris, 100);
    for (int i = 0; i < s.ntris; i++) {
        cr_assert_eq(s.tris[i].texture, 1, "the screen triangle keeps its texture");
        for (int k = 0; k < 3; k++)
            cr_assert(s.tris[i].v[k].s == s.tris[i].v[k].r && s.tris[i].v[k].t == s.tris[i].v[k].g,
                      "screen triangle %d vertex %d: s %.17g r %.17g, t %.17g g %.17g", i, k,
                      s.tris[i].v[k].s, s.tris[i].v[k].r, s.tris[i].v[k].t, s.tris[i].v[k].g);
    }
    scene_free(&s);
}

/* --- lesson 09's built-in scenes ------------------------------------------------------ */

/* A built-in scene drawn by the reference with trilinear filtering, keeping
 * each pixel's lambda and elongation. */
static void draw_builtin(const char *name, struct scene *s, struct texref_target *fb)
{
    char err[256];
    cr_assert(scene_builtin(s, name, err, sizeof err), "%s", err);
    cr_assert_gt(s->world.camera_line, 0, "builtin:%s is a 3-D scene", name);
    cr_assert(front_scene(s));
    cr_assert(texref_target_init(fb, s->w, s->h, scene_background(s)));
    fb->lambda = malloc((size_t)s->w * s->h * sizeof *fb->lambda);
    fb->elongation = malloc((size_t)s->w * s->h * sizeof *fb->elongation);
    cr_assert(fb->lambda && fb->elongation);
    for (int i = 0; i < s->w * s->h; i++)
        fb->lambda[i] = fb->elongation[i] = NAN;
    cr_assert(texref_draw_scene(fb, s, TEXREF_TRILINEAR, 16));
}

Test(texture, lesson_09_scenes_show_what_they_say)
{
    struct scene s;
    struct texref_target fb;

    /* the floor: magnified under the eye, minified by 8 or more texels a
     * pixel below the horizon, and the sky above it */
    draw_builtin("texture-floor", &s, &fb);
    cr_expect(fb.lambda[(s.h - 1) * s.w + s.w / 2] < 0, "magnified at the bottom: lambda %g",
              fb.lambda[(s.h - 1) * s.w + s.w / 2]);
    float far = -INFINITY;
    int sky = 0;
    for (int i = 0; i < s.w * s.h; i++) {
        if (isfinite(fb.lambda[i]) && fb.lambda[i] > far)
            far = fb.lambda[i];
        sky += fb.covered[i] == 0;
    }
    cr_expect_geq(far, 3, "minified towards the horizon: lambda up to %g", far);
    cr_expect(sky > s.w * s.h / 3 && sky < s.w * s.h * 2 / 3, "sky above the horizon: %d pixels", sky);
    texref_target_free(&fb);
    scene_free(&s);

    /* the wall: footprints ten times longer than wide, far along it */
    draw_builtin("texture-wall", &s, &fb);
    int long_thin = 0, textured = 0;
    for (int i = 0; i < s.w * s.h; i++) {
        textured += !isnan(fb.lambda[i]);
        long_thin += fb.elongation[i] >= 10 && fb.lambda[i] > 2;
    }
    cr_expect_gt(textured, s.w * s.h / 4, "the wall fills a good part of the view");
    cr_expect_gt(long_thin, 100, "%d pixels of the wall see a footprint 10 x longer than wide", long_thin);
    texref_target_free(&fb);
    scene_free(&s);

    /* the torus: every visible triangle textured, hundreds of pixels */
    draw_builtin("texture-model", &s, &fb);
    for (int i = 0; i < s.ntris; i++)
        cr_assert_eq(s.tris[i].texture, 1);
    cr_expect_gt(fb.shaded, 1000, "the torus is seen");
    texref_target_free(&fb);
    scene_free(&s);

    /* tiny triangles: 8 pixels each, and a helper for every two pixels shaded */
    draw_builtin("texture-tiny", &s, &fb);
    cr_expect_eq(s.ntris, 32 * 24 * 2);
    cr_expect_eq(fb.shaded, (long)s.w * s.h, "the sheet covers the view once");
    cr_expect_leq(fb.shaded / s.ntris, 8, "%ld pixels a triangle", fb.shaded / s.ntris);
    cr_expect_geq(2 * fb.helpers, fb.shaded, "%ld helpers for %ld pixels", fb.helpers, fb.shaded);
    texref_target_free(&fb);
    scene_free(&s);
}
