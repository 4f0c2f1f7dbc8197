/* test_lesson06.c - lesson 06: the narrated front end and its exhibits.
 *
 *   - the narration: every world triangle is told, once, in scene order
 *     (view, each plane, each kept, dropped or new vertex, projection, guard
 *     band, fan), those that make no screen triangle (wholly clipped or
 *     culled) too, each before the rasterizer's steps on its own screen
 *     triangles, which point at the last line; every new vertex lies on its
 *     plane with its t in [0, 1], and there are as many as the stages make
 *     when run here, untold;
 *   - the exact variants cover what the reference covers on the built-in
 *     3-D scenes;
 *   - every exhibit is counted, and the numbers are the ones the lesson's
 *     README quotes (README_* below).
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "explore/replay.h"     /* render_scene */
#include "front/front.h"
#include "testlib.h"

extern const struct lesson lesson_06;

/* Numbers quoted in lessons/06-clipping/README.md. */
#define README_ROOM_TRIANGLES 18        /* builtin:room: 12 world triangles -> 18 on screen */
#define README_PROJECT_FIRST_WRONG 3072 /* builtin:room, project-first: pixels not covered once */
#define README_VIEWPORT_CUT 8           /* builtin:room, viewport: world triangles cut in x, y */
#define README_VIEWPORT_MADE 12         /* ... and the new vertices on the screen's border */
#define README_NO_GUARD_WRONG 175       /* builtin:room, no-guard-32: pixels not covered once */
#define README_DEPTH_WRONG_NDC24 3072   /* builtin:depth-pair: pixels showing the wrong wall */
#define README_MODEL_TRIANGLES 266     /* builtin:model, cull back: 576 world triangles -> 266 */
#define README_NDC24_STEP 0.95          /* units of depth per 24-bit step at d = 400, n = 0.01, f = 1000 */
#define README_FRUSTUM_T0 0.114         /* figure 06-frustum: the t of the two new vertices */
#define README_FRUSTUM_T1 0.917
#define README_DEPTH_WRONG_D 0
#define README_DEPTH_WRONG_INVERSE 0
#define README_DEPTH_WRONG_REVERSED 0

static struct scene load(const char *name, const struct lesson_variant *v)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, name, err, sizeof err), "%s", err);
    cr_assert(lesson_front(&lesson_06, v)(&s));
    return s;
}

static const struct lesson_variant *variant(const char *name)
{
    const struct lesson_variant *v = lesson_variant(&lesson_06, name);
    cr_assert_not_null(v, "lesson 06 has no variant %s", name);
    return v;
}

static struct target render(const struct scene *s, const struct lesson_variant *v)
{
    struct raster_params p = default_params();
    p.at = &(struct run_place){ .scene = s };
    struct target fb;
    cr_assert(render_scene(s, v, &p, &fb));
    return fb;
}

/* --- the narration --------------------------------------------------------------- */

struct told {
    int front, raster, news, views, triangles, worlds;
    int world;                  /* the last world triangle told, -1 before the first */
    const int *from;            /* the world triangle of each screen triangle */
    bool order_ok;
    int bad_line;
    double near, far;
    bool t_ok, on_plane;
};

static void listen(void *ctx, const struct trace_event *ev)
{
    struct told *t = ctx;
    if (ev->kind == TRACE_FRONT) {
        t->front++;
        if (ev->klass == FRONT_WORLD) {     /* each world triangle once, in order */
            t->order_ok = t->order_ok && ev->part == t->world + 1;
            t->world = ev->part;
            t->worlds++;
        }
        t->order_ok = t->order_ok && ev->part == t->world;
        if (ev->klass == FRONT_VIEW)
            t->views++;
        if (ev->klass == FRONT_TRIANGLE)
            t->triangles++;
        if (ev->klass == FRONT_NEW && ev->x <= PLANE_FAR) {
            t->news++;
            t->t_ok = t->t_ok && ev->aux[3] >= 0 && ev->aux[3] <= 1;
            float plane = (float)(ev->x == PLANE_NEAR ? t->near : t->far);
            t->on_plane = t->on_plane && ev->aux[2] == plane;
        }
    } else {
        t->raster++;
        /* the front end of the screen triangle's world triangle comes first */
        t->order_ok = t->order_ok && t->from[ev->tri] == t->world && ev->part == t->world;
        if (ev->line != 7)
            t->bad_line++;
    }
}

