/* test_lesson09_tiles.c - lesson 09's twin `tiles` (the quads on lesson
 * 07's bins and workers, colour and depth in tile buffers, the textures
 * shared) writes the bytes of `quads`: colours, depths and coverage counts,
 * for every filter, both wraps, several textures in one scene, on 1 to 8
 * workers, in both builds; and the explorer's steps, the units of its own
 * run, narrated one after another, write the fast build's bytes step by
 * step, each inside its tile, each bin in scene order. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "explore/replay.h"
#include "testlib.h"
#include "../lessons/09-textures/textures.h"

extern const struct lesson lesson_09, lesson_09_fast;

static const char *const names[] = { "checker-numbers", "bricks", "grid", "rgby" };

/* A random 2-D scene of w x h over several tiles: n triangles under two
 * builtin textures taking turns (both repeat, both clamp, or one of each
 * as `wrap` says: 0, 1, 2), s and t in [-3, 3], depths 0.5..4, some
 * untextured, some tiny, some large, some at one depth (the order decides). */
static void random_scene(struct scene *s, struct rng *r, int w, int h, int n, int wrap)
{
    static char text[65536];
    size_t at = (size_t)snprintf(text, sizeof text, "size %d %d\nbackground 0.1 0.1 0.2\n", w, h);
    const char *name[2] = { names[rng_int(r, 0, 3)], names[rng_int(r, 0, 3)] };
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        random_tri(r, rng_chance(r, 0.25) ? CAT_TINY : rng_chance(r, 0.25) ? CAT_LARGE : CAT_GENERIC,
                   w, h, v);
        bool textured = !rng_chance(r, 0.1), flat = rng_chance(r, 0.2);
        if (i % 8 == 0) {
            int k = i / 8 % 2;
            at += (size_t)snprintf(text + at, sizeof text - at, "texture builtin:%s %s\n", name[k],
                                   (wrap == 2 ? k : wrap) ? "clamp" : "repeat");
        }
        at += (size_t)snprintf(text + at, sizeof text - at, "tri");
        for (int k = 0; k < 3; k++) {
            at += (size_t)snprintf(text + at, sizeof text - at, "  %.17g %.17g %.17g  %.3f %.3f %.3f",
                                   v[k].x, v[k].y, flat ? 2.0 : rng_range(r, 0.5, 4),
                                   rng_range(r, 0.3, 1), rng_range(r, 0.3, 1), rng_range(r, 0.3, 1));
            if (textured)
                at += (size_t)snprintf(text + at, sizeof text - at, " %.6f %.6f", rng_range(r, -3, 3),
                                       rng_range(r, -3, 3));
        }
        at += (size_t)snprintf(text + at, sizeof text - at, "\n");
        cr_assert_lt(at, sizeof text - 512);
    }
    char err[256];
    cr_assert(scene_parse(s, "random", text, at, err, sizeof err), "%s\n%s", err, text);
}

static const struct lesson_variant *variant(const struct lesson *l, const char *name)
{
    const struct lesson_variant *v = lesson_variant(l, name);
    cr_assert_not_null(v, "%s has no variant %s", l->id, name);
    return v;
}

static struct raster_params params_for(int filter, int threads)
{
    struct raster_params p = default_params();
    p.knob[P_FILTER] = filter;
    p.knob[P_MAX_ANISO] = 16;
    if (threads > 0)
        cr_assert(lesson_param_set(&lesson_09, &p, "threads", threads));
    return p;
}

static void expect_same(const struct target *a, const struct target *b, const char *what)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    cr_assert_eq(memcmp(a->count, b->count, n), 0, "%s: coverage counts differ", what);
    cr_assert_eq(memcmp(a->depth, b->depth, n * sizeof *a->depth), 0, "%s: depths differ", what);
    cr_assert_eq(memcmp(a->color, b->color, n * sizeof *a->color), 0, "%s: colours differ", what);
}

/* quads triangle by triangle (the narrated algorithm) against tiles on the
 * whole scene, every filter, 1, 2, 3 and 8 workers and the default, both
 * builds; and against tiles triangle by triangle (a scene of one triangle
 * at a time through the same bins). */
