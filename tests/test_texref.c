/* test_texref.c - the independent reference sampler (texref.c) on cases
 * whose answers are computed by hand from lessons/CONVENTIONS.md "Textures": a
 * 2 x 2 texture, a constant one, a magnified checker, the level chosen at
 * known rho, the trilinear mix, anisotropic taps, helper pixels and the
 * horizon. Lesson 09 is checked against this reference. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "texref.h"
#include "testlib.h"

#define RGB(r, g, b) (0xff000000u | (uint32_t)(r) << 16 | (uint32_t)(g) << 8 | (uint32_t)(b))

/*   red    green        (0,0) (1,0)
 *   blue   yellow       (0,1) (1,1)      its 1 x 1 level: (128, 128, 64) */
static const uint32_t rgby[4] = { RGB(255, 0, 0), RGB(0, 255, 0), RGB(0, 0, 255), RGB(255, 255, 0) };

static void expect_rgb(const double got[3], double r, double g, double b, const char *what)
{
    cr_expect(fabs(got[0] - r) < 1e-9 && fabs(got[1] - g) < 1e-9 && fabs(got[2] - b) < 1e-9,
              "%s: (%.10g, %.10g, %.10g), expected (%g, %g, %g)", what, got[0], got[1], got[2], r, g, b);
}

static const struct texref_deriv magnified = { 0.25, 0, 0, 0.25, false };

/* Taps on the 2 x 2 texture, worked out by hand. */
static const struct {
    enum texref_filter f;
    enum texref_wrap wrap;
    double s, t, rgb[3];
    const char *what;
} taps[] = {
    { TEXREF_NEAREST, TEXREF_REPEAT, 0.25, 0.25, { 255, 0, 0 }, "(0.25, 0.25): texel (0, 0)" },
    { TEXREF_NEAREST, TEXREF_REPEAT, 0.75, 0.25, { 0, 255, 0 }, "(0.75, 0.25): texel (1, 0)" },
    { TEXREF_NEAREST, TEXREF_REPEAT, 0.5, 0.5, { 255, 255, 0 }, "(0.5, 0.5): u = v = 1, texel (1, 1)" },
    /* u = 2.5, v = -0.5: texel (2 mod 2, -1 mod 2) = (0, 1) */
    { TEXREF_NEAREST, TEXREF_REPEAT, 1.25, -0.25, { 0, 0, 255 }, "repeat: (1.25, -0.25) is texel (0, 1)" },
    { TEXREF_NEAREST, TEXREF_CLAMP, 1.25, -0.25, { 0, 255, 0 }, "clamp: (1.25, -0.25) is texel (1, 0)" },
    /* the centre: u - 1/2 = 0.5, a = b = 1/2, each texel 1/4 */
    { TEXREF_BILINEAR, TEXREF_REPEAT, 0.5, 0.5, { 127.5, 127.5, 63.75 }, "bilinear at the centre" },
    { TEXREF_BILINEAR, TEXREF_REPEAT, 0.75, 0.25, { 0, 255, 0 }, "bilinear at the centre of texel (1, 0)" },
    /* (0, 0) with repeat: i0 = -1 -> 1, a = 1/2: the four texels again */
    { TEXREF_BILINEAR, TEXREF_REPEAT, 0, 0, { 127.5, 127.5, 63.75 }, "bilinear, repeat at the corner" },
    /* u = 0.75, v = 0.5: a = 1/4 between columns 0 and 1, row 0 alone */
    { TEXREF_BILINEAR, TEXREF_REPEAT, 0.375, 0.25, { 191.25, 63.75, 0 }, "bilinear a quarter of the way" },
    { TEXREF_BILINEAR, TEXREF_CLAMP, 0, 0, { 255, 0, 0 }, "bilinear, clamp at the corner: texel (0, 0) four times" },
    { TEXREF_BILINEAR, TEXREF_CLAMP, 0.5, 0, { 127.5, 127.5, 0 }, "bilinear, clamp on the top edge: red and green" },
};

