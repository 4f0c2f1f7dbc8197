/* test_lesson08_tiles.c - lesson 08's twin `tiles` (msaa on lesson 07's
 * bins and workers, samples in tile buffers, resolved at the tile's store)
 * writes msaa's bytes: colours, depths, coverage counts and every sample,
 * at 1, 4 and 8 samples, for every thread count, in both builds; its
 * per-sample coverage is the exact rule's over many tiles; and the
 * explorer's units of its run, drawn one after another, make the same
 * picture. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "explore/replay.h"

extern const struct lesson lesson_08, lesson_08_fast;

/* Mixed triangles over several 64 x 64 tiles, some vertices on the standard
 * 4- and 8-sample positions (edges through samples), some a checker. */
static void random_scene(struct scene *s, struct rng *rng, int w, int h, int n, int checker)
{
    static const int on[][2] = { { 96, 32 }, { 224, 96 }, { 32, 160 }, { 160, 224 }, { 144, 80 },
                                 { 112, 176 }, { 208, 144 }, { 80, 48 }, { 240, 16 } };
    memset(s, 0, sizeof *s);
    s->w = w, s->h = h, s->checker = checker;
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        random_tri(rng, (enum tri_category)rng_int(rng, 0, CAT_COUNT - 1), w, h, v);
        for (int k = 0; k < 3 && i % 3 == 0; k++) {
            int q = rng_int(rng, 0, 8);
            v[k].x = rng_int(rng, -2, w + 1) + on[q][0] / 256.0;
            v[k].y = rng_int(rng, -2, h + 1) + on[q][1] / 256.0;
        }
        for (int k = 0; k < 3 && checker; k++)
            v[k].s = rng_unit(rng), v[k].t = rng_unit(rng);
        cr_assert(scene_add(s, v));
    }
}

static void expect_same(const struct target *a, const struct target *b, const char *what)
{
    size_t m = (size_t)a->w * (size_t)a->h;
    cr_assert_eq(memcmp(a->color, b->color, m * sizeof *a->color), 0, "%s: colours differ", what);
    cr_assert_eq(memcmp(a->depth, b->depth, m * sizeof *a->depth), 0, "%s: depths differ", what);
    cr_assert_eq(memcmp(a->count, b->count, m), 0, "%s: coverage counts differ", what);
    cr_assert_eq(!a->samples, !b->samples, "%s: one has samples, the other not", what);
    if (a->samples) {
        size_t k = m * (size_t)a->samples->n;
        cr_assert_eq(a->samples->n, b->samples->n, "%s", what);
        cr_assert_eq(memcmp(a->samples->color, b->samples->color, k * 4), 0, "%s: samples differ", what);
        cr_assert_eq(memcmp(a->samples->depth, b->samples->depth, k * 4), 0, "%s: sample depths differ",
                     what);
    }
}

/* msaa triangle by triangle (the narrated algorithm) against tiles on the
 * whole scene, every thread count from 1 to 8 and the default, both builds. */
