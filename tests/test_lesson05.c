/* test_lesson05.c - lesson 05's claims: the exhibits lose or add pixels on
 * their scene, the blocks of every run tile the bounding box exactly once
 * with corner masks that say what the corners really are, full blocks are
 * full and empty blocks empty, the four-pixel and the one-pixel loops write
 * the same bytes, and the perspective-correct shading agrees with the
 * double-precision reference within a named tolerance.
 *
 * (Coverage against the reference on 100,000 random triangles, for every
 * exact variant in both builds, is test_property.c's job.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"
#include "explore/replay.h"

extern const struct lesson lesson_05, lesson_05_fast;

/* Colour: one unit of 255 for the rounding of the final value, plus the float
 * arithmetic (1/z by a reciprocal estimate and one Newton step, a/z in
 * single precision) that may push a value across a rounding boundary. */
#define COLOUR_TOLERANCE 1
/* Depth: the Newton-refined reciprocal is good to about 22 bits. */
#define DEPTH_REL_TOLERANCE 2e-6

static const struct lesson_variant *variant(const struct lesson *l, const char *name)
{
    const struct lesson_variant *v = lesson_variant(l, name);
    cr_assert_not_null(v, "lesson 05 has no variant %s", name);
    return v;
}

/* Coverage of one triangle by the reference and by a variant. */
struct diff {
    int ref, got, missing, extra;
};

static struct diff compare_one(const struct lesson_variant *v, const struct scene_tri *st, int w, int h)
{
    struct tri_setup t;
    tri_setup(&t, st->v, w, h);
    uint8_t *ref = calloc((size_t)w * (size_t)h, 1);
    cr_assert_not_null(ref);
    reference_mask(&t, ref);
    struct target fb;
    cr_assert(target_init(&fb, w, h, 0xff000000u));
    rasterize_one(v, NULL, &t, &fb, NULL);
    struct diff d = { 0 };
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        d.ref += ref[i];
        d.got += fb.count[i];
        d.missing += ref[i] > fb.count[i];
        d.extra += fb.count[i] > ref[i];
    }
    target_free(&fb);
    free(ref);
    return d;
}

static void load(struct scene *s, const char *name)
{
    char err[256];
    cr_assert(scene_builtin(s, name, err, sizeof err), "%s", err);
}

Test(lesson05, corners_outside_loses_the_small_triangle_and_the_sliver)
{
    struct scene s;
    load(&s, lesson_05.exhibit_scene);
    cr_assert_eq(s.ntris, 3);
    const struct lesson *ls[] = { &lesson_05, &lesson_05_fast };
    for (int b = 0; b < 2; b++) {
        const struct lesson_variant *v = variant(ls[b], "corners-outside");
        /* triangle 0: inside one block, containing none of the block's corners */
        struct diff small = compare_one(v, &s.tris[0], s.w, s.h);
        cr_expect_gt(small.ref, 5, "the small triangle covers %d pixels", small.ref);
        cr_expect_eq(small.got, 0, "corners-outside drew %d of its %d pixels", small.got, small.ref);
        /* triangle 1: a sliver between the corners of the blocks it crosses */
        struct diff sliver = compare_one(v, &s.tris[1], s.w, s.h);
        cr_expect_gt(sliver.missing, sliver.ref / 2, "the sliver lost only %d of %d pixels",
                     sliver.missing, sliver.ref);
        cr_expect_eq(sliver.extra, 0);
        /* never a pixel too many: skipping is all this exhibit does wrong */
        struct diff wide = compare_one(v, &s.tris[2], s.w, s.h);
        cr_expect_eq(wide.extra, 0);
    }
    scene_free(&s);
}

Test(lesson05, or_inside_draws_pixels_outside_the_triangle)
{
    struct scene s;
    load(&s, lesson_05.exhibit_scene);
    const struct lesson *ls[] = { &lesson_05, &lesson_05_fast };
    for (int b = 0; b < 2; b++) {
        const struct lesson_variant *v = variant(ls[b], "or-inside");
        struct diff wide = compare_one(v, &s.tris[2], s.w, s.h);
        cr_expect_gt(wide.extra, 20, "or-inside added only %d pixels", wide.extra);
        cr_expect_eq(wide.missing, 0, "or-inside lost %d pixels", wide.missing);
    }
    scene_free(&s);
}

