/* replay.c - counting a scene's events and drawing it as of any step. */
#include "replay.h"

#include <stdlib.h>
#include <string.h>

bool replay_setup(const struct replay *r, int i, struct tri_setup *t)
{
    int bits = r->params.subpixel_bits;     /* 0..8, taken as given: 0 is whole pixels */
    return tri_setup_bits(t, r->scene->tris[i].v, r->scene->w, r->scene->h, bits);
}

/* sum = a + b, field by field */
static void add_counters(struct trace_counters *sum, const struct trace_counters *a,
                         const struct trace_counters *b)
{
    sum->events = a->events + b->events;
    sum->tested = a->tested + b->tested;
    sum->covered = a->covered + b->covered;
    sum->written = a->written + b->written;
    for (int k = 0; k < BLOCK_CLASS_COUNT; k++)
        sum->blocks[k] = a->blocks[k] + b->blocks[k];
    sum->rows = a->rows + b->rows;
    sum->spans = a->spans + b->spans;
    sum->mul = a->mul + b->mul;
    sum->add = a->add + b->add;
}

bool replay_recount(struct replay *r)
{
    struct target scratch;
    if (!target_init(&scratch, r->scene->w, r->scene->h, scene_background(r->scene)))
        return false;
    uint64_t *start = realloc(r->start, ((size_t)r->scene->ntris + 1) * sizeof *start);
    if (!start) {
        target_free(&scratch);
        return false;
    }
    r->start = start;
    struct trace_counters *sums = realloc(r->sums, ((size_t)r->scene->ntris + 1) * sizeof *sums);
    if (!sums) {
        target_free(&scratch);
        return false;
    }
    r->sums = sums;
    r->ntris = r->scene->ntris;
    uint64_t total = 0;
    memset(&sums[0], 0, sizeof sums[0]);
    struct trace tr = { 0 };
    for (int i = 0; i < r->ntris; i++) {
        struct tri_setup t;
        replay_setup(r, i, &t);
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        r->variant->rasterize(&t, &r->params, &scratch, &tr);
        start[i] = total;
        total += tr.count;
        add_counters(&sums[i + 1], &sums[i], &tr.c);
    }
    start[r->ntris] = total;
    r->total = total;
    target_free(&scratch);
    target_free(&r->base);      /* the cached picture is stale */
    r->base_upto = 0;
    return true;
}

bool replay_init(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p)
{
    memset(r, 0, sizeof *r);
    r->scene = s;
    r->variant = v;
    r->params = *p;
    return replay_recount(r);
}

void replay_free(struct replay *r)
{
    free(r->start);
    free(r->sums);
    target_free(&r->base);
    memset(r, 0, sizeof *r);
}

int replay_locate(const struct replay *r, uint64_t step, uint64_t *local)
{
    if (step == 0 || r->ntris == 0) {
        *local = 0;
        return -1;
    }
    if (step > r->total)
        step = r->total;
    uint64_t last = step - 1;           /* the last event that happened */
    int lo = 0, hi = r->ntris - 1;      /* largest i with start[i] <= last */
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        if (r->start[mid] <= last)
            lo = mid;
        else
            hi = mid - 1;
    }
    *local = last - r->start[lo];
    return lo;
}

/* Bring the cached base picture to "triangles [0, upto) drawn". */
static bool advance_base(struct replay *r, int upto)
{
    if (!r->base.color || upto < r->base_upto) {
        target_free(&r->base);
        if (!target_init(&r->base, r->scene->w, r->scene->h, scene_background(r->scene)))
            return false;
        r->base_upto = 0;
    }
    for (; r->base_upto < upto; r->base_upto++) {
        struct tri_setup t;
        replay_setup(r, r->base_upto, &t);
        r->variant->rasterize(&t, &r->params, &r->base, NULL);
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
    r->variant->rasterize(&t, &r->params, fb, &tr);
    if (c)
        *c = tr.c;
    return cur;
}

bool render_scene(const struct scene *s, const struct lesson_variant *v,
                  const struct raster_params *p, struct target *fb)
{
    if (!target_init(fb, s->w, s->h, scene_background(s)))
        return false;
    int bits = p->subpixel_bits;           /* 0..8, taken as given: 0 is whole pixels */
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, bits);
        v->rasterize(&t, p, fb, NULL);
    }
    return true;
}
