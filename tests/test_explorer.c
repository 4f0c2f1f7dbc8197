/* test_explorer.c - the explorer's stepping logic, without a window.
 *
 * Every claim is checked against an independent run of the lesson: the
 * variant run triangle by triangle with a trace frozen after the wanted
 * number of events (trace.h), never against what the explorer said before.
 * Lessons: every lesson on its built-in scene, its exhibit scene and a small
 * random scene; the scale test builds 200,000 small triangles at 1920x1080.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "draw/paint.h"
#include "front/front.h"   /* front_scene */
#include "testlib.h"

/* --- scenes ------------------------------------------------------------------------ */

/* The scenes a lesson is tried on: 0 built-in, 1 exhibit scene, 2 random. */
enum { SCENE_BUILTIN, SCENE_EXHIBIT, SCENE_RANDOM, SCENE_KINDS };

static bool load_scene(const struct lesson *l, int kind, struct scene *s)
{
    char err[256];
    /* a 3-D scene (lesson 06) with its screen triangles, as the program makes them */
    if (kind == SCENE_BUILTIN)
        return scene_builtin(s, l->builtin_scene, err, sizeof err) && front_scene(s);
    if (kind == SCENE_EXHIBIT)
        return l->exhibit_scene && scene_builtin(s, l->exhibit_scene, err, sizeof err)
               && front_scene(s);
    /* a few random triangles of every category on a small target */
    memset(s, 0, sizeof *s);
    s->w = 20, s->h = 14;
    struct rng r = rng_for(0xe7b10e5u);
    for (int i = 0; i < 6; i++) {
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(i % CAT_COUNT), s->w, s->h, v);
        cr_assert(scene_add(s, v));
    }
    return true;
}

static void open_explorer(struct explorer *ex, const struct lesson *l, const struct scene *s)
{
    struct explorer_desc d = { .lesson = l, .scene = s, .scene_name = "test" };
    char err[256];
    cr_assert(explorer_init(ex, &d, err, sizeof err), "%s", err);
}

/* --- the independent run ---------------------------------------------------------- */

struct kinds {
    uint64_t n[TRACE_KIND_COUNT];
    uint64_t group_stops;       /* distinct STEP_GROUP stops over the scene */
    uint64_t base, last_stop;
};

static void count_kind(void *ctx, const struct trace_event *ev)
{
    struct kinds *k = ctx;
    k->n[ev->kind]++;
    if (ev->kind == TRACE_ROW || ev->kind == TRACE_BLOCK || ev->kind == TRACE_SPAN) {
        uint64_t stop = k->base + ev->index + 1;
        if (stop != k->last_stop)
            k->group_stops++, k->last_stop = stop;
    }
}

/* The scene as variant `variant` draws it: a 3-D scene under a variant
 * with a front end of its own (lesson 06's exhibits) has its own screen
 * triangles, made into *own (freed by scene_free), as the program and the
 * explorer make them. */
static const struct scene *as_drawn(const struct lesson *l, int variant, const struct scene *given,
                                    struct scene *own)
{
    *own = (struct scene){ 0 };
    front_fn front = lesson_front(l, &l->variants[variant]);
    if (!given->world.camera_line || front == front_scene)
        return given;
    cr_assert(scene_copy(own, given) && front(own));
    return own;
}

/* The units the lesson's narration steps through: one per triangle in
 * scene order, or the lesson's own order (lesson 07: a triangle inside a
 * tile, tile after tile), from the lesson itself. Returns how many; *out
 * is malloc'ed (NULL for one per triangle). */
static int units_of(const struct lesson *l, int variant, const struct scene *s,
                    const struct raster_params *p, struct lesson_unit **out)
{
    *out = NULL;
    if (!l->narration_units)
        return s->ntris;
    long n = l->narration_units(s, &l->variants[variant], p, NULL, 0);
    cr_assert_geq(n, 0, "%s: listing its units failed", l->id);
    *out = malloc((size_t)(n ? n : 1) * sizeof **out);
    cr_assert_not_null(*out);
    cr_assert_eq(l->narration_units(s, &l->variants[variant], p, *out, n), n);
    return (int)n;
}

/* The scene drawn by the variant with only the first `n` events happening
 * (n = UINT64_MAX: all), into fb. Returns the number of events that happened;
 * counts every kind of event and the row/block/span stops into *k. */