/* --- the blocks of a narrated run ------------------------------------------ */

struct blocks_seen {
    const struct tri_setup *t;
    int w, h;
    uint8_t *leaf;          /* how many leaf blocks hold each pixel of the box */
    uint8_t *tested;        /* how many PIXEL_TEST events each pixel had */
    int bad_mask, full_not_full, empty_not_empty, leaves, partial_area;
    int last_partial_x0, last_partial_y0, last_partial_x1, last_partial_y1;
    int pixel_outside_partial;
    const uint8_t *ref;
};

static void on_event(void *ctx, const struct trace_event *ev)
{
    struct blocks_seen *b = ctx;
    const struct tri_setup *t = b->t;
    if (ev->kind == TRACE_PIXEL_TEST) {
        b->tested[(size_t)ev->y * (size_t)b->w + (size_t)ev->x]++;
        if (ev->x < b->last_partial_x0 || ev->x > b->last_partial_x1
            || ev->y < b->last_partial_y0 || ev->y > b->last_partial_y1)
            b->pixel_outside_partial++;
        return;
    }
    if (ev->kind != TRACE_BLOCK)
        return;
    /* the masks, recomputed from scratch at the corner pixels' centres */
    int cx[4] = { ev->x, ev->x1, ev->x, ev->x1 }, cy[4] = { ev->y, ev->y, ev->y1, ev->y1 };
    for (int k = 0; k < 3; k++) {
        unsigned m = 0;
        for (int c = 0; c < 4; c++)
            m |= (unsigned)edge_inside(t, k, edge_value(t, k, cx[c], cy[c])) << (3 - c);
        b->bad_mask += m != ev->mask[k];
    }
    /* a partial coarse block of the hierarchical variant (aux: q = 64): its
     * sub-blocks follow and are the leaves */
    if (ev->klass == BLOCK_PARTIAL && ev->aux[0] == 64.0f)
        return;
    b->leaves++;
    for (int y = ev->y; y <= ev->y1; y++)
        for (int x = ev->x; x <= ev->x1; x++) {
            size_t i = (size_t)y * (size_t)b->w + (size_t)x;
            b->leaf[i]++;
            b->full_not_full += ev->klass == BLOCK_FULL && !b->ref[i];
            b->empty_not_empty += ev->klass == BLOCK_EMPTY && b->ref[i];
        }
    if (ev->klass == BLOCK_PARTIAL) {
        b->partial_area += (ev->x1 - ev->x + 1) * (ev->y1 - ev->y + 1);
        b->last_partial_x0 = ev->x;
        b->last_partial_y0 = ev->y;
        b->last_partial_x1 = ev->x1;
        b->last_partial_y1 = ev->y1;
    } else {
        b->last_partial_x0 = b->last_partial_y0 = 1;    /* no pixel events until the next partial */
        b->last_partial_x1 = b->last_partial_y1 = 0;
    }
}

