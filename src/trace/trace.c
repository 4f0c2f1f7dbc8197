/* trace.c - delivering the narration, and freezing it at the chosen step. */
#include "trace.h"

#include <string.h>

void trace_begin(struct trace *tr, uint32_t tri, uint64_t limit)
{
    tr->tri = tri;
    tr->count = 0;
    tr->limit = limit;
    tr->frozen = false;
    tr->part = 0;
    memset(&tr->c, 0, sizeof tr->c);
}

static void count(struct trace_counters *c, const struct trace_event *ev)
{
    c->events++;
    switch ((enum trace_kind)ev->kind) {
    case TRACE_PIXEL_TEST:
        c->tested++;
        c->covered += (ev->flags & TRACE_INSIDE) != 0;
        break;
    case TRACE_PIXEL_WRITE:
        c->written += (ev->flags & TRACE_DEPTH_PASS) != 0;
        break;
    case TRACE_BLOCK:
        if (ev->klass < BLOCK_CLASS_COUNT)
            c->blocks[ev->klass]++;
        if (ev->klass == BLOCK_FULL)    /* covered without a test of their own */
            c->covered += (uint64_t)(ev->x1 - ev->x + 1) * (uint64_t)(ev->y1 - ev->y + 1);
        break;
    case TRACE_SPAN:
        c->spans++;
        if (ev->x1 >= ev->x)            /* a span's pixels are covered by construction */
            c->covered += (uint64_t)(ev->x1 - ev->x + 1);
        break;
    case TRACE_ROW:
        c->rows++;
        break;
    case TRACE_SETUP:
    case TRACE_FRONT:
    case TRACE_STEP:
    case TRACE_KIND_COUNT:
        break;
    }
}

void trace_counters_add(struct trace_counters *sum, const struct trace_counters *a,
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

void trace_emit(struct trace *tr, struct trace_event *ev)
{
    uint64_t index = tr->count++;
    if (tr->frozen || index >= tr->limit) {
        tr->frozen = true;
        return;
    }
    ev->tri = tr->tri;
    ev->part = tr->part;
    if (tr->one_line) {
        ev->line = tr->line;
        ev->span = 0;
    }
    ev->index = (uint32_t)index;
    ev->mul = tr->c.mul;
    ev->add = tr->c.add;
    count(&tr->c, ev);
    if (tr->sink)
        tr->sink(tr->ctx, ev);
}

void trace_plot(struct trace *tr, struct target *fb, int line, int x, int y,
                float z, uint32_t rgba)
{
    struct trace_event ev = {
        .kind = TRACE_PIXEL_WRITE, .line = (uint8_t)(line & 0xff), .span = (uint8_t)(line >> 8),
        .x = x, .y = y, .z = z, .rgba = rgba,
        .flags = target_depth_pass(fb, x, y, z) ? TRACE_DEPTH_PASS : 0,
    };
    trace_emit(tr, &ev);
    if (!tr->frozen)
        target_write(fb, x, y, z, rgba);
}
