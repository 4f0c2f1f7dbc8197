/* exercise.c - the student's code as a variant: checked writes, a write as
 * a step, counted direct evaluations; the exact rule as a variant. */
#include "exercise.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "exercise/student.h"
#include "shade/shade.h"

/* The code run by the exercise variant, its lesson, and the trace of the
 * triangle being run (the student's helpers may not pass it along). */
static rasterize_fn current_fn;
static bool (*remote_draw)(struct target *fb, struct trace *tr);
static const struct lesson *current_lesson;
static struct trace *current_tr;
static struct exercise_fault fault;
static struct texel_fault texel_fault;
static struct texel_reads texel_reads;

static const struct exercise_variant *current_variant;

void exercise_use(const struct lesson *l, rasterize_fn fn)
{
    current_lesson = l;
    current_fn = fn;
    current_variant = NULL;
    exercise_use_clip(NULL);
    exercise_use_front(NULL);
}

void exercise_use_variant(const struct exercise_variant *v)
{
    current_variant = v;
}

const struct exercise_variant *exercise_current_variant(void)
{
    return current_variant;
}

enum fill_convention exercise_rule(void)
{
    return current_variant ? current_variant->rule : FILL_TOP_LEFT;
}

const struct exercise_variant *exercise_variant_named(const struct lesson *l, const char *name)
{
    for (const struct exercise_variant *v = l->exercise.variants; v && v->name; v++)
        if (strcmp(v->name, name) == 0)
            return v;
    return NULL;
}

void exercise_use_remote(bool (*draw)(struct target *fb, struct trace *tr))
{
    remote_draw = draw;
}

const struct exercise_fault *exercise_fault(void)
{
    return &fault;
}

void exercise_fault_clear(void)
{
    memset(&fault, 0, sizeof fault);
    memset(&texel_fault, 0, sizeof texel_fault);
    exercise_texel_reads_clear();
}

const struct texel_reads *exercise_texel_reads(void)
{
    return &texel_reads;
}

void exercise_texel_reads_clear(void)
{
    memset(&texel_reads, 0, sizeof texel_reads);
}

void exercise_texel_reads_add(const struct texel_reads *r)
{
    texel_reads.n += r->n;
    texel_reads.levels |= r->levels;
}

const struct texel_fault *exercise_texel_fault(void)
{
    return &texel_fault;
}

void exercise_fault_set(const struct exercise_fault *f, const struct texel_fault *t)
{
    fault = *f;
    texel_fault = *t;
}

uint32_t exercise_texel(const struct texture *tex, int k, int64_t i, int64_t j)
{
    bool level = k >= 0 && k < tex->nlevels;
    const struct texture_level *l = level ? &tex->level[k] : NULL;
    texel_reads.n++;
    if (level)
        texel_reads.levels |= 1u << k;
    if (l && i >= 0 && j >= 0 && i < l->w && j < l->h)
        return l->texel[(size_t)j * (size_t)l->w + (size_t)i];
    if (!texel_fault.any)
        texel_fault = (struct texel_fault){ true, k, tex->nlevels, (long long)i, (long long)j,
                                            l ? l->w : 0, l ? l->h : 0 };
    return 0xff000000u;
}

static void run_exercise(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    if (remote_draw) {          /* drawn by the runner: its results */
        remote_draw(fb, tr);
        return;
    }
    if (!current_fn)
        return;
    struct trace *saved = current_tr;
    current_tr = tr;
    current_fn(t, p, fb, tr);
    current_tr = saved;
}

