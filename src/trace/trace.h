/* trace.h - the narration: what a lesson says it does while it rasterizes.
 *
 * A lesson is an ordinary rasterizer loop that narrates itself:
 *
 *     NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = 4, .x = x, .y = y,
 *             .e = { f01, f02, f03 }, .flags = inside ? TRACE_INSIDE : 0);
 *
 * One line where it can: what the explorer can work out from the event and
 * the triangle (the barycentric weights from e and area2, the colour from
 * the write) is not narrated.
 *
 * The explorer never re-implements an algorithm: it replays the narration.
 * "Step N" means the first N events of the run have happened and the rest
 * have not: the trace delivers those N events to a sink and, from event N on,
 * it is frozen, so the lesson's writes (PLOT, FILL) no longer reach the
 * target. The picture at step N is therefore exactly the lesson's own output
 * stopped after N events, without storing any event.
 *
 * Events are numbered per triangle: the driver (replay.h) runs one triangle
 * at a time, so a scene of 200,000 triangles needs the event count of each
 * triangle (one int each), never every event at once.
 *
 * Compiled without TRISTEP_NARRATE (the fast build that `make bench` times)
 * every macro here is the bare operation or nothing at all.
 */
#ifndef TRISTEP_TRACE_H
#define TRISTEP_TRACE_H

#include <stdbool.h>
#include <stdint.h>

#include "raster/raster.h"

enum trace_kind {
    TRACE_SETUP,        /* triangle set up: box, edges, area */
    TRACE_ROW,          /* a new row (y) starts; x..x1 is the range walked */
    TRACE_SPAN,         /* a span x..x1 on row y (scanline lessons) */
    TRACE_BLOCK,        /* a q x q block at (x, y), size x1 - x + 1, class in klass */
    TRACE_PIXEL_TEST,   /* pixel (x, y) tested: edge values e, flags & TRACE_INSIDE */
    TRACE_PIXEL_WRITE,  /* pixel (x, y) written: z, rgba, flags & TRACE_DEPTH_PASS */
    TRACE_FRONT,        /* a step of the 3-D front end (src/front/, lesson 06):
                           klass = what (enum front_step), part = the world
                           triangle, (x, y) the pixel of a projected vertex,
                           aux[] its values */
    TRACE_STEP,         /* a step that touches no pixel: a value set up or
                           stepped, as the lit line says */
    TRACE_KIND_COUNT
};

enum trace_flags {
    TRACE_INSIDE = 1,       /* the pixel test said covered */
    TRACE_DEPTH_PASS = 2,   /* the fragment was nearer than the depth buffer */
};

enum block_class { BLOCK_EMPTY, BLOCK_FULL, BLOCK_PARTIAL, BLOCK_CLASS_COUNT };

/* What a TRACE_FRONT event says happened to a world triangle on its way to
 * the screen. */
enum front_step {
    FRONT_VIEW,         /* a vertex in view space: aux x_v, y_v, d */
    FRONT_PLANE,        /* clipping against a plane begins: aux the plane's value */
    FRONT_KEEP,         /* a vertex inside the plane is kept */
    FRONT_DROP,         /* a vertex outside is dropped */
    FRONT_NEW,          /* a new vertex on an edge: aux x, y, d, t */
    FRONT_PROJECT,      /* a vertex projected: (x, y) its pixel, aux x_s, y_s, d */
    FRONT_GUARD,        /* the guard band test: flags & TRACE_INSIDE when inside */
    FRONT_TRIANGLE,     /* a triangle of the fan: flags & TRACE_INSIDE when drawn (not culled) */
    FRONT_WORLD,        /* a world triangle enters the front end: y the scene's count */
    FRONT_STEP_COUNT
};

/* What one operation costs: multiplications (a division or a reciprocal
 * counts as one) and additions or subtractions. Each operation names its
 * cost once, beside its code, as OPERATION_COST (EDGE_VALUE_COST beside
 * edge_value() in raster/raster.h, PACK_RGB_COST beside pack_rgb(), ...);
 * lessons count with those names, never with hand-typed sums. */
struct op_cost {
    unsigned mul, add;
};

/* Running counts of what the algorithm did, as llvmpipe's LP_COUNT does. */
struct trace_counters {
    uint64_t events;
    uint64_t tested, covered, written;      /* pixels */
    uint64_t blocks[BLOCK_CLASS_COUNT];
    uint64_t rows, spans;
    uint64_t mul, add;                      /* arithmetic the lesson declared */
};

/* sum = a + b, field by field (sum may be a or b). */
void trace_counters_add(struct trace_counters *sum, const struct trace_counters *a,
                        const struct trace_counters *b);

