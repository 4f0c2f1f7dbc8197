/* test_lesson08.c - lesson 08's claims: per-sample coverage is exact for 1,
 * 4 and 8 samples (against a reference written here from lessons/CONVENTIONS.md's
 * table, with samples exactly on edges), a watertight mesh puts exactly N
 * samples in every pixel, the resolved colours agree with a reference
 * resolve within 2 levels, and the exhibits (jaggies at one sample, a
 * regular grid against the rotated pattern, the fill rule dropped per
 * sample) show what the lesson's text says, counted.
 *
 * (Coverage at the default one sample, every exact variant against the
 * pixel-centre reference, is test_property.c's job.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "lesson_explorer.h"

extern const struct lesson lesson_08, lesson_08_fast;

/* The lesson's text and answer key: the numbers they quote, marked
 * <!--=l08.KEY--> (testlib.h), are the ones recomputed here. */
#define README "lessons/08-multisampling/README.md"
#define ANSWERS "lessons/08-multisampling/ANSWERS.md"

/* The count `got` is the number the text quotes before marker `key`. */
static void expect_quoted(const char *path, const char *key, double got)
{
    double tol;
    double quoted = text_number(path, key, &tol);
    cr_expect(fabs(quoted - got) <= tol, "%s quotes %g for %s, the lesson computes %.17g", path,
              quoted, key, got);
}

/* lessons/CONVENTIONS.md, "Samples": positions in 1/256 pixel from the top-left
 * corner, typed in again here (not taken from the code under test). */
static const int pos1[1][2] = { { 128, 128 } };
static const int pos4[4][2] = { { 96, 32 }, { 224, 96 }, { 32, 160 }, { 160, 224 } };
static const int pos8[8][2] = { { 144, 80 }, { 112, 176 }, { 208, 144 }, { 80, 48 },
                                { 48, 208 }, { 16, 112 }, { 176, 240 }, { 240, 16 } };

static const int (*positions(int n))[2]
{
    return n == 1 ? pos1 : n == 4 ? pos4 : pos8;
}

static const struct lesson_variant *variant(const struct lesson *l, const char *name)
{
    const struct lesson_variant *v = lesson_variant(l, name);
    cr_assert_not_null(v, "lesson 08 has no variant %s", name);
    return v;
}

/* --- the reference, from the snapped vertices -------------------------------- */

/* (B - A) x (P - A) in 1/256 units: positive inside a triangle whose
 * orientation tri_setup normalised (y down). */
static int64_t cross(const struct tri_setup *t, int a, int b, int64_t px, int64_t py)
{
    return ((int64_t)t->x[b] - t->x[a]) * (py - t->y[a]) - (px - t->x[a]) * ((int64_t)t->y[b] - t->y[a]);
}

/* The top-left rule as lessons/CONVENTIONS.md words it: a top edge is horizontal
 * with the triangle below (walked to +x in this orientation), a left edge
 * has the interior at larger x (walked upwards, y decreasing). */
static bool top_left(const struct tri_setup *t, int a, int b)
{
    int64_t dy = (int64_t)t->y[b] - t->y[a], dx = (int64_t)t->x[b] - t->x[a];
    return dy < 0 || (dy == 0 && dx > 0);
}

/* Is the point (px, py) (1/256 units) covered? *on_edge: it lies exactly on an edge. */
static bool covered_at(const struct tri_setup *t, int64_t px, int64_t py, bool *on_edge)
{
    if (cross(t, 0, 1, t->x[2], t->y[2]) <= 0)
        return false;
    bool in = true, closed = true, zero = false;
    for (int k = 0; k < 3; k++) {
        int64_t f = cross(t, k, (k + 1) % 3, px, py);
        zero |= f == 0;
        closed &= f >= 0;
        if (f < 0 || (f == 0 && !top_left(t, k, (k + 1) % 3)))
            in = false;
    }
    *on_edge |= zero && closed;     /* on the triangle's boundary, not just an edge's line */
    return in;
}

/* Add the covered samples of t, pixel by pixel, to counts; returns how many
 * samples lay exactly on an edge of t. */