Test(texref, nearest_and_bilinear_on_a_2x2_texture_both_wraps)
{
    for (size_t i = 0; i < sizeof taps / sizeof taps[0]; i++) {
        struct texref r;
        cr_assert(texref_init(&r, 2, 2, rgby, taps[i].wrap));
        double c[3];
        texref_sample(&r, taps[i].f, 16, taps[i].s, taps[i].t, &magnified, c);
        expect_rgb(c, taps[i].rgb[0], taps[i].rgb[1], taps[i].rgb[2], taps[i].what);
        texref_free(&r);
    }
}

Test(texref, a_constant_texture_is_its_colour_under_every_filter)
{
    uint32_t im[16 * 8];
    for (int i = 0; i < 16 * 8; i++)
        im[i] = RGB(200, 100, 7);
    struct rng g = rng_for(0xc0);
    for (int wrap = 0; wrap < 2; wrap++) {
        struct texref r;
        cr_assert(texref_init(&r, 16, 8, im, (enum texref_wrap)wrap));
        for (int n = 0; n < 500; n++) {
            struct texref_deriv d = { rng_range(&g, -40, 40), rng_range(&g, -40, 40),
                                      rng_range(&g, -40, 40), rng_range(&g, -40, 40), n % 50 == 0 };
            if (n % 7 == 0)
                d.dudy = d.dvdy = 0;            /* P_min = 0: n = max_aniso */
            double c[3];
            enum texref_filter f = (enum texref_filter)(n % TEXREF_FILTERS);
            texref_sample(&r, f, 1 + n % 16, rng_range(&g, -9, 9), rng_range(&g, -9, 9), &d, c);
            expect_rgb(c, 200, 100, 7, texref_filter_name(f));
        }
        texref_free(&r);
    }
}

/* An 8 x 8 checker of single texels on a 64 x 64 square, 8 pixels a texel:
 * nearest gives pixel (x, y) texel (x / 8, y / 8) exactly. */
Test(texref, a_magnified_checker_drawn_pixel_by_pixel)
{
    uint32_t im[64];
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++)
            im[8 * j + i] = (i + j) % 2 ? RGB(255, 255, 255) : RGB(0, 0, 0);
    struct texref r;
    cr_assert(texref_init(&r, 8, 8, im, TEXREF_REPEAT));
    struct texref_target fb;
    cr_assert(texref_target_init(&fb, 64, 64, RGB(9, 9, 9)));
    const struct vertex a = { 0, 0, 1, 1, 1, 1, 0, 0 }, b = { 64, 0, 1, 1, 1, 1, 1, 0 },
                        c = { 64, 64, 1, 1, 1, 1, 1, 1 }, d = { 0, 64, 1, 1, 1, 1, 0, 1 };
    texref_draw_tri(&fb, (struct vertex[3]){ a, b, c }, &r, TEXREF_NEAREST, 16);
    texref_draw_tri(&fb, (struct vertex[3]){ a, c, d }, &r, TEXREF_NEAREST, 16);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            uint32_t want = (x / 8 + y / 8) % 2 ? RGB(255, 255, 255) : RGB(0, 0, 0);
            cr_assert_eq(fb.color[y * 64 + x], want, "pixel (%d, %d)", x, y);
            cr_assert_eq(fb.covered[y * 64 + x], 1, "the square covers (%d, %d) once", x, y);
        }
    /* bilinear at pixel (7, 4): u = 7.5 / 8, a = frac(u - 1/2) = 0.4375,
     * v = 4.5 / 8, b = 0.0625, between texels (0, 0) black, (1, 0) white,
     * (0, 1) white, (1, 1) black: white weighs a (1 - b) + (1 - a) b =
     * 0.4453125, 113.5546875 of 255, rounded 114 */
    texref_target_free(&fb);
    cr_assert(texref_target_init(&fb, 64, 64, 0));
    texref_draw_tri(&fb, (struct vertex[3]){ a, b, c }, &r, TEXREF_BILINEAR, 16);
    uint32_t p = fb.color[4 * 64 + 7];
    cr_expect_eq(p, RGB(114, 114, 114), "%08x", p);
    texref_target_free(&fb);
    texref_free(&r);
}