Test(lesson09_tiles, writes_the_bytes_of_quads_every_filter_wrap_and_thread_count, .timeout = 120)
{
    struct rng r = rng_for(0x09a1);
    static const int threads[] = { 0, 1, 2, 3, 8 };
    const struct lesson *builds[2] = { &lesson_09, &lesson_09_fast };
    for (int c = 0; c < 6; c++) {
        struct scene s;
        if (c < 2) {
            char err[256];
            cr_assert(scene_builtin(&s, c ? "texture-wall" : "texture-floor", err, sizeof err), "%s", err);
            cr_assert(front_scene(&s));
        } else {
            random_scene(&s, &r, 150 + 37 * c, 200 - 29 * c, 40, c % 3);
        }
        for (int f = FILTER_NEAREST; f <= FILTER_ANISO; f++) {
            struct raster_params p = params_for(f, 0);
            struct target ref;
            cr_assert(render_scene(&s, variant(&lesson_09, "quads"), &p, &ref));
            for (int b = 0; b < 2; b++)
                for (int k = 0; k < 5; k++) {
                    if (k > 1 && (c + f + b) % 2)   /* half the thread counts: time */
                        continue;
                    struct raster_params q = params_for(f, threads[k]);
                    struct target fb;
                    cr_assert(render_lesson_scene(builds[b], &s, variant(builds[b], "tiles"), &q, &fb));
                    char what[128];
                    snprintf(what, sizeof what, "scene %d, filter %d, %s build, %d threads", c, f,
                             b ? "fast" : "narrated", threads[k]);
                    expect_same(&ref, &fb, what);
                    target_free(&fb);
                }
            struct target one;
            cr_assert(render_scene(&s, variant(&lesson_09_fast, "tiles"), &p, &one));
            expect_same(&ref, &one, "triangle by triangle");
            target_free(&one);
            target_free(&ref);
        }
        scene_free(&s);
    }
}

/* What a narrated step wrote, from its events. */
struct writes {
    int x0, y0, x1, y1;         /* the step's tile; x1 < x0: no write allowed */
    int outside, writes, filtered;
};

static void on_event(void *ctx, const struct trace_event *ev)
{
    struct writes *w = ctx;
    w->filtered += ev->kind == TRACE_STEP && ev->line == L_FILTER;
    if (ev->kind != TRACE_PIXEL_WRITE)
        return;
    w->writes++;
    w->outside += ev->x < w->x0 || ev->x > w->x1 || ev->y < w->y0 || ev->y > w->y1;
}

/* The explorer's steps (the run's units, as the replay hands them to
 * `rasterize`), narrated and fast side by side: after every step both
 * pictures are the same bytes, a narrated step writes only inside its
 * tile, a tile's bin is drawn in scene order by one worker, and the last
 * picture is the fast build's timed scene run. */