/* The lesson's narrated order (units_of) over the scene as the variant draws
 * it (as_drawn: lesson 06's own screen triangles), with the params given. */
static uint64_t run_frozen_with(const struct lesson *l, int variant, const struct scene *given,
                                const struct raster_params *params, uint64_t n, struct target *fb,
                                struct kinds *k)
{
    struct scene own;
    const struct scene *s = as_drawn(l, variant, given, &own);
    cr_assert(target_init(fb, s->w, s->h, scene_background(s)));
    struct raster_params p = *params;
    p.scene = s;
    uint64_t done = 0;
    struct kinds local = { 0 };
    if (!k)
        k = &local;
    struct lesson_unit *units;
    int nunits = units_of(l, variant, s, &p, &units);
    for (int i = 0; i < nunits; i++) {
        struct tri_setup t;
        struct raster_params up = p;
        if (units) {    /* the triangle inside its tile, as lesson.h says */
            up.tile = units[i].tile + 1;
            up.bin_size = units[i].bin_size;
            up.bin_entry = units[i].bin_entry;
            up.thread = units[i].thread;
        }
        int tri = units ? (int)units[i].tri : i;
        up.texture = lesson_params_tri(&p, s, tri).texture;     /* as the drivers set it */
        tri_setup_bits(&t, s->tris[tri].v, s->w, s->h, p.subpixel_bits);
        struct trace tr = { .sink = count_kind, .ctx = k };
        k->base = done;
        trace_begin(&tr, (uint32_t)i, n - done);
        l->variants[variant].rasterize(&t, &up, fb, &tr);
        uint64_t happened = tr.count < n - done ? tr.count : n - done;
        done += happened;
        /* the triangle's end is a stop too (the group stop may coincide) */
        if (happened == tr.count && done != k->last_stop)
            k->group_stops++, k->last_stop = done;
    }
    free(units);
    scene_free(&own);
    return done;
}

static uint64_t run_frozen(const struct lesson *l, int variant, const struct scene *s, uint64_t n,
                           struct target *fb, struct kinds *k)
{
    struct raster_params p = default_params();
    p.checker = s->checker;
    return run_frozen_with(l, variant, s, &p, n, fb, k);
}

static bool targets_equal(const struct target *a, const struct target *b)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    return a->w == b->w && a->h == b->h && memcmp(a->color, b->color, n * 4) == 0
           && memcmp(a->depth, b->depth, n * sizeof *a->depth) == 0
           && memcmp(a->count, b->count, n) == 0;
}

/* --- the explorer's state, field by field ------------------------------------------- */

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001b3u;
    return h;
}

/* A hash of everything a picture is made of at the current step: the target,
 * the cells (field by field: no padding bytes), counters, position. */
static uint64_t state_hash(const struct explorer *ex)
{
    uint64_t h = 0xcbf29ce484222325u;
    size_t n = (size_t)ex->fb.w * (size_t)ex->fb.h;
    h = fnv(h, ex->fb.color, n * 4);
    h = fnv(h, ex->fb.depth, n * sizeof *ex->fb.depth);
    h = fnv(h, ex->fb.count, n);
    for (int y = 0; y < ex->cell_h; y++)
        for (int x = 0; x < ex->cell_w; x++) {
            const struct cell *c = explorer_cell(ex, ex->cell_x0 + x, ex->cell_y0 + y);
            h = fnv(h, c->e, sizeof c->e);
            h = fnv(h, c->bary, sizeof c->bary);
            h = fnv(h, c->aux, sizeof c->aux);
            h = fnv(h, &c->z, sizeof c->z);
            h = fnv(h, &c->rgba, sizeof c->rgba);
            h = fnv(h, &c->flags, 1);
            h = fnv(h, &c->klass, 1);
        }
    int pos[5] = { ex->cur, ex->focus, ex->cell_x0, ex->cell_y0, ex->cell_w * 65536 + ex->cell_h };
    h = fnv(h, pos, sizeof pos);
    h = fnv(h, &ex->local, sizeof ex->local);
    h = fnv(h, &ex->tri_c, sizeof ex->tri_c);
    h = fnv(h, &ex->extra, sizeof ex->extra);
    h = fnv(h, &ex->missing, sizeof ex->missing);
    return h;
}