/* A texture whose levels differ: texel (i, j) = (i * 16 + j * 3) mod 256. */
static struct texref levels_texture(void)
{
    static uint32_t im[64 * 64];
    for (int j = 0; j < 64; j++)
        for (int i = 0; i < 64; i++)
            im[64 * j + i] = RGB((i * 16 + j * 3) & 255, (i * j) & 255, (i ^ j) * 4 & 255);
    struct texref r;
    cr_assert(texref_init(&r, 64, 64, im, TEXREF_REPEAT));
    return r;
}

static bool same(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) < 1e-9 && fabs(a[1] - b[1]) < 1e-9 && fabs(a[2] - b[2]) < 1e-9;
}

Test(texref, the_level_at_known_rho)
{
    struct texref r = levels_texture();
    const double s = 0.3712, t = 0.6179;
    struct { double rho; int level; } cases[] = {
        { 0.5, 0 }, { 1, 0 }, { sqrt(2) * 0.9999, 0 }, { sqrt(2) * 1.0001, 1 }, { 2, 1 },
        { pow(2, 1.5), 1 }, { pow(2, 1.5) * 1.0001, 2 }, { 4, 2 }, { 64, 6 }, { 1e9, 6 },
    };   /* log2(2^1.5) is 1.5 exactly: a tie, to the finer level */
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        /* rho is the longer of the two derivatives: here the y one */
        struct texref_deriv d = { cases[i].rho / 3, 0, 0, cases[i].rho, false };
        cr_expect(fabs(texref_rho(&d) - cases[i].rho) < 1e-12);
        double got[3], want[3];
        texref_sample(&r, TEXREF_MIP_BILINEAR, 16, s, t, &d, got);
        texref_bilinear(&r, cases[i].level, s, t, want);
        cr_expect(same(got, want), "rho %.6g (lambda %.6g): mip-bilinear takes level %d", cases[i].rho,
                  log2(cases[i].rho), cases[i].level);
        for (int k = 0; k < r.nlevels; k++) {
            texref_bilinear(&r, k, s, t, want);
            cr_expect(k == cases[i].level || !same(got, want), "rho %g: not level %d", cases[i].rho, k);
        }
    }
    /* trilinear at lambda = 1.25: three quarters of level 1, one of level 2 */
    struct texref_deriv d = { pow(2, 1.25), 0, 0, 0.5, false };
    double got[3], l1[3], l2[3];
    texref_sample(&r, TEXREF_TRILINEAR, 16, s, t, &d, got);
    texref_bilinear(&r, 1, s, t, l1);
    texref_bilinear(&r, 2, s, t, l2);
    for (int c = 0; c < 3; c++)
        cr_expect(fabs(got[c] - (0.75 * l1[c] + 0.25 * l2[c])) < 1e-9, "trilinear channel %d", c);
    /* magnified (rho < 1): every filter but nearest is bilinear at level 0 */
    d = (struct texref_deriv){ 0.5, 0.25, 0.1, 0.3, false };
    texref_bilinear(&r, 0, s, t, l1);
    for (int f = TEXREF_BILINEAR; f < TEXREF_FILTERS; f++) {
        texref_sample(&r, (enum texref_filter)f, 16, s, t, &d, got);
        cr_expect(same(got, l1), "%s magnified", texref_filter_name((enum texref_filter)f));
    }
    /* beyond the last level: the 1 x 1 level; and the horizon takes it too */
    d = (struct texref_deriv){ 0, 0, 0, 0, true };
    texref_sample(&r, TEXREF_TRILINEAR, 16, s, t, &d, got);
    texref_bilinear(&r, 6, s, t, l2);
    cr_expect(same(got, l2), "beyond the horizon: the last level");
    texref_free(&r);
}

/* Rows of 0 and 255 (row j is 255 when j is odd) seen with du/dx = 8,
 * dv/dy = 1 texel: isotropically lambda = 3, where every level below 0 is
 * 128; anisotropically 8 taps along u at lambda 0, all on row 8: 0. */