static int reference_samples(const struct tri_setup *t, int n, uint8_t *counts)
{
    const int (*pos)[2] = positions(n);
    int on = 0;
    for (int py = 0; py < t->target_h; py++)
        for (int px = 0; px < t->target_w; px++)
            for (int s = 0; s < n; s++) {
                bool edge = false;
                bool in = covered_at(t, (int64_t)px * 256 + pos[s][0], (int64_t)py * 256 + pos[s][1], &edge);
                on += edge;
                uint8_t *c = &counts[(size_t)py * (size_t)t->target_w + (size_t)px];
                if (in && *c < 255)
                    (*c)++;
            }
    return on;
}

/* A vertex exactly on a sample position of an N-sample pattern, in a w x h target. */
static struct vertex on_sample(struct rng *r, int n, int w, int h)
{
    const int (*pos)[2] = positions(n);
    int s = rng_int(r, 0, n - 1);
    return test_vertex(rng_int(r, -2, w + 1) + pos[s][0] / 256.0, rng_int(r, -2, h + 1) + pos[s][1] / 256.0);
}

/* --- exact per sample --------------------------------------------------------- */

Test(lesson08, per_sample_coverage_equals_the_reference_for_1_4_8_samples, .timeout = 120)
{
    const int w = 24, h = 18, sizes[3] = { 1, 4, 8 };
    const char *names[2] = { "msaa", "ssaa" };
    const struct lesson *builds[2] = { &lesson_08, &lesson_08_fast };
    struct rng r = rng_for(0x0801);
    uint8_t *ref = malloc((size_t)w * h);
    cr_assert_not_null(ref);
    int on_edge = 0, cases = 0;
    for (int i = 0; i < 1500; i++) {
        int n = sizes[i % 3];
        struct vertex v[3];
        if (i % 4 == 0) {       /* edges through sample positions */
            for (int k = 0; k < 3; k++)
                v[k] = on_sample(&r, n, w, h);
        } else {
            random_tri(&r, (enum tri_category)(i % CAT_COUNT), w, h, v);
        }
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        memset(ref, 0, (size_t)w * h);
        on_edge += reference_samples(&t, n, ref);
        for (int b = 0; b < 2; b++)
            for (int k = 0; k < 2; k++) {
                struct raster_params p = default_params();
                p.samples = n;
                struct target fb;
                cr_assert(target_init(&fb, w, h, 0xff000000u));
                rasterize_one(variant(builds[b], names[k]), &p, &t, &fb, NULL);
                char what[160];
                snprintf(what, sizeof what, "%s %s, %d samples", builds[b] == &lesson_08 ? "narrated" : "fast",
                         names[k], n);
                struct case_info info = { what, test_seed(), (uint64_t)i, v, 3 };
                cr_assert(coverage_equal(ref, fb.count, w, h, &info), "%s", what);
                target_free(&fb);
                cases++;
            }
    }
    free(ref);
    cr_expect_gt(on_edge, 2000, "only %d samples exactly on an edge", on_edge);
    cr_expect_eq(cases, 6000);
}

/* The narrated run stopped at every step is the same algorithm: at the last
 * step the picture is the fast build's (whole-scene test). */
Test(lesson08, narrated_and_fast_builds_write_the_same_bytes)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "samples", err, sizeof err), "%s", err);
    for (int n = 1; n <= 8; n *= 2) {
        if (n == 2)
            continue;
        struct raster_params p = default_params();
        p.samples = n;
        struct target a, b;
        cr_assert(target_init(&a, s.w, s.h, scene_background(&s)));
        cr_assert(target_init(&b, s.w, s.h, scene_background(&s)));
        for (int i = 0; i < s.ntris; i++) {
            struct tri_setup t;
            tri_setup(&t, s.tris[i].v, s.w, s.h);
            struct trace tr = { 0 };
            trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
            lesson_08.variants[0].rasterize(&t, &p, &a, &tr);
            lesson_08_fast.variants[0].rasterize(&t, &p, &b, NULL);
        }
        size_t m = (size_t)s.w * (size_t)s.h;
        cr_expect_eq(memcmp(a.color, b.color, m * 4), 0, "%d samples: colours differ", n);
        cr_expect_eq(memcmp(a.count, b.count, m), 0, "%d samples: counts differ", n);
        target_free(&a);
        target_free(&b);
    }
    scene_free(&s);
}