const struct lesson_variant exercise_variant = {
    .name = "exercise", .kind = VARIANT_EXERCISE, .rasterize = run_exercise,
    .what = "your code, against the exact rule",
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

/* Depth at the point (sx, sy), in 1/256 pixel, in double precision: the
 * barycentric weights from the edge values there, z interpolated as 1/z
 * (perspective) or linearly. */
static double depth_at(const struct tri_setup *t, int64_t sx, int64_t sy, bool perspective)
{
    double w[3], z = 0;
    for (int i = 0; i < 3; i++) {   /* weight of vertex i: the edge facing it, (i + 1) % 3 */
        int k = (i + 1) % 3;
        w[i] = (double)(t->I[k] * sx + t->J[k] * sy + t->K[k]) / (double)t->area2;
        z += perspective ? w[i] / t->v[i].z : w[i] * t->v[i].z;
    }
    return perspective ? 1.0 / z : z;
}

/* The exact rule at n > 1 samples (lessons/CONVENTIONS.md, "Samples"): each sample
 * of sample_pattern(n) decided by reference_point_covered, its depth exact
 * at the sample, the colour the pixel centre's (one colour per pixel, as
 * MSAA shades); each covered sample depth-tested, the pixel resolved to the
 * rounded mean of its samples, the nearest sample's depth, and count plus
 * the covered samples. Every pixel a sample of which may be covered: the
 * box of centres and a pixel more each side. */
static void exact_samples(const struct tri_setup *t, const struct raster_params *p,
                          struct target *fb, struct trace *tr, bool perspective, int line)
{
    const struct sample_pattern *sp = sample_pattern(p->samples);
    if (!sp || ((!fb->samples || fb->samples->n != sp->n) && !target_multisample(fb, sp->n)))
        return;
    int n = sp->n;
    if (t->area2 <= 0)
        return;
    int x0 = t->minx - 1 < 0 ? 0 : t->minx - 1, y0 = t->miny - 1 < 0 ? 0 : t->miny - 1;
    int x1 = t->maxx + 1 >= fb->w ? fb->w - 1 : t->maxx + 1;
    int y1 = t->maxy + 1 >= fb->h ? fb->h - 1 : t->maxy + 1;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            unsigned mask = 0;
            for (int s = 0; s < n; s++)
                if (reference_point_covered_rule(t, exercise_rule(), (int64_t)x * SUBPIXEL_ONE + sp->x[s],
                                                 (int64_t)y * SUBPIXEL_ONE + sp->y[s]))
                    mask |= 1u << s;
            if (!mask)
                continue;
            double zc, rgb[3], st[2];
            reference_shade(t, x, y, perspective, &zc, rgb, st);
            uint32_t c = shade_pixel(p, NULL, rgb[0], rgb[1], rgb[2], st[0], st[1]);
            size_t i = (size_t)y * (size_t)fb->w + (size_t)x, base = i * (size_t)n;
            unsigned sum[3] = { 0, 0, 0 };
            float nearest = INFINITY;
            for (int s = 0; s < n; s++) {
                if (mask >> s & 1) {
                    float z = (float)depth_at(t, (int64_t)x * SUBPIXEL_ONE + sp->x[s],
                                              (int64_t)y * SUBPIXEL_ONE + sp->y[s], perspective);
                    if (z < fb->samples->depth[base + (size_t)s]) {
                        fb->samples->depth[base + (size_t)s] = z;
                        fb->samples->color[base + (size_t)s] = c;
                    }
                }
                uint32_t sc = fb->samples->color[base + (size_t)s];
                for (int ch = 0; ch < 3; ch++)
                    sum[ch] += sc >> (16 - 8 * ch) & 0xff;
                float sz = fb->samples->depth[base + (size_t)s];
                nearest = sz < nearest ? sz : nearest;
            }
            uint32_t rgba = 0xff000000u;
            for (int ch = 0; ch < 3; ch++)
                rgba |= (sum[ch] + (unsigned)n / 2) / (unsigned)n << (16 - 8 * ch);
            NARRATE(tr, .kind = TRACE_PIXEL_WRITE, .line = line, .x = x, .y = y, .z = nearest,
                    .rgba = rgba, .mask = { (uint16_t)mask },
                    .aux = { (float)n, (float)__builtin_popcount(mask), (float)mask, 0 });
            if (tr && tr->frozen)
                continue;
            fb->color[i] = rgba;
            fb->depth[i] = nearest;
            if (fb->count) {
                unsigned cnt = fb->count[i] + (unsigned)__builtin_popcount(mask);
                fb->count[i] = (uint8_t)(cnt > 255 ? 255 : cnt);
            }
        }
}

static void exact(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                  struct trace *tr, bool perspective)
{
    NARRATE(tr, .kind = TRACE_SETUP, .x = t->minx, .y = t->miny, .x1 = t->maxx, .y1 = t->maxy,
            .e = { t->area2, 0, 0 });
    int line = current_lesson ? current_lesson->exercise.write_line : 0;
    if (p->samples > 1) {
        exact_samples(t, p, fb, tr, perspective, line);
        return;
    }
    struct exact_run r = { t, p, fb, tr, perspective, line };
    reference_coverage_rule(t, exercise_rule(), exact_pixel, &r);
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
    { .name = "exact", .kind = VARIANT_ALGORITHM, .rasterize = exact_linear,
      .what = "the exact rule: reference coverage, colour and depth interpolated linearly" },
    { .name = "exact", .kind = VARIANT_ALGORITHM, .rasterize = exact_perspective,
      .what = "the exact rule: reference coverage, colour and depth perspective-correct" },
};

const struct lesson_variant *exercise_exact(bool perspective)
{
    return &exact_variants[perspective];
}

void exercise_lesson(struct lesson *out, struct lesson_variant variants[2], const struct lesson *l,
                     const char *file)
{
    static char what[300];
    if (current_variant)
        snprintf(what, sizeof what, "%s, against the exact rule, variant %s", file, current_variant->name);
    else
        snprintf(what, sizeof what, "%s, against the exact rule", file);
    *out = *l;
    /* the exact picture: the shared rule's, or the lesson's own where the
     * student writes a part of its shading (lesson 09's sampler) */
    variants[0] = l->exercise.textures ? l->variants[0] : *exercise_exact(l->perspective);
    variants[1] = exercise_variant;
    variants[1].what = what;
    out->variants = variants;
    out->nvariants = 2;
    /* the exact picture by the lesson's front end, the exercise's by the
     * one around the student's clipper (lesson 06); the depth buffer holds
     * z in both */
    variants[1].front = l->exercise.clip ? exercise_front : NULL;
    out->exhibit_scene = NULL;      /* X toggles on the student's scene */
    /* the exercise is one triangle at a time (lesson 07's whole-scene runs
     * and their narrated order belong to the lesson's own variants) */
    out->rasterize_scene = NULL;
    out->narration_units = NULL;
}