static void count_made(void *ctx, const struct trace_event *ev)
{
    *(int *)ctx += ev->kind == TRACE_FRONT && ev->klass == FRONT_NEW;
}

Test(lesson06, the_front_end_is_told_before_the_rasterizer)
{
    static const char *const names[] = { "room", "horizon", "model" };
    for (int k = 0; k < 3; k++) {
        const struct lesson_variant *v = &lesson_06.variants[0];
        struct scene s = load(names[k], v);
        struct raster_params p = default_params();
        p.at = &(struct run_place){ .scene = &s };
        struct target fb;
        cr_assert(target_init(&fb, s.w, s.h, 0));
        struct told told = { .world = -1, .from = s.world.from, .order_ok = true,
                             .near = s.world.cam.near, .far = s.world.cam.far,
                             .t_ok = true, .on_plane = true };
        struct trace tr = { .sink = listen, .ctx = &told };
        int worlds = s.world.ntris, drawn = 0;
        for (int i = 0; i < s.ntris; i++) {
            struct tri_setup t;
            tri_setup(&t, s.tris[i].v, s.w, s.h);
            trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
            v->rasterize(&t, &p, &fb, &tr);
            drawn += i == 0 || s.world.from[i] != s.world.from[i - 1];
        }
        /* the same world triangles through the stages, untold: the new
         * vertices near and far make */
        struct frustum fr;
        frustum_init(&fr, &s.world.cam, s.w, s.h);
        int made = 0;
        struct trace count = { .sink = count_made, .ctx = &made };
        trace_begin(&count, 0, TRACE_UNLIMITED);
        for (int i = 0; i < s.world.ntris; i++) {
            const struct world_tri *wt = &s.world.tris[i];
            struct poly a = { .n = 3 }, b, c;
            for (int j = 0; j < 3; j++)
                a.v[j] = view_vertex(&fr, wt->p[j], wt->rgb[j]);
            struct plane pn = depth_plane(&fr, PLANE_NEAR), pf = depth_plane(&fr, PLANE_FAR);
            clip_polygon(&b, &a, &pn, &count);
            if (b.n > 0)            /* wholly behind near: far is not run */
                clip_polygon(&c, &b, &pf, &count);
        }
        cr_log_info("%s: %d world triangles, %d of them drawn", names[k], worlds, drawn);
        cr_expect(told.order_ok, "%s: a step told out of order", names[k]);
        cr_expect_eq(told.worlds, worlds, "%s: every world triangle told once", names[k]);
        cr_expect_eq(told.views, 3 * worlds, "%s: three vertices to view space per world triangle",
                     names[k]);
        cr_expect_eq(told.news, made, "%s: %d new vertices told, the stages make %d", names[k],
                     told.news, made);
        cr_expect_geq(told.triangles, s.ntris, "%s: every drawn triangle told", names[k]);
        cr_expect(told.t_ok, "%s: a t outside [0, 1]", names[k]);
        cr_expect(told.on_plane, "%s: a new vertex off its plane", names[k]);
        cr_expect_gt(told.raster, 0);
        cr_expect_eq(told.bad_line, 0, "%s: rasterizer steps must point at line 8", names[k]);
        if (k == 0)
            cr_expect_gt(made, 0, "the room's walls are cut by the near plane");
        if (k == 2)
            cr_expect_gt(worlds, drawn, "the model's back faces are culled, and told");
        target_free(&fb);
        scene_free(&s);
    }
}

/* --- the exact variants --------------------------------------------------------- */