/* --- watertight per sample ----------------------------------------------------- */

/* A gx x gy grid over the whole w x h target, each cell two triangles (the
 * diagonal chosen at random), inner vertices jittered, some onto sample
 * positions, drawn in random order and winding. */
static int grid_mesh(struct rng *r, int n, int w, int h, int gx, int gy, struct vertex *out)
{
    struct vertex g[9][9];
    const int (*pos)[2] = positions(n);
    for (int j = 0; j <= gy; j++)
        for (int i = 0; i <= gx; i++) {
            double x = (double)i * w / gx, y = (double)j * h / gy;
            if (i > 0 && i < gx && j > 0 && j < gy) {
                if (rng_chance(r, 0.5)) {
                    int s = rng_int(r, 0, n - 1);
                    x = floor(x) + pos[s][0] / 256.0, y = floor(y) + pos[s][1] / 256.0;
                } else {
                    x += rng_range(r, -1.5, 1.5), y += rng_range(r, -1.5, 1.5);
                }
            }
            g[j][i] = test_vertex(x, y);
        }
    int nt = 0;
    for (int j = 0; j < gy; j++)
        for (int i = 0; i < gx; i++) {
            struct vertex a = g[j][i], b = g[j][i + 1], c = g[j + 1][i + 1], d = g[j + 1][i];
            if (rng_chance(r, 0.5)) {
                struct vertex t1[3] = { a, b, c }, t2[3] = { a, c, d };
                memcpy(&out[3 * nt++], t1, sizeof t1);
                memcpy(&out[3 * nt++], t2, sizeof t2);
            } else {
                struct vertex t1[3] = { a, b, d }, t2[3] = { b, c, d };
                memcpy(&out[3 * nt++], t1, sizeof t1);
                memcpy(&out[3 * nt++], t2, sizeof t2);
            }
        }
    for (int k = 0; k < nt; k++) {          /* random order and winding */
        int o = rng_int(r, 0, nt - 1);
        struct vertex tmp[3];
        memcpy(tmp, &out[3 * k], sizeof tmp);
        memcpy(&out[3 * k], &out[3 * o], sizeof tmp);
        memcpy(&out[3 * o], tmp, sizeof tmp);
        if (rng_chance(r, 0.5)) {
            struct vertex x = out[3 * k + 1];
            out[3 * k + 1] = out[3 * k + 2];
            out[3 * k + 2] = x;
        }
    }
    return nt;
}

static void draw_mesh(const struct lesson_variant *v, int n, const struct vertex *tris, int nt,
                      struct target *fb)
{
    struct raster_params p = default_params();
    p.samples = n;
    for (int k = 0; k < nt; k++) {
        struct tri_setup t;
        tri_setup(&t, &tris[3 * k], fb->w, fb->h);
        v->rasterize(&t, &p, fb, NULL);
    }
}

Test(lesson08, every_pixel_inside_a_watertight_mesh_holds_exactly_n_samples, .timeout = 120)
{
    const int w = 40, h = 30, sizes[3] = { 1, 4, 8 };
    const struct lesson *builds[2] = { &lesson_08, &lesson_08_fast };
    const char *names[2] = { "msaa", "ssaa" };
    struct rng r = rng_for(0x0802);
    struct vertex tris[3 * 128];
    for (int m = 0; m < 60; m++) {
        int n = sizes[m % 3];
        int nt = grid_mesh(&r, n, w, h, rng_int(&r, 2, 8), rng_int(&r, 2, 8), tris);
        for (int b = 0; b < 2; b++)
            for (int k = 0; k < 2; k++) {
                struct target fb;
                cr_assert(target_init(&fb, w, h, 0xff000000u));
                draw_mesh(variant(builds[b], names[k]), n, tris, nt, &fb);
                for (int i = 0; i < w * h; i++)
                    cr_assert_eq(fb.count[i], n, "mesh %d, %s, %d samples: pixel (%d, %d) holds %d",
                                 m, names[k], n, i % w, i / w, fb.count[i]);
                target_free(&fb);
            }
    }
}

