/* test_lesson07.c - lesson 07's claims: the whole-scene run (bins, tiles in
 * cache, workers) covers exactly what the reference covers, on random scenes
 * of every category and on target sizes that are no multiple of a tile; it
 * writes the same bytes as drawing the triangles one after another; the
 * picture is the same bytes for 1, 2, 3 and 8 threads; the AVX2, SSE2 and
 * plain C twins write the same bytes; the shading agrees with the
 * double-precision reference within lesson 05's tolerances; the narration's
 * FULL and EMPTY tiles and blocks are what they say; and the exhibits lose
 * pixels (wrong corner) or change the picture (unordered bins).
 *
 * (The per-triangle path against the reference on 100,000 random triangles,
 * both builds, is test_property.c's job; ThreadSanitizer runs on the
 * threaded path in tsan_tiles below.) */
#define _POSIX_C_SOURCE 200809L     /* mkdtemp */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testlib.h"
#include "explore/explorer.h"
#include "explore/replay.h"

extern const struct lesson lesson_07, lesson_07_fast;

/* Lesson 05's tolerances: the same planes, a true division for z. */
#define COLOUR_TOLERANCE 1
#define DEPTH_REL_TOLERANCE 2e-6

static const struct lesson *const builds[] = { &lesson_07, &lesson_07_fast };

static const struct lesson_variant *variant(const struct lesson *l, const char *name)
{
    const struct lesson_variant *v = lesson_variant(l, name);
    cr_assert_not_null(v, "lesson 07 has no variant %s", name);
    return v;
}

/* A random scene of n triangles of mixed categories on a w x h target;
 * `layers`: every depth 1, so only the order of drawing decides colours. */
static void random_scene(struct scene *s, struct rng *rng, int w, int h, int n, bool layers,
                         int checker)
{
    memset(s, 0, sizeof *s);
    s->w = w, s->h = h;
    s->checker = checker;
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        enum tri_category c = (enum tri_category)rng_int(rng, 0, CAT_COUNT - 1);
        random_tri(rng, c, w, h, v);
        for (int k = 0; k < 3; k++) {
            if (layers)
                v[k].z = 1;
            if (checker) {
                v[k].s = rng_unit(rng);
                v[k].t = rng_unit(rng);
            }
        }
        cr_assert(scene_add(s, v));
    }
}

static void draw_whole(const struct lesson *l, const char *name, const struct scene *s,
                       const struct raster_params *p, struct target *fb)
{
    const struct lesson_variant *v = variant(l, name);
    rasterize_scene_fn whole = lesson_scene_fn(l, v);
    cr_assert_not_null(whole, "%s has no scene-level twin", name);
    cr_assert(target_init(fb, s->w, s->h, scene_background(s)));
    cr_assert(whole(s, p, fb), "%s: out of memory", name);
}

static bool same_bytes(const struct target *a, const struct target *b)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    return a->w == b->w && a->h == b->h && memcmp(a->color, b->color, n * sizeof *a->color) == 0
           && memcmp(a->depth, b->depth, n * sizeof *a->depth) == 0
           && memcmp(a->count, b->count, n) == 0;
}

/* Sizes: one tile, no multiple of 8, of 64, a single pixel, wide and tall. */
static const int sizes[][2] = {
    { 64, 48 }, { 1, 1 }, { 200, 130 }, { 129, 65 }, { 61, 253 }, { 333, 41 },
};

Test(lesson07, scene_coverage_equals_the_reference_for_every_exact_variant)
{
    struct rng rng = rng_for(0x07c0);
    struct raster_params p = default_params();
    int scenes = 0;
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (int rep = 0; rep < 4; rep++) {
            struct scene s;
            random_scene(&s, &rng, sizes[si][0], sizes[si][1], 120, false, 0);
            uint8_t *ref = reference_scene(&s);
            cr_assert_not_null(ref);
            for (int b = 0; b < 2; b++)
                for (int vi = 0; vi < builds[b]->nvariants; vi++) {
                    const struct lesson_variant *v = &builds[b]->variants[vi];
                    if (variant_against_exact(v))
                        continue;
                    struct target fb;
                    draw_whole(builds[b], v->name, &s, &p, &fb);
                    char what[128];
                    snprintf(what, sizeof what, "07-tiles/%s (%s), scene %d of %d x %d", v->name,
                             b ? "fast" : "narrated", rep, s.w, s.h);
                    struct case_info info = { .what = what, .seed = test_seed(),
                                              .index = (uint64_t)scenes };
                    cr_assert(coverage_equal(ref, fb.count, s.w, s.h, &info));
                    target_free(&fb);
                }
            free(ref);
            scene_free(&s);
            scenes++;
        }
}