struct trace_event {
    uint8_t kind;       /* enum trace_kind */
    uint8_t line;       /* line of the lesson's pseudo-code, 0-based */
    uint8_t flags;      /* enum trace_flags */
    uint8_t klass;      /* enum block_class, for TRACE_BLOCK */
    uint8_t span;       /* the step lights lines line - span .. line: a few
                           lines the code does at once (0: line alone) */
    int32_t x, y;       /* pixel; row start; span start; block origin */
    int32_t x1, y1;     /* span end; block's last pixel (inclusive) */
    int64_t e[3];       /* edge values F01, F02, F03 (1/65536 px^2) */
    float z;            /* depth (z, not 1/z) */
    uint32_t rgba;      /* 0xAARRGGBB */
    uint16_t mask[3];   /* block corner masks per edge (checkw, checku, checkv) */
    float aux[6];       /* lesson-specific values, named by lesson->aux_names */
    /* filled in by trace_emit: */
    uint32_t tri;       /* index of the triangle in the scene */
    int32_t part;       /* what the triangle's steps are about (trace.part) */
    uint32_t index;     /* event number within the triangle */
    uint64_t mul, add;  /* arithmetic so far in this triangle */
};

struct trace {
    uint32_t tri;                   /* triangle being run */
    uint64_t count;                 /* events emitted so far in this triangle */
    uint64_t limit;                 /* events numbered >= limit have not happened */
    bool frozen;                    /* an event at or past the limit was emitted */
    struct trace_counters c;        /* counts over the events that happened */
    /* What the steps are about, when a triangle's run tells of more than
     * the triangle (lesson 06: the world triangle whose front end is told),
     * copied into each event; 0 from trace_begin. */
    int32_t part;
    /* A lesson that runs another lesson's rasterizer as one line of its own
     * pseudo-code (lesson 06 runs lesson 05's) tells every event at that
     * line while one_line is set. */
    bool one_line;
    uint8_t line;
    void (*sink)(void *ctx, const struct trace_event *ev);   /* may be NULL */
    void *ctx;
};

/* Begin a triangle: nothing has happened yet, the first `limit` events will. */
void trace_begin(struct trace *tr, uint32_t tri, uint64_t limit);
/* Deliver one event (or freeze). Lessons use NARRATE, not this. */
void trace_emit(struct trace *tr, struct trace_event *ev);
/* Narrated write of one covered pixel: a TRACE_PIXEL_WRITE event, then the
 * write itself unless the trace is frozen. line: a line, or TRACE_LINES(). */
void trace_plot(struct trace *tr, struct target *fb, int line, int x, int y,
                float z, uint32_t rgba);

#define TRACE_UNLIMITED UINT64_MAX

/* The line of a PLOT or NARRATE_SETUP that lights the lines first .. last:
 * a write or a setup that does a few lines of the pseudo-code at once. */
#define TRACE_LINES(first, last) ((last) | ((last) - (first)) << 8)

#ifdef TRISTEP_NARRATE
/* Say what happens; the fields are a designated initializer list. */
#define NARRATE(tr, ...) \
    do { if (tr) trace_emit((tr), &(struct trace_event){ __VA_ARGS__ }); } while (0)
/* Count n operations of a named cost: COUNT(tr, 3, EDGE_VALUE_COST). */
#define COUNT(tr, n, cost) \
    do { if ((tr) && !(tr)->frozen) { \
        (tr)->c.mul += (uint64_t)(n) * ((struct op_cost)cost).mul; \
        (tr)->c.add += (uint64_t)(n) * ((struct op_cost)cost).add; } } while (0)
/* Write a covered pixel as a step of its own. */
#define PLOT(fb, tr, line, x, y, z, rgba) \
    do { if (tr) trace_plot((tr), (fb), (line), (x), (y), (z), (rgba)); \
         else target_write((fb), (x), (y), (z), (rgba)); } while (0)
/* Write a covered pixel that belongs to the step just narrated (a block
 * filled in one step): no event, but nothing is written once frozen. */
#define FILL(fb, tr, x, y, z, rgba) \
    do { if (!(tr) || !(tr)->frozen) target_write((fb), (x), (y), (z), (rgba)); } while (0)
#define NARRATING 1
#else
/* The fast build never narrates, but still compiles the narration (in dead
 * code the compiler drops): a helper only narration uses is not "unused". */
#define NARRATE(tr, ...) \
    do { if (0) trace_emit((tr), &(struct trace_event){ __VA_ARGS__ }); } while (0)
#define COUNT(tr, n, cost) ((void)(tr), (void)(n))
#define PLOT(fb, tr, line, x, y, z, rgba) target_write((fb), (x), (y), (z), (rgba))
#define FILL(fb, tr, x, y, z, rgba) target_write((fb), (x), (y), (z), (rgba))
#define NARRATING 0
#endif

/* Has the run reached a step that has not happened? Then its writes must
 * not reach the target: a lesson that writes without PLOT or FILL (a block
 * or a tile stored at once) asks this first. Always false in the fast build. */
static inline bool trace_frozen(const struct trace *tr)
{
    return NARRATING && tr && tr->frozen;
}

/* The triangle is set up: its box and twice its area, the first event of
 * every triangle (the explorer draws the box). */
#define NARRATE_SETUP(tr, t, ln) \
    NARRATE(tr, .kind = TRACE_SETUP, .line = (uint8_t)((ln) & 0xff), .span = (uint8_t)((ln) >> 8), \
            .x = (t)->minx, .y = (t)->miny, \
            .x1 = (t)->maxx, .y1 = (t)->maxy, .e = { (t)->area2, 0, 0 })

#endif
