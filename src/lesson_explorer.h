/* lesson_explorer.h - what the explorer adds for one lesson, kept out of the
 * lesson's algorithm file: views of its own, drawings over the canvas, the
 * triangle's constants and the values the watch panel derives from an event.
 *
 * Each lesson folder holds its algorithm (NAME.c, struct lesson, lesson.h)
 * and, beside it, NAME_explorer.c with one struct lesson_explorer naming the
 * lesson it belongs to:
 *
 *     const struct lesson_explorer lesson_03_explorer = {
 *         .lesson = &lesson_03,
 *         .overlay = overlay,
 *         .constants = constants,
 *     };
 *
 * Only the narrated build compiles NAME_explorer.c; the fast build that
 * `make bench` times holds the algorithm alone. The explorer pairs the two
 * (lesson_explorer_of). Nothing here draws with cairo directly: a lesson
 * draws with the canvas's verbs in the colours the explorer's palette names,
 * so a theme recolours lessons too.
 */
#ifndef TRISTEP_LESSON_EXPLORER_H
#define TRISTEP_LESSON_EXPLORER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lesson.h"

/* The explorer's palette, by name (src/draw/canvas.c gives the colours). */
enum ink {
    INK_NONE,                                   /* nothing: no fill, no outline */
    INK_EDGE_AB, INK_EDGE_BC, INK_EDGE_CA,      /* the edges' colours, as on the canvas */
    INK_VERTEX_A, INK_VERTEX_B, INK_VERTEX_C,   /* the vertices' (and their weights') */
    INK_TEXT,                                   /* the panel's text */
    INK_MARK,                                   /* a mark over any cell: white */
    INK_OUTLINE,                                /* an outline around a mark: black */
    INK_BACKING,                                /* a dark backing under drawings and labels */
    INK_PROBE,                                  /* a point the lesson computes (e.g. a crossing) */
    INK_UPPER, INK_LOWER,                       /* two parts of one triangle */
    INK_BRIGHTER, INK_DEEPER,                   /* gradients: of luminance, of depth */
    INK_COUNT
};

/* How a shape is drawn: designated initialisers, zero is the default
 *
 *     (struct pen){ .fill = INK_UPPER, .alpha = 0.3 }
 *     (struct pen){ .stroke = INK_MARK, .width = 1.5, .dashed = true }
 */
struct pen {
    enum ink fill;          /* INK_NONE: not filled */
    enum ink stroke;        /* INK_NONE: no outline */
    double width;           /* of the outline, in screen pixels; 0: 1 */
    double alpha;           /* opacity of fill and outline; 0: opaque */
    bool dashed;            /* outline 6 screen pixels on, 4 off */
};

/* Where a lesson's overlay draws: coordinates are scene pixels ((x, y) is
 * the scene point x, y; pixel (px, py) is the square px..px+1, its centre
 * px + 0.5), y down. One screen pixel is `unit` scene pixels: sizes given in
 * screen pixels (widths, radii, label sizes) stay the same at any zoom. */
struct lesson_canvas {
    double unit;                        /* scene pixels per screen pixel */
    const char *view;                   /* "color", "spans", "blocks", ... */
    void (*line)(const struct lesson_canvas *c, double x0, double y0, double x1, double y1,
                 struct pen pen);
    /* a closed polygon of n points xy[i][0], xy[i][1] */
    void (*polygon)(const struct lesson_canvas *c, const double (*xy)[2], int n, struct pen pen);
    /* a disc of `radius` screen pixels centred on (x, y) */
    void (*disc)(const struct lesson_canvas *c, double x, double y, double radius, struct pen pen);
    /* text in the explorer's font, top-left corner at (x, y), `size` screen
     * pixels, on a dark backing so that it reads over any cell */
    void (*label)(const struct lesson_canvas *c, double x, double y, const char *text,
                  double size, enum ink ink);
    /* an arrow from (x0, y0) to (x1, y1) in the explorer's style */
    void (*arrow)(const struct lesson_canvas *c, double x0, double y0, double x1, double y1,
                  enum ink ink);
    /* an image of w x h pixels (0xAARRGGBB, row-major, row 0 at the top,
     * alpha ignored) stretched over the rectangle (x, y)..(x + dw, y + dh),
     * each pixel a sharp square (no smoothing): a texture, a level of its
     * pyramid. The data's colours, not the palette's */
    void (*image)(const struct lesson_canvas *c, double x, double y, double dw, double dh,
                  const uint32_t *px, int w, int h);
    /* paint the whole canvas over in the backing ink: for a view that
     * draws a picture of its own */
    void (*cover)(const struct lesson_canvas *c);
    void *painter;                      /* the explorer's, for the verbs */
};