/* Bins and tiles change the order of the work, never the picture: the same
 * bytes as every triangle through `rasterize`, one after another. */
Test(lesson07, scene_run_writes_the_bytes_of_the_triangle_by_triangle_run)
{
    struct rng rng = rng_for(0x07b1);
    struct raster_params p = default_params();
    for (int rep = 0; rep < 6; rep++) {
        struct scene s;
        random_scene(&s, &rng, 200 + rep * 17, 140 - rep * 9, 200, rep % 2 == 0, rep % 3 == 2 ? 6 : 0);
        p.checker = s.checker;
        for (int b = 0; b < 2; b++) {
            struct target one, whole;
            cr_assert(render_scene(&s, variant(builds[b], "tiles"), &p, &one));
            draw_whole(builds[b], "tiles", &s, &p, &whole);
            cr_assert(same_bytes(&one, &whole), "scene %d (%s): the tiled run differs from the "
                      "triangle-by-triangle run", rep, b ? "fast" : "narrated");
            target_free(&one);
            target_free(&whole);
        }
        scene_free(&s);
    }
}

/* Scene order kept inside every tile: any number of workers, the same bytes,
 * on layers at one depth where the order alone decides the colours. */
Test(lesson07, picture_is_the_same_bytes_for_1_2_3_and_8_threads)
{
    struct rng rng = rng_for(0x07d2);
    static const int threads[] = { 1, 2, 3, 8 };
    for (int rep = 0; rep < 5; rep++) {
        struct scene s;
        random_scene(&s, &rng, 300, 200, 400, true, rep == 4 ? 4 : 0);
        struct raster_params p = default_params();
        p.checker = s.checker;
        struct target first;
        for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
            lesson_param_set(&lesson_07, &p, "threads", threads[k]);
            for (int b = 0; b < 2; b++) {
                for (int again = 0; again < 3; again++) {
                    struct target fb;
                    draw_whole(builds[b], "tiles", &s, &p, &fb);
                    if (k == 0 && b == 0 && again == 0) {
                        first = fb;
                        continue;
                    }
                    cr_assert(same_bytes(&first, &fb), "scene %d: %d threads (%s, run %d) "
                              "differ from 1 thread", rep, threads[k], b ? "fast" : "narrated", again);
                    target_free(&fb);
                }
            }
        }
        target_free(&first);
        scene_free(&s);
    }
}

/* The three twins of the pixel work write the same bytes, textured or not,
 * with tile buffers or in place. */
Test(lesson07, avx2_sse2_and_plain_c_twins_write_the_same_bytes)
{
    struct rng rng = rng_for(0x07e3);
    static const char *const names[] = { "sse2", "scalar", "in-place", "1-thread" };
    for (int rep = 0; rep < 8; rep++) {
        struct scene s;
        random_scene(&s, &rng, 150 + 13 * rep, 90 + 7 * rep, 150, rep % 4 == 1, rep % 2 ? 5 : 0);
        struct raster_params p = default_params();
        p.checker = s.checker;
        for (int b = 0; b < 2; b++) {
            struct target best;     /* AVX2 where the CPU has it */
            draw_whole(builds[b], "tiles", &s, &p, &best);
            for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
                struct target fb;
                draw_whole(builds[b], names[k], &s, &p, &fb);
                cr_assert(same_bytes(&best, &fb), "scene %d (%s): %s differs from tiles", rep,
                          b ? "fast" : "narrated", names[k]);
                target_free(&fb);
            }
            target_free(&best);
        }
        scene_free(&s);
    }
}

Test(lesson07, shading_is_perspective_correct_within_lesson_05s_tolerance)
{
    struct rng rng = rng_for(0x07f4);
    int checked = 0;
    for (int sc = 0; sc < 16; sc++) {
        struct vertex v[3];
        int w = 150, h = 100;
        random_tri(&rng, sc % 3 ? CAT_LARGE : CAT_GENERIC, w, h, v);
        for (int k = 0; k < 3; k++)
            v[k].z = rng_range(&rng, 0.5, 50.0);
        struct scene s = { .w = w, .h = h };
        cr_assert(scene_add(&s, v));
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        struct raster_params p = default_params();
        for (int b = 0; b < 2; b++) {
            struct target fb;
            draw_whole(builds[b], "tiles", &s, &p, &fb);
            char why[160];
            int k = reference_shading_check(&fb, &t, COLOUR_TOLERANCE, DEPTH_REL_TOLERANCE, why, sizeof why);
            cr_assert_geq(k, 0, "%s: %s", b ? "fast build" : "narrated build", why);
            checked += k;
            target_free(&fb);
        }
        scene_free(&s);
    }
    cr_assert_gt(checked, 20000, "only %d pixels compared", checked);
}