/* A hash of the painted frame (small, so that every step can be painted). */
static uint64_t picture_hash(struct explorer *ex)
{
    enum { W = 420, H = 300 };
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H);
    cairo_t *cr = cairo_create(img);
    explorer_paint(ex, cr, W, H);
    cr_assert_eq(cairo_status(cr), CAIRO_STATUS_SUCCESS);
    cairo_destroy(cr);
    cairo_surface_flush(img);
    uint64_t h = fnv(0xcbf29ce484222325u, cairo_image_surface_get_data(img),
                     (size_t)cairo_image_surface_get_stride(img) * H);
    cairo_surface_destroy(img);
    return h;
}

/* --- counts per step kind ---------------------------------------------------------- */

static uint64_t walk(struct explorer *ex, enum step_unit unit)
{
    cr_assert(explorer_set_step(ex, 0));
    uint64_t steps = 0, prev = 0;
    while (ex->step < ex->replay.total) {
        cr_assert(explorer_move(ex, unit, +1));
        cr_assert_gt(ex->step, prev, "a step forward must move forward");
        prev = ex->step;
        steps++;
    }
    return steps;
}

Test(explorer, counts_per_step_kind)
{
    for (int li = 0; all_lessons[li]; li++)
        for (int kind = 0; kind < SCENE_KINDS; kind++) {
            const struct lesson *l = all_lessons[li];
            struct scene s;
            if (!load_scene(l, kind, &s))
                continue;
            struct target fb;
            struct kinds k = { .last_stop = 0 };
            uint64_t total = run_frozen(l, 0, &s, UINT64_MAX, &fb, &k);
            target_free(&fb);
            struct explorer ex;
            open_explorer(&ex, l, &s);
            cr_assert_eq(ex.replay.total, total, "%s scene %d: total events", l->id, kind);
            struct raster_params p = default_params();
            p.checker = s.checker;
            struct lesson_unit *units;
            uint64_t nunits = (uint64_t)units_of(l, 0, &s, &p, &units), setups = nunits;
            for (uint64_t u = 0; units && u < nunits; u++)    /* lesson 07: the binning steps */
                setups -= units[u].tile >= 0;
            free(units);
            cr_assert_eq(k.n[TRACE_SETUP], setups, "%s: one setup event a triangle set up",
                         l->id);
            /* one event at a time replays the current triangle each time:
             * walked on scenes of modest size only */
            if (total <= 5000)
                cr_assert_eq(walk(&ex, STEP_EVENT), total, "%s scene %d: event steps", l->id,
                             kind);
            cr_assert_eq(walk(&ex, STEP_TRIANGLE), nunits,
                         "%s scene %d: triangle (unit) steps", l->id, kind);
            cr_assert_eq(walk(&ex, STEP_GROUP), k.group_stops,
                         "%s scene %d: row/block/span steps", l->id, kind);
            explorer_free(&ex);
            scene_free(&s);
        }
}

/* --- forward then back --------------------------------------------------------------- */

Test(explorer, forward_then_back_is_identical)
{
    struct rng r = rng_for(0xf0ba);
    for (int li = 0; all_lessons[li]; li++)
        for (int kind = 0; kind < SCENE_KINDS; kind++) {
            const struct lesson *l = all_lessons[li];
            struct scene s;
            if (!load_scene(l, kind, &s))
                continue;
            struct explorer ex;
            open_explorer(&ex, l, &s);
            uint64_t total = ex.replay.total;
            for (int trial = 0; trial < 12; trial++) {
                enum step_unit unit = (enum step_unit)(trial % 3);
                uint64_t at = (uint64_t)rng_int(&r, 0, (int)(total - 1));
                cr_assert(explorer_set_step(&ex, at));
                if (unit != STEP_EVENT) {
                    /* start at a stop of this unit, so that back lands on it */
                    cr_assert(explorer_move(&ex, unit, +1));
                    if (ex.step >= total)
                        cr_assert(explorer_move(&ex, unit, -1));
                }
                uint64_t s0 = ex.step, h0 = state_hash(&ex);
                cr_assert(explorer_move(&ex, unit, +1));
                cr_assert(explorer_move(&ex, unit, -1));
                cr_assert_eq(ex.step, s0, "%s scene %d unit %d: back to step %llu", l->id, kind,
                             unit, (unsigned long long)s0);
                cr_assert_eq(state_hash(&ex), h0, "%s scene %d unit %d: state at step %llu",
                             l->id, kind, unit, (unsigned long long)s0);
            }
            explorer_free(&ex);
            scene_free(&s);
        }
}

