/* replay.c - counting a scene's events and drawing it as of any step. */
#include "replay.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

int replay_unit_tri(const struct replay *r, int i)
{
    return r->units ? (int)r->units[i].tri : i;
}

bool replay_setup(const struct replay *r, int i, struct tri_setup *t)
{
    int bits = r->params.subpixel_bits;     /* 0..8, taken as given: 0 is whole pixels */
    return tri_setup_bits(t, r->scene->tris[replay_unit_tri(r, i)].v, r->scene->w, r->scene->h,
                          bits);
}

struct raster_params replay_params(const struct replay *r, int i)
{
    struct raster_params p = r->params;
    if (i >= 0 && i < r->ntris)
        p = lesson_params_tri(&r->params, r->scene, replay_unit_tri(r, i));
    if (r->units && i >= 0 && i < r->ntris) {
        const struct lesson_unit *u = &r->units[i];
        p.tile = u->tile + 1;
        p.bin_size = u->bin_size;
        p.bin_entry = u->bin_entry;
        p.thread = u->thread;
        p.units = r->units;
        p.nunits = r->ntris;
    }
    return p;
}

/* The units of the run: one per triangle, or the lesson's own order. */
static bool list_units(struct replay *r)
{
    free(r->units);
    r->units = NULL;
    r->ntris = r->scene->ntris;
    if (!r->units_fn)
        return true;
    long n = r->units_fn(r->scene, r->variant, &r->params, NULL, 0);
    if (n < 0 || n > INT32_MAX - 1)
        return false;
    r->units = malloc((size_t)(n ? n : 1) * sizeof *r->units);
    if (!r->units || r->units_fn(r->scene, r->variant, &r->params, r->units, n) != n)
        return false;
    r->ntris = (int)n;
    return true;
}

static void undo_clear(struct replay *r);

/* A picture of the scene's size and background, with the run's samples
 * (lesson 08); t is left empty when memory runs out. */
static bool blank_picture(const struct replay *r, struct target *t)
{
    if (target_init(t, r->scene->w, r->scene->h, scene_background(r->scene))
        && target_multisample(t, r->params.samples))
        return true;
    target_free(t);
    return false;
}

/* --- checkpoints ---------------------------------------------------------- */

static size_t target_bytes(const struct target *t)
{
    size_t n = (size_t)t->w * (size_t)t->h;
    size_t each = sizeof *t->color + sizeof *t->depth + 1;
    if (t->samples)             /* lesson 08's samples are copied too */
        each += (size_t)t->samples->n * (sizeof *t->samples->color + sizeof *t->samples->depth);
    return n * each;
}

static uint64_t check_step(const struct replay *r, int k)
{
    return r->start[r->checks[k].upto];
}

/* The checkpoint whose removal leaves the smallest gap (the new one, at
 * r->total, closes the last gap), and that gap in *gap. */
static int closest_checkpoint(const struct replay *r, uint64_t *gap)
{
    int drop = -1;
    *gap = UINT64_MAX;
    for (int k = 0; k < r->nchecks; k++) {
        uint64_t lo = k ? check_step(r, k - 1) : 0;
        uint64_t hi = k + 1 < r->nchecks ? check_step(r, k + 1) : r->total;
        if (hi - lo < *gap)
            *gap = hi - lo, drop = k;
    }
    return drop;
}

/* Remove checkpoint k: the one after it (or the new one, p) takes its
 * pixels, so that it still applies to the picture before k. */
static bool drop_checkpoint(struct replay *r, int k, struct patch *p)
{
    struct patch *next = k + 1 < r->nchecks ? &r->checks[k + 1].p : p, merged;
    if (!patch_merge(&merged, &r->checks[k].p, next))
        return false;
    r->check_used -= r->checks[k].p.bytes + (next == p ? 0 : next->bytes);
    r->check_used += next == p ? 0 : merged.bytes;
    patch_free(&r->checks[k].p);
    patch_free(next);
    *next = merged;
    memmove(&r->checks[k], &r->checks[k + 1], (size_t)(r->nchecks - k - 1) * sizeof *r->checks);
    r->nchecks--;
    return true;
}