/* A view of the lesson's own, added to the explorer's view cycle after the
 * built-in views (colour, coverage, edges, barycentrics, depth, blocks,
 * spans). The explorer keeps, for every pixel the current triangle has
 * reached, the last pixel-test and pixel-write events (edge values, z,
 * colour, aux values); `cell` turns them into a colour:
 *
 *     static bool lanes_cell(const struct tri_setup *t, const struct trace_event *test,
 *                            const struct trace_event *write, double rgb[3])
 *     {
 *         if (!test) return false;             // not reached: leave it dark
 *         rgb[0] = test->aux[0]; ...           // e.g. which SIMD lane
 *         return true;
 *     }
 *     static const struct lesson_view views[] = {
 *         { "lanes", "which of the four lanes tested the pixel", lanes_cell },
 *     };
 *
 * `test` or `write` is NULL when the pixel saw no such event this step (a
 * pixel covered without a test of its own, in a full block or a span, gets
 * a test event with its x, y and TRACE_INSIDE, the rest zero; its aux and
 * line are those of the pixel's last test or cell_lines step); `t` is the
 * triangle's setup (its vertices, for values the events do not carry).
 * The name is what --view accepts; the legend is shown under it. */
struct lesson_view {
    const char *name;
    const char *legend;
    bool (*cell)(const struct tri_setup *t, const struct trace_event *test,
                 const struct trace_event *write, double rgb[3]);
};

/* A colour a view names under its legend (lesson_explorer.swatches). */
struct lesson_swatch {
    double rgb[3];
    char label[48];
};

struct lesson_explorer {
    const struct lesson *lesson;        /* the algorithm it belongs to */
    const struct lesson_view *views;    /* views of its own, or NULL */
    int nviews;

    /* Drawings of its own over the canvas, or NULL: called after the
     * triangle's edges are drawn, in every view (it looks at c->view to
     * draw only where it means to). `t` is the focus triangle's setup (it
     * may be empty: area2 == 0), `p` the run's params, `last` the last event
     * of the step shown (NULL before the first). */
    void (*overlay)(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last);

    /* Per-triangle constants for the watch panel's TRIANGLE section, or
     * NULL: a few lines "name = value" (newline-separated, NUL-terminated,
     * at most n bytes) computed from the focus triangle's setup. Not called
     * for an empty triangle. */
    void (*constants)(const struct tri_setup *t, const struct raster_params *p, char *buf,
                      size_t n);

    /* Values the watch panel shows about event `ev` that follow from the
     * event and the triangle, so that the lesson need not narrate them; or
     * NULL. Writes lines as `constants` does (an empty string: nothing). */
    void (*watch)(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n);

    /* What the watch panel calls a pixel test's verdict, or NULL for
     * "outside" and "inside" (the centre's): verdict[0] without
     * TRACE_INSIDE, verdict[1] with it. For a lesson whose pixel test is
     * not the centre's alone (lesson 08: any of its samples), so that the
     * centre's edge values printed after it do not contradict it. */
    const char *const *verdict;

    /* Lines whose TRACE_STEP events tell about the pixel (x, y), ending
     * with -1, or NULL: the explorer keeps such a step's aux in the pixel's
     * cell, as a pixel test's, and a view's cell() sees it with the line in
     * test->line (lesson 09: a pixel's (u, v) evaluated, helper or not; its
     * texel filtered, the levels and weights). */
    const int *cell_lines;

    /* The colours view `view` (one of the lesson's own) names one by one
     * under its legend, or NULL: at most `max` written to out, their count
     * returned (0: none). For a view whose colours depend on the run (one
     * colour per level of the scene's texture pyramids, lesson 09). */
    int (*swatches)(const char *view, const struct raster_params *p, struct lesson_swatch *out,
                    int max);
};

/* Every lesson's explorer side, NULL-terminated (the generated lessons.c),
 * and the one belonging to lesson l (found by id), or NULL. */
extern const struct lesson_explorer *const all_lesson_explorers[];
const struct lesson_explorer *lesson_explorer_of(const struct lesson *l);

#endif