/* --- replay of N is the lesson stopped after N events ------------------------------ */

Test(explorer, replay_equals_frozen_run)
{
    struct rng r = rng_for(0x4e9a);
    for (int li = 0; all_lessons[li]; li++)
        for (int kind = 0; kind < SCENE_KINDS; kind++) {
            const struct lesson *l = all_lessons[li];
            struct scene s;
            if (!load_scene(l, kind, &s))
                continue;
            for (int v = 0; v < l->nvariants; v++) {
                struct explorer ex;
                struct explorer_desc d = { .lesson = l, .scene = &s, .variant = &l->variants[v] };
                char err[256];
                cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
                uint64_t total = ex.replay.total;
                uint64_t steps[8] = { 0, 1, total / 2, total - 1, total };
                for (int i = 5; i < 8; i++)
                    steps[i] = (uint64_t)rng_int(&r, 0, (int)total);
                for (int i = 0; i < 8; i++) {
                    cr_assert(explorer_set_step(&ex, steps[i]));
                    struct target fb;
                    uint64_t done = run_frozen(l, v, &s, steps[i], &fb, NULL);
                    cr_assert_eq(done, steps[i]);
                    cr_assert(targets_equal(&ex.fb, &fb), "%s/%s scene %d: picture at step %llu",
                              l->id, l->variants[v].name, kind, (unsigned long long)steps[i]);
                    target_free(&fb);
                }
                explorer_free(&ex);
            }
            scene_free(&s);
        }
}

/* --- counted a part at a time, with checkpoints and steps back -------------------- */

/* A scene of many small triangles, counted later a part at a time (as the
 * window does) with a checkpoint budget of four pictures and a tiny undo
 * room, so that checkpoints are thinned out (merged into the ones after
 * them) and the undo history overflows and breaks: every picture must
 * still be the lesson stopped there. Kept as patches, more checkpoints fit
 * than whole pictures would. */
Test(explorer, counted_later_with_checkpoints_and_steps_back, .timeout = 120)
{
    struct scene s = { .w = 160, .h = 120 };
    struct rng r = rng_for(0xc4ec);
    for (int i = 0; i < 600; i++) {
        struct vertex v[3];
        random_tri(&r, i % 50 == 0 ? CAT_LARGE : CAT_GENERIC, s.w, s.h, v);
        cr_assert(scene_add(&s, v));
    }
    size_t picture = (size_t)s.w * (size_t)s.h * 9;
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        struct explorer ex, at_once;
        struct explorer_desc d = { .lesson = l, .scene = &s, .count_later = true };
        char err[256];
        cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
        cr_assert_eq(ex.replay.counted, 0, "%s: nothing counted before the first step", l->id);
        ex.replay.check_bytes = 4 * picture;
        ex.replay.check_gap = 1000;
        ex.replay.undo_bytes = 64 << 10;
        int slices = 0;
        while (explorer_counting(&ex)) {
            cr_assert(explorer_count(&ex, 0.2));
            slices++;
        }
        cr_assert_gt(slices, 1, "%s: counted in more than one part", l->id);
        cr_assert_gt(ex.replay.nchecks, 4, "%s: %d checkpoints in four pictures' memory", l->id,
                     ex.replay.nchecks);
        cr_assert_leq(ex.replay.check_used, ex.replay.check_bytes, "%s", l->id);
        cr_assert_gt(ex.replay.check_gap, 1000, "%s: thinned out", l->id);
        int units = ex.replay.ntris;    /* triangles, or lesson 07's (tile, triangle) units */
        cr_assert_geq(units, s.ntris, "%s", l->id);
        cr_assert_eq(ex.replay.checks[ex.replay.nchecks - 1].upto, replay_end_checkpoint(units),
                     "%s: a checkpoint near the end (End)", l->id);
        cr_assert(replay_end_checkpoint(units) < units - 1);

        /* the same counts as counting all at once */
        open_explorer(&at_once, l, &s);
        cr_assert_eq(ex.replay.total, at_once.replay.total);
        cr_assert(memcmp(ex.replay.start, at_once.replay.start,
                         ((size_t)units + 1) * sizeof *ex.replay.start) == 0, "%s: start[]", l->id);
        cr_assert(memcmp(ex.replay.sums, at_once.replay.sums,
                         ((size_t)units + 1) * sizeof *ex.replay.sums) == 0, "%s: sums[]", l->id);
        for (int k = 0; k < ex.ncompare; k++)
            cr_assert(memcmp(ex.compare_replay[k].sums, at_once.compare_replay[k].sums,
                             ((size_t)s.ntris + 1) * sizeof *ex.replay.sums) == 0,
                      "%s: the counts of %s", l->id, ex.compare[k]->id);
        explorer_free(&at_once);

        /* jumps anywhere, then steps back a triangle at a time */
        uint64_t total = ex.replay.total;
        for (int i = 0; i < 12; i++) {
            uint64_t step = i == 0 ? total : i == 1 ? total - 1 : (uint64_t)rng_int(&r, 0, (int)total);
            cr_assert(explorer_set_step(&ex, step));
            int back = i % 3 == 0 ? 8 : 1;
            for (int b = 0; b <= back; b++) {
                if (b > 0)
                    cr_assert(explorer_move(&ex, STEP_TRIANGLE, -1));
                struct target fb;
                run_frozen(l, 0, &s, ex.step, &fb, NULL);
                cr_assert(targets_equal(&ex.fb, &fb), "%s: picture at step %llu (jump %d, back %d)",
                          l->id, (unsigned long long)ex.step, i, b);
                target_free(&fb);
            }
        }
        explorer_free(&ex);
    }
    scene_free(&s);
}

