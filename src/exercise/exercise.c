/* exercise.c - the student's code as a variant: checked writes, a write as
 * a step, counted direct evaluations; the exact rule as a variant. */
#include "exercise.h"

#include <stdio.h>
#include <string.h>

#include "exercise/student.h"
#include "shade/shade.h"

/* The code run by the exercise variant, its lesson, and the trace of the
 * triangle being run (the student's helpers may not pass it along). */
static rasterize_fn current_fn;
static const struct lesson *current_lesson;
static struct trace *current_tr;
static struct exercise_fault fault;

void exercise_use(const struct lesson *l, rasterize_fn fn)
{
    current_lesson = l;
    current_fn = fn;
}

const struct exercise_fault *exercise_fault(void)
{
    return &fault;
}

void exercise_fault_clear(void)
{
    memset(&fault, 0, sizeof fault);
}

static void run_exercise(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    if (!current_fn)
        return;
    struct trace *saved = current_tr;
    current_tr = tr;
    current_fn(t, p, fb, tr);
    current_tr = saved;
}

const struct lesson_variant exercise_variant = {
    "exercise", "your code, against the exact rule", run_exercise, true,
};

/* --- the student's writes --------------------------------------------------------- */

static bool on_target(const struct target *fb, int x, int y)
{
    if (x >= 0 && y >= 0 && x < fb->w && y < fb->h)
        return true;
    if (!fault.any)
        fault = (struct exercise_fault){ true, x, y, fb->w, fb->h };
    return false;
}

/* Undo student.h for the real calls below. */
#undef target_write
#undef edge_value
#undef pixel_centre

void exercise_plot(struct target *fb, struct trace *tr, int line, int x, int y, float z,
                   uint32_t rgba)
{
    if (!on_target(fb, x, y))
        return;
    if (tr)
        trace_plot(tr, fb, line, x, y, z, rgba);
    else
        target_write(fb, x, y, z, rgba);
}

void exercise_write(struct target *fb, int x, int y, float z, uint32_t rgba)
{
    int line = current_lesson ? current_lesson->exercise.write_line : 0;
    exercise_plot(fb, current_tr, line, x, y, z, rgba);
}

void exercise_fill(struct target *fb, struct trace *tr, int x, int y, float z, uint32_t rgba)
{
    if (on_target(fb, x, y) && (!tr || !tr->frozen))
        target_write(fb, x, y, z, rgba);
}

/* Direct evaluations are multiplications: I * x + J * y + K is two of them
 * (EDGE_VALUE_COST), a pixel's centre p * 256 + 128 one. */
#define PIXEL_CENTRE_COST { .mul = 1, .add = 1 }
int64_t exercise_edge_value(const struct tri_setup *t, int k, int px, int py)
{
    COUNT(current_tr, 1, EDGE_VALUE_COST);
    return edge_value(t, k < 0 ? 0 : k > 2 ? 2 : k, px, py);
}

int64_t exercise_pixel_centre(int p)
{
    COUNT(current_tr, 1, PIXEL_CENTRE_COST);
    return pixel_centre(p);
}

/* --- the exact rule ------------------------------------------------------------- */

struct exact_run {
    const struct tri_setup *t;
    const struct raster_params *p;
    struct target *fb;
    struct trace *tr;
    bool perspective;
    int line;
};

static void exact_pixel(void *ctx, int x, int y)
{
    struct exact_run *r = ctx;
    double z, rgb[3], st[2];
    reference_shade(r->t, x, y, r->perspective, &z, rgb, st);
    uint32_t c = shade_pixel(r->p, r->tr, rgb[0], rgb[1], rgb[2], st[0], st[1]);
    if (r->tr)
        trace_plot(r->tr, r->fb, r->line, x, y, (float)z, c);
    else
        target_write(r->fb, x, y, (float)z, c);
}

static void exact(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                  struct trace *tr, bool perspective)
{
    NARRATE(tr, .kind = TRACE_SETUP, .x = t->minx, .y = t->miny, .x1 = t->maxx, .y1 = t->maxy,
            .e = { t->area2, 0, 0 });
    int line = current_lesson ? current_lesson->exercise.write_line : 0;
    struct exact_run r = { t, p, fb, tr, perspective, line };
    reference_coverage(t, exact_pixel, &r);
}

static void exact_linear(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    exact(t, p, fb, tr, false);
}

static void exact_perspective(const struct tri_setup *t, const struct raster_params *p,
                              struct target *fb, struct trace *tr)
{
    exact(t, p, fb, tr, true);
}

static const struct lesson_variant exact_variants[2] = {
    { "exact", "the exact rule: reference coverage, colour and depth interpolated linearly",
      exact_linear, false },
    { "exact", "the exact rule: reference coverage, colour and depth perspective-correct",
      exact_perspective, false },
};

const struct lesson_variant *exercise_exact(bool perspective)
{
    return &exact_variants[perspective];
}

void exercise_lesson(struct lesson *out, struct lesson_variant variants[2], const struct lesson *l,
                     const char *file)
{
    static char what[300];
    snprintf(what, sizeof what, "%s, against the exact rule", file);
    *out = *l;
    variants[0] = *exercise_exact(l->perspective);
    variants[1] = exercise_variant;
    variants[1].what = what;
    out->variants = variants;
    out->nvariants = 2;
    out->exhibit_scene = NULL;      /* X toggles on the student's scene */
}
