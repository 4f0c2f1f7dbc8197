/* lesson.h - what a lesson file provides: its algorithm, variants, narration
 * and views (lesson_main in src/cli/cli.h turns it into a program). */
#ifndef TRISTEP_LESSON_H
#define TRISTEP_LESSON_H

#include <cairo.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "trace/trace.h"

#define CHECKER_DARK 0.35   /* brightness of the checkerboard's dark squares */

/* Settings a run may change without changing the algorithm. */
struct raster_params {
    int checker;          /* the scene's "texture checker N", 0 = untextured */
    int block_size;       /* q for block lessons (0 = the lesson's default) */
    bool affine;          /* texture affinely, not perspective-correct (exhibit) */
    int subpixel_bits;    /* snapping precision, SUBPIXEL_BITS unless an exhibit */
};

typedef void (*rasterize_fn)(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr);

/* One way of running the lesson: the algorithm itself, a faster twin, or an
 * exhibit that reproduces a slip of the source texts. */
struct lesson_variant {
    const char *name;       /* --variant NAME */
    const char *what;       /* one line for --help and the explorer */
    rasterize_fn rasterize;
    bool exhibit;           /* deliberately not exact: shown against the exact rule */
};

#define LESSON_COMPARE_MAX 2

/* Every lesson, narrated (NULL-terminated): every program links them all, so
 * the explorer can run an earlier lesson on the same scene for comparison. */
extern const struct lesson *const all_lessons[];

/* Which raster_params a lesson reacts to: the explorer offers keys for
 * exactly these (and lists them in its help overlay). */
enum lesson_param_flags {
    LESSON_PARAM_SUBPIXEL = 1,  /* subpixel_bits 0..8 (lesson 03) */
    LESSON_PARAM_BLOCK = 2,     /* block_size 4, 8, 16 (lesson 05) */
    LESSON_PARAM_AFFINE = 4,    /* affine vs perspective-correct (lesson 04) */
};

/* A view of the lesson's own, added to the explorer's view cycle after the
 * built-in views (colour, coverage, edges, barycentrics, depth, blocks,
 * spans). The explorer keeps, for every pixel the current triangle has
 * reached, the last pixel-test and pixel-write events (edge values, weights,
 * z, colour, aux values); `cell` turns them into a colour:
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
 *     ... .views = views, .nviews = 1,
 *
 * `test` or `write` is NULL when the pixel saw no such event this step; `t`
 * is the triangle's setup (its vertices, for values the events do not carry).
 * The name is what --view accepts; the legend is shown under it. */
struct lesson_view {
    const char *name;
    const char *legend;
    bool (*cell)(const struct tri_setup *t, const struct trace_event *test,
                 const struct trace_event *write, double rgb[3]);
};

/* Where a lesson's overlay draws (see `overlay` below). `cr` is the
 * explorer's cairo context already transformed to scene pixel units: (x, y)
 * is the scene point x, y (pixel (px, py) is the square px..px+1, its centre
 * px + 0.5), y down. One screen pixel is `unit` scene pixels, so a line
 * 2 screen pixels wide is cairo_set_line_width(cr, 2 * c->unit). `label`
 * writes text in the explorer's font at scene point (x, y) (its top-left
 * corner), `size` in screen pixels, on a dark backing so it reads over any
 * cell. `edge_rgb` are the colours the explorer gives the edges AB, BC, CA
 * (0xRRGGBB), `view` the name of the view shown. */
struct lesson_canvas {
    cairo_t *cr;
    double unit;                        /* scene pixels per screen pixel */
    const char *view;                   /* "color", "spans", "blocks", ... */
    uint32_t edge_rgb[3];
    void (*label)(const struct lesson_canvas *c, double x, double y, const char *text,
                  double size, uint32_t rgb);
    /* an arrow from (x0, y0) to (x1, y1), scene pixels, in the explorer's style */
    void (*arrow)(const struct lesson_canvas *c, double x0, double y0, double x1, double y1,
                  uint32_t rgb);
    void *painter;                      /* the explorer's, for `label` */
};

struct lesson {
    const char *id;                     /* "02-barycentric", as the program's name */
    const char *title;
    const char *const *pseudocode;      /* lines, NULL-terminated; events point at them */
    const char *builtin_scene;          /* the scene opened by default */
    const char *exhibit_scene;          /* the scene its exhibits are shown on */
    bool perspective;                   /* interpolates 1/z (lesson 04 onwards) */
    const struct lesson_variant *variants;  /* variants[0] is the lesson's algorithm */
    int nvariants;
    const char *const *aux_names;       /* names of trace_event.aux[], NULL-terminated */
    unsigned params;                    /* enum lesson_param_flags it reacts to */
    /* ids of earlier lessons (at most LESSON_COMPARE_MAX, NULL-terminated)
     * that the explorer runs on the same scene, to show their counters
     * (pixels tested, arithmetic per pixel) beside this lesson's */
    const char *const *compare;
    const struct lesson_view *views;    /* views of its own, or NULL */
    int nviews;

    /* Drawings of its own over the canvas, or NULL: called after the
     * triangle's edges are drawn, in every view (the lesson looks at c->view
     * to draw only where it means to). `t` is the focus triangle's setup (it
     * may be empty: area2 == 0), `p` the run's params, `last` the last event
     * of the step shown (NULL before the first). It draws and returns; the
     * explorer saves and restores the cairo state around it. */
    void (*overlay)(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last);

    /* Per-triangle constants for the watch panel's TRIANGLE section, or NULL:
     * writes a few lines "name = value" (newline-separated, NUL-terminated,
     * at most n bytes) computed from the focus triangle's setup. Not called
     * for an empty triangle. */
    void (*constants)(const struct tri_setup *t, const struct raster_params *p, char *buf,
                      size_t n);
};

const struct lesson_variant *lesson_variant(const struct lesson *l, const char *name);

/* Colour of a covered pixel from interpolated values, shared by every lesson:
 * the Gouraud colour, darkened on the dark squares of the checkerboard when
 * the scene has "texture checker N" (texture coordinates in [0, 1]). */
static inline uint32_t shade_pixel(const struct raster_params *p, double r, double g,
                                   double b, double s, double t)
{
    if (p->checker > 0) {
        long i = (long)floor(s * p->checker), j = (long)floor(t * p->checker);
        if ((i + j) & 1) {
            r *= CHECKER_DARK;
            g *= CHECKER_DARK;
            b *= CHECKER_DARK;
        }
    }
    return pack_rgb(r, g, b);
}

#endif
