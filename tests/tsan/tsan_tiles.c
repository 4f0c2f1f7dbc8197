/* tsan_tiles.c - lesson 07's workers under ThreadSanitizer, drawing lesson
 * 07's pixels, lesson 08's samples (its twin `tiles`, at 4 samples) and
 * lesson 09's textured quads (its twin `tiles`, two textures shared by the
 * workers, every filter).
 *
 * Criterion runs each test in a process of its own in a way TSan does not
 * support, so this is a small program of its own, built with
 * -fsanitize=thread (make test builds BUILD/tsan-tiles; test_lesson07.c runs
 * it). It draws seeded random scenes, layered at one depth so that only the
 * order of drawing decides the colours, with every exact scene-level variant
 * on 2, 3 and 8 threads, and compares each picture with the one-thread
 * picture byte for byte. Prints "tsan-tiles: ok" and exits 0 when all are
 * equal; TSan itself reports any data race on stderr (and exits 66).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"

extern const struct lesson lesson_07, lesson_08, lesson_09;

static uint64_t next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static double uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (double)(next(s) >> 11) * 0x1p-53;
}

static bool same(const struct target *a, const struct target *b)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    size_t m = a->samples ? n * (size_t)a->samples->n : 0;
    return memcmp(a->color, b->color, n * 4) == 0 && memcmp(a->depth, b->depth, n * 4) == 0
           && memcmp(a->count, b->count, n) == 0 && !a->samples == !b->samples
           && (!m || (memcmp(a->samples->color, b->samples->color, m * 4) == 0
                      && memcmp(a->samples->depth, b->samples->depth, m * 4) == 0));
}

/* The row of lesson l's table that --threads sets (lesson.c is not linked here). */
static int threads_row(const struct lesson *l)
{
    int i = 0;
    while (l->params[i].option && strcmp(l->params[i].option, "threads") != 0)
        i++;
    return i;
}

/* The row of lesson l's table with option `name` (lesson.c is not linked here). */
static int row_of(const struct lesson *l, const char *name)
{
    int i = 0;
    while (l->params[i].option && strcmp(l->params[i].option, name) != 0)
        i++;
    return i;
}

/* A textured scene for lesson 09: triangles of every size at one depth,
 * under two builtin textures taking turns (repeat and clamp). */
static bool textured_scene(struct scene *s, uint64_t *seed, int w, int h, int n)
{
    size_t cap = (size_t)n * 256 + 256, at = 0;
    char *text = malloc(cap), err[256];
    if (!text)
        return false;
    at += (size_t)snprintf(text + at, cap - at, "size %d %d\n", w, h);
    for (int i = 0; i < n; i++) {
        if (i % 20 == 0)
            at += (size_t)snprintf(text + at, cap - at, "texture builtin:%s\n",
                                   i % 40 ? "bricks clamp" : "checker-numbers repeat");
        double cx = uniform(seed, -20, w + 20), cy = uniform(seed, -20, h + 20);
        double r = i % 10 == 0 ? 120 : i % 3 == 0 ? 25 : 5;
        at += (size_t)snprintf(text + at, cap - at, "tri");
        for (int k = 0; k < 3; k++)
            at += (size_t)snprintf(text + at, cap - at, " %.3f %.3f 1 %.3f %.3f %.3f %.3f %.3f",
                                   cx + uniform(seed, -r, r), cy + uniform(seed, -r, r),
                                   uniform(seed, 0.3, 1), uniform(seed, 0.3, 1), uniform(seed, 0.3, 1),
                                   uniform(seed, -2, 2), uniform(seed, -2, 2));
        at += (size_t)snprintf(text + at, cap - at, "\n");
    }
    bool ok = scene_parse(s, "tsan", text, at, err, sizeof err);
    if (!ok)
        fprintf(stderr, "tsan-tiles: %s\n", err);
    free(text);
    return ok;
}

int main(void)
{
    uint64_t seed = 0x75a2;
    static const int threads[] = { 2, 3, 8 };
    int pictures = 0;
    for (int rep = 0; rep < 4; rep++) {
        struct scene s = { .w = 150 + 61 * rep, .h = 100 + 23 * rep };
        for (int i = 0; i < 300; i++) {
            double cx = uniform(&seed, -20, s.w + 20), cy = uniform(&seed, -20, s.h + 20);
            double r = i % 10 == 0 ? 120 : i % 3 == 0 ? 25 : 5;
            struct vertex v[3];
            for (int k = 0; k < 3; k++)
                v[k] = (struct vertex){ cx + uniform(&seed, -r, r), cy + uniform(&seed, -r, r), 1,
                                        uniform(&seed, 0, 1), uniform(&seed, 0, 1),
                                        uniform(&seed, 0, 1), 0, 0 };
            if (!scene_add(&s, v))
                return 1;
        }
        static const struct lesson *const tiled[] = { &lesson_07, &lesson_08 };
        for (int li = 0; li < 2; li++) {
            for (int vi = 0; vi < tiled[li]->nvariants; vi++) {
                const struct lesson *l = tiled[li];
                rasterize_scene_fn whole = l->rasterize_scene[vi];
                if (variant_against_exact(&l->variants[vi]) || !whole)
                    continue;
                struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS,
                                           .samples = l == &lesson_08 ? 4 : 0 };
                p.knob[threads_row(l)] = 1;
                struct target one;
                if (!target_init(&one, s.w, s.h, 0xff000000u) || !whole(&s, &p, &one))
                    return 1;
                for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
                    struct target fb;
                    p.knob[threads_row(l)] = threads[k];
                    if (!target_init(&fb, s.w, s.h, 0xff000000u) || !whole(&s, &p, &fb))
                        return 1;
                    if (!same(&one, &fb)) {
                        fprintf(stderr, "tsan-tiles: %s %s on %d threads differs from 1 thread "
                                "(scene %d)\n", l->id, l->variants[vi].name, threads[k], rep);
                        return 1;
                    }
                    target_free(&fb);
                    pictures++;
                }
                target_free(&one);
            }
        }
        scene_free(&s);
        /* lesson 09's tiles: every filter, the textures read by every worker */
        const struct lesson *l = &lesson_09;
        int vi = 0;
        while (vi < l->nvariants && strcmp(l->variants[vi].name, "tiles") != 0)
            vi++;
        if (vi == l->nvariants || !textured_scene(&s, &seed, 150 + 61 * rep, 100 + 23 * rep, 200))
            return 1;
        for (int f = 1; f <= 5; f++) {
            struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS };
            p.knob[row_of(l, "filter")] = f;
            p.knob[row_of(l, "threads")] = 1;
            struct target one;
            if (!target_init(&one, s.w, s.h, 0xff000000u) || !l->rasterize_scene[vi](&s, &p, &one))
                return 1;
            for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
                struct target fb;
                p.knob[row_of(l, "threads")] = threads[k];
                if (!target_init(&fb, s.w, s.h, 0xff000000u) || !l->rasterize_scene[vi](&s, &p, &fb))
                    return 1;
                if (!same(&one, &fb)) {
                    fprintf(stderr, "tsan-tiles: %s tiles, filter %d, on %d threads differs from 1 "
                            "thread (scene %d)\n", l->id, f, threads[k], rep);
                    return 1;
                }
                target_free(&fb);
                pictures++;
            }
            target_free(&one);
        }
        scene_free(&s);
    }
    printf("tsan-tiles: ok, %d pictures equal to their one-thread run\n", pictures);
    return 0;
}