/* Without the fill rule a sample exactly on a shared edge is covered by both
 * triangles: the meshes above, whose inner vertices sit on samples, then
 * hold more than N samples in some pixels. */
Test(lesson08, without_the_fill_rule_shared_edges_cover_samples_twice)
{
    const int w = 40, h = 30;
    struct rng r = rng_for(0x0803);
    struct vertex tris[3 * 128];
    long extra = 0;
    for (int m = 0; m < 20; m++) {
        int nt = grid_mesh(&r, 4, w, h, 6, 5, tris);
        struct target fb;
        cr_assert(target_init(&fb, w, h, 0xff000000u));
        draw_mesh(variant(&lesson_08, "no-fill-rule"), 4, tris, nt, &fb);
        for (int i = 0; i < w * h; i++) {
            cr_assert_geq(fb.count[i], 4, "no sample is lost, only doubled");
            extra += fb.count[i] - 4;
        }
        target_free(&fb);
    }
    cr_expect_gt(extra, 20, "only %ld samples covered twice", extra);
}

/* The exhibit scene's two rectangles split along their diagonals: samples
 * exactly on the shared edges, counted. */
static long scene_samples(const char *scene, const char *vname, int n, int from, int to,
                          struct target *fb)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, scene, err, sizeof err), "%s", err);
    cr_assert(target_init(fb, s.w, s.h, scene_background(&s)));
    struct raster_params p = default_params();
    p.samples = n;
    for (int i = from; i < to && i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        variant(&lesson_08, vname)->rasterize(&t, &p, fb, NULL);
    }
    long sum = 0;
    for (int i = 0; i < s.w * s.h; i++)
        sum += fb->count[i];
    scene_free(&s);
    return sum;
}

Test(lesson08, exhibit_fill_rule_on_the_exhibit_scene)
{
    /* The shared edge x = 16.375 = 16 + 96/256 from y = 38.5 to 46.5 passes
     * exactly through sample 0 (96, 32) of pixel (16, y) for y = 39 .. 46:
     * 8 samples, no other sample on any edge of the four triangles (their
     * other edges lie on half pixels or cross no sample: checked here too). */
    struct target a, b;
    long with = scene_samples("samples-exhibits", "msaa", 4, 5, 9, &a);
    long without = scene_samples("samples-exhibits", "no-fill-rule", 4, 5, 9, &b);
    cr_expect_eq(without - with, 8, "samples covered twice: %ld", without - with);
    expect_quoted(README, "l08.fill.doubled", (double)(without - with));
    int doubled = 0;
    for (int i = 0; i < a.w * a.h; i++) {
        bool column16 = i % a.w == 16 && i / a.w >= 39 && i / a.w <= 46;
        cr_expect_eq(b.count[i] - a.count[i], column16 ? 1 : 0, "pixel (%d, %d)", i % a.w, i / a.w);
        cr_expect_leq(a.count[i], 4, "with the fill rule, at most 4 samples in a pixel");
        doubled += b.count[i] > a.count[i];
    }
    cr_expect_eq(doubled, 8, "pixels with a sample covered twice: %d", doubled);
    target_free(&a);
    target_free(&b);
    /* the reference agrees: samples exactly on an edge of the four triangles */
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "samples-exhibits", err, sizeof err), "%s", err);
    int on = 0;
    uint8_t *ref = calloc((size_t)s.w * (size_t)s.h, 1);
    cr_assert_not_null(ref);
    for (int i = 5; i < 9; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        on += reference_samples(&t, 4, ref);
    }
    cr_expect_eq(on, 16, "8 samples on the shared edge, seen from both triangles");
    free(ref);
    scene_free(&s);
    /* the whole scene: the near-horizontal quad's diagonal (2, 10) - (30, 30)
     * passes through 8 more samples */
    long all_with = scene_samples("samples-exhibits", "msaa", 4, 0, 9, &a);
    long all_without = scene_samples("samples-exhibits", "no-fill-rule", 4, 0, 9, &b);
    int pixels = 0;
    for (int i = 0; i < a.w * a.h; i++)
        pixels += b.count[i] > a.count[i];
    cr_expect_eq(all_without - all_with, 16);
    cr_expect_eq(pixels, 16);
    expect_quoted(README, "l08.fill.scene", pixels);
    target_free(&a);
    target_free(&b);
}