/* Bytes of the patches since the last whole checkpoint. */
static size_t patches_since_whole(const struct replay *r)
{
    size_t n = (size_t)r->counting.w * (size_t)r->counting.h, bytes = 0;
    for (int k = r->nchecks - 1; k >= 0 && !patch_is_whole(&r->checks[k].p, n); k--)
        bytes += r->checks[k].p.bytes;
    return bytes;
}

/* A checkpoint at triangle `counted` (the counting picture): the pixels
 * changed since the last one, or the whole picture. When the budget is
 * full, the ones whose removal leaves the smallest gap make room (unless
 * the new one would be the closest: then none is taken, unless forced),
 * and checkpoints are taken no closer than that gap from then on. */
static bool take_checkpoint(struct replay *r, bool force)
{
    size_t whole = target_bytes(&r->counting);
    if (whole + 2 * sizeof *r->checks->p.runs > r->check_bytes)
        return true;            /* not even one picture fits (its one run included) */
    struct patch p;
    if (r->nchecks == 0 ? !patch_whole(&p, &r->counting)
                        : !patch_diff(&p, &r->counting, &r->check_then))
        return false;
    if (r->nchecks > 0 && patches_since_whole(r) + p.bytes > whole) {
        patch_free(&p);         /* a picture far back would cost more than one picture */
        if (!patch_whole(&p, &r->counting))
            return false;
    }
    uint64_t gap;
    if (r->check_used + p.bytes > r->check_bytes && !force
        && r->total - check_step(r, r->nchecks - 1) < (closest_checkpoint(r, &gap), gap)) {
        r->check_gap = gap > r->check_gap ? gap : r->check_gap;
        patch_free(&p);         /* the new one would be the closest pair: not worth it */
        return true;
    }
    while (r->check_used + p.bytes > r->check_bytes && r->nchecks > 0) {
        int drop = closest_checkpoint(r, &gap);
        if (gap > r->check_gap)
            r->check_gap = gap;
        if (!drop_checkpoint(r, drop, &p)) {
            patch_free(&p);
            return false;
        }
    }
    if (r->nchecks == r->checks_cap) {
        int cap = r->checks_cap ? 2 * r->checks_cap : 16;
        struct replay_checkpoint *c = realloc(r->checks, (size_t)cap * sizeof *c);
        if (!c) {
            patch_free(&p);
            return false;
        }
        r->checks = c;
        r->checks_cap = cap;
    }
    /* the picture now, for the next patch: p turns the last one into it
     * (merged with a dropped one or not), far cheaper than a copy */
    if (r->check_then.color) {
        patch_apply(&p, &r->check_then);
    } else if (!target_copy(&r->check_then, &r->counting)) {
        patch_free(&p);
        return false;
    }
    r->checks[r->nchecks++] = (struct replay_checkpoint){ .upto = r->counted, .p = p };
    r->check_used += p.bytes;
    r->check_last = r->total;
    return true;
}

static void free_checkpoints(struct replay *r)
{
    for (int k = 0; k < r->nchecks; k++)
        patch_free(&r->checks[k].p);
    r->nchecks = 0;
    r->check_used = 0;
    r->check_gap = REPLAY_CHECKPOINT_EVENTS;
    r->check_last = 0;
    target_free(&r->check_then);
}

/* --- counting ------------------------------------------------------------- */

bool replay_restart(struct replay *r)
{
    if (!list_units(r))         /* sets ntris: the number of units */
        return false;
    uint64_t *start = realloc(r->start, ((size_t)r->ntris + 1) * sizeof *start);
    if (!start)
        return false;
    r->start = start;
    struct trace_counters *sums = realloc(r->sums, ((size_t)r->ntris + 1) * sizeof *sums);
    if (!sums)
        return false;
    r->sums = sums;
    r->counted = 0;
    r->total = 0;
    start[0] = 0;
    memset(&sums[0], 0, sizeof sums[0]);
    target_free(&r->counting);
    target_free(&r->base);      /* the cached picture is stale */
    r->base_upto = 0;
    undo_clear(r);
    free_checkpoints(r);
    return true;
}

