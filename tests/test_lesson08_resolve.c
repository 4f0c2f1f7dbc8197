/* test_lesson08_resolve.c - lesson 08's resolve as a filter, and its
 * pictures for paper.
 *
 * The box resolve (the mean of a pixel's own samples) is test_lesson08.c's.
 * Here the tent variant: its picture is the tent filter of the samples it
 * stored, against a reference written from the filter's definition and
 * lessons/CONVENTIONS.md's sample positions (typed in again); it changes the edges
 * and leaves the insides of triangles within a level of the box's; the
 * count of pixels it changes is the one the lesson's text quotes. And the
 * light theme, where the scene is drawn on the page: every pixel is the
 * lesson's own picture on a white background, so an edge pixel blends with
 * white, never darker than the same pixel on the screen's dark background. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "explore/explorer.h"
#include "explore/replay.h"

extern const struct lesson lesson_08;

#define README "lessons/08-multisampling/README.md"

/* lessons/CONVENTIONS.md, "Samples" (1/256 pixel from the pixel's top-left corner). */
static const int pos4[4][2] = { { 96, 32 }, { 224, 96 }, { 32, 160 }, { 160, 224 } };
static const int pos8[8][2] = { { 144, 80 }, { 112, 176 }, { 208, 144 }, { 80, 48 },
                                { 48, 208 }, { 16, 112 }, { 176, 240 }, { 240, 16 } };

static struct target draw(const struct scene *s, const char *variant, int n)
{
    const struct lesson_variant *v = lesson_variant(&lesson_08, variant);
    cr_assert_not_null(v, "lesson 08 has no variant %s", variant);
    struct raster_params p = default_params();
    p.samples = n;
    struct target fb;
    cr_assert(render_lesson_scene(&lesson_08, s, v, &p, &fb), "out of memory");
    return fb;
}

static int channel(uint32_t c, int ch)
{
    return (int)(c >> (16 - 8 * ch) & 0xff);
}

/* The tent of radius one pixel, from its definition: every sample on the
 * screen at (dx, dy) pixels from the centre of (x, y) with |dx|, |dy| < 1
 * weighs (1 - |dx|)(1 - |dy|); the weighted mean, rounded to nearest. */
static uint32_t reference_tent(const struct target *fb, int x, int y)
{
    int n = fb->samples->n;
    const int (*pos)[2] = n == 4 ? pos4 : pos8;
    double sum[3] = { 0, 0, 0 }, total = 0;
    for (int ny = y - 1; ny <= y + 1; ny++)
        for (int nx = x - 1; nx <= x + 1; nx++) {
            if (nx < 0 || ny < 0 || nx >= fb->w || ny >= fb->h)
                continue;
            for (int s = 0; s < n; s++) {
                double dx = nx - x + (pos[s][0] - 128) / 256.0, dy = ny - y + (pos[s][1] - 128) / 256.0;
                double w = fmax(0, 1 - fabs(dx)) * fmax(0, 1 - fabs(dy));
                uint32_t c = fb->samples->color[((size_t)ny * (size_t)fb->w + (size_t)nx) * (size_t)n + (size_t)s];
                for (int ch = 0; ch < 3; ch++)
                    sum[ch] += w * channel(c, ch);
                total += w;
            }
        }
    uint32_t rgba = 0xff000000u;
    for (int ch = 0; ch < 3; ch++)
        rgba |= (uint32_t)floor(sum[ch] / total + 0.5) << (16 - 8 * ch);
    return rgba;
}