/* Triangles reaching the guard band's corners: (E) stays exact in int32. */
Test(lesson07, guard_band_triangles_stay_exact)
{
    static const double tri[][6] = {
        { -16383.9, -16383.9, 16383.9, -16000.1, 0.5, 16383.9 },
        { -16000.3, 100.7, 16300.1, 40.2, 30.5, 16200.9 },
        { 63.99, -16384, 64.01, 16383.5, -16384, 47.5 },
        { 16383.99, 0.5, -16384, 0.5, 100.25, 100.5 },
    };
    for (size_t k = 0; k < sizeof tri / sizeof tri[0]; k++) {
        struct scene s = { .w = 301, .h = 203 };
        struct vertex v[3] = { test_vertex(tri[k][0], tri[k][1]), test_vertex(tri[k][2], tri[k][3]),
                               test_vertex(tri[k][4], tri[k][5]) };
        cr_assert(scene_add(&s, v));
        uint8_t *ref = reference_scene(&s);
        cr_assert_not_null(ref);
        int covered = 0;
        for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++)
            covered += ref[i];
        cr_assert_gt(covered, 100, "triangle %zu covers only %d pixels", k, covered);
        struct raster_params p = default_params();
        for (int b = 0; b < 2; b++)
            for (int vi = 0; vi < builds[b]->nvariants; vi++) {
                if (variant_against_exact(&builds[b]->variants[vi]))
                    continue;
                struct target fb;
                draw_whole(builds[b], builds[b]->variants[vi].name, &s, &p, &fb);
                struct case_info info = { .what = builds[b]->variants[vi].name, .v = v, .nv = 3 };
                cr_assert(coverage_equal(ref, fb.count, s.w, s.h, &info));
                target_free(&fb);
            }
        free(ref);
        scene_free(&s);
    }
}

/* --- the narration: tiles and blocks are what they say ------------------------ */

struct seen {
    const uint8_t *ref;     /* the triangle's reference coverage */
    int w, h;
    int tiles[BLOCK_CLASS_COUNT], blocks[BLOCK_CLASS_COUNT];
    int full_not_full, empty_not_empty, small;
};

static void on_event(void *ctx, const struct trace_event *ev)
{
    struct seen *s = ctx;
    if (ev->kind != TRACE_BLOCK)
        return;
    bool tile = ev->aux[1] == 0;
    if (ev->klass < BLOCK_CLASS_COUNT)
        (tile ? s->tiles : s->blocks)[ev->klass]++;
    s->small += ev->line == 8;
    for (int y = ev->y; y <= ev->y1; y++)
        for (int x = ev->x; x <= ev->x1; x++) {
            if (x < 0 || y < 0 || x >= s->w || y >= s->h)
                continue;
            bool in = s->ref[(size_t)y * (size_t)s->w + (size_t)x];
            s->full_not_full += ev->klass == BLOCK_FULL && !in;
            s->empty_not_empty += ev->klass == BLOCK_EMPTY && in;
        }
}