/* --- jaggies and the exact area ------------------------------------------------- */

/* Over triangles from .. to - 1 of the exhibit scene (one shape: a sliver,
 * or a quad of two triangles), pixel by pixel: the sample estimate (covered
 * samples / N, summed over the triangles) against the exact area covered. */
struct jaggies {
    int off;            /* |covered / N - area| > tol */
    int odd;            /* partly covered pixels with an odd count of samples */
    double worst;
};

static struct jaggies jaggies(const char *vname, int from, int to, int n, double tol)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "samples-exhibits", err, sizeof err), "%s", err);
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, 0));
    struct raster_params p = default_params();
    p.samples = n;
    double *area = calloc((size_t)s.w * (size_t)s.h, sizeof *area);
    cr_assert_not_null(area);
    for (int i = from; i < to; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        variant(&lesson_08, vname)->rasterize(&t, &p, &fb, NULL);
        for (int y = 0; y < s.h; y++)
            for (int x = 0; x < s.w; x++)
                area[y * s.w + x] += reference_pixel_area(&t, x, y);
    }
    struct jaggies j = { 0 };
    for (int i = 0; i < s.w * s.h; i++) {
        double e = fabs(fb.count[i] / (double)n - area[i]);
        j.off += e > tol;
        j.worst = e > j.worst ? e : j.worst;
        j.odd += area[i] > 1e-9 && area[i] < 1 - 1e-9 && fb.count[i] % 2 == 1;
    }
    free(area);
    target_free(&fb);
    scene_free(&s);
    return j;
}

Test(lesson08, exact_area_of_a_pixel)
{
    /* a right triangle over pixel (2, 2): half of it; a big one: all of it */
    struct vertex v[3] = { test_vertex(2, 2), test_vertex(3, 2), test_vertex(3, 3) };
    struct tri_setup t;
    tri_setup(&t, v, 8, 8);
    cr_expect_float_eq(reference_pixel_area(&t, 2, 2), 0.5, 1e-12);
    cr_expect_float_eq(reference_pixel_area(&t, 1, 2), 0.0, 1e-12);
    struct vertex big[3] = { test_vertex(-10, -10), test_vertex(30, -10), test_vertex(-10, 30) };
    tri_setup(&t, big, 8, 8);
    cr_expect_float_eq(reference_pixel_area(&t, 4, 4), 1.0, 1e-12);
    /* a triangle cutting a corner off pixel (0, 0): x + y < 0.5 */
    struct vertex corner[3] = { test_vertex(0, 0), test_vertex(0.5, 0), test_vertex(0, 0.5) };
    tri_setup(&t, corner, 8, 8);
    cr_expect_float_eq(reference_pixel_area(&t, 0, 0), 0.125, 1e-12);
}

/* The numbers lessons/08-multisampling/README.md quotes ("Exhibits"). */
enum { SLIVER = 0, HORIZONTAL = 1, VERTICAL = 3, RECTANGLES = 5 };  /* first triangles */

