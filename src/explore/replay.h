/* replay.h - "replay the first N events": the whole scene as a lesson draws
 * it, stopped after any step.
 *
 * Global step numbers run over the scene: triangle i owns the events
 * start[i] .. start[i+1] - 1. Only the per-triangle event counts are kept;
 * the events themselves are produced again, one triangle at a time, when a
 * step is shown. A cached target holds the picture of the triangles before
 * the current one, so stepping inside a triangle redraws only that triangle.
 *
 * A scene-level lesson (lesson 07) narrates in an order of its own: units,
 * each one triangle inside one tile, tile after tile (lesson.h,
 * lesson_units_fn). Then "triangle i" of the replay is unit i: replay_setup
 * sets up its triangle and replay_params hands the unit to the lesson
 * (raster_params.at).
 */
#ifndef TRISTEP_REPLAY_H
#define TRISTEP_REPLAY_H

#include <stdint.h>

#include "lesson.h"
#include "explore/patch.h"

/* The picture of the scene with triangles [0, upto) drawn, kept so that a
 * step far back needs only the triangles since the nearest one: the
 * pixels that changed since the checkpoint before (a patch), or the whole
 * picture (the first one, and one whenever the patches since the last
 * whole one would outweigh a picture). A picture is a whole checkpoint and
 * the patches after it applied in turn. */
struct replay_checkpoint {
    int upto;
    struct patch p;
};

struct replay {
    const struct lesson_variant *variant;
    const struct scene *scene;
    struct raster_params params;
    int ntris;
    int counted;            /* triangles whose events are counted so far */
    uint64_t *start;        /* ntris + 1 entries, known for [0, counted]; start[counted] = total */
    uint64_t total;         /* events of the counted triangles (the whole scene once counted) */
    struct trace_counters *sums;    /* ntris + 1 entries, [0, counted]: counters of triangles [0, i) */
    struct target counting; /* the picture of triangles [0, counted), where counting goes on */
    struct target base;     /* the scene with triangles [0, base_upto) drawn */
    int base_upto;
    lesson_units_fn units_fn;       /* NULL: one unit per triangle, in scene order */
    struct lesson_unit *units;      /* ntris entries when units_fn */

    /* checkpoints, taken while counting (replay_keep_pictures) every
     * check_gap events, at most check_bytes of them; when they would exceed
     * it, the one whose removal leaves the smallest gap goes (merged into
     * the one after it), and the gap grows to that */
    bool keep_pictures;
    struct replay_checkpoint *checks;
    int nchecks, checks_cap;
    uint64_t check_gap, check_last;     /* events apart; step of the last one */
    size_t check_bytes;                 /* REPLAY_CHECKPOINT_BYTES (a test may lower it) */
    size_t check_used;                  /* bytes the checkpoints hold */
    struct target check_then;           /* while counting: the picture at the last checkpoint */

    /* what the last triangles drawn into base overwrote (their boxes), for
     * stepping back a triangle without a redraw: records of triangles
     * [base_upto - nundo, base_upto), at most undo_bytes of pixels */
    struct replay_undo *undo;
    int nundo, undo_cap;
    unsigned char *undo_data;
    size_t undo_used, undo_bytes;       /* REPLAY_UNDO_BYTES (a test may lower it) */
};

struct replay_undo {
    int x0, y0, w, h;       /* the box of pixels the triangle may write (w = 0: none) */
    size_t at;              /* its saved colour, depth and count in undo_data */
};

#define REPLAY_UNDO_BYTES ((size_t)32 << 20)
/* ... and only for this many triangles before the one a redraw stops at:
 * a jump redraws thousands since a checkpoint, and steps back start from
 * where it landed (saving every box would cost a fifth of the jump). */
#define REPLAY_UNDO_TRIANGLES 1024

/* Checkpoints: at most this much memory, and this many events apart when
 * it allows (about 6,500 small triangles, 5 ms of redrawing). Kept as
 * patches, they cost about twice the pixels a scene writes, whatever the
 * gap: 2,000,000 triangles at 1920 x 1080 fit 300 of them in 520 MB. */
#define REPLAY_CHECKPOINT_BYTES ((size_t)640 << 20)
#define REPLAY_CHECKPOINT_EVENTS ((uint64_t)1 << 18)
/* One more checkpoint this many triangles before the end (an eighth of a
 * small scene): End redraws them and keeps what they overwrote, so that
 * steps back from the end are quick too. */
#define REPLAY_END_TRIANGLES 1024

static inline int replay_end_checkpoint(int ntris)
{
    int k = ntris / 8 < REPLAY_END_TRIANGLES ? ntris / 8 : REPLAY_END_TRIANGLES;
    return ntris - (k > 1 ? k : 1);
}

/* Count every triangle's events (runs the whole scene once). */
bool replay_init(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p);
/* The same in the units of a scene-level lesson (units NULL: triangles). */
bool replay_init_units(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, lesson_units_fn units);
/* The same, but nothing counted yet: replay_count does it a part at a time
 * (a window stays responsive while a scene of millions of triangles is
 * counted, and steps through what is counted already). */
bool replay_begin(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                  const struct raster_params *p);
/* The same in a scene-level lesson's units (units NULL: triangles). */
bool replay_begin_units(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                        const struct raster_params *p, lesson_units_fn units);
/* Count up to n more units (all of them: INT_MAX). False when out of memory. */
bool replay_count(struct replay *r, int n);
static inline bool replay_counted(const struct replay *r)
{
    return r->counted == r->ntris;
}
/* Keep checkpoints of the picture while counting (the explorer's own run;
 * call before counting). */
void replay_keep_pictures(struct replay *r);
void replay_free(struct replay *r);
/* Count again after the scene or params changed (a vertex was dragged). */
bool replay_recount(struct replay *r);
/* Forget every count (the scene or params changed); counting starts over. */
bool replay_restart(struct replay *r);

/* Set up the triangle of unit i (triangle i of the scene without units)
 * with the run's precision. */
bool replay_setup(const struct replay *r, int i, struct tri_setup *t);
/* The scene's triangle of unit i. */
int replay_unit_tri(const struct replay *r, int i);
/* The params to run unit i with: the run's, with where unit i stands in
 * the run (its scene, and its unit of a scene-level lesson's order) in *at,
 * which must outlive the params' use. */
struct raster_params replay_params(const struct replay *r, int i, struct run_place *at);

/* The triangle that global event number `event` belongs to: the last i
 * with start[i] <= event (0 for a scene without triangles). */
int replay_triangle_of(const struct replay *r, uint64_t event);

/* The triangle that the last happened event of step `step` belongs to
 * (-1 at step 0), and that event's number inside it via *local. Steps
 * past the counted ones are taken as the last counted step. */
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
/* The same through the lesson's scene-level twin when it has one (lesson 07). */
bool render_lesson_scene(const struct lesson *l, const struct scene *s,
                         const struct lesson_variant *v, const struct raster_params *p,
                         struct target *fb);

#endif