/* Found by the soak test: a pixel pinned in the lesson's scene, then X
 * switching to the smaller exhibit scene, and the watch panel read the
 * pinned pixel outside the new scene's target. */
Test(explorer, exhibit_scene_switch_unpins_a_pixel_outside_it)
{
    int tried = 0;
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        struct scene s;
        if (!l->exhibit_scene || !load_scene(l, SCENE_BUILTIN, &s))
            continue;
        struct explorer ex;
        struct explorer_desc d = { .lesson = l, .scene = &s, .scene_name = "test",
                                   .scene_is_default = true };
        char err[256];
        cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
        ex.pinned = true;
        ex.pin_x = s.w - 1, ex.pin_y = s.h - 1;
        cr_assert(explorer_cycle_exhibit(&ex));
        cr_assert(!ex.pinned || (ex.pin_x < ex.scene.w && ex.pin_y < ex.scene.h),
                  "%s: pinned (%d, %d) in a %d x %d scene", l->id, ex.pin_x, ex.pin_y,
                  ex.scene.w, ex.scene.h);
        cr_assert_geq(explorer_frame_ms(&ex, 640, 400, 1), 0);  /* the sanitizers watch */
        explorer_free(&ex);
        scene_free(&s);
        tried++;
    }
    cr_assert_gt(tried, 0);
}

/* --- stepping back from the end reproduces every picture ---------------------------- */

Test(explorer, back_from_end_reproduces_every_picture)
{
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        struct scene s;
        cr_assert(load_scene(l, SCENE_RANDOM, &s));
        struct explorer ex;
        open_explorer(&ex, l, &s);
        uint64_t total = ex.replay.total;
        /* paint every step of lesson 02 (the acceptance case); the
         * state behind the picture for every step of the others */
        bool paint = strncmp(l->id, "02", 2) == 0;
        uint64_t *hash = calloc(total + 1, sizeof *hash);
        cr_assert(hash);
        ex.view = VIEW_COVERAGE;
        for (uint64_t i = 0;; i++) {
            cr_assert_eq(ex.step, i);
            hash[i] = paint ? picture_hash(&ex) : state_hash(&ex);
            if (i == total)
                break;
            cr_assert(explorer_move(&ex, STEP_EVENT, +1));
        }
        for (uint64_t i = total; i-- > 0;) {
            cr_assert(explorer_move(&ex, STEP_EVENT, -1));
            cr_assert_eq(ex.step, i);
            uint64_t h = paint ? picture_hash(&ex) : state_hash(&ex);
            cr_assert_eq(h, hash[i], "%s: the picture of step %llu differs going back", l->id,
                         (unsigned long long)i);
        }
        free(hash);
        explorer_free(&ex);
        scene_free(&s);
    }
}

/* --- dragging a vertex keeps the step ---------------------------------------------- */