Test(lesson09_tiles, narrated_steps_write_the_fast_builds_pixels_tile_by_tile, .timeout = 60)
{
    struct rng r = rng_for(0x09a2);
    for (int rep = 0; rep < 3; rep++) {
        struct scene s;
        int threads = 1 + rep;
        random_scene(&s, &r, 170 + 23 * rep, 140 - 13 * rep, 50, rep % 3);
        struct raster_params p = params_for(rep == 2 ? FILTER_ANISO : FILTER_TRILINEAR, threads);
        const struct lesson_variant *vn = variant(&lesson_09, "tiles");
        const struct lesson_variant *vf = variant(&lesson_09_fast, "tiles");
        long n = lesson_09.narration_units(&s, vn, &p, NULL, 0);
        cr_assert_gt(n, s.ntris);
        struct lesson_unit *u = malloc((size_t)n * sizeof *u);
        cr_assert_not_null(u);
        cr_assert_eq(lesson_09.narration_units(&s, vn, &p, u, n), n);
        struct target a, b, whole;
        cr_assert(target_init(&a, s.w, s.h, scene_background(&s)));
        cr_assert(target_init(&b, s.w, s.h, scene_background(&s)));
        int nx = (s.w + 63) / 64, tiles = nx * ((s.h + 63) / 64);
        int *next_entry = calloc((size_t)tiles, sizeof *next_entry);
        int *worker = malloc((size_t)tiles * sizeof *worker);
        uint32_t *last_tri = calloc((size_t)tiles, sizeof *last_tri);
        cr_assert(next_entry && worker && last_tri);
        int writes = 0, filtered = 0, setups = 0;
        for (long i = 0; i < n; i++) {
            struct run_place at = { .scene = &s, .unit = &u[i], .units = u, .nunits = (int)n };
            struct raster_params up = lesson_params_tri(&p, &s, (int)u[i].tri);
            up.at = &at;
            struct writes w = { 0, 0, -1, -1, 0, 0, 0 };
            int tile = u[i].tile;
            setups += tile < 0;
            if (tile >= 0) {
                w.x0 = tile % nx * 64, w.y0 = tile / nx * 64, w.x1 = w.x0 + 63, w.y1 = w.y0 + 63;
                cr_assert_eq(u[i].bin_entry, next_entry[tile], "step %ld: tile %d's entries out of order",
                             i, tile);
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
            struct trace tr = { .sink = on_event, .ctx = &w };
            trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
            vn->rasterize(&t, &up, &a, &tr);
            vf->rasterize(&t, &up, &b, NULL);
            cr_assert(!tr.one_line, "the trace's line is given back");
            cr_assert_eq(w.outside, 0, "step %ld wrote outside its tile", i);
            writes += w.writes, filtered += w.filtered;
            char what[64];
            snprintf(what, sizeof what, "scene %d, step %ld", rep, i);
            expect_same(&a, &b, what);
        }
        cr_assert_eq(setups, s.ntris, "one set-up step per triangle");
        for (int tile = 0; tile < tiles; tile++)    /* every bin drawn to its end */
            for (long i = 0; i < n; i++)
                if (u[i].tile == tile)
                    cr_assert_eq(next_entry[tile], u[i].bin_size, "tile %d: bin not finished", tile);
        cr_assert_gt(writes, 0);
        cr_assert_gt(filtered, 0, "no filter step told");
        cr_assert(render_lesson_scene(&lesson_09_fast, &s, vf, &p, &whole));
        expect_same(&a, &whole, "the narrated steps against the timed run");
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

/* (s, t) by one reciprocal (textures.h: q = sum F_k Q_k, s = (sum F_k s_k
 * Q_k) / q) moves from the weights' value (F_k / (2 area) / z_k, summed
 * and divided, the rule's order) by at most 2^-48 texels per texel of
 * max |s_k| W at every covered pixel centre of random textured triangles,
 * large and tiny, near and far: 256 times less than the distance from a
 * texel's edge (TEX_TIE) inside which nearest takes the weights' value. */
Test(lesson09_tiles, one_reciprocal_moves_st_far_less_than_the_tie_distance, .timeout = 60)
{
    struct rng r = rng_for(0x09a3);
    double worst = 0;
    long pixels = 0;
    for (int c = 0; c < 400; c++) {
        struct vertex v[3];
        int w = 256, h = 256;
        random_tri(&r, c % 4 == 0 ? CAT_TINY : c % 4 == 1 ? CAT_LARGE : CAT_GENERIC, w, h, v);
        double scale = c % 3 == 0 ? 1 : c % 3 == 1 ? 100 : 0.01;
        for (int k = 0; k < 3; k++) {
            v[k].z = rng_range(&r, 0.1, c % 5 == 0 ? 1000 : 10);
            v[k].s = rng_range(&r, -3, 3) * scale, v[k].t = rng_range(&r, -3, 3) * scale;
        }
        struct tri_setup t;
        if (!tri_setup(&t, v, w, h) || t.empty)
            continue;
        double ms = 0, mt = 0;
        for (int k = 0; k < 3; k++)
            ms = fmax(ms, fabs(t.v[k].s)), mt = fmax(mt, fabs(t.v[k].t));
        double Q[3], SQ[3], TQ[3];
        for (int k = 0; k < 3; k++)
            Q[k] = 1 / t.v[k].z, SQ[k] = t.v[k].s * Q[k], TQ[k] = t.v[k].t * Q[k];
        for (int y = t.miny; y <= t.maxy; y++)
            for (int x = t.minx; x <= t.maxx; x++) {
                int64_t e[3];
                bool in = true;
                for (int k = 0; k < 3; k++) {
                    e[k] = edge_value(&t, k, x, y);
                    in = in && e[k] + t.bias[k] >= 0;
                }
                if (!in)
                    continue;
                double f[3] = { (double)e[EDGE_BC], (double)e[EDGE_CA], (double)e[EDGE_AB] };
                double q = 0, S = 0, T = 0, s0, t0;
                for (int k = 0; k < 3; k++)
                    q += f[k] * Q[k], S += f[k] * SQ[k], T += f[k] * TQ[k];
                double rq = 1 / q;
                tex_st_by_weights(&t, f, &s0, &t0);
                worst = fmax(worst, fmax(fabs(S * rq - s0) / fmax(ms, 1), fabs(T * rq - t0) / fmax(mt, 1)));
                pixels++;
            }
    }
    cr_log_info("one reciprocal: %ld pixels, the largest move %g of max |s_k| (2^%.1f)", pixels, worst,
                log2(worst));
    cr_assert_gt(pixels, 100000);
    cr_assert_leq(worst, 0x1p-48, "(s, t) moved by %g of max |s_k|", worst);
    cr_assert_leq(worst * 256, TEX_TIE);
}