Test(lesson06, the_lesson_and_its_storages_cover_what_the_reference_covers)
{
    static const char *const names[] = { "room", "horizon", "model", "depth-pair" };
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < lesson_06.nvariants; i++) {
            const struct lesson_variant *v = &lesson_06.variants[i];
            /* the lesson, and the storages: their coverage is exact too */
            if (variant_against_exact(v) && strcmp(v->name, "inverse") != 0 && strcmp(v->name, "reversed") != 0)
                continue;
            struct scene s = load(names[k], v);
            uint8_t *ref = calloc((size_t)s.w * s.h, 1);
            for (int j = 0; j < s.ntris; j++) {
                struct tri_setup t;
                tri_setup(&t, s.tris[j].v, s.w, s.h);
                reference_mask(&t, ref);
            }
            struct target fb = render(&s, v);
            char what[128];
            snprintf(what, sizeof what, "06 %s on builtin:%s", v->name, names[k]);
            struct case_info info = { what, 0, 0, NULL, 0 };
            cr_assert(coverage_equal(ref, fb.count, s.w, s.h, &info));
            target_free(&fb);
            free(ref);
            scene_free(&s);
        }
}

/* --- the exhibits ------------------------------------------------------------------ */

/* Pixels of the room not covered exactly once (the room is closed). */
static int not_once(const char *variant_name, int *triangles)
{
    struct scene s = load("room", variant(variant_name));
    struct target fb = render(&s, variant(variant_name));
    int n = 0;
    for (int i = 0; i < s.w * s.h; i++)
        n += fb.count[i] != 1;
    if (triangles)
        *triangles = s.ntris;
    target_free(&fb);
    scene_free(&s);
    return n;
}

Test(lesson06, exhibits_on_the_room_are_counted)
{
    int tris;
    cr_expect_eq(not_once("clip", &tris), 0, "the exact front end: every pixel once");
    cr_expect_eq(tris, README_ROOM_TRIANGLES);
    int wrong = not_once("project-first", NULL);
    cr_expect_eq(wrong, README_PROJECT_FIRST_WRONG, "project-first: %d pixels not covered once", wrong);
    cr_expect_eq(not_once("viewport", NULL), 0, "viewport: the same picture");
    wrong = not_once("no-guard-32", NULL);
    cr_expect_eq(wrong, README_NO_GUARD_WRONG, "no-guard-32: %d pixels not covered once", wrong);
}

/* The x, y clipping a front end did: world triangles with a vertex on the
 * screen's border exactly (where a clipped coordinate is set), and the
 * distinct such vertices. */
static void border_work(const struct scene *s, int *cut, int *made)
{
    *cut = *made = 0;
    int last = -1;      /* the fan of a world triangle is consecutive */
    for (int i = 0; i < s->ntris; i++) {
        bool any = false;
        for (int k = 0; k < 3; k++) {
            const struct vertex *v = &s->tris[i].v[k];
            if (!(v->x == 0 || v->x == s->w || v->y == 0 || v->y == s->h))
                continue;
            any = true;
            bool seen = false;      /* the same vertex used before? */
            for (int j = 0; j < 3 * i + k && !seen; j++) {
                const struct vertex *u = &s->tris[j / 3].v[j % 3];
                seen = u->x == v->x && u->y == v->y && u->z == v->z;
            }
            *made += !seen;
        }
        if (any && s->world.from[i] != last) {
            (*cut)++;
            last = s->world.from[i];
        }
    }
}

Test(lesson06, viewport_clipping_does_work_the_guard_band_does_not)
{
    struct scene exact = load("room", variant("clip")), vp = load("room", variant("viewport"));
    int cut, made;
    border_work(&exact, &cut, &made);
    cr_expect(cut == 0 && made == 0, "the guard band cuts nothing on the room");
    border_work(&vp, &cut, &made);
    cr_log_info("viewport on the room: %d triangles out, %d cut, %d new vertices", vp.ntris, cut, made);
    cr_expect_eq(cut, README_VIEWPORT_CUT, "viewport: %d world triangles cut in x, y", cut);
    cr_expect_eq(made, README_VIEWPORT_MADE, "viewport: %d new vertices", made);
    scene_free(&exact);
    scene_free(&vp);
}

/* Screen vertices that should be one and are two: closer than 10^-6 px
 * but not the same bits. */
static int near_twins(const struct scene *s)
{
    int n = 0;
    for (int i = 0; i < 3 * s->ntris; i++)
        for (int j = i + 1; j < 3 * s->ntris; j++) {
            const struct vertex *a = &s->tris[i / 3].v[i % 3], *b = &s->tris[j / 3].v[j % 3];
            double dx = fabs(a->x - b->x), dy = fabs(a->y - b->y);
            n += dx < 1e-6 && dy < 1e-6 && (a->x != b->x || a->y != b->y);
        }
    return n;
}