Test(lesson07, full_and_empty_tiles_and_blocks_are_what_they_say)
{
    struct rng rng = rng_for(0x07a5);
    struct seen total = { 0 };
    int w = 260, h = 190;
    uint8_t *ref = malloc((size_t)w * (size_t)h);
    cr_assert_not_null(ref);
    for (int rep = 0; rep < 300; rep++) {
        struct vertex v[3];
        random_tri(&rng, rep % 3 == 0 ? CAT_LARGE : rep % 3 == 1 ? CAT_GENERIC : CAT_OFFSCREEN, w, h, v);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        memset(ref, 0, (size_t)w * (size_t)h);
        reference_mask(&t, ref);
        struct seen s = { .ref = ref, .w = w, .h = h };
        struct target fb;
        cr_assert(target_init(&fb, w, h, 0xff000000u));
        struct trace tr = { .sink = on_event, .ctx = &s };
        trace_begin(&tr, 0, TRACE_UNLIMITED);
        rasterize_one(variant(&lesson_07, "tiles"), NULL, &t, &fb, &tr);
        cr_assert_eq(s.full_not_full, 0, "case %d: a FULL tile or block holds uncovered pixels", rep);
        cr_assert_eq(s.empty_not_empty, 0, "case %d: an EMPTY tile or block holds covered pixels", rep);
        for (int k = 0; k < BLOCK_CLASS_COUNT; k++) {
            total.tiles[k] += s.tiles[k];
            total.blocks[k] += s.blocks[k];
        }
        total.small += s.small;
        target_free(&fb);
    }
    free(ref);
    /* and every kind of decision happened */
    for (int k = 0; k < BLOCK_CLASS_COUNT; k++) {
        cr_expect_gt(total.tiles[k], 10, "tiles of class %d: %d", k, total.tiles[k]);
        cr_expect_gt(total.blocks[k], 10, "blocks of class %d: %d", k, total.blocks[k]);
    }
    cr_expect_gt(total.small, 10, "small-triangle paths: %d", total.small);
}

/* --- the exhibits ------------------------------------------------------------------ */

Test(lesson07, wrong_corner_loses_pixels_and_adds_none)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_07.exhibit_scene, err, sizeof err), "%s", err);
    uint8_t *ref = reference_scene(&s);
    cr_assert_not_null(ref);
    struct raster_params p = default_params();
    for (int b = 0; b < 2; b++) {
        struct target fb;
        draw_whole(builds[b], "wrong-corner", &s, &p, &fb);
        int missing = 0, extra = 0;
        for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++) {
            missing += ref[i] > fb.count[i];
            extra += fb.count[i] > ref[i];
        }
        cr_expect_gt(missing, 500, "the wrong corner lost only %d pixels", missing);
        cr_expect_eq(extra, 0, "the wrong corner added %d pixels", extra);
        target_free(&fb);
    }
    free(ref);
    scene_free(&s);
}

/* Unordered bins: on one thread there is one share, so the order is kept;
 * coverage never changes, only which of two layers at one depth shows. */
Test(lesson07, unordered_bins_keep_coverage_and_one_thread_keeps_the_picture)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_07.exhibit_scene, err, sizeof err), "%s", err);
    uint8_t *ref = reference_scene(&s);
    cr_assert_not_null(ref);
    struct raster_params p = default_params();
    struct target exact, one, two;
    draw_whole(&lesson_07_fast, "tiles", &s, &p, &exact);
    lesson_param_set(&lesson_07, &p, "threads", 1);
    draw_whole(&lesson_07_fast, "unordered", &s, &p, &one);
    cr_assert(same_bytes(&exact, &one), "unordered on one thread changed the picture");
    lesson_param_set(&lesson_07, &p, "threads", 2);
    draw_whole(&lesson_07_fast, "unordered", &s, &p, &two);
    cr_assert(memcmp(ref, two.count, (size_t)s.w * (size_t)s.h) == 0, "unordered changed coverage");
    target_free(&exact);
    target_free(&one);
    target_free(&two);
    free(ref);
    scene_free(&s);
}

/* --- ThreadSanitizer ---------------------------------------------------------------- */

/* make test builds BUILD/tsan-tiles (tests/tsan/tsan_tiles.c, the lesson and
 * the raster core compiled with -fsanitize=thread): it draws random scenes
 * on 2, 3 and 8 threads and compares them with one thread. Criterion does
 * not run under TSan, so it is a program of its own, run from here. */
Test(lesson07, threaded_path_is_clean_under_threadsanitizer)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "%s/tsan-tiles 2>&1", test_build_dir());
    FILE *f = popen(cmd, "r");
    cr_assert_not_null(f);
    char line[512];
    bool report = false, done = false;
    while (fgets(line, sizeof line, f)) {
        report = report || strstr(line, "ThreadSanitizer") != NULL;
        done = done || strstr(line, "tsan-tiles: ok") != NULL;
    }
    int status = pclose(f);
    cr_assert(!report, "ThreadSanitizer reported a race (run %s/tsan-tiles)", test_build_dir());
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0 && done,
              "%s/tsan-tiles failed (status 0x%x)", test_build_dir(), status);
}

/* Unit i of the n units u, as replay_params hands it to `rasterize`
 * (where it stands in *at). */