Test(lesson08, exhibit_jaggies_fewer_with_more_samples)
{
    struct jaggies s1 = jaggies("msaa", SLIVER, 1, 1, 0.25), s4 = jaggies("msaa", SLIVER, 1, 4, 0.25),
                   s8 = jaggies("msaa", SLIVER, 1, 8, 0.25);
    struct jaggies h1 = jaggies("msaa", HORIZONTAL, 3, 1, 0.25), h4 = jaggies("msaa", HORIZONTAL, 3, 4, 0.25),
                   h8 = jaggies("msaa", HORIZONTAL, 3, 8, 0.25);
    cr_log_info("off by more than 1/4: sliver %d %d %d, near-horizontal %d %d %d\n", s1.off, s4.off,
                s8.off, h1.off, h4.off, h8.off);
    cr_expect(s1.off > s4.off && s4.off >= s8.off && h1.off > h4.off && h4.off >= h8.off);
    expect_quoted(README, "l08.sliver.off1", s1.off);
    expect_quoted(README, "l08.horizontal.off1", h1.off);
    cr_expect_eq(s4.off + s8.off + h4.off + h8.off, 0, "the text says: none at 4 or 8 samples");
    /* more than 1/N off: never at N = 4 on these edges, and only on the sliver at 8 */
    struct jaggies s4n = jaggies("msaa", SLIVER, 1, 4, 0.25), s8n = jaggies("msaa", SLIVER, 1, 8, 0.125);
    struct jaggies h4n = jaggies("msaa", HORIZONTAL, 3, 4, 0.25), h8n = jaggies("msaa", HORIZONTAL, 3, 8, 0.125);
    cr_log_info("off by more than 1/N: sliver %d %d, near-horizontal %d %d\n", s4n.off, s8n.off,
                h4n.off, h8n.off);
    cr_expect_eq(s4n.off + h4n.off + h8n.off, 0, "the text says: none but the sliver at 8");
    expect_quoted(README, "l08.sliver.off8n", s8n.off);
    expect_quoted(README, "l08.sliver.worst1", s1.worst);
}

Test(lesson08, exhibit_regular_grid_against_the_rotated_pattern)
{
    /* 4 samples on the near-horizontal and the near-vertical edge: the grid
     * has two rows (columns) of samples, so an edge nearly parallel to them
     * crosses both of a column's (row's) samples at once: even counts, and
     * estimates up to a quarter pixel off; the rotated pattern puts its 4
     * samples at 4 different heights and 4 different x. */
    const int first[2] = { HORIZONTAL, VERTICAL };
    for (int e = 0; e < 2; e++) {
        /* off by more than an eighth (half a step of 4 samples), above rounding */
        struct jaggies rot = jaggies("msaa", first[e], first[e] + 2, 4, 0.125 + 1e-9);
        struct jaggies grid = jaggies("grid", first[e], first[e] + 2, 4, 0.125 + 1e-9);
        cr_log_info("%s: off by more than 1/8: rotated %d, grid %d; odd counts %d, %d; worst %.3f, %.3f\n",
                    e ? "near-vertical" : "near-horizontal", rot.off, grid.off, rot.odd, grid.odd,
                    rot.worst, grid.worst);
        cr_expect_gt(grid.off, rot.off);
        cr_expect_gt(rot.odd, 2 * grid.odd, "the rotated pattern sees odd counts, the grid hardly");
        cr_expect_lt(rot.worst, grid.worst);
        cr_expect_eq(rot.off, 0, "the text says: the rotated pattern is never off by more than 1/8");
        cr_expect_eq(grid.odd, 0, "the text says: the grid never gives an odd count");
        cr_expect_float_eq(rot.worst, 0.125, 1e-6);
        expect_quoted(README, "l08.grid.off", grid.off);
        expect_quoted(README, "l08.grid.worst", grid.worst);
        expect_quoted(README, e ? "l08.vertical.odd" : "l08.horizontal.odd", rot.odd);
    }
}

/* --- resolve ---------------------------------------------------------------------- */

/* Perspective-correct colour of t at the point (px, py) in 1/256 units, in
 * double precision from the snapped vertices (1/z weighted, formula 23). */
static void colour_at(const struct tri_setup *t, double px, double py, double rgb[3], double *z)
{
    double a2 = (double)cross(t, 0, 1, t->x[2], t->y[2]);
    double w[3];
    /* weights from double cross products at a point that need not be integer */
    for (int i = 0; i < 3; i++) {
        int a = (i + 1) % 3, b = (i + 2) % 3;
        w[i] = (((double)t->x[b] - t->x[a]) * (py - t->y[a]) - (px - t->x[a]) * ((double)t->y[b] - t->y[a])) / a2;
    }
    double inv = 0, num[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; i++) {
        inv += w[i] / t->v[i].z;
        num[0] += w[i] * t->v[i].r / t->v[i].z;
        num[1] += w[i] * t->v[i].g / t->v[i].z;
        num[2] += w[i] * t->v[i].b / t->v[i].z;
    }
    for (int c = 0; c < 3; c++)
        rgb[c] = num[c] / inv;
    *z = 1 / inv;
}