Test(lesson08_tiles, writes_msaas_bytes_at_every_sample_count_and_thread_count, .timeout = 120)
{
    struct rng rng = rng_for(0x0825);
    const struct lesson *builds[2] = { &lesson_08, &lesson_08_fast };
    int cases = 0;
    for (int sc = 0; sc < 4; sc++) {
        struct scene s;
        char err[256];
        if (sc == 0)
            cr_assert(scene_builtin(&s, "tiles", err, sizeof err), "%s", err);
        else
            random_scene(&s, &rng, 150 + 37 * sc, 90 + 23 * sc, 150, sc == 2 ? 5 : 0);
        for (int n = 1; n <= 8; n *= 2) {
            if (n == 2)
                continue;
            struct raster_params p = default_params();
            p.samples = n;
            p.checker = s.checker;
            struct target ref;
            cr_assert(render_scene(&s, lesson_variant(&lesson_08, "msaa"), &p, &ref));
            for (int b = 0; b < 2; b++)
                for (int threads = 0; threads <= 8; threads++) {
                    const struct lesson_variant *v = lesson_variant(builds[b], "tiles");
                    cr_assert_not_null(v);
                    cr_assert(lesson_param_set(builds[b], &p, "threads", threads));
                    struct target fb;
                    cr_assert(render_lesson_scene(builds[b], &s, v, &p, &fb));
                    char what[128];
                    snprintf(what, sizeof what, "scene %d, %d samples, %s build, threads %d", sc, n,
                             b ? "fast" : "narrated", threads);
                    expect_same(&ref, &fb, what);
                    target_free(&fb);
                    cases++;
                }
            /* one triangle at a time through the tiles (the tests' and the
             * replay's entry point) */
            cr_assert(lesson_param_set(&lesson_08_fast, &p, "threads", 0));
            struct target one;
            cr_assert(render_scene(&s, lesson_variant(&lesson_08_fast, "tiles"), &p, &one));
            expect_same(&ref, &one, "tiles triangle by triangle");
            target_free(&one);
            target_free(&ref);
        }
        scene_free(&s);
    }
    cr_expect_eq(cases, 4 * 3 * 2 * 9);
}

/* Every sample's coverage, summed per pixel, is the exact rule's
 * (reference_point_covered at the standard positions), over many tiles. */
Test(lesson08_tiles, per_sample_coverage_is_the_exact_rules_over_many_tiles)
{
    struct rng rng = rng_for(0x0826);
    for (int rep = 0; rep < 3; rep++) {
        struct scene s;
        random_scene(&s, &rng, 200 + 11 * rep, 140 - 9 * rep, 120, 0);
        for (int n = 4; n <= 8; n += 4) {
            const struct sample_pattern *sp = sample_pattern(n);
            size_t m = (size_t)s.w * (size_t)s.h;
            uint8_t *ref = calloc(m, 1);
            cr_assert_not_null(ref);
            for (int i = 0; i < s.ntris; i++) {
                struct tri_setup t;
                tri_setup(&t, s.tris[i].v, s.w, s.h);
                for (int y = 0; y < s.h; y++)
                    for (int x = 0; x < s.w; x++)
                        for (int k = 0; k < n; k++) {
                            uint8_t *c = &ref[(size_t)y * (size_t)s.w + (size_t)x];
                            if (reference_point_covered(&t, (int64_t)x * SUBPIXEL_ONE + sp->x[k],
                                                        (int64_t)y * SUBPIXEL_ONE + sp->y[k]))
                                *c += *c < 255;
                        }
            }
            struct raster_params p = default_params();
            p.samples = n;
            struct target fb;
            const struct lesson_variant *v = lesson_variant(&lesson_08_fast, "tiles");
            cr_assert(render_lesson_scene(&lesson_08_fast, &s, v, &p, &fb));
            size_t wrong = 0;
            for (size_t i = 0; i < m; i++)
                wrong += fb.count[i] != ref[i];
            cr_expect_eq(wrong, 0, "scene %d, %d samples: %zu pixels' sample counts differ", rep, n, wrong);
            target_free(&fb);
            free(ref);
        }
        scene_free(&s);
    }
}

/* The explorer's order: each triangle set up and binned, then each entry
 * of a bin as its worker drew it; every unit drawn in that order, narrated
 * (the explorer's replay), makes msaa's picture, on 1 to 3 threads. */