Test(explorer, drag_keeps_step)
{
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        struct scene s;
        cr_assert(load_scene(l, SCENE_BUILTIN, &s));
        struct explorer ex;
        open_explorer(&ex, l, &s);
        uint64_t at = ex.replay.total / 3;
        cr_assert(explorer_set_step(&ex, at));
        int focus = ex.focus;
        /* vertex A after setup is the scene's first vertex */
        double x = ex.scene.tris[focus].v[0].x + 0.3, y = ex.scene.tris[focus].v[0].y - 0.7;
        size_t wbytes = (size_t)ex.scene.world.ntris * sizeof *ex.scene.world.tris;
        struct world_tri *world = malloc(wbytes ? wbytes : 1);
        cr_assert_not_null(world);
        if (wbytes)
            memcpy(world, ex.scene.world.tris, wbytes);
        cr_assert(explorer_move_vertex(&ex, 0, x, y));
        cr_assert_eq(ex.step, at, "%s: the step moved with the vertex", l->id);
        if (!ex.scene.world.camera_line) {
            cr_assert_eq(ex.scene.tris[focus].v[0].x, (double)lrint(x * 256) / 256, "%s", l->id);
            cr_assert_eq(ex.scene.tris[focus].v[0].y, (double)lrint(y * 256) / 256, "%s", l->id);
        } else {
            /* a 3-D scene: the model moved (tests/test_front.c checks where
             * to), or the vertex was the clipper's and the window says so */
            bool moved = memcmp(world, ex.scene.world.tris, wbytes) != 0;
            cr_assert(moved || strstr(ex.message, "the clipper made it"), "%s: %s", l->id,
                      ex.message);
        }
        free(world);
        /* the lesson re-ran: the picture is the moved scene's, frozen at the step */
        struct target fb;
        run_frozen(l, 0, &ex.scene, at, &fb, NULL);
        cr_assert(targets_equal(&ex.fb, &fb), "%s: picture after the drag", l->id);
        target_free(&fb);
        explorer_free(&ex);
        scene_free(&s);
    }
}

/* --- views ----------------------------------------------------------------------------- */

Test(explorer, every_listed_view_is_accepted)
{
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        struct scene s;
        cr_assert(load_scene(l, SCENE_BUILTIN, &s));
        struct explorer ex;
        open_explorer(&ex, l, &s);
        cr_assert_geq(explorer_view_count(&ex), VIEW_BUILTIN_COUNT);
        for (int v = 0; v < explorer_view_count(&ex); v++) {
            ex.edge = -1;
            char name[64];
            snprintf(name, sizeof name, "%s", explorer_view_name(&ex, v));
            ex.view = VIEW_COLOR;
            cr_assert(explorer_set_view_name(&ex, name), "%s: view '%s'", l->id, name);
            cr_assert_eq(ex.view, v, "%s: view '%s'", l->id, name);
        }
        const char *edges[] = { "edge-ab", "edge-bc", "edge-ca" };
        for (int k = 0; k < 3; k++) {
            cr_assert(explorer_set_view_name(&ex, edges[k]));
            cr_assert_eq(ex.view, VIEW_EDGES);
            cr_assert_eq(ex.edge, k);
        }
        cr_assert_not(explorer_set_view_name(&ex, "colour-of-money"));
        explorer_free(&ex);
        scene_free(&s);
    }
}

/* --- scale: 200,000 small triangles at 1920x1080 ---------------------------------- */