Test(texref, aniso_keeps_what_trilinear_blurs)
{
    uint32_t im[16 * 16];
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++)
            im[16 * j + i] = j % 2 ? RGB(255, 255, 255) : RGB(0, 0, 0);
    struct texref r;
    cr_assert(texref_init(&r, 16, 16, im, TEXREF_REPEAT));
    const struct texref_deriv d = { 8, 0, 0, 1, false };
    const double s = 0.5, t = 8.5 / 16;         /* u = 8, v = 8.5: the centre of row 8 */
    double c[3];
    texref_sample(&r, TEXREF_TRILINEAR, 16, s, t, &d, c);
    expect_rgb(c, 128, 128, 128, "trilinear at lambda 3: (0 + 0 + 255 + 255 + 2) / 4");
    texref_sample(&r, TEXREF_ANISO, 16, s, t, &d, c);
    expect_rgb(c, 0, 0, 0, "aniso: n = 8 taps on row 8 at level 0");
    texref_sample(&r, TEXREF_ANISO, 1, s, t, &d, c);
    expect_rgb(c, 128, 128, 128, "--max-aniso 1 is trilinear");
    /* max 4: n = 4, lambda = log2(8 / 4) = 1, level 1 is 128 everywhere */
    texref_sample(&r, TEXREF_ANISO, 4, s, t, &d, c);
    expect_rgb(c, 128, 128, 128, "aniso 4: level 1");
    /* the taps: at u = 8 + 8 ((i + 1/2) / 8 - 1/2) = 4.5 .. 11.5, row 8.5 +
     * 0.5: on row 9 they read 255; on the columns of a column pattern they
     * alternate */
    texref_sample(&r, TEXREF_ANISO, 16, s, 9.5 / 16, &d, c);
    expect_rgb(c, 255, 255, 255, "aniso on row 9");
    texref_free(&r);
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 16; i++)
            im[16 * j + i] = i % 2 ? RGB(255, 0, 0) : RGB(0, 0, 0);
    cr_assert(texref_init(&r, 16, 16, im, TEXREF_REPEAT));
    texref_sample(&r, TEXREF_ANISO, 16, s, t, &d, c);
    expect_rgb(c, 127.5, 0, 0, "taps on texel centres 4 .. 11 of alternating columns");
    texref_free(&r);
}

/* One covered pixel: its quad has three helper pixels, evaluated, not
 * written. A quad whose helper lies beyond the horizon takes the last level. */
Test(texref, helper_pixels_and_the_horizon)
{
    struct texref r;
    cr_assert(texref_init(&r, 2, 2, rgby, TEXREF_REPEAT));
    struct texref_target fb;
    cr_assert(texref_target_init(&fb, 8, 8, 0));
    const struct vertex a = { 2.3, 2.2, 1, 1, 1, 1, 0, 0 }, b = { 2.9, 2.2, 1, 1, 1, 1, 1, 0 },
                        c = { 2.3, 2.9, 1, 1, 1, 1, 0, 1 };
    texref_draw_tri(&fb, (struct vertex[3]){ a, b, c }, &r, TEXREF_TRILINEAR, 16);
    cr_expect_eq(fb.shaded, 1);
    cr_expect_eq(fb.helpers, 3);
    int n = 0;
    for (int i = 0; i < 64; i++)
        n += fb.covered[i];
    cr_expect(n == 1 && fb.covered[2 * 8 + 2] == 1, "only pixel (2, 2) is written");
    texref_target_free(&fb);

    /* a floor: 1/z at y = 3 (the top edge) is 1e-6, and grows by about 1/16
     * a row, so the helpers of row 2 (centre 2.5) lie beyond the horizon */
    cr_assert(texref_target_init(&fb, 16, 8, 0));
    const struct vertex p = { 0, 3, 1e6, 1, 1, 1, 0, 0 }, q = { 16, 3, 1e6, 1, 1, 1, 1000, 0 },
                        o = { 8, 19, 1, 1, 1, 1, 0.3, 0.3 };
    texref_draw_tri(&fb, (struct vertex[3]){ p, q, o }, &r, TEXREF_TRILINEAR, 16);
    cr_expect_eq(fb.covered[3 * 16 + 8], 1);
    cr_expect_eq(fb.color[3 * 16 + 8], RGB(128, 128, 64), "row 3: the 1 x 1 level, %08x", fb.color[3 * 16 + 8]);
    texref_target_free(&fb);
    texref_free(&r);
}