Test(lesson08_tiles, the_explorers_units_drawn_in_order_make_the_same_picture)
{
    struct rng rng = rng_for(0x0827);
    struct scene s;
    random_scene(&s, &rng, 170, 120, 60, 0);
    const struct lesson_variant *v = lesson_variant(&lesson_08, "tiles");
    for (int threads = 1; threads <= 3; threads++) {
        struct raster_params p = default_params();
        p.samples = 4;
        cr_assert(lesson_param_set(&lesson_08, &p, "threads", threads));
        long n = lesson_08.narration_units(&s, v, &p, NULL, 0);
        cr_assert_gt(n, s.ntris, "fewer units than set-ups and entries");
        struct lesson_unit *u = malloc((size_t)n * sizeof *u);
        cr_assert_not_null(u);
        cr_assert_eq(lesson_08.narration_units(&s, v, &p, u, n), n);
        int setups = 0;
        for (long i = 0; i < n; i++)
            setups += u[i].tile < 0;
        cr_expect_eq(setups, s.ntris, "one set-up unit per triangle");
        struct target fb, ref;
        cr_assert(target_init(&fb, s.w, s.h, scene_background(&s)));
        cr_assert(target_multisample(&fb, 4));
        for (long i = 0; i < n; i++) {
            struct tri_setup t;
            tri_setup(&t, s.tris[u[i].tri].v, s.w, s.h);
            struct raster_params q = p;
            struct run_place at = { .scene = &s, .unit = &u[i], .units = u, .nunits = (int)n };
            q.at = &at;
            struct trace tr = { 0 };
            trace_begin(&tr, u[i].tri, TRACE_UNLIMITED);
            v->rasterize(&t, &q, &fb, &tr);
            cr_assert(!tr.one_line, "the trace's line is given back");
        }
        cr_assert(render_scene(&s, lesson_variant(&lesson_08, "msaa"), &p, &ref));
        expect_same(&ref, &fb, "units in order");
        target_free(&fb);
        target_free(&ref);
        free(u);
    }
    scene_free(&s);
}

/* Layers a hair apart in depth (relative 1e-2 down to 1e-7, and equal),
 * tilted, drawn far-to-near and near-to-far: where the fast build decides a
 * sample is hidden without its division (pixels.c), and where it must not,
 * tiles writes msaa's bytes. */
Test(lesson08_tiles, layers_a_hair_apart_in_depth_resolve_as_msaas)
{
    static const double gap[] = { 1e-2, 2e-3, 1e-3, 1e-4, 1e-7, 0 };
    struct scene s;
    memset(&s, 0, sizeof s);
    s.w = 140, s.h = 75;
    for (int order = 0; order < 2; order++)
        for (int g = 0; g < 6; g++) {
            int k = order ? 5 - g : g;
            double z = 10.0 * (1 + gap[k]), lean = 0.5 * k;    /* far to near, then near to far */
            struct vertex a[3] = { { -3.3, -2.1, z, 0.1 * k, 0.5, 0.9, 0, 0 },
                                   { 150.6, -1.7, z + lean, 0.9, 0.1 * k, 0.2, 0, 0 },
                                   { 4.2, 80.4, z - lean, 0.3, 0.7, 0.1 * k, 0, 0 } };
            struct vertex b[3] = { a[1], { 149.7, 79.2, z, 0.5, 0.5, 0.5, 0, 0 }, a[2] };
            cr_assert(scene_add(&s, a));
            cr_assert(scene_add(&s, b));
        }
    for (int n = 4; n <= 8; n += 4) {
        struct raster_params p = default_params();
        p.samples = n;
        struct target ref;
        cr_assert(render_scene(&s, lesson_variant(&lesson_08, "msaa"), &p, &ref));
        for (int threads = 1; threads <= 2; threads++) {
            struct target fb;
            cr_assert(lesson_param_set(&lesson_08_fast, &p, "threads", threads));
            cr_assert(render_lesson_scene(&lesson_08_fast, &s, lesson_variant(&lesson_08_fast, "tiles"),
                                          &p, &fb));
            char what[64];
            snprintf(what, sizeof what, "%d samples, %d threads", n, threads);
            expect_same(&ref, &fb, what);
            target_free(&fb);
        }
        target_free(&ref);
    }
    scene_free(&s);
}