/* A scene of random triangles, slivers among them, apart in depth. */
static struct scene random_scene(uint64_t salt)
{
    struct rng r = rng_for(salt);
    char text[8192];
    int at = snprintf(text, sizeof text, "size 40 30\nbackground 0.1 0.2 0.3\n");
    for (int k = 0; k < 8; k++) {
        struct vertex v[3];
        random_tri(&r, k % 2 ? CAT_GENERIC : CAT_SLIVER, 40, 30, v);
        at += snprintf(text + at, sizeof text - (size_t)at, "tri");
        for (int i = 0; i < 3; i++)
            at += snprintf(text + at, sizeof text - (size_t)at, "  %.17g %.17g %.17g  %.17g %.17g %.17g",
                           v[i].x, v[i].y, 1 + k + 0.3 * i, v[i].r, v[i].g, v[i].b);
        at += snprintf(text + at, sizeof text - (size_t)at, "\n");
    }
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "random", text, strlen(text), err, sizeof err), "%s", err);
    return s;
}

static struct scene builtin(const char *name)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, name, err, sizeof err), "%s", err);
    return s;
}

Test(lesson08, tent_resolve_is_the_tent_filter_of_the_stored_samples, .timeout = 60)
{
    struct scene scenes[3] = { builtin("samples"), builtin("samples-exhibits"), random_scene(0x0808) };
    long compared = 0;
    for (int k = 0; k < 3; k++)
        for (int n = 4; n <= 8; n += 4) {
            struct target fb = draw(&scenes[k], "tent", n);
            cr_assert(fb.samples && fb.samples->n == n);
            for (int y = 0; y < fb.h; y++)
                for (int x = 0; x < fb.w; x++) {
                    uint32_t want = reference_tent(&fb, x, y), got = fb.color[(size_t)y * (size_t)fb.w + (size_t)x];
                    cr_assert_eq(got & 0xffffff, want & 0xffffff, "scene %d, %d samples: pixel (%d, %d) is "
                                 "#%06x, the tent of its samples #%06x", k, n, x, y,
                                 (unsigned)(got & 0xffffff), (unsigned)(want & 0xffffff));
                    compared++;
                }
            /* the samples themselves are the box variant's: only the resolve differs */
            struct target box = draw(&scenes[k], "msaa", n);
            size_t ns = (size_t)fb.w * (size_t)fb.h * (size_t)n;
            cr_expect(memcmp(fb.samples->color, box.samples->color, ns * sizeof *fb.samples->color) == 0,
                      "scene %d, %d samples: the tent variant stored other samples", k, n);
            cr_expect(memcmp(fb.count, box.count, (size_t)fb.w * (size_t)fb.h) == 0);
            target_free(&fb);
            target_free(&box);
        }
    for (int k = 0; k < 3; k++)
        scene_free(&scenes[k]);
    cr_expect_gt(compared, 3 * 1000);
}

/* With one sample the tent reaches no neighbour (their centres are a pixel
 * away: weight 0): the picture is the box's. */
Test(lesson08, tent_at_one_sample_is_the_box)
{
    struct scene s = builtin("samples");
    struct target a = draw(&s, "tent", 1), b = draw(&s, "msaa", 1);
    cr_expect(memcmp(a.color, b.color, (size_t)a.w * (size_t)a.h * sizeof *a.color) == 0);
    target_free(&a);
    target_free(&b);
    scene_free(&s);
}

/* On builtin:samples at 4 samples the tent changes the edges and keeps the
 * rest within a level of the box (there the samples in reach carry a smooth
 * gradient, each pixel's rounded once); the count of pixels it changes by
 * more than a level is quoted. */
