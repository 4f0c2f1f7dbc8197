/* test_lesson02.c - lesson 02's exhibits are real, with the counts its text
 * states, and its interpolation agrees with the double-precision reference. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "explore/replay.h"
#include "testlib.h"

extern const struct lesson lesson_02;

/* Coverage counts of a whole scene drawn by the exact reference. */
static void reference_counts(const struct scene *s, uint8_t *count)
{
    memset(count, 0, (size_t)s->w * (size_t)s->h);
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        reference_mask(&t, count);
    }
}

struct exhibit_counts {
    int doubled;     /* pixels the variant covers twice or more */
    int extra;       /* coverage beyond the exact rule, summed over pixels */
    int missing;     /* coverage the exact rule has and the variant lacks */
    int diagonal_missing;   /* missing pixels on the shared diagonal x == y */
};

static struct exhibit_counts run_exhibit(const char *variant)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_02.exhibit_scene, err, sizeof err), "%s", err);
    const struct lesson_variant *v = lesson_variant(&lesson_02, variant);
    cr_assert_not_null(v, "lesson 02 has no variant %s", variant);
    struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS };
    struct target fb;
    cr_assert(render_scene(&s, v, &p, &fb));
    uint8_t ref[16 * 16];
    cr_assert_eq(s.w * s.h, (int)sizeof ref);
    reference_counts(&s, ref);

    struct exhibit_counts c = { 0 };
    for (int y = 0; y < s.h; y++)
        for (int x = 0; x < s.w; x++) {
            int got = fb.count[y * s.w + x], want = ref[y * s.w + x];
            c.doubled += got >= 2;
            c.extra += got > want ? got - want : 0;
            c.missing += want > got ? want - got : 0;
            c.diagonal_missing += x == y && want > got;
        }
    target_free(&fb);
    scene_free(&s);
    return c;
}

/* The shared-edge scene: a 12 x 12 square of pixel centres, (1.5, 1.5) to
 * (13.5, 13.5), cut along its diagonal. The exact rule covers columns and
 * rows 1..12 once each; the lesson text derives the exhibits' counts. */
Test(lesson02, inclusive_rule_covers_the_shared_diagonal_twice)
{
    struct exhibit_counts c = run_exhibit("inclusive");
    cr_expect_eq(c.doubled, 13, "13 diagonal centres (1,1)..(13,13) lie on both triangles");
    cr_expect_eq(c.extra, 38, "12 doubled + 2 at (13,13) + 12 right column + 12 bottom row");
    cr_expect_eq(c.missing, 0);
}

Test(lesson02, strict_rule_leaves_a_crack_along_the_shared_edge)
{
    struct exhibit_counts c = run_exhibit("strict");
    cr_expect_eq(c.missing, 34, "12 on the diagonal + 11 on the top row + 11 on the left column");
    cr_expect_eq(c.diagonal_missing, 12, "the crack: diagonal centres (1,1)..(12,12)");
    cr_expect_eq(c.extra, 0);
    cr_expect_eq(c.doubled, 0);
}

/* Colour and z at every covered pixel agree with reference_shade (double
 * precision, linear in screen space). The lesson computes the same formula in
 * double and packs colour to 8 bits, so the named tolerance is one step of
 * 8-bit colour and float rounding of z. */
#define COLOR_TOLERANCE 1      /* 8-bit steps: rounding at a .5 boundary */
#define Z_TOLERANCE 1e-6       /* relative: z is stored as float */

Test(lesson02, interpolation_matches_the_reference)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "overlap", err, sizeof err), "%s", err);
    struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS };
    for (int i = 0; i < s.ntris; i++) {
        struct target fb;
        cr_assert(target_init(&fb, s.w, s.h, 0xff000000u));
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        lesson_02.variants[0].rasterize(&t, &p, &fb, NULL);
        int checked = 0;
        for (int y = 0; y < s.h; y++)
            for (int x = 0; x < s.w; x++) {
                size_t k = (size_t)y * (size_t)s.w + (size_t)x;
                if (!fb.count[k])
                    continue;
                double z, rgb[3], st[2];
                reference_shade(&t, x, y, false, &z, rgb, st);
                cr_expect(fabs(fb.depth[k] - z) <= Z_TOLERANCE * z, "z at (%d,%d): %g vs %g",
                          x, y, fb.depth[k], z);
                for (int c = 0; c < 3; c++) {
                    int got = (int)(fb.color[k] >> (16 - 8 * c) & 0xff);
                    int want = (int)lrint(rgb[c] * 255);
                    cr_expect(abs(got - want) <= COLOR_TOLERANCE, "channel %d at (%d,%d): %d vs %d",
                              c, x, y, got, want);
                }
                checked++;
            }
        cr_expect_gt(checked, 50, "triangle %d covered only %d pixels", i, checked);
        target_free(&fb);
    }
    scene_free(&s);
}
