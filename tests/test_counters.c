/* test_counters.c - the operation counters are the named costs.
 *
 * Every lesson declares what one pixel costs in named operations
 * (lesson->cost_tested: every pixel tested, lesson->cost_covered: on top of
 * that every pixel covered, shading included), and its code counts with the
 * same names (COUNT(tr, n, EDGE_VALUE_COST), trace/trace.h). This test
 * recounts, for each lesson's algorithm (variants[0]), the multiplications
 * between one pixel and the next of the same row from the events the code
 * narrates, and holds them equal to what the declaration adds up to. So
 * "0 multiplications per pixel" in lesson 03 is a measured fact about the
 * code, shading of the covered pixels included.
 */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"
#include "testlib.h"

extern const struct lesson lesson_03;

/* The sum of a declaration's terms. */
static struct op_cost declared(const struct cost_term *terms)
{
    struct op_cost sum = { 0, 0 };
    for (; terms && terms->n; terms++) {
        sum.mul += terms->n * terms->cost.mul;
        sum.add += terms->n * terms->cost.add;
    }
    return sum;
}

struct events {
    struct trace_event *ev;
    size_t n, cap;
};

static void keep(void *ctx, const struct trace_event *ev)
{
    struct events *e = ctx;
    if (e->n == e->cap) {
        e->cap = e->cap ? 2 * e->cap : 1024;
        e->ev = realloc(e->ev, e->cap * sizeof *e->ev);
        cr_assert_not_null(e->ev);
    }
    e->ev[e->n++] = *ev;
}

/* One pixel as the narration shows it: a test, a write, or a test and the
 * write of the same pixel right after it; `end` is its last event. */
struct pixel {
    int x, y;
    bool covered;
    const struct trace_event *end;
};

/* Multiplications per pixel of one triangle run through the lesson: every
 * pair of neighbouring pixels of a row with no other event between them.
 * Returns the number of pairs checked. */
static int check_triangle(const struct lesson *l, const struct tri_setup *t, int n)
{
    struct target fb;
    cr_assert(target_init(&fb, t->target_w, t->target_h, 0));
    struct events e = { 0 };
    struct trace tr = { .sink = keep, .ctx = &e };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    struct raster_params p = default_params();
    l->variants[0].rasterize(t, &p, &fb, &tr);

    unsigned tested = declared(l->cost_tested).mul, covered = declared(l->cost_covered).mul;
    int pairs = 0;
    struct pixel prev = { .end = NULL };
    for (size_t i = 0; i < e.n; i++) {
        const struct trace_event *ev = &e.ev[i];
        if (ev->kind != TRACE_PIXEL_TEST && ev->kind != TRACE_PIXEL_WRITE) {
            prev.end = NULL;            /* a row, span or block between: start again */
            continue;
        }
        struct pixel px = { ev->x, ev->y, ev->kind == TRACE_PIXEL_WRITE, ev };
        if (ev->kind == TRACE_PIXEL_TEST && i + 1 < e.n && e.ev[i + 1].kind == TRACE_PIXEL_WRITE
            && e.ev[i + 1].x == ev->x && e.ev[i + 1].y == ev->y) {
            px.covered = true;
            px.end = &e.ev[++i];
        }
        if (prev.end && px.y == prev.y && px.x == prev.x + 1) {
            /* a write with no test of its own (a quad's pixels written after
             * its tests, lesson 09) costs what a covered pixel adds */
            bool bare = ev->kind == TRACE_PIXEL_WRITE;
            uint64_t want = (bare ? 0 : tested) + (px.covered ? covered : 0);
            uint64_t got = px.end->mul - prev.end->mul;
            cr_assert_eq(got, want, "%s, triangle %d: pixel (%d, %d) %s cost %llu "
                         "multiplications, the declaration says %llu", l->id, n, px.x, px.y,
                         px.covered ? "covered" : "tested", (unsigned long long)got,
                         (unsigned long long)want);
            pairs++;
        }
        prev = px;
    }
    free(e.ev);
    target_free(&fb);
    return pairs;
}

Test(counters, every_lesson_counts_what_it_declares_per_pixel)
{
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        cr_assert_not_null(l->cost_covered, "%s declares no cost per covered pixel", l->id);
        struct rng r = rng_for(0xc0 + (uint64_t)li);
        int pairs = 0;
        for (int n = 0; n < 60; n++) {
            struct vertex v[3];
            random_tri(&r, n % 2 ? CAT_GENERIC : CAT_LARGE, 64, 48, v);
            struct tri_setup t;
            tri_setup(&t, v, 64, 48);
            pairs += check_triangle(l, &t, n);
        }
        cr_expect_gt(pairs, 1000, "%s: only %d neighbouring pixels recounted", l->id, pairs);
    }
}

/* The lesson's claim, from both sides: its declaration adds up to no
 * multiplication per pixel, tested or covered, and the recount above holds
 * the code to it. */
