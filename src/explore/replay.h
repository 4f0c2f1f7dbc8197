/* replay.h - "replay the first N events": the whole scene as a lesson draws
 * it, stopped after any step.
 *
 * Global step numbers run over the scene: triangle i owns the events
 * start[i] .. start[i+1] - 1. Only the per-triangle event counts are kept;
 * the events themselves are produced again, one triangle at a time, when a
 * step is shown. A cached target holds the picture of the triangles before
 * the current one, so stepping inside a triangle redraws only that triangle.
 */
#ifndef TRISTEP_REPLAY_H
#define TRISTEP_REPLAY_H

#include <stdint.h>

#include "lesson.h"

struct replay {
    const struct lesson_variant *variant;
    const struct scene *scene;
    struct raster_params params;
    int ntris;
    uint64_t *start;        /* ntris + 1 entries; start[ntris] = total */
    uint64_t total;         /* events in the whole scene */
    struct trace_counters *sums;    /* ntris + 1 entries: counters of triangles [0, i) */
    struct target base;     /* the scene with triangles [0, base_upto) drawn */
    int base_upto;
};

/* Count every triangle's events (runs the whole scene once). */
bool replay_init(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p);
void replay_free(struct replay *r);
/* Count again after the scene or params changed (a vertex was dragged). */
bool replay_recount(struct replay *r);

/* Set up triangle i of the scene with the run's precision. */
bool replay_setup(const struct replay *r, int i, struct tri_setup *t);

/* The triangle that the last happened event of step `step` belongs to
 * (-1 at step 0), and that event's number inside it via *local. */
int replay_locate(const struct replay *r, uint64_t step, uint64_t *local);

/* Draw the scene as it is after `step` events into fb (allocated as needed),
 * delivering the current triangle's events [0, local] to sink. Returns the
 * current triangle (-1 at step 0) and its finished trace counters in *c. */
int replay_to(struct replay *r, uint64_t step, struct target *fb,
              void (*sink)(void *ctx, const struct trace_event *ev), void *ctx,
              struct trace_counters *c);

/* Run a whole scene with a variant, no narration: what --dump-* writes. */
bool render_scene(const struct scene *s, const struct lesson_variant *v,
                  const struct raster_params *p, struct target *fb);

#endif