Test(lesson08, resolved_colours_within_2_levels_of_a_reference_resolve, .timeout = 120)
{
    const int w = 32, h = 24, sizes[3] = { 1, 4, 8 };
    const char *names[2] = { "msaa", "ssaa" };
    struct rng r = rng_for(0x0804);
    int compared = 0;
    for (int m = 0; m < 30; m++) {
        int n = sizes[m % 3], nt = 6;
        const int (*pos)[2] = positions(n);
        struct vertex v[6][3];
        struct tri_setup t[6];
        for (int k = 0; k < nt; k++) {
            random_tri(&r, k % 2 ? CAT_GENERIC : CAT_SLIVER, w, h, v[k]);
            double z = 1 + k + rng_range(&r, 0, 0.5);   /* apart in depth: no near ties */
            for (int i = 0; i < 3; i++)
                v[k][i].z = z + rng_range(&r, 0, 0.4);
            tri_setup(&t[k], v[k], w, h);
        }
        for (int vi = 0; vi < 2; vi++) {
            struct raster_params p = default_params();
            p.samples = n;
            struct target fb;
            const uint32_t bg = 0xff102030u;
            cr_assert(target_init(&fb, w, h, bg));
            for (int k = nt - 1; k >= 0; k--)           /* far to near and near to far alike */
                variant(&lesson_08, names[vi])->rasterize(&t[(k * 5 + m) % nt], &p, &fb, NULL);
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    double sum[3] = { 0, 0, 0 };
                    for (int s = 0; s < n; s++) {
                        int64_t sx = (int64_t)x * 256 + pos[s][0], sy = (int64_t)y * 256 + pos[s][1];
                        double best = INFINITY;
                        uint32_t c = bg;
                        for (int k = 0; k < nt; k++) {
                            bool edge = false;
                            if (!covered_at(&t[k], sx, sy, &edge))
                                continue;
                            double rgb[3], z;
                            colour_at(&t[k], (double)sx, (double)sy, rgb, &z);
                            if (z < best) {
                                best = z;
                                if (vi == 0)    /* MSAA: the colour at the pixel centre */
                                    colour_at(&t[k], x * 256.0 + 128, y * 256.0 + 128, rgb, &z);
                                c = pack_rgb(rgb[0], rgb[1], rgb[2]);
                            }
                        }
                        for (int ch = 0; ch < 3; ch++)
                            sum[ch] += c >> (16 - 8 * ch) & 0xff;
                    }
                    uint32_t got = fb.color[y * w + x];
                    for (int ch = 0; ch < 3; ch++) {
                        double want = sum[ch] / n, have = got >> (16 - 8 * ch) & 0xff;
                        cr_assert(fabs(want - have) <= 2, "scene %d, %s, %d samples: pixel (%d, %d) "
                                  "channel %d is %g, the reference resolve %g", m, names[vi], n, x, y,
                                  ch, have, want);
                    }
                    compared++;
                }
            target_free(&fb);
        }
    }
    cr_expect_eq(compared, 30 * 2 * w * h);
}

/* --- what each way of shading costs ------------------------------------------------ */

static struct trace_counters run_counted_q(const char *vname, int n, int q)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "samples", err, sizeof err), "%s", err);
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, 0));
    struct raster_params p = default_params();
    p.samples = n;
    cr_assert(lesson_param_set(&lesson_08, &p, "block-size", q));
    struct trace_counters sum = { 0 };
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        struct trace tr = { 0 };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        variant(&lesson_08, vname)->rasterize(&t, &p, &fb, &tr);
        trace_counters_add(&sum, &sum, &tr.c);
    }
    target_free(&fb);
    scene_free(&s);
    return sum;
}

