/* overlay.c - the lesson's canvas: where a lesson's overlay draws over the
 * pixel grid (struct lesson_canvas in lesson_explorer.h), built here and
 * only here. Its verbs draw in scene pixel units, sizes in screen pixels,
 * colours by name from the painter's palette. */
#include "painter.h"

#include <math.h>

#include "views.h"

struct overlay_painter {
    struct painter *p;
    cairo_matrix_t screen;          /* the context's matrix before the scene transform */
};

static struct painter *painter_of(const struct lesson_canvas *c)
{
    return ((const struct overlay_painter *)c->painter)->p;
}

/* The palette's colour for a lesson's ink. */
static uint32_t ink_rgb(const struct palette *pal, enum ink ink)
{
    switch (ink) {
    case INK_EDGE_AB: case INK_EDGE_BC: case INK_EDGE_CA:
        return pal->edge[ink - INK_EDGE_AB];
    case INK_VERTEX_A: case INK_VERTEX_B: case INK_VERTEX_C:
        return pal->vertex[ink - INK_VERTEX_A];
    case INK_TEXT: return pal->text;
    case INK_MARK: return pal->mark;
    case INK_OUTLINE: case INK_BACKING: return pal->shadow;
    case INK_PROBE: return pal->probe;
    case INK_UPPER: return pal->upper;
    case INK_LOWER: return pal->lower;
    case INK_BRIGHTER: return pal->brighter;
    case INK_DEEPER: return pal->deeper;
    case INK_NONE: case INK_COUNT: break;
    }
    return pal->text;
}

/* Fill and outline the current path with a pen, then clear it. */
static void draw_path(const struct lesson_canvas *c, struct pen pen)
{
    struct painter *p = painter_of(c);
    cairo_t *cr = p->cr;
    double alpha = pen.alpha > 0 ? pen.alpha : 1;
    if (pen.fill != INK_NONE) {
        set_rgba(cr, ink_rgb(p->pal, pen.fill), alpha);
        if (pen.stroke != INK_NONE)
            cairo_fill_preserve(cr);
        else
            cairo_fill(cr);
    }
    if (pen.stroke != INK_NONE) {
        set_rgba(cr, ink_rgb(p->pal, pen.stroke), alpha);
        cairo_set_line_width(cr, (pen.width > 0 ? pen.width : 1) * c->unit);
        double dash[] = { 6 * c->unit, 4 * c->unit };
        if (pen.dashed)
            cairo_set_dash(cr, dash, 2, 0);
        cairo_stroke(cr);
        if (pen.dashed)
            cairo_set_dash(cr, NULL, 0, 0);
    }
    cairo_new_path(cr);
}

static void overlay_line(const struct lesson_canvas *c, double x0, double y0, double x1,
                         double y1, struct pen pen)
{
    cairo_t *cr = painter_of(c)->cr;
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1, y1);
    pen.fill = INK_NONE;
    draw_path(c, pen);
}

static void overlay_polygon(const struct lesson_canvas *c, const double (*xy)[2], int n,
                            struct pen pen)
{
    cairo_t *cr = painter_of(c)->cr;
    cairo_move_to(cr, xy[0][0], xy[0][1]);
    for (int i = 1; i < n; i++)
        cairo_line_to(cr, xy[i][0], xy[i][1]);
    cairo_close_path(cr);
    draw_path(c, pen);
}

static void overlay_disc(const struct lesson_canvas *c, double x, double y, double radius,
                         struct pen pen)
{
    cairo_t *cr = painter_of(c)->cr;
    cairo_new_path(cr);
    cairo_arc(cr, x, y, radius * c->unit, 0, 6.283185307179586);
    draw_path(c, pen);
}

/* Arrows for the lessons' overlays: a shaft 2.5 screen pixels wide and a head
 * of 9, whatever the zoom. */
static void overlay_arrow(const struct lesson_canvas *c, double x, double y, double ex, double ey,
                          enum ink ink)
{
    struct painter *p = painter_of(c);
    cairo_t *cr = p->cr;
    double dx = ex - x, dy = ey - y, d = hypot(dx, dy), h = 9 * c->unit;
    if (!(d > 0))
        return;
    dx /= d, dy /= d;
    set_rgb(cr, ink_rgb(p->pal, ink));
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
                          double size, enum ink ink)
{
    const struct overlay_painter *o = c->painter;
    struct painter *p = o->p;
    const struct explorer_layout *L = &p->L;
    cairo_save(p->cr);
    cairo_set_matrix(p->cr, &o->screen);
    double sx = L->ox + x * L->zoom, sy = L->oy + y * L->zoom;
    double tw = text_width(p, str, size), th = text_px(p, size) * 1.3;
    set_rgba(p->cr, p->pal->shadow, 0.7);
    cairo_rectangle(p->cr, sx - 2 * p->s, sy, tw + 4 * p->s, th);
    cairo_fill(p->cr);
    draw_text(p, sx, sy, 0, str, size, ink_rgb(p->pal, ink), false);
    cairo_restore(p->cr);
}

/* An image as sharp squares: an image surface scaled without smoothing
 * (cairo writes it into a PDF or SVG as the image it is). */
static void overlay_image(const struct lesson_canvas *c, double x, double y, double dw, double dh,
                          const uint32_t *px, int w, int h)
{
    if (w <= 0 || h <= 0 || !(dw > 0) || !(dh > 0))
        return;
    cairo_t *cr = painter_of(c)->cr;
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(img);
        return;
    }
    uint32_t *to = (uint32_t *)cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img) / 4;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            to[(size_t)j * (size_t)stride + (size_t)i] = px[(size_t)j * (size_t)w + (size_t)i] & 0xffffff;
    paint_sharp_image(cr, img, x, y, dw / w, dh / h);
}

static void overlay_cover(const struct lesson_canvas *c)
{
    struct painter *p = painter_of(c);
    set_rgb(p->cr, p->pal->shadow);
    cairo_paint(p->cr);
}

/* Build the canvas for the lesson and let its overlay draw: in scene pixel
 * units, after the triangle's edges. */
void paint_overlay(struct painter *p)
{
    struct explorer *ex = p->ex;
    if (!ex->side || !ex->side->overlay || ex->scene.ntris == 0)
        return;
    const struct explorer_layout *L = &p->L;
    struct overlay_painter o = { .p = p };
    cairo_get_matrix(p->cr, &o.screen);
    struct lesson_canvas c = {
        .unit = 1 / L->zoom, .view = explorer_view_name(ex, ex->view),
        .line = overlay_line, .polygon = overlay_polygon, .disc = overlay_disc,
        .label = overlay_label, .arrow = overlay_arrow, .image = overlay_image,
        .cover = overlay_cover, .painter = &o,
    };
    cairo_save(p->cr);
    cairo_translate(p->cr, L->ox, L->oy);
    cairo_scale(p->cr, L->zoom, L->zoom);
    cairo_new_path(p->cr);
    struct run_place at;
    struct raster_params params = replay_params(&ex->replay, ex->cur, &at);  /* the unit's, lesson 07 */
    at.told = ex->told;
    ex->side->overlay(&c, &ex->tri, &params, ex->has_last ? &ex->last : NULL);
    cairo_restore(p->cr);
}
