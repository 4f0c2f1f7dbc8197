/* stepping.c - the explorer's steps by a unit: the next or the previous
 * event, row, block or span (a group: the events the lesson marks as one),
 * or triangle, found from the replay's counts and, for groups, from the
 * current triangle's narration run once more into a scratch target. */
#include "explorer.h"

#include <stdlib.h>

static void collect_mark(void *ctx, const struct trace_event *ev)
{
    struct explorer *ex = ctx;
    if (ev->kind != TRACE_ROW && ev->kind != TRACE_BLOCK && ev->kind != TRACE_SPAN)
        return;
    if (ex->nmarks == ex->marks_cap) {
        size_t cap = ex->marks_cap ? 2 * ex->marks_cap : 256;
        uint32_t *m = realloc(ex->marks, cap * sizeof *m);
        if (!m)
            return;     /* fewer stops, never a wrong one */
        ex->marks = m;
        ex->marks_cap = cap;
    }
    ex->marks[ex->nmarks++] = ev->index;
}

/* The numbers of the row, block and span events of triangle i. */
static void find_marks(struct explorer *ex, int i)
{
    if (ex->marks_tri == i)
        return;
    ex->nmarks = 0;
    ex->marks_tri = -1;
    if (!ex->scratch.color
        && !target_init(&ex->scratch, ex->scene.w, ex->scene.h, scene_background(&ex->scene)))
        return;
    struct tri_setup t;
    replay_setup(&ex->replay, i, &t);
    struct trace tr = { .sink = collect_mark, .ctx = ex };
    trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
    struct run_place at;
    struct raster_params p = replay_params(&ex->replay, i, &at);
    ex->lesson->variants[ex->variant].rasterize(&t, &p, &ex->scratch, &tr);
    ex->marks_tri = i;
}

uint64_t explorer_find_step(struct explorer *ex, enum step_unit unit, int dir)
{
    const struct replay *r = &ex->replay;
    uint64_t s = ex->step;
    if (dir > 0 && s >= r->total)
        return r->total;
    if (dir < 0 && s == 0)
        return 0;
    if (unit == STEP_EVENT || r->counted == 0)
        return dir > 0 ? s + 1 : s - 1;
    if (dir > 0) {
        int i = replay_triangle_of(r, s);      /* the triangle of the next event */
        if (unit == STEP_GROUP) {
            find_marks(ex, i);
            for (size_t k = 0; k < ex->nmarks; k++)
                if (r->start[i] + ex->marks[k] + 1 > s)
                    return r->start[i] + ex->marks[k] + 1;
        }
        return r->start[i + 1];
    }
    int i = replay_triangle_of(r, s - 1);      /* the triangle of the last event */
    if (unit == STEP_GROUP) {
        find_marks(ex, i);
        for (size_t k = ex->nmarks; k-- > 0;)
            if (r->start[i] + ex->marks[k] + 1 < s)
                return r->start[i] + ex->marks[k] + 1;
    }
    return r->start[i];
}

bool explorer_move(struct explorer *ex, enum step_unit unit, int dir)
{
    return explorer_set_step(ex, explorer_find_step(ex, unit, dir));
}
