/* replay.c - counting a scene's events and drawing it as of any step. */
#include "replay.h"

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

bool replay_recount(struct replay *r)
{
    struct target scratch;
    if (!list_units(r))
        return false;
    if (!target_init(&scratch, r->scene->w, r->scene->h, scene_background(r->scene)))
        return false;
    if (!target_multisample(&scratch, r->params.samples)) {    /* lesson 08's samples */
        target_free(&scratch);
        return false;
    }
    uint64_t *start = realloc(r->start, ((size_t)r->ntris + 1) * sizeof *start);
    if (!start) {
        target_free(&scratch);
        return false;
    }
    r->start = start;
    struct trace_counters *sums = realloc(r->sums, ((size_t)r->ntris + 1) * sizeof *sums);
    if (!sums) {
        target_free(&scratch);
        return false;
    }
    r->sums = sums;
    uint64_t total = 0;
    memset(&sums[0], 0, sizeof sums[0]);
    struct trace tr = { 0 };
    for (int i = 0; i < r->ntris; i++) {
        struct tri_setup t;
        replay_setup(r, i, &t);
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        struct raster_params p = replay_params(r, i);
        r->variant->rasterize(&t, &p, &scratch, &tr);
        start[i] = total;
        total += tr.count;
        trace_counters_add(&sums[i + 1], &sums[i], &tr.c);
    }
    start[r->ntris] = total;
    r->total = total;
    target_free(&scratch);
    target_free(&r->base);      /* the cached picture is stale */
    r->base_upto = 0;
    return true;
}

bool replay_init_units(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, lesson_units_fn units)
{
    memset(r, 0, sizeof *r);
    r->scene = s;
    r->variant = v;
    r->params = *p;
    r->units_fn = units;
    return replay_recount(r);
}

bool replay_init(struct replay *r, const struct scene *s, const struct lesson_variant *v,
                 const struct raster_params *p)
{
    return replay_init_units(r, s, v, p, NULL);
}

void replay_free(struct replay *r)
{
    free(r->start);
    free(r->sums);
    free(r->units);
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
    int i = replay_triangle_of(r, last);
    *local = last - r->start[i];
    return i;
}

int replay_triangle_of(const struct replay *r, uint64_t event)
{
    int lo = 0, hi = r->ntris - 1;      /* binary search: largest i with start[i] <= event */
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        if (r->start[mid] <= event)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* Bring the cached base picture to "triangles [0, upto) drawn". */
static bool advance_base(struct replay *r, int upto)
{
    if (!r->base.color || upto < r->base_upto) {
        target_free(&r->base);
        if (!target_init(&r->base, r->scene->w, r->scene->h, scene_background(r->scene))
            || !target_multisample(&r->base, r->params.samples))
            return false;
        r->base_upto = 0;
    }
    for (; r->base_upto < upto; r->base_upto++) {
        struct tri_setup t;
        replay_setup(r, r->base_upto, &t);
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
        v->rasterize(&t, p, fb, NULL);
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
