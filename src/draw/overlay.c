/* overlay.c - the lesson's canvas: where a lesson's overlay draws over the
 * pixel grid (struct lesson_canvas in lesson.h), built here and only here. */
#include "painter.h"

#include <math.h>

#include "views.h"

struct overlay_painter {
    struct painter *p;
    cairo_matrix_t screen;          /* the context's matrix before the scene transform */
};

/* Arrows for the lessons' overlays: a shaft 2.5 screen pixels wide and a head
 * of 9, whatever the zoom. */
static void overlay_arrow(const struct lesson_canvas *c, double x, double y, double ex, double ey,
                          uint32_t rgb)
{
    cairo_t *cr = c->cr;
    double dx = ex - x, dy = ey - y, d = hypot(dx, dy), h = 9 * c->unit;
    if (!(d > 0))
        return;
    dx /= d, dy /= d;
    set_rgb(cr, rgb);
    cairo_set_line_width(cr, 2.5 * c->unit);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, ex - dx * h * 0.8, ey - dy * h * 0.8);
    cairo_stroke(cr);
    cairo_move_to(cr, ex, ey);
    cairo_line_to(cr, ex - dx * h - dy * h * 0.5, ey - dy * h + dx * h * 0.5);
    cairo_line_to(cr, ex - dx * h + dy * h * 0.5, ey - dy * h - dx * h * 0.5);
    cairo_close_path(cr);
    cairo_fill(cr);
}

static void overlay_label(const struct lesson_canvas *c, double x, double y, const char *str,
                          double size, uint32_t rgb)
{
    const struct overlay_painter *o = c->painter;
    struct painter *p = o->p;
    const struct explorer_layout *L = &p->L;
    cairo_save(p->cr);
    cairo_set_matrix(p->cr, &o->screen);
    double sx = L->ox + x * L->zoom, sy = L->oy + y * L->zoom;
    double tw = text_width(p, str, size), th = size * 1.3 * p->s;
    set_rgba(p->cr, p->pal->shadow, 0.7);
    cairo_rectangle(p->cr, sx - 2 * p->s, sy, tw + 4 * p->s, th);
    cairo_fill(p->cr);
    draw_text(p, sx, sy, 0, str, size, rgb, false);
    cairo_restore(p->cr);
}

/* Build the canvas for the lesson and let its overlay draw: in scene pixel
 * units, after the triangle's edges. */
void paint_overlay(struct painter *p)
{
    struct explorer *ex = p->ex;
    if (!ex->lesson->overlay || ex->scene.ntris == 0)
        return;
    const struct explorer_layout *L = &p->L;
    struct overlay_painter o = { .p = p };
    cairo_get_matrix(p->cr, &o.screen);
    struct lesson_canvas c = {
        .cr = p->cr, .unit = 1 / L->zoom, .view = explorer_view_name(ex, ex->view),
        .label = overlay_label, .arrow = overlay_arrow, .painter = &o,
    };
    for (int k = 0; k < 3; k++)
        c.edge_rgb[k] = p->pal->edge[k];
    cairo_save(p->cr);
    cairo_translate(p->cr, L->ox, L->oy);
    cairo_scale(p->cr, L->zoom, L->zoom);
    cairo_new_path(p->cr);
    ex->lesson->overlay(&c, &ex->tri, &ex->params, ex->has_last ? &ex->last : NULL);
    cairo_restore(p->cr);
}
