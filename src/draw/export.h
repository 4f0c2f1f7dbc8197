/* export.h - pictures written to files through cairo: the explorer's view as
 * a figure (PNG, SVG or PDF) and a target's colour buffer as PNG. */
#ifndef TRISTEP_EXPORT_H
#define TRISTEP_EXPORT_H

#include <cairo.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "explore/explorer.h"

/* Write the current frame (w x h) to FILE.png, .svg or .pdf, all or nothing. */
bool explorer_export(struct explorer *ex, const char *path, int w, int h,
                     char *err, size_t errlen);
/* The same; a PDF on a page of paper (A4 or Letter, landscape for a wide
 * view), the view fitted within margins and its cell numbers legible in
 * print (at least 6 pt, over the edges with a halo, or left out), and its
 * labels and names at least 6 pt too. */
bool explorer_export_paper(struct explorer *ex, const char *path, int w, int h, enum paper paper,
                           char *err, size_t errlen);
/* The page such a PDF has, in points, and its picture drawn on cr in
 * points (the view of w x h fitted, the cell numbers for print). */
void paper_page_size(enum paper paper, int w, int h, double *pw, double *ph);
void explorer_paint_page(struct explorer *ex, cairo_t *cr, int w, int h, enum paper paper);

/* PNG of the colour buffer. */
bool write_color_png(FILE *out, const struct target *fb);

#endif