static struct raster_params unit_params(const struct raster_params *p, const struct lesson_unit *u,
                                        long i, long n, struct run_place *at)
{
    struct raster_params up = *p;
    *at = (struct run_place){ .unit = &u[i], .units = u, .nunits = (int)n };
    up.at = at;
    return up;
}

/* The narrated run of variant `name` on `threads` workers: its units, one
 * after another, as the explorer replays them (the oracle is the lesson's
 * own list of units and its per-triangle rasterize). */
static void draw_units(const char *name, const struct scene *s, int threads, struct target *fb)
{
    const struct lesson_variant *v = variant(&lesson_07, name);
    struct raster_params p = default_params();
    lesson_param_set(&lesson_07, &p, "threads", threads);
    long n = lesson_07.narration_units(s, v, &p, NULL, 0);
    cr_assert_geq(n, 0);
    struct lesson_unit *u = malloc((size_t)(n ? n : 1) * sizeof *u);
    cr_assert_not_null(u);
    cr_assert_eq(lesson_07.narration_units(s, v, &p, u, n), n);
    cr_assert(target_init(fb, s->w, s->h, scene_background(s)));
    for (long i = 0; i < n; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[u[i].tri].v, s->w, s->h);
        struct run_place at;
        struct raster_params up = unit_params(&p, u, i, n, &at);
        v->rasterize(&t, &up, fb, NULL);
    }
    free(u);
}

static int colours_differing(const struct target *a, const struct target *b)
{
    int d = 0;
    for (size_t i = 0; i < (size_t)a->w * (size_t)a->h; i++)
        d += a->color[i] != b->color[i];
    return d;
}

#define README "lessons/07-tiles/README.md"

static void expect_quoted(const char *key, double got)
{
    double tol;
    double quoted = text_number(README, key, &tol);
    cr_expect(fabs(quoted - got) <= tol, "%s quotes %g for %s, the lesson computes %.17g", README,
              quoted, key, got);
}

/* What the lesson text quotes about its exhibits' scene: the pixels the
 * wrong corner leaves without a triangle they have (of the covered pixels,
 * overdraw included); without per-tile order the layers at one depth come
 * out differently on 2 and on 3 workers (the narrated schedule, the same on
 * every run), and the narrated exact run is the scene run. */
Test(lesson07, exhibit_numbers_quoted_in_the_text)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_07.exhibit_scene, err, sizeof err), "%s", err);
    uint8_t *ref = reference_scene(&s);
    cr_assert_not_null(ref);
    struct raster_params p = default_params();
    struct target wrong;
    draw_whole(&lesson_07_fast, "wrong-corner", &s, &p, &wrong);
    int covered = 0, missing = 0;
    for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++) {
        covered += ref[i];
        missing += ref[i] > wrong.count[i];     /* pixels that lost a triangle */
    }
    expect_quoted("l07.exhibits.covered", covered);
    expect_quoted("l07.wrong-corner.missing", missing);

    struct target exact, two, three, whole;
    draw_units("tiles", &s, 2, &exact);
    draw_units("unordered", &s, 2, &two);
    draw_units("unordered", &s, 3, &three);
    draw_whole(&lesson_07_fast, "tiles", &s, &p, &whole);
    cr_assert(same_bytes(&exact, &whole), "the narrated exact run differs from the scene run");
    int d2 = colours_differing(&exact, &two), d3 = colours_differing(&exact, &three);
    int d23 = colours_differing(&two, &three);
    expect_quoted("l07.unordered.diff2", d2);
    expect_quoted("l07.unordered.diff3", d3);
    expect_quoted("l07.unordered.diff23", d23);
    cr_expect_gt(d2, 0);
    cr_expect_gt(d3, 0);
    target_free(&wrong);
    target_free(&exact);
    target_free(&two);
    target_free(&three);
    target_free(&whole);
    free(ref);
    scene_free(&s);
}

/* The explorer's diff of the exhibit `unordered` (figure 07-unordered-diff):
 * once every unit is finished, the picture is compared with the scene as
 * the lesson draws it in order, and the pixels whose colour differs are
 * marked; coverage is the same, so nothing is extra or missing. Before the
 * end the units of another order compare nothing. The count is the one the
 * text quotes, and the one of the narrated run drawn unit by unit. */
