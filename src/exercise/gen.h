/* gen.h - what the scene generators of make check share (scenes.c, the
 * 2-D scenes; scenes3.c, lesson 06's 3-D ones). */
#ifndef TRISTEP_EXERCISE_GEN_H
#define TRISTEP_EXERCISE_GEN_H

#include <stdint.h>

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

#endif