/* Run one triangle narrated and check what the blocks say. */
static void check_blocks(const struct lesson_variant *v, const struct vertex tri[3], int w, int h,
                         const struct raster_params *p, const char *what)
{
    struct tri_setup t;
    tri_setup(&t, tri, w, h);
    size_t n = (size_t)w * (size_t)h;
    uint8_t *ref = calloc(n, 1), *leaf = calloc(n, 1), *tested = calloc(n, 1);
    cr_assert(ref && leaf && tested);
    reference_mask(&t, ref);
    struct target fb;
    cr_assert(target_init(&fb, w, h, 0xff000000u));
    struct blocks_seen b = { .t = &t, .w = w, .h = h, .leaf = leaf, .tested = tested, .ref = ref,
                             .last_partial_x0 = 1 };
    struct trace tr = { .sink = on_event, .ctx = &b };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    rasterize_one(v, p, &t, &fb, &tr);

    cr_assert_eq(b.bad_mask, 0, "%s: %d corner masks disagree with the edge values", what, b.bad_mask);
    cr_assert_eq(b.pixel_outside_partial, 0, "%s: pixel tests outside the partial block", what);
    uint64_t blocks = tr.c.blocks[BLOCK_EMPTY] + tr.c.blocks[BLOCK_FULL] + tr.c.blocks[BLOCK_PARTIAL];
    if (t.empty) {
        cr_assert_eq(blocks, 0, "%s: blocks for an empty triangle", what);
    } else {
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                bool in_box = x >= t.minx && x <= t.maxx && y >= t.miny && y <= t.maxy;
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                cr_assert_eq(leaf[i], in_box ? 1 : 0, "%s: pixel (%d, %d) is in %d blocks (box %s)",
                             what, x, y, leaf[i], in_box ? "inside" : "outside");
                /* a pixel is tested once if its block is partial, never otherwise */
                cr_assert_leq(tested[i], 1, "%s: pixel (%d, %d) tested twice", what, x, y);
            }
    }
    if (!variant_against_exact(v)) {
        cr_assert_eq(b.full_not_full, 0, "%s: a full block holds uncovered pixels", what);
        cr_assert_eq(b.empty_not_empty, 0, "%s: an empty block holds covered pixels", what);
        uint64_t ref_covered = 0;
        for (size_t i = 0; i < n; i++)
            ref_covered += ref[i];
        cr_assert_eq(tr.c.covered, ref_covered, "%s: the counters say %llu covered, the reference %llu",
                     what, (unsigned long long)tr.c.covered, (unsigned long long)ref_covered);
    }
    cr_assert_eq(tr.c.tested, (uint64_t)b.partial_area,
                 "%s: %llu pixel tests for %d pixels of partial blocks", what,
                 (unsigned long long)tr.c.tested, b.partial_area);
    target_free(&fb);
    free(ref);
    free(leaf);
    free(tested);
}

Test(lesson05, blocks_tile_the_box_once_with_true_masks)
{
    struct scene s;
    load(&s, lesson_05.builtin_scene);
    struct rng rng = rng_for(0x05b10c);
    for (int vi = 0; vi < lesson_05.nvariants; vi++) {
        const struct lesson_variant *v = &lesson_05.variants[vi];
        char what[160];
        for (int i = 0; i < s.ntris; i++) {
            snprintf(what, sizeof what, "%s on builtin:%s", v->name, lesson_05.builtin_scene);
            check_blocks(v, s.tris[i].v, s.w, s.h, NULL, what);
        }
        for (int i = 0; i < 300; i++) {
            struct vertex tri[3];
            enum tri_category cat = (enum tri_category)(i % CAT_COUNT);
            int w = 150, h = 110;
            random_tri(&rng, cat, w, h, tri);
            snprintf(what, sizeof what, "%s, random %s triangle %d (seed %#llx)", v->name,
                     tri_category_name(cat), i, (unsigned long long)test_seed());
            check_blocks(v, tri, w, h, NULL, what);
        }
    }
    /* every block size the explorer offers for variants[0] */
    int sizes[] = { 4, 8, 16 };
    for (int k = 0; k < 3; k++) {
        struct raster_params p = default_params();
        cr_assert(lesson_param_set(&lesson_05, &p, "block-size", sizes[k]));
        char what[96];
        snprintf(what, sizeof what, "q8 with --block-size %d", sizes[k]);
        check_blocks(&lesson_05.variants[0], s.tris[0].v, s.w, s.h, &p, what);
    }
    scene_free(&s);
}

/* --- shading ---------------------------------------------------------------- */

static void render(const struct lesson_variant *v, const struct scene *s, const struct raster_params *p,
                   bool traced, struct target *fb)
{
    cr_assert(target_init(fb, s->w, s->h, scene_background(s)));
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        struct trace tr = { 0 };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        rasterize_one(v, p, &t, fb, traced ? &tr : NULL);
    }
}

/* A random scene of overlapping triangles with varied depths. */
static void random_scene(struct scene *s, struct rng *rng, int w, int h, int n, int checker)
{
    memset(s, 0, sizeof *s);
    s->w = w;
    s->h = h;
    s->checker = checker;
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        random_tri(rng, i % 3 ? CAT_GENERIC : CAT_LARGE, w, h, v);
        for (int k = 0; k < 3; k++) {
            v[k].z = rng_range(rng, 1.0, 20.0);
            v[k].s = rng_unit(rng);
            v[k].t = rng_unit(rng);
        }
        cr_assert(scene_add(s, v));
    }
}