Test(lesson06, walk_order_clipping_splits_shared_vertices)
{
    static const char *const names[] = { "room", "horizon" };
    int twins = 0;
    for (int k = 0; k < 2; k++) {
        struct scene exact = load(names[k], variant("clip"));
        struct scene walk = load(names[k], variant("walk-order"));
        cr_expect_eq(near_twins(&exact), 0, "%s: the canonical order makes every shared vertex once",
                     names[k]);
        twins += near_twins(&walk);
        scene_free(&exact);
        scene_free(&walk);
    }
    cr_expect_gt(twins, 0, "walk-order: no shared vertex came out twice");
}

/* Which wall each pixel of builtin:depth-pair shows against the exact
 * answer (the smaller exact d wins): pixels showing the wrong wall. */
static int wrong_wall(const char *variant_name)
{
    const struct lesson_variant *v = variant(variant_name);
    struct scene s = load("depth-pair", v);
    struct target fb = render(&s, v);
    int wrong = 0;
    for (int y = 0; y < s.h; y++)
        for (int x = 0; x < s.w; x++) {
            double best = INFINITY;
            bool red = false;
            for (int i = 0; i < s.ntris; i++) {
                struct tri_setup t;
                if (!tri_setup(&t, s.tris[i].v, s.w, s.h))
                    continue;
                bool in = true;
                for (int k = 0; k < 3; k++)
                    in = in && edge_inside(&t, k, edge_value(&t, k, x, y));
                double d, rgb[3], st[2];
                if (!in)
                    continue;
                reference_shade(&t, x, y, true, &d, rgb, st);
                if (d < best)
                    best = d, red = rgb[0] > rgb[2];
            }
            uint32_t c = fb.color[(size_t)y * s.w + x];
            bool shows_red = ((c >> 16) & 0xff) > (c & 0xff);
            wrong += isfinite(best) && shows_red != red;
        }
    target_free(&fb);
    scene_free(&s);
    return wrong;
}

Test(lesson06, depth_precision_exhibit_is_counted)
{
    int ndc = wrong_wall("ndc24"), d = wrong_wall("clip"), inv = wrong_wall("inverse"),
        rev = wrong_wall("reversed");
    cr_log_info("depth-pair wrong pixels: ndc24 %d, d %d, 1/d %d, reversed %d", ndc, d, inv, rev);
    cr_expect_eq(ndc, README_DEPTH_WRONG_NDC24, "24-bit NDC z: %d wrong pixels", ndc);
    cr_expect_eq(d, README_DEPTH_WRONG_D, "float d: %d wrong pixels", d);
    cr_expect_eq(inv, README_DEPTH_WRONG_INVERSE, "float 1/d: %d wrong pixels", inv);
    cr_expect_eq(rev, README_DEPTH_WRONG_REVERSED, "reversed float: %d wrong pixels", rev);
}

/* --- the other numbers of the text --------------------------------------------------- */

struct ts {
    int n;
    double t[4];
};

static void keep_t(void *ctx, const struct trace_event *ev)
{
    struct ts *ts = ctx;
    if (ev->kind == TRACE_FRONT && ev->klass == FRONT_NEW && ts->n < 4)
        ts->t[ts->n++] = ev->aux[3];
}