bool replay_count(struct replay *r, int n)
{
    if (r->counted < r->ntris && !r->counting.color && !blank_picture(r, &r->counting))
        return false;
    struct trace tr = { 0 };
    for (; n > 0 && r->counted < r->ntris; n--) {
        int i = r->counted;
        struct tri_setup t;
        replay_setup(r, i, &t);
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        struct raster_params p = replay_params(r, i);
        r->variant->rasterize(&t, &p, &r->counting, &tr);
        r->total += tr.count;
        r->start[i + 1] = r->total;
        trace_counters_add(&r->sums[i + 1], &r->sums[i], &tr.c);
        r->counted = i + 1;
        /* one near the end too, and none after it: End is a step often
         * taken, and steps back from it use what its redraw overwrote */
        int end = replay_end_checkpoint(r->ntris);
        if (r->keep_pictures && r->counted <= end
            && (r->total - r->check_last >= r->check_gap || r->counted == end)
            && !take_checkpoint(r, r->counted == end))
            return false;
    }
    if (r->counted == r->ntris) {
        target_free(&r->counting);  /* every step is known: its picture is not needed */
        target_free(&r->check_then);
    }
    return true;
}

bool replay_recount(struct replay *r)
{
    return replay_restart(r) && replay_count(r, INT_MAX);
}

bool replay_begin_units(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                        const struct raster_params *p, lesson_units_fn units)
{
    memset(r, 0, sizeof *r);
    r->scene = s;
    r->variant = v;
    r->params = *p;
    r->units_fn = units;
    r->check_bytes = REPLAY_CHECKPOINT_BYTES;
    r->undo_bytes = REPLAY_UNDO_BYTES;
    return replay_restart(r);
}

bool replay_begin(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                  const struct raster_params *p)
{
    return replay_begin_units(r, s, v, p, NULL);
}

bool replay_init_units(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, lesson_units_fn units)
{
    return replay_begin_units(r, s, v, p, units) && replay_count(r, INT_MAX);
}

bool replay_init(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p)
{
    return replay_init_units(r, s, v, p, NULL);
}

void replay_keep_pictures(struct replay *r)
{
    r->keep_pictures = true;
}

void replay_free(struct replay *r)
{
    free_checkpoints(r);
    free(r->checks);
    free(r->undo);
    free(r->undo_data);
    free(r->start);
    free(r->sums);
    free(r->units);
    target_free(&r->counting);
    target_free(&r->base);
    memset(r, 0, sizeof *r);
}

int replay_locate(const struct replay *r, uint64_t step, uint64_t *local)
{
    if (step == 0 || r->counted == 0) {
        *local = 0;
        return -1;
    }
    if (step > r->total)
        step = r->total;
    uint64_t last = step - 1;           /* the last event that happened */
    int i = replay_triangle_of(r, last);
    *local = last - r->start[i];
    return i;
}

int replay_triangle_of(const struct replay *r, uint64_t event)
{
    int lo = 0, hi = r->counted - 1;    /* binary search: largest i with start[i] <= event */
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        if (r->start[mid] <= event)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo < 0 ? 0 : lo;
}

/* --- stepping back a triangle: what it overwrote ---------------------------- */

static void undo_clear(struct replay *r)
{
    r->nundo = 0;
    r->undo_used = 0;
}

/* Copy a box of the target's pixels to or from saved bytes (colour rows,
 * then depth rows, then count rows). */