Test(lesson08, tent_changes_the_edges_counted)
{
    struct scene s = builtin("samples");
    struct target tent = draw(&s, "tent", 4), box = draw(&s, "msaa", 4);
    int w = box.w, h = box.h, n = 4;
    long changed = 0, edge_px = 0, inside_moved = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            /* an edge: within reach, a pixel whose samples differ (covered in part,
             * or by two triangles), or pixels drawn beside pixels not drawn */
            bool edge = false, drawn = false, blank = false;
            for (int ny = y - 1; ny <= y + 1; ny++)
                for (int nx = x - 1; nx <= x + 1; nx++) {
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h)
                        continue;
                    size_t i = (size_t)ny * (size_t)w + (size_t)nx;
                    const uint32_t *c = &box.samples->color[i * (size_t)n];
                    for (int k = 1; k < n; k++)
                        edge |= c[k] != c[0];
                    drawn |= box.count[i] > 0;
                    blank |= box.count[i] == 0;
                }
            edge |= drawn && blank;
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            int diff = 0;
            for (int ch = 0; ch < 3; ch++)
                diff = abs(channel(tent.color[i], ch) - channel(box.color[i], ch)) > diff
                     ? abs(channel(tent.color[i], ch) - channel(box.color[i], ch)) : diff;
            changed += diff > 1;
            edge_px += edge;
            if (!edge && diff > 1)
                inside_moved++;
        }
    cr_log_info("tent against box, builtin:samples at 4 samples: %ld pixels change by more than a "
                "level, %ld edge pixels\n", changed, edge_px);
    cr_expect_eq(inside_moved, 0, "%ld pixels away from every edge moved by more than a level",
                 inside_moved);
    cr_expect_gt(changed, 0);
    cr_expect_leq(changed, edge_px);
    double tol;
    double quoted = text_number(README, "l08.tent.changed", &tol);
    cr_expect(fabs(quoted - (double)changed) <= tol, "%s quotes %g for l08.tent.changed, the lesson "
              "computes %ld", README, quoted, changed);
    quoted = text_number(README, "l08.tent.pixels", &tol);
    cr_expect(fabs(quoted - (double)(w * h)) <= tol, "%s quotes %g for l08.tent.pixels, the scene has %d",
              README, quoted, w * h);
    target_free(&tent);
    target_free(&box);
    scene_free(&s);
}

/* --- the light theme: the scene on the page ------------------------------------------ */

Test(lesson08, light_theme_resolves_edges_against_the_page, .timeout = 60)
{
    struct scene s = builtin("samples");
    char err[256];
    struct raster_params p = default_params();
    p.samples = 4;
    struct explorer dark, light;
    struct explorer_desc d = { .lesson = &lesson_08, .scene = &s, .scene_name = "samples",
                               .params = &p, .step_end = true };
    cr_assert(explorer_init(&dark, &d, err, sizeof err), "%s", err);
    d.theme = THEME_LIGHT;
    cr_assert(explorer_init(&light, &d, err, sizeof err), "%s", err);
    /* the light picture is the lesson's own on a white background */
    struct scene white = builtin("samples");
    white.background[0] = white.background[1] = white.background[2] = 1;
    struct target want;
    cr_assert(render_lesson_scene(&lesson_08, &white, &lesson_08.variants[0], &p, &want));
    size_t npx = (size_t)s.w * (size_t)s.h;
    cr_expect(memcmp(light.fb.color, want.color, npx * sizeof *want.color) == 0,
              "the light theme's picture is not the scene drawn on white");
    /* an edge pixel (some samples covered, not all) is lighter on paper */
    long partial = 0;
    for (size_t i = 0; i < npx; i++) {
        if (dark.fb.count[i] == 0 || dark.fb.count[i] >= 4)
            continue;
        int sd = 0, sl = 0;
        for (int ch = 0; ch < 3; ch++)
            sd += channel(dark.fb.color[i], ch), sl += channel(light.fb.color[i], ch);
        cr_expect_gt(sl, sd, "pixel %zu, %u of 4 samples: darker on paper", i, (unsigned)dark.fb.count[i]);
        partial++;
    }
    cr_expect_gt(partial, 100);
    /* and L in the window switches back and forth to the same pictures */
    cr_assert(explorer_set_theme(&light, THEME_DARK));
    cr_expect(memcmp(light.fb.color, dark.fb.color, npx * sizeof *dark.fb.color) == 0);
    cr_assert(explorer_set_theme(&light, THEME_LIGHT));
    cr_expect(memcmp(light.fb.color, want.color, npx * sizeof *want.color) == 0);
    cr_expect(light.own_background[0] == s.background[0], "the scene's own background is kept");
    target_free(&want);
    explorer_free(&dark);
    explorer_free(&light);
    scene_free(&white);
    scene_free(&s);
}