Test(lesson05, one_pixel_and_four_pixel_loops_write_the_same_bytes)
{
    struct rng rng = rng_for(0x05a11);
    for (int sc = 0; sc < 4; sc++) {
        struct scene s;
        random_scene(&s, &rng, 97, 61, 40, sc & 1 ? 4 : 0);
        struct raster_params p = default_params();
        p.checker = s.checker;
        struct target quads, pixels, traced, fast;
        render(variant(&lesson_05, "q8"), &s, &p, false, &quads);
        render(variant(&lesson_05, "q8-pixel"), &s, &p, false, &pixels);
        render(variant(&lesson_05, "q8"), &s, &p, true, &traced);
        render(variant(&lesson_05_fast, "q8"), &s, &p, false, &fast);
        size_t n = (size_t)s.w * (size_t)s.h;
        const struct target *others[] = { &pixels, &traced, &fast };
        const char *names[] = { "q8-pixel", "q8 narrated, traced", "q8 fast build" };
        for (int o = 0; o < 3; o++) {
            cr_assert(memcmp(quads.color, others[o]->color, n * sizeof *quads.color) == 0,
                      "scene %d: %s writes other colours than q8", sc, names[o]);
            cr_assert(memcmp(quads.depth, others[o]->depth, n * sizeof *quads.depth) == 0,
                      "scene %d: %s writes other depths than q8", sc, names[o]);
        }
        target_free(&quads);
        target_free(&pixels);
        target_free(&traced);
        target_free(&fast);
        scene_free(&s);
    }
}

Test(lesson05, shading_is_perspective_correct_within_tolerance)
{
    struct rng rng = rng_for(0x05c01);
    const char *names[] = { "q8", "q4", "q16", "hier", "q8-pixel" };
    int checked = 0;
    for (int sc = 0; sc < 12; sc++) {
        struct vertex v[3];
        int w = 80, h = 60;
        random_tri(&rng, sc % 3 ? CAT_LARGE : CAT_GENERIC, w, h, v);
        for (int k = 0; k < 3; k++)
            v[k].z = rng_range(&rng, 0.5, 50.0);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        for (int vi = 0; vi < 5; vi++) {
            for (int b = 0; b < 2; b++) {
                const struct lesson_variant *lv = variant(b ? &lesson_05_fast : &lesson_05, names[vi]);
                struct target fb;
                cr_assert(target_init(&fb, w, h, 0xff000000u));
                rasterize_one(lv, NULL, &t, &fb, NULL);
                char why[160];
                int k = reference_shading_check(&fb, &t, COLOUR_TOLERANCE, DEPTH_REL_TOLERANCE, why, sizeof why);
                cr_assert_geq(k, 0, "%s: %s", names[vi], why);
                checked += k;
                target_free(&fb);
            }
        }
    }
    cr_assert_gt(checked, 10000, "only %d pixels compared", checked);
}

/* Edges too long for the int32 lanes of the four-pixel partial loop: the
 * lesson falls back to the exact 64-bit loop, and stays exact. */
Test(lesson05, huge_triangles_stay_exact)
{
    struct vertex v[3] = { test_vertex(-16000.3, 100.7), test_vertex(16300.1, 40.2),
                           test_vertex(30.5, 16200.9) };   /* edge AB crosses the target */
    struct scene_tri st;
    memcpy(st.v, v, sizeof v);
    const struct lesson *ls[] = { &lesson_05, &lesson_05_fast };
    for (int b = 0; b < 2; b++)
        for (int vi = 0; vi < ls[b]->nvariants; vi++) {
            if (variant_against_exact(&ls[b]->variants[vi]))
                continue;
            struct diff d = compare_one(&ls[b]->variants[vi], &st, 301, 203);
            cr_expect_gt(d.ref, 1000);
            cr_expect(d.missing == 0 && d.extra == 0, "%s: %d missing, %d extra",
                      ls[b]->variants[vi].name, d.missing, d.extra);
        }
}