/* A textured scene through texref_draw_scene: each triangle under its own
 * texture and wrap, untextured ones in the vertex colour, depth kept. */
Test(texref, a_scene_with_two_textures)
{
    struct scene s;
    char err[256];
    const char *text = "size 16 8\nbackground 0 0 0.5\n"
                       "texture builtin:rgby clamp\n"
                       "tri 0 0 2 1 1 1 0 0  8 0 2 1 1 1 1 0  0 8 2 1 1 1 0 1\n"
                       "tri 0 0 1 0.5 0.5 0.5  16 0 1 0.5 0.5 0.5  0 1 1 0.5 0.5 0.5\n"
                       "texture builtin:grid\n"
                       "tri 8 0 1 1 1 1 0 0  16 0 1 1 1 1 1 0  16 8 1 1 1 1 1 1\n";
    cr_assert(scene_parse(&s, "t.scene", text, strlen(text), err, sizeof err), "%s", err);
    struct texref_target fb;
    cr_assert(texref_target_init(&fb, 16, 8, scene_background(&s)));
    cr_assert(texref_draw_scene(&fb, &s, TEXREF_NEAREST, 16));
    cr_expect_eq(fb.color[0 * 16 + 1], RGB(128, 128, 128), "row 0: the nearer grey triangle (z = 1)");
    cr_expect_eq(fb.color[2 * 16 + 1], RGB(255, 0, 0), "texel (0, 0) of rgby");
    cr_expect_eq(fb.color[2 * 16 + 4], RGB(0, 255, 0), "texel (1, 0) of rgby");
    cr_expect_eq(fb.color[5 * 16 + 1], RGB(0, 0, 255), "texel (0, 1) of rgby");
    cr_expect_eq(fb.color[7 * 16 + 7], RGB(0, 0, 128), "the background");
    cr_expect_eq(fb.covered[1 * 16 + 12], 1, "the grid's triangle");
    texref_target_free(&fb);
    scene_free(&s);
}

/* The comparison lesson 09 is checked with: a lesson's picture of an
 * untextured scene (vertex colours, perspective-correct) is the
 * reference's within 2 levels, coverage exact; a picture off by 3 levels
 * in one pixel is caught there. */
Test(texref, a_lesson_picture_compares_within_two_levels)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "blocks", err, sizeof err), "%s", err);
    const struct lesson *l = NULL;
    for (int i = 0; all_lessons[i]; i++)
        if (strncmp(all_lessons[i]->id, "04-", 3) == 0)
            l = all_lessons[i];
    cr_assert(l && l->perspective, "lesson 04 interpolates perspective-correctly");
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, scene_background(&s)));
    struct raster_params p = default_params();
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        if (tri_setup(&t, s.tris[i].v, s.w, s.h))
            rasterize_one(&l->variants[0], &p, &t, &fb, NULL);
    }
    struct texref_target ref;
    cr_assert(texref_target_init(&ref, s.w, s.h, scene_background(&s)));
    cr_assert(texref_draw_scene(&ref, &s, TEXREF_TRILINEAR, 16));
    struct texref_diff d = texref_compare(&ref, &fb, 2);
    cr_expect(d.coverage == 0 && d.colour == 0, "%ld pixels covered otherwise, %ld coloured (first at %d, %d)",
              d.coverage, d.colour, d.x, d.y);
    cr_expect_gt(ref.shaded, 500);
    int k = 30 * s.w + 30;
    cr_assert(ref.covered[k]);
    fb.color[k] += 3;                                           /* blue three levels up */
    d = texref_compare(&ref, &fb, 2);
    cr_expect(d.colour == 1 && d.x == 30 && d.y == 30);
    texref_target_free(&ref);
    target_free(&fb);
    scene_free(&s);
}