static void box_pixels(struct target *t, const struct replay_undo *u, unsigned char *bytes,
                       bool save)
{
    size_t n = (size_t)u->w * (size_t)u->h;
    unsigned char *colour = bytes, *depth = colour + 4 * n, *count = depth + 4 * n;
    for (int y = 0; y < u->h; y++) {
        size_t i = (size_t)(u->y0 + y) * (size_t)t->w + (size_t)u->x0, k = (size_t)y * (size_t)u->w;
        size_t w = (size_t)u->w;
        if (save) {
            memcpy(colour + 4 * k, t->color + i, 4 * w);
            memcpy(depth + 4 * k, t->depth + i, 4 * w);
            memcpy(count + k, t->count + i, w);
        } else {
            memcpy(t->color + i, colour + 4 * k, 4 * w);
            memcpy(t->depth + i, depth + 4 * k, 4 * w);
            memcpy(t->count + i, count + k, w);
        }
    }
}

/* Before triangle base_upto is drawn into base: keep what its box holds.
 * An exact variant writes only the pixels the reference covers (the tests
 * hold every one to that), all inside the box that setup computed; an
 * exhibit may stray outside it, and lesson 08's samples are not in the
 * record, so their steps back redraw instead. When the
 * room is full the older half goes; a box too large for it ends the history
 * (stepping back then starts from a checkpoint). */
static void undo_save(struct replay *r, const struct tri_setup *t)
{
    if (variant_against_exact(r->variant) || r->base.samples) {
        undo_clear(r);          /* the record holds colour, depth and count, not samples */
        return;
    }
    struct replay_undo u = { .x0 = t->minx, .y0 = t->miny, .at = r->undo_used };
    if (t->minx <= t->maxx && t->miny <= t->maxy) {
        u.w = t->maxx - t->minx + 1;
        u.h = t->maxy - t->miny + 1;
    }
    if (!r->undo_data) {
        /* no more room than a few pictures' worth: a small scene's steps
         * back need little, and memory should not grow with a long session */
        size_t few = 4 * target_bytes(&r->base);
        if (r->undo_bytes > few)
            r->undo_bytes = few > ((size_t)1 << 20) ? few : (size_t)1 << 20;
        if (!(r->undo_data = malloc(r->undo_bytes))) {
            undo_clear(r);
            return;
        }
    }
    size_t bytes = (size_t)u.w * (size_t)u.h * 9;
    if (bytes > r->undo_bytes / 4) {
        undo_clear(r);
        return;
    }
    if (r->undo_used + bytes > r->undo_bytes) {
        int keep = r->nundo / 2;                /* the newer half */
        size_t from = r->undo[r->nundo - keep].at;
        if (keep == 0)
            from = r->undo_used;
        memmove(r->undo_data, r->undo_data + from, r->undo_used - from);
        memmove(r->undo, r->undo + (r->nundo - keep), (size_t)keep * sizeof *r->undo);
        for (int k = 0; k < keep; k++)
            r->undo[k].at -= from;
        r->nundo = keep;
        r->undo_used -= from;
        u.at = r->undo_used;
    }
    if (r->nundo == r->undo_cap) {
        int cap = r->undo_cap ? 2 * r->undo_cap : 1024;
        struct replay_undo *n = realloc(r->undo, (size_t)cap * sizeof *n);
        if (!n) {
            undo_clear(r);
            return;
        }
        r->undo = n;
        r->undo_cap = cap;
    }
    box_pixels(&r->base, &u, r->undo_data + u.at, true);
    r->undo[r->nundo++] = u;
    r->undo_used += bytes;
}

/* Take the last triangle drawn into base out again. */
static void undo_last(struct replay *r)
{
    struct replay_undo *u = &r->undo[--r->nundo];
    box_pixels(&r->base, u, r->undo_data + u->at, false);
    r->undo_used = u->at;
    r->base_upto--;
}

/* Events worth redrawing rather than copying a whole picture. */
#define REDRAW_RATHER_THAN_COPY ((uint64_t)1 << 17)

/* Bring base to checkpoint j: from the last whole one at or before it, or
 * from base itself when it is at a checkpoint since then, the patches up
 * to j applied in turn. */