/* What the explorer holds, counted from its own fields. */
static size_t explorer_bytes(const struct explorer *ex)
{
    size_t px = sizeof(uint32_t) + sizeof(float) + 1;   /* colour, depth, count */
    size_t n = 0;
    const struct target *t[] = { &ex->fb, &ex->scratch, &ex->exact, &ex->replay.base };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
        if (t[i]->color)
            n += (size_t)t[i]->w * (size_t)t[i]->h * px;
    n += (size_t)ex->scene.cap * sizeof *ex->scene.tris;
    n += (size_t)(ex->replay.ntris + 1) * (sizeof *ex->replay.start + sizeof *ex->replay.sums);
    n += ex->cell_cap * sizeof *ex->cells + ex->marks_cap * sizeof *ex->marks;
    n += ex->replay.check_used;
    if (ex->replay.undo_data)
        n += ex->replay.undo_bytes + (size_t)ex->replay.undo_cap * sizeof *ex->replay.undo;
    if (ex->diff)
        n += (size_t)ex->scene.w * (size_t)ex->scene.h;
    return n;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

Test(explorer, scale_200k_triangles, .timeout = 120)
{
    enum { W = 1920, H = 1080, N = 200000 };
    struct scene s = { .w = W, .h = H };
    struct rng r = rng_for(0x200000);
    for (int i = 0; i < N; i++) {
        double x = rng_range(&r, 0, W - 4), y = rng_range(&r, 0, H - 4);
        struct vertex v[3] = { test_vertex(x, y), test_vertex(x + rng_range(&r, 0.5, 4), y + 0.3),
                               test_vertex(x + 0.2, y + rng_range(&r, 0.5, 4)) };
        cr_assert(scene_add(&s, v));
    }
    const struct lesson *l = all_lessons[0];
    for (int li = 0; all_lessons[li]; li++)
        if (strncmp(all_lessons[li]->id, "02", 2) == 0)
            l = all_lessons[li];
    double t0 = now_ms();
    struct explorer ex;
    open_explorer(&ex, l, &s);
    double t1 = now_ms();
    uint64_t total = ex.replay.total;
    cr_assert_eq(ex.replay.ntris, N);
    cr_assert(explorer_set_step(&ex, total / 2));
    int mid = 0;
    while (ex.replay.start[mid + 1] < total / 2)
        mid++;
    cr_assert_eq(ex.cur, mid, "the triangle of the middle step");
    double t2 = now_ms();
    cr_assert(explorer_move(&ex, STEP_TRIANGLE, +1));
    cr_assert(explorer_move(&ex, STEP_EVENT, -1));
    cr_assert(explorer_set_step(&ex, total));
    cr_assert_eq(ex.cur, N - 1);
    double t3 = now_ms();
    cr_assert(explorer_set_step(&ex, total - 1));
    cr_assert(explorer_set_step(&ex, total / 2 + 1));
    double t4 = now_ms();
    size_t bytes = explorer_bytes(&ex);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    cr_log_info("200,000 triangles: %llu events; init %.0f ms, middle %.0f ms, end %.0f ms, "
                "back and forth %.0f ms; explorer holds %.1f MiB, peak RSS %.1f MiB",
                (unsigned long long)total, t1 - t0, t2 - t1, t3 - t2, t4 - t3,
                (double)bytes / 1048576, (double)ru.ru_maxrss / 1024);
    cr_assert_lt(bytes, (size_t)256 << 20, "the explorer holds %zu bytes", bytes);
    cr_assert_lt((size_t)ru.ru_maxrss * 1024, (size_t)1 << 30, "peak RSS %ld KiB", ru.ru_maxrss);
    explorer_free(&ex);
    scene_free(&s);
}

/* The explorer and the headless programs agree for every parameter value:
 * the explorer's picture at the last step is render_scene()'s (what
 * --dump-coverage and --dump-image write) with the same params. It once
 * read subpixel_bits 0 as "the default" and snapped to 8 bits. */
Test(explorer, agrees_with_headless_for_every_parameter_value, .timeout = 120)
{
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        /* every sub-pixel precision, and every value of each parameter of
         * the lesson's own that the explorer has a key for */
        struct raster_params cases[32];
        int n = 0;
        for (int bits = 0; bits <= SUBPIXEL_BITS; bits++)
            cases[n++] = (struct raster_params){ .subpixel_bits = bits };
        for (int i = 0; l->params && l->params[i].option; i++) {
            const struct lesson_param *r = &l->params[i];
            for (int v = r->min; r->key && r->slot == PARAM_OWN && v <= r->max && n < 32; v++)
                if (lesson_param_allows(r, v)) {
                    cases[n] = (struct raster_params){ .subpixel_bits = SUBPIXEL_BITS };
                    *lesson_param_slot(l, i, &cases[n++]) = v;
                }
        }
        for (int kind = SCENE_BUILTIN; kind <= SCENE_EXHIBIT; kind++) {
            struct scene s;
            if (!load_scene(l, kind, &s))
                continue;
            for (int v = 0; v < l->nvariants; v++)
                for (int c = 0; c < n; c++) {
                    struct raster_params p = cases[c];
                    p.checker = s.checker;
                    struct explorer ex;
                    struct explorer_desc d = { .lesson = l, .scene = &s, .variant = &l->variants[v],
                                               .params = &p, .step_end = true };
                    char err[256];
                    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
                    /* headless as the program runs it: the variant's screen
                     * triangles, the scene in the params, in the lesson's
                     * narrated order (scene order, or its units: lesson 07,
                     * whose exhibit `unordered` orders them by its workers) */
                    struct target fb;
                    struct scene own;
                    const struct scene *hs = as_drawn(l, v, &s, &own);
                    p.scene = hs;
                    if (l->narration_units)
                        run_frozen_with(l, v, &s, &p, UINT64_MAX, &fb, NULL);
                    else
                        cr_assert(render_scene(hs, &l->variants[v], &p, &fb));
                    cr_assert(targets_equal(&ex.fb, &fb),
                              "%s %s on %s: the explorer differs from the headless run with "
                              "subpixel_bits %d, knobs %d %d", l->id,
                              l->variants[v].name, kind ? "the exhibit scene" : "the built-in scene",
                              p.subpixel_bits, p.knob[0], p.knob[1]);
                    cr_assert_eq(ex.params.subpixel_bits, p.subpixel_bits);
                    scene_free(&own);
                    target_free(&fb);
                    explorer_free(&ex);
                }
            scene_free(&s);
        }
    }
}