Test(counters, lesson03_pixel_loop_has_no_multiplication)
{
    cr_expect_eq(declared(lesson_03.cost_tested).mul, 0);
    cr_expect_eq(declared(lesson_03.cost_covered).mul, 0);
    cr_expect_gt(declared(lesson_03.cost_tested).add, 0, "it does add");
}

/* Lesson 03's README, "What it costs": the counts on builtin:edge-steps and
 * builtin:float-drift, and the table's per-pixel figures they follow from
 * (edge-steps: 187 tested, 82 covered, 11 rows, one triangle). */
static void scene_counts(const struct lesson *l, const char *name, struct trace_counters *sum)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, name, err, sizeof err), "%s", err);
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, 0));
    struct raster_params p = default_params();
    p.checker = s.checker;
    memset(sum, 0, sizeof *sum);
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        struct trace tr = { 0 };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        l->variants[0].rasterize(&t, &p, &fb, &tr);
        sum->mul += tr.c.mul, sum->add += tr.c.add;
        sum->tested += tr.c.tested, sum->covered += tr.c.covered, sum->rows += tr.c.rows;
    }
    target_free(&fb);
    scene_free(&s);
}

Test(counters, lesson03_readme_counts)
{
    extern const struct lesson lesson_02;
    struct trace_counters c02, c03;
    scene_counts(&lesson_02, "edge-steps", &c02);
    scene_counts(&lesson_03, "edge-steps", &c03);
    cr_assert_eq(c02.tested, 187);
    cr_assert_eq(c02.covered, 82);
    cr_assert_eq(c03.rows, 11);
    /* the table: lesson 02 6 mul, 9 add per pixel tested, 24 mul, 15 add more
     * per pixel covered; lesson 03 0 mul, 9 add, then 3 add, per row 21 mul,
     * 18 add, per triangle 52 mul, 21 add */
    cr_expect_eq(c02.mul, 187 * 6 + 82 * 24);
    cr_expect_eq(c02.add, 187 * 9 + 82 * 15);
    cr_expect_eq(c03.mul, 52 + 11 * 21);
    cr_expect_eq(c03.add, 21 + 11 * 18 + 187 * 9 + 82 * 3);
    /* the numbers the text quotes */
    cr_expect_eq(c02.mul, 3090);
    cr_expect_eq(c02.add, 2913);
    cr_expect_eq(c03.mul, 283);
    cr_expect_eq(c03.add, 2148);
    scene_counts(&lesson_02, "float-drift", &c02);
    scene_counts(&lesson_03, "float-drift", &c03);
    cr_expect_eq(c02.mul, 1229874);
    cr_expect_eq(c03.mul, 6551);
}

/* Lesson 05 shades the pixels of a full block without testing them, four at
 * a time: no narrated pixel to recount there. Over a whole triangle its
 * multiplications are then the blocks' corner tests plus the declared cost
 * of every covered pixel, full blocks included: what is left after taking
 * the covered pixels off is the same amount for every block classified. */
Test(counters, lesson05_full_blocks_shade_at_the_declared_cost)
{
    extern const struct lesson lesson_05;
    unsigned covered = declared(lesson_05.cost_covered).mul;
    cr_assert_gt(covered, 0);
    struct rng r = rng_for(0xc05);
    int64_t per_block = -1;
    int full = 0;
    for (int n = 0; n < 200; n++) {
        struct vertex v[3];
        random_tri(&r, n % 2 ? CAT_GENERIC : CAT_LARGE, 96, 64, v);
        struct tri_setup t;
        tri_setup(&t, v, 96, 64);
        if (t.empty)
            continue;
        struct target fb;
        cr_assert(target_init(&fb, 96, 64, 0));
        struct trace tr = { 0 };
        trace_begin(&tr, 0, TRACE_UNLIMITED);
        struct raster_params p = default_params();
        lesson_05.variants[0].rasterize(&t, &p, &fb, &tr);
        uint64_t blocks = 0;
        for (int k = 0; k < BLOCK_CLASS_COUNT; k++)
            blocks += tr.c.blocks[k];
        full += tr.c.blocks[BLOCK_FULL] > 0;
        int64_t rest = (int64_t)tr.c.mul - (int64_t)(tr.c.covered * covered);
        cr_assert_gt(blocks, 0);
        cr_assert_eq(rest % (int64_t)blocks, 0, "triangle %d: %lld multiplications besides the "
                     "covered pixels for %llu blocks", n, (long long)rest, (unsigned long long)blocks);
        if (per_block < 0)
            per_block = rest / (int64_t)blocks;
        cr_assert_eq(rest / (int64_t)blocks, per_block, "triangle %d: the same cost per block", n);
        target_free(&fb);
    }
    cr_expect_gt(per_block, 0, "classifying a block multiplies");
    cr_expect_gt(full, 20, "only %d triangles with a full block", full);
}