static bool restore_checkpoint(struct replay *r, int j)
{
    size_t n = (size_t)r->scene->w * (size_t)r->scene->h;
    int from = j;
    while (from > 0 && !patch_is_whole(&r->checks[from].p, n))
        from--;                 /* checks[0] is whole */
    int at = -1;
    for (int k = from; r->base.color && k <= j; k++)
        if (r->checks[k].upto == r->base_upto)
            at = k;
    if (at >= 0) {
        from = at + 1;
    } else if (!r->base.color && !blank_picture(r, &r->base)) {
        return false;
    }
    for (int k = from; k <= j; k++)
        patch_apply(&r->checks[k].p, &r->base);
    r->base_upto = r->checks[j].upto;
    undo_clear(r);
    return true;
}

/* Bring the cached base picture to "triangles [0, upto) drawn", from
 * itself, the nearest checkpoint before upto, or the background. */
static bool advance_base(struct replay *r, int upto)
{
    if (r->base.color && upto < r->base_upto && r->base_upto - upto <= r->nundo)
        while (r->base_upto > upto)
            undo_last(r);
    int from = -1;
    for (int k = 0; k < r->nchecks && r->checks[k].upto <= upto; k++)
        from = k;
    bool base_ok = r->base.color && r->base_upto <= upto;
    if (from >= 0 && (!base_ok || (r->base_upto < r->checks[from].upto
                                   && r->start[r->checks[from].upto] - r->start[r->base_upto]
                                          > REDRAW_RATHER_THAN_COPY))) {
        if (!restore_checkpoint(r, from))
            return false;
    } else if (!base_ok) {
        if (r->base.color)
            target_clear(&r->base);     /* its memory again: no fresh pages to fault in */
        else if (!blank_picture(r, &r->base))
            return false;
        r->base_upto = 0;
        undo_clear(r);
    }
    if (upto - r->base_upto > REPLAY_UNDO_TRIANGLES)
        undo_clear(r);          /* the records start again near upto */
    for (; r->base_upto < upto; r->base_upto++) {
        struct tri_setup t;
        replay_setup(r, r->base_upto, &t);
        if (upto - r->base_upto <= REPLAY_UNDO_TRIANGLES)
            undo_save(r, &t);
        struct raster_params p = replay_params(r, r->base_upto);
        r->variant->rasterize(&t, &p, &r->base, NULL);
    }
    return true;
}

int replay_to(struct replay *r, uint64_t step, struct target *fb,
              void (*sink)(void *ctx, const struct trace_event *ev), void *ctx,
              struct trace_counters *c)
{
    uint64_t local;
    int cur = replay_locate(r, step, &local);
    if (c)
        memset(c, 0, sizeof *c);
    if (!advance_base(r, cur < 0 ? 0 : cur) || !target_copy(fb, &r->base))
        return -2;
    if (cur < 0)
        return -1;
    struct tri_setup t;
    replay_setup(r, cur, &t);
    struct trace tr = { .sink = sink, .ctx = ctx };
    trace_begin(&tr, (uint32_t)cur, local + 1);
    struct raster_params p = replay_params(r, cur);
    r->variant->rasterize(&t, &p, fb, &tr);
    if (c)
        *c = tr.c;
    return cur;
}

bool render_scene(const struct scene *s, const struct lesson_variant *v,
                  const struct raster_params *p, struct target *fb)
{
    if (!target_init(fb, s->w, s->h, scene_background(s)))
        return false;
    if (!target_multisample(fb, p->samples)) {     /* lesson 08: memory for its samples */
        target_free(fb);
        return false;
    }
    int bits = p->subpixel_bits;           /* 0..8, taken as given: 0 is whole pixels */
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, bits);
        struct raster_params pi = lesson_params_tri(p, s, i);
        v->rasterize(&t, &pi, fb, NULL);
    }
    return true;
}

bool render_lesson_scene(const struct lesson *l, const struct scene *s,
                         const struct lesson_variant *v, const struct raster_params *p,
                         struct target *fb)
{
    rasterize_scene_fn whole = lesson_scene_fn(l, v);
    if (!whole)
        return render_scene(s, v, p, fb);
    if (!target_init(fb, s->w, s->h, scene_background(s)))
        return false;
    if (whole(s, p, fb))
        return true;
    target_free(fb);
    return false;
}
