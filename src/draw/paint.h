/* paint.h - the painter: one frame of the explorer drawn with cairo, for the
 * SDL window, for figures and for the bench's timing. Its views and its
 * file export are in views.h and export.h, included here. */
#ifndef TRISTEP_PAINT_H
#define TRISTEP_PAINT_H

#include <cairo.h>

#include "draw/export.h"
#include "draw/views.h"
#include "explore/explorer.h"

/* Paint one frame of w x h (the window, a figure, or the bench's timing).
 * Text goes through Pango with DejaVu Sans Mono, pinned by explorer_fonts(). */
void explorer_paint(struct explorer *ex, cairo_t *cr, double w, double h);
/* Paint one frame into ARGB32 pixels (pw x ph, `stride` bytes a row) at
 * `ratio` pixels per unit of the layout: 1, or 2 in a HiDPI window whose
 * size and mouse count in points (the frame is then pw / 2 x ph / 2 units,
 * drawn twice as sharp). Returns cairo's status after drawing. */
cairo_status_t explorer_paint_pixels(struct explorer *ex, unsigned char *pixels, int pw, int ph,
                                     int stride, double ratio);
/* Pin fontconfig to DejaVu only and find DejaVu Sans Mono; call before
 * anything touches Pango. False, with the reason in err, when that failed:
 * text would then come out in whatever fonts the system has, so figures
 * must not be drawn. Once per process; later calls give the same answer. */
bool explorer_fonts(char *err, size_t errlen);
/* Milliseconds per frame, averaged over n frames painted into a w x h image
 * surface (what `make bench` reports as the explorer's frame time). */
double explorer_frame_ms(struct explorer *ex, int w, int h, int n);

#endif