Test(lesson07, explorer_marks_the_pixels_unordered_threads_change)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, lesson_07.exhibit_scene, err, sizeof err), "%s", err);
    for (int threads = 2; threads <= 3; threads++) {
        struct explorer ex;
        struct raster_params p = default_params();
        lesson_param_set(&lesson_07, &p, "threads", threads);
        cr_assert(explorer_init(&ex, &(struct explorer_desc){ .lesson = &lesson_07, .scene = &s,
                                                             .variant = variant(&lesson_07, "unordered"),
                                                             .params = &p, .step_end = true },
                                err, sizeof err), "%s", err);
        cr_expect_eq(ex.extra, 0);
        cr_expect_eq(ex.missing, 0);
        expect_quoted(threads == 2 ? "l07.unordered.diff2" : "l07.unordered.diff3", (double)ex.wrong_colour);
        uint64_t marked = 0;
        for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++)
            marked += ex.diff[i] == EXHIBIT_COLOUR;
        cr_expect_eq(marked, ex.wrong_colour);
        /* one step before the end: the exhibit's order, nothing compared */
        cr_assert(explorer_set_step(&ex, ex.replay.total - 1));
        cr_expect_eq(ex.extra + ex.missing + ex.wrong_colour, 0);
        explorer_free(&ex);
    }
    scene_free(&s);
}

/* The whole file at path, malloc'ed, its size in *n. */
static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s: not written", path);
    unsigned char *buf = malloc(1 << 20);
    cr_assert_not_null(buf);
    *n = fread(buf, 1, 1 << 20, f);
    cr_assert(feof(f), "%s: larger than 1 MiB", path);
    fclose(f);
    return buf;
}

/* Lesson 07 reads 3-D scenes like every lesson from 05 on: the program's
 * headless run (the shared front end, then bins and tiles on 2 workers)
 * covers exactly the pixels that lesson 05's program covers, on every
 * built-in 3-D scene. */
Test(lesson07, program_covers_3d_scenes_as_lesson_05_does, .timeout = 60)
{
    char dir[] = "/tmp/tristep-l07-3d-XXXXXX";
    cr_assert(mkdtemp(dir));
    int scenes = 0;
    for (int i = 0; i < builtin_scene_count; i++) {
        if (!strstr(builtin_scenes[i].text, "\ncamera "))
            continue;
        const char *const progs[] = { "07-tiles --threads 2", "05-block-classification" };
        unsigned char *pgm[2];
        size_t n[2];
        for (int k = 0; k < 2; k++) {
            char path[256], cmd[1024];
            snprintf(path, sizeof path, "%s/%d.pgm", dir, k);
            snprintf(cmd, sizeof cmd, "%s/%s --scene builtin:%s --dump-coverage %s", test_build_dir(),
                     progs[k], builtin_scenes[i].name, path);
            int st = system(cmd);
            cr_assert(WIFEXITED(st) && WEXITSTATUS(st) == 0, "%s: status 0x%x", cmd, st);
            pgm[k] = slurp(path, &n[k]);
            remove(path);
        }
        cr_assert(n[0] == n[1] && memcmp(pgm[0], pgm[1], n[0]) == 0,
                  "builtin:%s: lesson 07 covers other pixels than lesson 05", builtin_scenes[i].name);
        size_t covered = 0, k = 0;  /* the pixels follow the header's 3 lines */
        for (int lines = 0; k < n[0] && lines < 3; k++)
            lines += pgm[0][k] == '\n';
        for (; k < n[0]; k++)
            covered += pgm[0][k] != 0;
        cr_assert_gt(covered, 0, "builtin:%s: nothing covered", builtin_scenes[i].name);
        free(pgm[0]);
        free(pgm[1]);
        scenes++;
    }
    rmdir(dir);
    cr_assert_geq(scenes, 4, "only %d built-in 3-D scenes", scenes);
}

/* --- the explorer steps through the timed run ---------------------------------------- */

/* What a narrated step wrote, seen from its events: every PIXEL_WRITE inside
 * the step's tile (its whole picture for a set-up and binning step: none). */
struct writes {
    int x0, y0, x1, y1;         /* the tile; x1 < x0: no write allowed */
    int outside, writes;
    bool lit[32];               /* pseudo-code lines lit */
};

static void on_write(void *ctx, const struct trace_event *ev)
{
    struct writes *w = ctx;
    if (ev->line < 32)
        w->lit[ev->line] = true;
    if (ev->kind != TRACE_PIXEL_WRITE)
        return;
    w->writes++;
    w->outside += ev->x < w->x0 || ev->x > w->x1 || ev->y < w->y0 || ev->y > w->y1;
}

/* A random scene of n triangles on a w x h screen (textured with a
 * checker when checker > 0) and the params that draw it on `threads`
 * workers. */