Test(lesson06, the_numbers_of_the_text)
{
    struct scene s = load("model", &lesson_06.variants[0]);
    cr_expect_eq(s.world.ntris, 576);
    cr_expect_eq(s.ntris, README_MODEL_TRIANGLES, "model: %d screen triangles", s.ntris);
    scene_free(&s);

    /* one step of a 24-bit window depth, in units of depth, at d = 400:
     * the smallest change of d that changes the stored integer, from the
     * NDC formula of the issue, z = (f+n)/(f-n) - 2fn/((f-n) d) */
    double n = 0.01, f = 1000, d = 400;
    double window = ((f + n) / (f - n) - 2 * f * n / ((f - n) * d) + 1) / 2;
    double slope = f * n / ((f - n) * d * d);           /* d(window)/dd */
    double step = 1.0 / 16777215 / slope;
    cr_expect(window > 0.99 && fabs(step - README_NDC24_STEP) < 0.005, "step %.4f", step);

    /* the t of the new vertices of the frustum figure (room, first triangle) */
    s = load("room", &lesson_06.variants[0]);
    struct raster_params p = default_params();
    p.at = &(struct run_place){ .scene = &s };
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, 0));
    struct ts ts = { 0 };
    struct trace tr = { .sink = keep_t, .ctx = &ts };
    struct tri_setup t;
    tri_setup(&t, s.tris[0].v, s.w, s.h);
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    lesson_06.variants[0].rasterize(&t, &p, &fb, &tr);
    cr_assert_geq(ts.n, 2);
    cr_expect(fabs(ts.t[0] - README_FRUSTUM_T0) < 0.0005 && fabs(ts.t[1] - README_FRUSTUM_T1) < 0.0005,
              "t = %.4f and %.4f", ts.t[0], ts.t[1]);
    target_free(&fb);
    scene_free(&s);
}

#if !TRISTEP_NO_ANSWERS
/* lessons/06-clipping/ANSWERS.md */
Test(lesson06, the_numbers_of_the_answers)
{
    /* 4: the 24-bit step at d = 400, f = 1000, for n = 0.01 and n = 1 */
    double f = 1000, d = 400, steps[2], ns[2] = { 0.01, 1 };
    for (int i = 0; i < 2; i++)
        steps[i] = 1.0 / 16777215 / (f * ns[i] / ((f - ns[i]) * d * d));
    cr_expect(fabs(steps[0] - 0.95) < 0.005 && fabs(steps[1] - 0.0095) < 0.00005,
              "steps %.5f %.6f", steps[0], steps[1]);
    /* 5: an edge from d = 1 (red 0) to d = 100 (red 1), cut at t = 0.5 on
     * the screen, through the guard band's own interpolation */
    struct poly p = { 3, { { .pos = { 0, 0, 1 }, .rgb = { 0, 0, 0 } },
                           { .pos = { 2 * (GUARD_BAND - 1), 0, 100 }, .rgb = { 1, 0, 0 } },
                           { .pos = { 0, 50, 1 }, .rgb = { 0, 0, 0 } } } };
    clip_guard_band(&p, NULL);
    const struct pvert *cut = NULL;
    for (int i = 0; i < p.n; i++)
        if (p.v[i].pos[0] == GUARD_BAND - 1 && p.v[i].pos[1] == 0)
            cut = &p.v[i];
    cr_assert_not_null(cut);
    /* the plane sits a hair past the middle: 16383 of 32766 */
    cr_expect(fabs(cut->pos[2] - 1.98) < 0.01, "d = %.4f", cut->pos[2]);
    cr_expect(fabs(cut->rgb[0] - 0.0099) < 0.0005, "red = %.5f", cut->rgb[0]);
    cr_expect_eq((int)lrint((0.5 - cut->rgb[0]) * 255), 125);
}
#endif

/* --- the walk order's cracks, found by the seeded search --------------------------- */

#include "search/cracks.h"

/* A number the lesson text states, by its marker (testlib.h). */
static long stated(const char *key)
{
    return (long)text_number("lessons/06-clipping/README.md", key, NULL);
}

#define CRACK_SEEDS 1300        /* the floors the text says were searched: seeds 1 to 1300 */

/* The floors of tests/search/cracks.c, seeds 1 to CRACK_SEEDS: the float
 * clipper in each triangle's own walking order cracks some of them (pixels
 * missed or covered twice along a clipped shared edge); the same float
 * clipper in the canonical order cracks none, and neither does the exact
 * front end; the counts are the text's. */