static struct trace_counters run_counted(const char *vname, int n)
{
    return run_counted_q(vname, n, 0);
}

Test(lesson08, supersampling_multiplies_the_shading_multisampling_does_not)
{
    struct trace_counters m1 = run_counted("msaa", 1), m4 = run_counted("msaa", 4),
                          m8 = run_counted("msaa", 8), s4 = run_counted("ssaa", 4),
                          s8 = run_counted("ssaa", 8);
    cr_log_info("mul: msaa 1 %llu, 4 %llu, 8 %llu; ssaa 4 %llu, 8 %llu\n",
                (unsigned long long)m1.mul, (unsigned long long)m4.mul, (unsigned long long)m8.mul,
                (unsigned long long)s4.mul, (unsigned long long)s8.mul);
    /* per covered sample MSAA adds a depth (one reciprocal), SSAA a depth and
     * a colour (a reciprocal and three attributes): its cost grows faster */
    cr_expect_lt(m4.mul, s4.mul);
    cr_expect_lt(m8.mul - m4.mul, s8.mul - s4.mul);
    cr_expect_lt(m4.mul, 2 * m1.mul, "MSAA at 4 samples: less than twice one sample");
    /* the numbers the lesson's text quotes */
    expect_quoted(README, "l08.mul.msaa1", (double)m1.mul);
    expect_quoted(README, "l08.mul.msaa4", (double)m4.mul);
    expect_quoted(README, "l08.mul.msaa8", (double)m8.mul);
    expect_quoted(README, "l08.mul.ssaa4", (double)s4.mul);
    expect_quoted(README, "l08.mul.ssaa8", (double)s8.mul);
#if !TRISTEP_NO_ANSWERS
    /* answer 2: the blocks full and the pixels tested at 1, 4 and 8 samples */
    struct trace_counters b1 = run_counted_q("msaa", 1, 8), b4 = run_counted_q("msaa", 4, 8),
                          b8 = run_counted_q("msaa", 8, 8);
    expect_quoted(ANSWERS, "l08.full1", (double)b1.blocks[BLOCK_FULL]);
    expect_quoted(ANSWERS, "l08.full4", (double)b4.blocks[BLOCK_FULL]);
    expect_quoted(ANSWERS, "l08.full8", (double)b8.blocks[BLOCK_FULL]);
    expect_quoted(ANSWERS, "l08.tested1", (double)b1.tested);
    expect_quoted(ANSWERS, "l08.tested4", (double)b4.tested);
    cr_expect_geq(b1.blocks[BLOCK_FULL], b4.blocks[BLOCK_FULL], "fewer full blocks with samples");
#endif
}

#if !TRISTEP_NO_ANSWERS
/* Answer 1: the offsets O_s of the edge (0, 0) - (8, 2) at 4 samples, as
 * the explorer's TRIANGLE section prints them. */
Test(lesson08, answer_1_offsets_as_the_explorer_prints_them)
{
    struct vertex v[3] = { test_vertex(0, 0), test_vertex(8, 2), test_vertex(0, 6) };
    struct tri_setup t;
    tri_setup(&t, v, 16, 16);
    const struct lesson_explorer *x = lesson_explorer_of(&lesson_08);
    cr_assert(x && x->constants);
    struct raster_params p = default_params();
    p.samples = 4;
    char buf[1024];
    x->constants(&t, &p, buf, sizeof buf);
    /* edge AB of the triangle as set up (t.swapped says whether B and C traded places) */
    const char *want[4] = { "O_0 = -2.750", "O_1 = -1.750", "O_2 = 1.750", "O_3 = 2.750" };
    const char *want_swapped[4] = { "O_0 = 2.750", "O_1 = 1.750", "O_2 = -1.750", "O_3 = -2.750" };
    for (int s = 0; s < 4; s++) {
        const char *w = t.swapped ? want_swapped[s] : want[s];
        bool found = false;
        for (const char *line = buf; line && *line && !found; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL)
            found = strncmp(line, w, strlen(w)) == 0;
        cr_expect(found, "no \"%s\" in:\n%s", w, buf);
    }
}
#endif
