/* test_lines.c - every line of every lesson's pseudo-code is lit by some
 * step of its narration.
 *
 * The explorer lights the pseudo-code line an event points at (and the
 * lines above it that the event's span takes in). A line that
 * no event ever points at is one the student can never watch happen: the
 * narration skips a step of the algorithm it shows (or the line describes
 * code that is not there). Each lesson is stepped through every variant on
 * every built-in scene, as its program and explorer run them (a 3-D scene
 * through the variant's front end, units in the lesson's own order, lesson
 * 08 at its default sample count), and the lines lit are collected; the
 * test fails on each line lit by none, and names it.
 */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "explore/replay.h"
#include "front/front.h"
#include "testlib.h"

#define MAX_LINES 64

struct lit {
    bool line[MAX_LINES];
    int beyond;                 /* events pointing past the last line */
};

static void light(void *ctx, const struct trace_event *ev)
{
    struct lit *l = ctx;
    if (ev->line >= MAX_LINES || ev->span > ev->line) {
        l->beyond++;
        return;
    }
    for (int n = ev->line - ev->span; n <= ev->line; n++)   /* a step may light a few lines */
        l->line[n] = true;
}

/* Every step of variant v on scene s (its screen triangles made), unit by
 * unit as the explorer's replay counts them, each event told to light(). */
static void step_through(const struct lesson *l, const struct lesson_variant *v, const struct scene *s,
                         struct lit *lit)
{
    struct raster_params p = default_params();
    p.at = &(struct run_place){ .scene = s };
    if (lesson_param(l, "samples", NULL))
        p.samples = lesson_param(l, "samples", NULL)->def;
    struct replay r;
    cr_assert(replay_begin_units(&r, s, v, &p, l->narration_units), "%s/%s: out of memory", l->id,
              v->name);
    struct target fb;
    cr_assert(target_init(&fb, s->w, s->h, scene_background(s)) && target_multisample(&fb, p.samples));
    struct trace tr = { .sink = light, .ctx = lit };
    for (int i = 0; i < r.ntris; i++) {
        struct tri_setup t;
        replay_setup(&r, i, &t);
        struct run_place at;
        struct raster_params pi = replay_params(&r, i, &at);
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        v->rasterize(&t, &pi, &fb, &tr);
    }
    target_free(&fb);
    replay_free(&r);
}

Test(lines, every_pseudocode_line_is_lit_by_a_step, .timeout = 240)
{
    char unlit[4096] = "";
    size_t at = 0;
    int missing = 0;
    for (int li = 0; all_lessons[li]; li++) {
        const struct lesson *l = all_lessons[li];
        int nlines = 0;
        while (l->pseudocode[nlines])
            nlines++;
        cr_assert_leq(nlines, MAX_LINES);
        struct lit lit = { 0 };
        for (int k = 0; k < builtin_scene_count; k++) {
            struct scene given;
            char err[256];
            cr_assert(scene_builtin(&given, builtin_scenes[k].name, err, sizeof err), "%s", err);
            for (int vi = 0; vi < l->nvariants; vi++) {
                const struct lesson_variant *v = &l->variants[vi];
                struct scene s;
                cr_assert(scene_copy(&s, &given) && lesson_front(l, v)(&s));
                step_through(l, v, &s, &lit);
                scene_free(&s);
            }
            scene_free(&given);
        }
        cr_expect_eq(lit.beyond, 0, "%s: %d events point past its %d pseudo-code lines", l->id,
                     lit.beyond, nlines);
        for (int n = 0; n < nlines; n++) {
            if (!lit.line[n]) {
                missing++;
                at += (size_t)snprintf(unlit + at, at < sizeof unlit ? sizeof unlit - at : 0,
                                       "\n  %s line %d: %s", l->id, n + 1, l->pseudocode[n]);
                at = at < sizeof unlit ? at : sizeof unlit - 1;
            }
        }
    }
    cr_expect_eq(missing, 0, "%d pseudo-code lines lit by no step:%s", missing, unlit);
}