/* explorer_init has one cleanup path and says why it failed: a description
 * that does not hold together is refused with its reason, leaving nothing
 * allocated (LeakSanitizer checks that under make test SANITIZE=1). */
Test(explorer, init_says_why_it_fails)
{
    const struct lesson *l = all_lessons[0], *other = all_lessons[1];
    cr_assert_not_null(other);
    struct scene s;
    cr_assert(load_scene(l, SCENE_BUILTIN, &s));
    struct explorer ex;
    char err[256] = "";
    struct explorer_desc d = { .lesson = l, .scene = &s, .variant = &other->variants[0] };
    cr_assert_not(explorer_init(&ex, &d, err, sizeof err));
    cr_assert(strstr(err, l->id) && strstr(err, "variant"), "message: %s", err);
    cr_assert_null(ex.replay.start, "a failed init kept its replay");
    d.variant = NULL;
    d.scene = NULL;
    cr_assert_not(explorer_init(&ex, &d, err, sizeof err));
    cr_assert(strstr(err, "no scene"), "message: %s", err);
    d.scene = &s;
    d.lesson = NULL;
    cr_assert_not(explorer_init(&ex, &d, err, sizeof err));
    cr_assert(strstr(err, "no lesson"), "message: %s", err);
    d.lesson = l;
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    explorer_free(&ex);
    scene_free(&s);
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#endif

#ifndef UNDER_ASAN
/* Out of memory (the address space of this test's process capped 64 MB above
 * what it uses, a 4096 x 4096 target needing 150 MB): the message names what
 * could not be done and the scene's size. ASan reserves terabytes of address
 * space for its shadow, so this test is left out of make test SANITIZE=1. */
Test(explorer, init_out_of_memory_says_so)
{
    struct scene s = { .w = 4096, .h = 4096 };
    struct vertex v[3] = { { .x = 1, .y = 1, .z = 1 }, { .x = 4000, .y = 9, .z = 1 },
                           { .x = 9, .y = 4000, .z = 1 } };
    cr_assert(scene_add(&s, v));
    FILE *f = fopen("/proc/self/statm", "r");
    cr_assert_not_null(f);
    unsigned long pages = 0;
    cr_assert_eq(fscanf(f, "%lu", &pages), 1);
    fclose(f);
    struct rlimit old, cap;
    cr_assert_eq(getrlimit(RLIMIT_AS, &old), 0);
    cap = old;
    cap.rlim_cur = pages * 4096ul + (64ul << 20);
    cr_assert_eq(setrlimit(RLIMIT_AS, &cap), 0);
    struct explorer ex;
    char err[256] = "";
    struct explorer_desc d = { .lesson = all_lessons[0], .scene = &s };
    bool ok = explorer_init(&ex, &d, err, sizeof err);
    setrlimit(RLIMIT_AS, &old);
    cr_assert_not(ok, "a 4096 x 4096 explorer fitted into 64 MB");
    cr_assert(strstr(err, "out of memory") && strstr(err, "4096 x 4096"), "message: %s", err);
    scene_free(&s);
}
#endif
