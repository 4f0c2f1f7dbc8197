/* paint.c - the one painter: one frame of the explorer (the pixel grid in
 * the current view with the triangle as exact vectors, the scrub bar, the
 * panel, the help overlay) drawn with cairo into whatever surface it is
 * given: the window's texture, a PNG, SVG or PDF file. The parts are in the
 * files painter.h lists. */
#define _POSIX_C_SOURCE 200809L   /* clock_gettime */

#include "painter.h"

#include <time.h>

void explorer_paint(struct explorer *ex, cairo_t *cr, double w, double h)
{
    mono_face();        /* pins the fonts before Pango starts */
    struct painter p = { .cr = cr, .ex = ex, .pal = palette_of(ex->theme) };
    explorer_layout(ex, w, h, &p.L);
    p.s = p.L.s;
    p.layout = pango_cairo_create_layout(cr);
    pango_cairo_context_set_font_options(pango_layout_get_context(p.layout), font_options());
    pango_layout_context_changed(p.layout);
    cairo_save(cr);
    set_rgb(cr, p.pal->bg);
    cairo_paint(cr);
    p.text_min = ex->text_min;      /* on paper: the canvas's labels as large as its numbers */
    paint_canvas(&p);
    p.text_min = 0;
    if (ex->part == PART_ALL) {     /* --figure-part canvas: the grid alone */
        paint_bar(&p);
        paint_panel(&p);
    }
    if (ex->help)
        paint_help(&p);
    cairo_restore(cr);
    g_object_unref(p.layout);
}

cairo_status_t explorer_paint_pixels(struct explorer *ex, unsigned char *pixels, int pw, int ph,
                                     int stride, double ratio)
{
    cairo_surface_t *s = cairo_image_surface_create_for_data(pixels, CAIRO_FORMAT_ARGB32, pw, ph,
                                                             stride);
    cairo_t *cr = cairo_create(s);
    cairo_scale(cr, ratio, ratio);
    explorer_paint(ex, cr, pw / ratio, ph / ratio);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_flush(s);
    cairo_surface_destroy(s);
    return st;
}

double explorer_frame_ms(struct explorer *ex, int w, int h, int n)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
    cairo_t *cr = cairo_create(img);
    explorer_paint(ex, cr, w, h);       /* warm the caches */
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 0; i < n; i++)
        explorer_paint(ex, cr, w, h);
    cairo_surface_flush(img);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    return ((double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) / 1e6)
           / (n > 0 ? n : 1);
}