static void random_run(struct scene *s, struct raster_params *p, struct rng *rng, int w, int h,
                       int n, int checker, int threads)
{
    random_scene(s, rng, w, h, n, true, checker);
    *p = default_params();
    p->checker = s->checker;
    cr_assert(lesson_param_set(&lesson_07, p, "threads", threads));
}

/* The explorer's steps of the scene run, as replay_params hands them to
 * `rasterize`, narrated and fast side by side: after every step both
 * pictures are the same bytes, the narrated step writes only inside its
 * tile, each tile's bin is drawn in scene order with its entries numbered
 * 0, 1, ... by one worker of the run, and the last picture is the fast
 * build's timed scene run. So the narrated build writes the pixels of the
 * fast build, in the same order per tile. */
Test(lesson07, narrated_steps_write_the_fast_builds_pixels_tile_by_tile)
{
    struct rng rng = rng_for(0x07e7);
    for (int rep = 0; rep < 4; rep++) {
        struct scene s;
        struct raster_params p;
        int threads = 1 + rep % 3;
        random_run(&s, &p, &rng, 200 + 31 * rep, 150 - 17 * rep, 150, rep == 3 ? 5 : 0, threads);
        const struct lesson_variant *vn = variant(&lesson_07, "tiles");
        const struct lesson_variant *vf = variant(&lesson_07_fast, "tiles");
        long n = lesson_07.narration_units(&s, vn, &p, NULL, 0);
        cr_assert_gt(n, s.ntris);
        struct lesson_unit *u = malloc((size_t)n * sizeof *u);
        cr_assert_not_null(u);
        cr_assert_eq(lesson_07.narration_units(&s, vn, &p, u, n), n);
        struct target a, b, whole;
        cr_assert(target_init(&a, s.w, s.h, scene_background(&s)));
        cr_assert(target_init(&b, s.w, s.h, scene_background(&s)));
        int nx = (s.w + 63) / 64, tiles = nx * ((s.h + 63) / 64);
        int *next_entry = calloc((size_t)tiles, sizeof *next_entry);
        int *worker = malloc((size_t)tiles * sizeof *worker);
        uint32_t *last_tri = calloc((size_t)tiles, sizeof *last_tri);
        cr_assert(next_entry && worker && last_tri);
        int writes = 0;
        for (long i = 0; i < n; i++) {
            struct run_place at;
            struct raster_params up = unit_params(&p, u, i, n, &at);
            struct writes w = { 0, 0, -1, -1, 0, 0, { false } };
            int tile = u[i].tile;
            if (tile >= 0) {
                w.x0 = tile % nx * 64, w.y0 = tile / nx * 64, w.x1 = w.x0 + 63, w.y1 = w.y0 + 63;
                cr_assert_eq(u[i].bin_entry, next_entry[tile], "step %ld: tile %d's entries "
                             "out of order", i, tile);
                if (u[i].bin_entry == 0)
                    worker[tile] = u[i].thread;
                cr_assert_eq(u[i].thread, worker[tile], "tile %d: two workers", tile);
                cr_assert(u[i].thread >= 0 && u[i].thread < threads);
                cr_assert(u[i].bin_entry == 0 || u[i].tri > last_tri[tile],
                          "tile %d: its bin is not drawn in scene order", tile);
                next_entry[tile]++;
                last_tri[tile] = u[i].tri;
            }
            struct tri_setup t;
            tri_setup(&t, s.tris[u[i].tri].v, s.w, s.h);
            struct trace tr = { .sink = on_write, .ctx = &w };
            trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
            vn->rasterize(&t, &up, &a, &tr);
            vf->rasterize(&t, &up, &b, NULL);
            cr_assert_eq(w.outside, 0, "step %ld wrote outside its tile", i);
            writes += w.writes;
            cr_assert(same_bytes(&a, &b), "scene %d, step %ld: the narrated and the fast build "
                      "differ", rep, i);
        }
        for (int tile = 0; tile < tiles; tile++)    /* every bin drawn to its end */
            for (long i = 0; i < n; i++)
                if (u[i].tile == tile)
                    cr_assert_eq(next_entry[tile], u[i].bin_size, "tile %d: bin not finished", tile);
        cr_assert_gt(writes, 0);
        draw_whole(&lesson_07_fast, "tiles", &s, &p, &whole);
        cr_assert(same_bytes(&a, &whole), "scene %d: the narrated steps differ from the timed run", rep);
        free(next_entry);
        free(worker);
        free(last_tri);
        free(u);
        target_free(&a);
        target_free(&b);
        target_free(&whole);
        scene_free(&s);
    }
}

