/* painter.h - what the files of the painter share (private to src/draw/):
 * the palette, the painter of one frame, text, and the parts of the frame.
 *
 *     paint.c    the frame: background, canvas, scrub bar, panel, help
 *     canvas.c   the pixel grid, the triangle as exact vectors, the current step
 *     views.c    the built-in views: name, cell colour, numbers, legend
 *     overlay.c  the lesson's canvas: where lesson overlays draw
 *     panel.c    the side panel and the help overlay
 *     bar.c      the scrub bar
 *     fonts.c    pinned fonts and text (Pango, DejaVu Sans Mono)
 *     palette.c  the colours, named once
 *     export.c   the frame as a PNG, SVG or PDF file (export.h, public)
 */
#ifndef TRISTEP_PAINTER_H
#define TRISTEP_PAINTER_H

#include <pango/pangocairo.h>
#include <stdbool.h>
#include <stdint.h>

#include "paint.h"

/* --- colours ------------------------------------------------------------------- */

/* Every colour of the interface (0xRRGGBB), named once. A theme is one of
 * these: the painter draws with whichever palette it is given. The colours
 * of the data itself (the scene's own colours, barycentrics as RGB, depth
 * as grey) are not in it. */
struct palette {
    uint32_t bg, canvas, panel, rule;               /* frame, canvas, panel, separators */
    uint32_t text, dim, accent, hilite;             /* text; the current step; pseudo-code line */
    uint32_t track;                                 /* scrub bar's track */
    uint32_t grid, centre, border;                  /* pixel grid, pixel centres, target border */
    uint32_t shadow;                                /* backing of labels, halo of lines */
    uint32_t box, pin, handle_rim;                  /* bounding box, pinned pixel, vertex rims */
    uint32_t edge[3], vertex[3];                    /* edges AB, BC, CA; vertices A, B, C */
    uint32_t covered, outside, untested;            /* coverage of the current triangle */
    uint32_t earlier1, earlier2, empty_px;          /* covered before once, twice; never */
    uint32_t pos, neg, zero;                        /* sign of one edge value */
    uint32_t fail_one, fail_two;                    /* outside one edge, two edges */
    uint32_t block_empty, block_full, block_partial;
    uint32_t partial_inside, partial_outside;       /* tested pixels of a partial block */
    uint32_t span, row;
    uint32_t extra, missing, exhibit, on_exhibit;   /* an exhibit against the exact rule */
    uint32_t wrong_colour;                          /* covered alike, coloured otherwise */
    /* what lessons draw with (enum ink in lesson_explorer.h), beside the
     * edges, vertices, text and shadow above */
    uint32_t mark;                                  /* a mark over any cell */
    uint32_t probe;                                 /* a point a lesson computes */
    uint32_t upper, lower;                          /* two parts of one triangle */
    uint32_t brighter, deeper;                      /* gradients of luminance, of depth */
};

extern const struct palette palette_dark, palette_light;

/* The palette of a theme. */
const struct palette *palette_of(enum theme t);

static inline void set_rgba(cairo_t *cr, uint32_t c, double a)
{
    cairo_set_source_rgba(cr, (c >> 16 & 255) / 255.0, (c >> 8 & 255) / 255.0, (c & 255) / 255.0, a);
}

static inline void set_rgb(cairo_t *cr, uint32_t c)
{
    cairo_set_source_rgb(cr, (c >> 16 & 255) / 255.0, (c >> 8 & 255) / 255.0, (c & 255) / 255.0);
}

uint32_t mix(uint32_t a, uint32_t b, double t);     /* a*(1-t) + b*t */
uint32_t from_rgb(double r, double g, double b);    /* components in [0, 1] */
double luma(uint32_t c);                            /* 0 black .. 1 white */

/* --- one frame ------------------------------------------------------------------ */

struct painter {
    cairo_t *cr;
    struct explorer *ex;
    struct explorer_layout L;
    PangoLayout *layout;
    double s;                       /* interface scale */
    const struct palette *pal;
    double text_min;                /* on paper, while the canvas is drawn: its smallest text */
};

void paint_canvas(struct painter *p);
/* An RGB24 image surface drawn with its pixels as sharp squares (no
 * smoothing), its top-left corner at (x, y), a pixel sx by sy; the surface
 * is released. */
void paint_sharp_image(cairo_t *cr, cairo_surface_t *img, double x, double y, double sx, double sy);
void paint_overlay(struct painter *p);
void paint_bar(struct painter *p);
void paint_panel(struct painter *p);
void paint_help(struct painter *p);

/* --- text ----------------------------------------------------------------------- */

cairo_font_options_t *font_options(void);
/* DejaVu Sans Mono as a cairo face, for the numbers in cells; NULL if missing. */
cairo_font_face_t *mono_face(void);

/* The height of text of `size` interface pixels in frame units: on the
 * canvas on paper never below p->text_min, the cell numbers' floor, so that
 * labels and names print at least as large as the numbers. */
double text_px(const struct painter *p, double size);
/* Draw text (Pango markup when markup) at (x, y) top-left, at most `width`
 * wide (0: no limit), `size` in interface pixels; returns its height. */
double draw_text(struct painter *p, double x, double y, double width, const char *str,
                 double size, uint32_t colour, bool markup);
double text_width(struct painter *p, const char *str, double size);

/* Numbers in cells: glyphs collected over the frame, shown in one batch. */
struct glyph_batch {
    cairo_glyph_t *g;
    int n, cap;
};
void batch_add(cairo_t *cr, struct glyph_batch *b, double cx, double cy, const char *str,
               double advance);

/* --- views ---------------------------------------------------------------------- */

/* What a view's cells need: the explorer, the palette, the scene's depth range. */
struct view_ctx {
    const struct explorer *ex;
    const struct palette *pal;
    double zmin, zmax;
};

struct swatch {
    uint32_t colour;
    const char *label;
};
#define VIEW_LEGEND_MAX 13      /* a texture's 13 levels, one colour each (lesson 09) */

void view_ctx_init(struct view_ctx *v, const struct explorer *ex, const struct palette *pal);
/* Colour of pixel (x, y) in the current view. */
uint32_t view_cell(const struct view_ctx *v, int x, int y);
/* The numbers shown in cell (x, y), up to 3 lines; returns the line count. */
int view_numbers(const struct view_ctx *v, int x, int y, char out[3][16]);
/* The most lines of numbers a cell of the current view shows. */
int view_lines(const struct explorer *ex);
/* The current view's legend: swatches, and *note a remark or NULL. */
int view_legend(const struct view_ctx *v, struct swatch out[VIEW_LEGEND_MAX], const char **note);

/* The current triangle's cell at (x, y), or NULL (also before the first step). */
const struct cell *cur_cell(const struct explorer *ex, int x, int y);
/* An edge value (1/65536 px^2) in pixels squared, in a few digits. */
void format_edge(char *buf, size_t n, int64_t F);
extern const char *const edge_names[3];     /* "F_ab", "F_bc", "F_ca" */

#endif
