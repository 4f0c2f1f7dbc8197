/* gen.h - what the scene generators of make check share (scenes.c, the
 * 2-D scenes; scenes3.c, lesson 06's 3-D ones). */
#ifndef TRISTEP_EXERCISE_GEN_H
#define TRISTEP_EXERCISE_GEN_H

#include <stdint.h>
#include <stdio.h>

#include "scene/scene.h"

/* splitmix64: the checks draw the same scenes on every run */
struct rng {
    uint64_t s;
};

/* The seed of the random scenes (SEED=): 0, the scenes make check draws;
 * another, scenes the students never checked against (make grade). */
extern uint64_t check_seed;

/* A generator's stream: its own start, moved by the seed. */
static inline struct rng rng_start(uint64_t s)
{
    return (struct rng){ check_seed ? s ^ (check_seed * 0x9e3779b97f4a7c15u) : s };
}

static inline uint64_t rng_next(struct rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static inline double rng_unit(struct rng *r)
{
    return (double)(rng_next(r) >> 11) * 0x1p-53;
}

static inline double rng_range(struct rng *r, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(r);
}

/* An empty scene of w x h pixels. */
void check_scene_start(struct scene *s, int w, int h);

/* What scenes.c's generators build with (the search's too, search.c): a
 * coordinate on the 1/256 grid, a pixel centre or an integer, at random;
 * a vertex, one of random colour and depth in [zmin, zmax]; a triangle
 * added with its coordinates held to the limits, walked the other way
 * round when flip; a jittered grid of nx x ny cells over [x0, x1] x [y0,
 * y1], each cut in two. */
double gen_grid(struct rng *r, double v);
struct vertex gen_vtx(double x, double y, double z, double r, double g, double b);
struct vertex gen_rvtx(struct rng *r, double x, double y, double zmin, double zmax);
bool gen_add(struct scene *s, struct vertex a, struct vertex b, struct vertex c);
bool gen_add_flipped(struct scene *s, struct vertex a, struct vertex b, struct vertex c, bool flip);
void gen_grid_mesh(struct scene *s, struct rng *r, int nx, int ny, double x0, double y0, double x1, double y1,
                   double jitter);

/* A scene written as a scene file's text and read by scene_parse (so that
 * its textures are the built-in ones a counterexample names again):
 * started with its size and a texture line (NULL: none), a textured
 * triangle (x y z r g b s t for each vertex), ended into s. */
struct gen_text {
    char *buf;
    size_t len;
    FILE *f;
};
struct tv {
    double x, y, z, r, g, b, s, t;
};
bool gen_text_start(struct gen_text *x, int w, int h, const char *texture);
void gen_tri(struct gen_text *x, struct tv a, struct tv b, struct tv c);
bool gen_text_end(struct gen_text *x, struct scene *s);

#endif
