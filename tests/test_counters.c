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
            uint64_t want = tested + (px.covered ? covered : 0);
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