Test(lesson06, the_walk_order_cracks_floors_the_canonical_order_does_not, .timeout = 240)
{
    front_fn walk = lesson_front(&lesson_06, variant("walk-order"));
    front_fn canon = lesson_front(&lesson_06, variant("float-canonical"));
    int found = 0, canonical = 0, exact = 0, first = 0, missed = 0, doubled = 0;
    for (uint64_t seed = 1; seed <= CRACK_SEEDS; seed++) {
        struct scene s;
        cr_assert(crack_floor(&s, seed));
        int *want = crack_coverage(&s, front_scene), *w = crack_coverage(&s, walk), *c = crack_coverage(&s, canon);
        cr_assert(want && w && c);
        struct cracks kw = crack_compare(want, w, s.w, s.h), kc = crack_compare(want, c, s.w, s.h),
                      ke = crack_compare(want, want, s.w, s.h);
        if (kw.missed + kw.doubled > 0) {
            found++;
            first = first ? first : (int)seed;
            missed += kw.missed, doubled += kw.doubled;
        }
        canonical += kc.missed + kc.doubled;
        exact += ke.doubled;
        free(want), free(w), free(c);
        scene_free(&s);
    }
    cr_log_info("walk order: %d of %d floors cracked (first seed %d), %d missed, %d doubled", found,
                CRACK_SEEDS, first, missed, doubled);
    cr_expect_gt(found, 0, "the walk order cracked none of the floors");
    cr_expect_eq(found, stated("l06.cracks.found"));
    cr_expect_eq(first, stated("l06.cracks.first-seed"));
    cr_expect_eq(missed, stated("l06.cracks.missed"));
    cr_expect_eq(doubled, stated("l06.cracks.doubled"));
    cr_expect_eq(canonical, 0, "the float clipper in the canonical order cracked %d pixels", canonical);
    cr_expect_eq(canonical, stated("l06.cracks.canonical"));
    cr_expect_eq(exact, 0, "the exact front end covers a pixel of a flat floor twice");
}

/* --- clipping in clip space: the same planes ---------------------------------------- */

/* A camera near the scene's own: the eye moved up to a unit, any direction,
 * any fovy, near from 10^-3 to 1 and far from 2 to 100 near planes away. */
static struct camera nearby_camera(struct rng *r, const struct camera *c)
{
    struct camera k = *c;
    for (int i = 0; i < 3; i++) {
        k.eye[i] += rng_range(r, -1, 1);
        k.target[i] = k.eye[i] + rng_range(r, -1, 1);
        k.up[i] = rng_range(r, -1, 1);
    }
    k.target[1] += 0.01;        /* never straight up or down: up is not parallel */
    k.up[1] = 2;
    k.fovy = rng_range(r, 20, 150);
    k.near = pow(10, rng_range(r, -3, 0));
    k.far = k.near * rng_range(r, 2, 100);
    return k;
}

struct sameness {
    int cameras, tris, vertices;
    int count_differs, snapped_differs, pixels_differ, colours_differ;
    int cut;                    /* vertices the lesson made on near or far */
    double most, most_kept;     /* the largest difference of a screen coordinate, px: of any
                                   vertex, of a world vertex kept as it was */
};

/* The scene under camera c through the lesson's front end and through a
 * clip-space variant, compared triangle by triangle and pixel by pixel. */
static void compare_fronts(const struct scene *world, const struct camera *c, const char *name,
                           struct sameness *m)
{
    struct scene a, b;
    cr_assert(scene_copy(&a, world) && scene_copy(&b, world));
    a.world.cam = b.world.cam = *c;
    const struct lesson_variant *v = variant(name);
    cr_assert(front_scene(&a) && lesson_front(&lesson_06, v)(&b));
    m->cameras++;
    if (a.ntris != b.ntris) {
        m->count_differs++;
    } else {
        m->tris += a.ntris;
        for (int i = 0; i < a.ntris; i++)
            for (int k = 0; k < 3; k++) {
                const struct vertex *p = &a.tris[i].v[k], *q = &b.tris[i].v[k];
                m->vertices++;
                double dxy = fmax(fabs(p->x - q->x), fabs(p->y - q->y));
                m->most = fmax(m->most, dxy);
                bool made = p->z == c->near || p->z == c->far;
                m->cut += made;
                if (!made)
                    m->most_kept = fmax(m->most_kept, dxy);
                m->snapped_differs += snap_coord(p->x, SUBPIXEL_BITS) != snap_coord(q->x, SUBPIXEL_BITS)
                                      || snap_coord(p->y, SUBPIXEL_BITS) != snap_coord(q->y, SUBPIXEL_BITS);
            }
        struct target fa = render(&a, &lesson_06.variants[0]), fb = render(&b, v);
        for (int i = 0; i < a.w * a.h; i++) {
            m->pixels_differ += fa.count[i] != fb.count[i];
            m->colours_differ += fa.color[i] != fb.color[i];
        }
        target_free(&fa);
        target_free(&fb);
    }
    scene_free(&a);
    scene_free(&b);
}