/* tiles.c: the units as a narrated run that draws every pixel records them */
long tiles_drawn_units(const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, struct lesson_unit *out, long cap);

/* The units that `f` lists for variant v, counted (*n) then written. */
static struct lesson_unit *units_by(lesson_units_fn f, const struct scene *s,
                                    const struct lesson_variant *v, const struct raster_params *p,
                                    long *n)
{
    *n = f(s, v, p, NULL, 0);
    cr_assert_gt(*n, s->ntris, "%s", v->name);
    struct lesson_unit *u = malloc((size_t)*n * sizeof *u);
    cr_assert_not_null(u);
    cr_assert_eq(f(s, v, p, u, *n), *n, "%s", v->name);
    return u;
}

/* The explorer's list of steps comes from a run that draws no pixel: it is
 * the list that the whole narrated run, drawing every pixel, records, unit
 * for unit, for every variant, on one to three workers. */
Test(lesson07, the_steps_are_those_of_the_drawing_run)
{
    struct rng rng = rng_for(0x07d7);
    for (int rep = 0; rep < 3; rep++) {
        struct scene s;
        struct raster_params p;
        random_run(&s, &p, &rng, 190 + 37 * rep, 140 - 11 * rep, 120, rep == 2 ? 5 : 0, 1 + rep);
        for (int vi = 0; vi < lesson_07.nvariants; vi++) {
            const struct lesson_variant *v = &lesson_07.variants[vi];
            long n, m;
            struct lesson_unit *a = units_by(lesson_07.narration_units, &s, v, &p, &n);
            struct lesson_unit *b = units_by(tiles_drawn_units, &s, v, &p, &m);
            cr_assert_eq(n, m, "%s: another number of steps", v->name);
            for (long i = 0; i < n; i++)
                cr_assert(a[i].tri == b[i].tri && a[i].tile == b[i].tile
                          && a[i].bin_size == b[i].bin_size && a[i].bin_entry == b[i].bin_entry
                          && a[i].thread == b[i].thread,
                          "scene %d, %s, step %ld: (%u, %d, %d/%d, %d) instead of (%u, %d, %d/%d, %d)",
                          rep, v->name, i, a[i].tri, a[i].tile, a[i].bin_entry, a[i].bin_size,
                          a[i].thread, b[i].tri, b[i].tile, b[i].bin_entry, b[i].bin_size, b[i].thread);
            free(a);
            free(b);
        }
        scene_free(&s);
    }
}

/* Every line of the pseudo-code is lit by some event of the explorer's
 * steps, on the lesson's built-in scenes and its variants. */
Test(lesson07, every_pseudocode_line_is_lit)
{
    struct writes w = { 0, 0, INT32_MAX, INT32_MAX, 0, 0, { false } };
    const char *scenes[] = { lesson_07.builtin_scene, lesson_07.exhibit_scene };
    for (int k = 0; k < 2; k++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, scenes[k], err, sizeof err), "%s", err);
        for (int vi = 0; vi < lesson_07.nvariants; vi++) {
            const struct lesson_variant *v = &lesson_07.variants[vi];
            struct raster_params p = default_params();
            p.checker = s.checker;
            long n = lesson_07.narration_units(&s, v, &p, NULL, 0);
            cr_assert_geq(n, 0);
            struct lesson_unit *u = malloc((size_t)(n ? n : 1) * sizeof *u);
            cr_assert_not_null(u);
            cr_assert_eq(lesson_07.narration_units(&s, v, &p, u, n), n);
            struct target fb;
            cr_assert(target_init(&fb, s.w, s.h, scene_background(&s)));
            for (long i = 0; i < n; i++) {
                struct run_place at;
                struct raster_params up = unit_params(&p, u, i, n, &at);
                struct tri_setup t;
                tri_setup(&t, s.tris[u[i].tri].v, s.w, s.h);
                struct trace tr = { .sink = on_write, .ctx = &w };
                trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
                v->rasterize(&t, &up, &fb, &tr);
            }
            target_free(&fb);
            free(u);
        }
        scene_free(&s);
    }
    for (int line = 0; lesson_07.pseudocode[line]; line++)
        cr_expect(w.lit[line], "pseudo-code line %d (\"%s\") is lit by no event", line,
                  lesson_07.pseudocode[line]);
}