/* What a narrated step told: its writes, and how many fall outside its tile. */
struct told {
    int x0, y0, x1, y1;         /* the step's tile; x1 < x0: no write allowed */
    int outside, writes, masks;
};

static void on_told(void *ctx, const struct trace_event *ev)
{
    struct told *w = ctx;
    w->masks += ev->kind == TRACE_PIXEL_TEST;
    if (ev->kind != TRACE_PIXEL_WRITE)
        return;
    w->writes++;
    w->outside += ev->x < w->x0 || ev->x > w->x1 || ev->y < w->y0 || ev->y > w->y1;
}

/* The explorer's steps of the tiled run (its units, as the replay hands
 * them over), narrated and fast side by side at 4 and 8 samples: after
 * every step both pictures are the same bytes (every sample too), a step
 * tells its pixels' masks and writes (the SIMD pixels where the CPU has
 * them, narrated) only inside its tile, and the last picture is the fast
 * build's timed scene run. */
Test(lesson08_tiles, narrated_steps_write_the_fast_builds_bytes_step_by_step, .timeout = 60)
{
    struct rng rng = rng_for(0x0828);
    for (int rep = 0; rep < 2; rep++) {
        struct scene s;
        random_scene(&s, &rng, 150 + 40 * rep, 110, 50, 0);
        const struct lesson_variant *vn = lesson_variant(&lesson_08, "tiles");
        const struct lesson_variant *vf = lesson_variant(&lesson_08_fast, "tiles");
        struct raster_params p = default_params();
        p.samples = rep ? 8 : 4;
        cr_assert(lesson_param_set(&lesson_08, &p, "threads", 1 + rep));
        long n = lesson_08.narration_units(&s, vn, &p, NULL, 0);
        cr_assert_gt(n, s.ntris);
        struct lesson_unit *u = malloc((size_t)n * sizeof *u);
        cr_assert_not_null(u);
        cr_assert_eq(lesson_08.narration_units(&s, vn, &p, u, n), n);
        struct target a, b, whole;
        cr_assert(target_init(&a, s.w, s.h, scene_background(&s)) && target_multisample(&a, p.samples));
        cr_assert(target_init(&b, s.w, s.h, scene_background(&s)) && target_multisample(&b, p.samples));
        int nx = (s.w + 63) / 64, writes = 0, masks = 0;
        for (long i = 0; i < n; i++) {
            struct run_place at = { .scene = &s, .unit = &u[i], .units = u, .nunits = (int)n };
            struct raster_params q = p;
            q.at = &at;
            struct told w = { 0, 0, -1, -1, 0, 0, 0 };
            if (u[i].tile >= 0)
                w.x0 = u[i].tile % nx * 64, w.y0 = u[i].tile / nx * 64, w.x1 = w.x0 + 63, w.y1 = w.y0 + 63;
            struct tri_setup t;
            tri_setup(&t, s.tris[u[i].tri].v, s.w, s.h);
            struct trace tr = { .sink = on_told, .ctx = &w };
            trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
            vn->rasterize(&t, &q, &a, &tr);
            vf->rasterize(&t, &q, &b, NULL);
            cr_assert_eq(w.outside, 0, "step %ld wrote outside its tile", i);
            writes += w.writes, masks += w.masks;
            char what[64];
            snprintf(what, sizeof what, "%d samples, step %ld", p.samples, i);
            expect_same(&a, &b, what);
        }
        cr_assert_gt(writes, 0);
        cr_assert_gt(masks, writes, "no pixel told its mask");
        cr_assert(target_init(&whole, s.w, s.h, scene_background(&s)) && target_multisample(&whole, p.samples));
        cr_assert(lesson_scene_fn(&lesson_08_fast, vf)(&s, &p, &whole));
        expect_same(&a, &whole, "the narrated steps against the timed run");
        free(u);
        target_free(&a);
        target_free(&b);
        target_free(&whole);
        scene_free(&s);
    }
}