/* The variants clip-space-gl and clip-space-vk cut at the same planes as
 * the lesson, d = near and d = far, but compute each new vertex from other
 * numbers: t = b0 / (b0 - b1) of the homogeneous boundary values instead of
 * (plane - d0) / (d1 - d0), coordinates interpolated in clip space and
 * divided by w afterwards instead of projected from view space. Equal in
 * exact arithmetic, the two round differently, so a screen coordinate may
 * differ in its last bits (a new vertex by up to about 10^-5 px here, a
 * vertex kept as it was, through the divide alone, by about 10^-9 px).
 * Coverage is decided on coordinates snapped to 1/256 px, so the pictures
 * are the same unless a coordinate lies within that difference of a half
 * step of the grid, where the two may snap apart; nothing guarantees it
 * never does. What the test holds, on every built-in 3-D scene from its own
 * camera and from 250 random cameras around it (near from 10^-3 to 1, far
 * up to 100 near planes away, fovy 20-150 degrees; one vertex in seven
 * made on near or far, every scene cut): the same screen triangles, in the same order, with
 * the same snapped vertices; the same coverage and colour in every pixel;
 * and no screen coordinate more than 10^-4 px (1/39 of a grid step) from
 * the lesson's. */
Test(lesson06, clipping_in_clip_space_gives_the_same_pixels, .timeout = 120)
{
    static const char *const names[] = { "clip-space-gl", "clip-space-vk" };
    for (int n = 0; n < 2; n++) {
        struct sameness m = { 0 };
        struct rng r = rng_for(6023 + (uint64_t)n);
        for (int i = 0; i < builtin_scene_count; i++) {
            struct scene s;
            char err[256];
            cr_assert(scene_builtin(&s, builtin_scenes[i].name, err, sizeof err), "%s", err);
            if (s.world.camera_line) {
                int cut_before = m.cut;
                compare_fronts(&s, &s.world.cam, names[n], &m);
                for (int k = 0; k < 250; k++) {
                    struct camera c = nearby_camera(&r, &s.world.cam);
                    compare_fronts(&s, &c, names[n], &m);
                }
                cr_expect_gt(m.cut, cut_before, "%s: no camera made near or far cut %s", names[n],
                             builtin_scenes[i].name);
            }
            scene_free(&s);
        }
        cr_log_info("%s: %d cameras, %d triangles, %d vertices (%d on near or far): %d counts, "
                    "%d snapped, %d pixels, %d colours differ; largest difference %.3g px, %.3g px "
                    "kept", names[n], m.cameras, m.tris, m.vertices, m.cut, m.count_differs,
                    m.snapped_differs, m.pixels_differ, m.colours_differ, m.most, m.most_kept);
        cr_expect_geq(m.cameras, 4 * 251, "%s: every built-in 3-D scene", names[n]);
        /* every scene cut (above), and one vertex in ten of all made on near
         * or far (lesson 09's sheet of small triangles cuts fewer) */
        cr_expect_gt(m.cut, m.vertices / 10, "%s: the cameras must make near and far cut", names[n]);
        cr_expect_eq(m.count_differs, 0, "%s: %d cameras made other numbers of triangles", names[n],
                     m.count_differs);
        cr_expect_eq(m.snapped_differs, 0, "%s: %d vertices snapped elsewhere", names[n], m.snapped_differs);
        cr_expect_eq(m.pixels_differ, 0, "%s: %d pixels covered otherwise", names[n], m.pixels_differ);
        cr_expect_eq(m.colours_differ, 0, "%s: %d pixels of another colour", names[n], m.colours_differ);
        cr_expect_lt(m.most, 1e-4, "%s: a screen coordinate %.3g px away", names[n], m.most);
    }
}
