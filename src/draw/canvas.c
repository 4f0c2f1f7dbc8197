/* canvas.c - the pixel grid in the current view, the triangle as exact
 * vectors over it, the current step outlined, and the numbers in cells. */
#include "painter.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "views.h"

static const char *const vertex_names[3] = { "A", "B", "C" };

static void cell_rect(const struct painter *p, double x0, double y0, double x1, double y1)
{
    const struct explorer_layout *L = &p->L;
    cairo_rectangle(p->cr, L->ox + x0 * L->zoom, L->oy + y0 * L->zoom, (x1 - x0) * L->zoom,
                    (y1 - y0) * L->zoom);
}

void paint_sharp_image(cairo_t *cr, cairo_surface_t *img, double x, double y, double sx, double sy)
{
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, sx, sy);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0, 0, cairo_image_surface_get_width(img), cairo_image_surface_get_height(img));
    cairo_fill(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
}

static void paint_cells(struct painter *p, int x0, int y0, int x1, int y1)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    struct view_ctx v;
    view_ctx_init(&v, ex, p->pal);
    int w = x1 - x0, h = y1 - y0;
    bool raster = cairo_surface_get_type(cairo_get_target(cr)) == CAIRO_SURFACE_TYPE_IMAGE;
    if (raster) {
        /* one image pixel per scene pixel, scaled up without smoothing */
        cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
        uint32_t *px = (uint32_t *)cairo_image_surface_get_data(img);
        int stride = cairo_image_surface_get_stride(img) / 4;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++)
                px[(y - y0) * stride + (x - x0)] = view_cell(&v, x, y);
        paint_sharp_image(cr, img, L->ox + x0 * L->zoom, L->oy + y0 * L->zoom, L->zoom, L->zoom);
        return;
    }
    /* vector surfaces: runs of one colour as rectangles */
    for (int y = y0; y < y1; y++) {
        int x = x0;
        while (x < x1) {
            uint32_t c = view_cell(&v, x, y);
            int e = x + 1;
            while (e < x1 && view_cell(&v, e, y) == c)
                e++;
            set_rgb(cr, c);
            cell_rect(p, x, y, e, y + 1);
            cairo_fill(cr);
            x = e;
        }
    }
}

/* The font size of the numbers in cells, or 0 when they are not shown:
 * the widest label is about 5 characters of 0.6 em. On paper (text_min)
 * they are at least text_min, or left out when the cell cannot hold them. */
static double numbers_size(const struct painter *p)
{
    const struct explorer *ex = p->ex;
    if (ex->numbers == NUMBERS_OFF)
        return 0;
    int lines = view_lines(ex);
    double fits = fmin(p->L.zoom * 0.86 / (lines * 1.2), p->L.zoom * 0.86 / (5.2 * 0.602));
    if (ex->text_min > 0)
        return fits < ex->text_min ? 0 : fmin(fits, fmax(13 * p->s, ex->text_min));
    double size = fmin(fits, 13 * p->s);
    return size < (ex->numbers == NUMBERS_ALWAYS ? 3.0 : 7.0) ? 0 : size;
}

static void paint_grid(struct painter *p, int x0, int y0, int x1, int y1)
{
    cairo_t *cr = p->cr;
    const struct explorer_layout *L = &p->L;
    if (L->zoom < 6)
        return;
    cairo_save(cr);
    cairo_set_line_width(cr, 1);
    set_rgba(cr, p->pal->grid, 0.45);
    for (int x = x0; x <= x1; x++) {
        double sx = L->ox + x * L->zoom + 0.5;
        cairo_move_to(cr, sx, L->oy + y0 * L->zoom);
        cairo_line_to(cr, sx, L->oy + y1 * L->zoom);
    }
    for (int y = y0; y <= y1; y++) {
        double sy = L->oy + y * L->zoom + 0.5;
        cairo_move_to(cr, L->ox + x0 * L->zoom, sy);
        cairo_line_to(cr, L->ox + x1 * L->zoom, sy);
    }
    cairo_stroke(cr);
    if (L->zoom >= 14) {    /* pixel centres: the samples that decide coverage */
        double r = fmax(1.0, L->zoom * 0.05);
        set_rgba(cr, p->pal->centre, 0.55);
        bool numbers = numbers_size(p) > 0;
        struct view_ctx v;
        view_ctx_init(&v, p->ex, p->pal);
        char out[3][16];
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                if (numbers && view_numbers(&v, x, y, out) > 0)
                    continue;       /* the cell's numbers sit where its centre is */
                cairo_rectangle(cr, L->ox + (x + 0.5) * L->zoom - r, L->oy + (y + 0.5) * L->zoom - r,
                                2 * r, 2 * r);
            }
        cairo_fill(cr);
    }
    cairo_restore(cr);
}

static void paint_exhibit(struct painter *p, int x0, int y0, int x1, int y1)
{
    struct explorer *ex = p->ex;
    if (!ex->diff || !variant_against_exact(&ex->lesson->variants[ex->variant]))
        return;
    cairo_t *cr = p->cr;
    const struct explorer_layout *L = &p->L;
    double lw = fmax(2 * p->s, L->zoom * 0.12);
    for (int kind = EXHIBIT_EXTRA; kind <= EXHIBIT_COLOUR; kind++) {
        set_rgb(cr, kind == EXHIBIT_EXTRA ? p->pal->extra : kind == EXHIBIT_MISSING ? p->pal->missing
                                                                     : p->pal->wrong_colour);
        bool any = false;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                if (ex->diff[(size_t)y * (size_t)ex->scene.w + (size_t)x] != kind)
                    continue;
                any = true;
                if (L->zoom < 8) {
                    cell_rect(p, x, y, x + 1, y + 1);
                } else {
                    double in = lw / 2 + 1;
                    cairo_rectangle(cr, L->ox + x * L->zoom + in, L->oy + y * L->zoom + in,
                                    L->zoom - 2 * in, L->zoom - 2 * in);
                }
            }
        if (!any)
            continue;
        if (L->zoom < 8) {
            cairo_fill(cr);
        } else {
            cairo_set_line_width(cr, lw);
            cairo_stroke(cr);
        }
    }
}

static void paint_triangle(struct painter *p)
{
    struct explorer *ex = p->ex;
    if (ex->scene.ntris == 0)
        return;
    cairo_t *cr = p->cr;
    const struct explorer_layout *L = &p->L;
    const struct tri_setup *t = &ex->tri;
    double vx[3], vy[3];
    for (int k = 0; k < 3; k++) {
        vx[k] = L->ox + L->zoom * t->x[k] / SUBPIXEL_ONE;
        vy[k] = L->oy + L->zoom * t->y[k] / SUBPIXEL_ONE;
    }
    cairo_save(cr);
    /* the bounding box of pixels whose centre may be covered */
    if (!t->empty) {
        cairo_set_line_width(cr, 1.5 * p->s);
        double dash[] = { 5 * p->s, 4 * p->s };
        cairo_set_dash(cr, dash, 2, 0);
        set_rgba(cr, p->pal->box, 0.9);
        cell_rect(p, t->minx, t->miny, t->maxx + 1, t->maxy + 1);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
    }
    /* the edges, exactly where the snapped vertices are */
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int k = 0; k < 3; k++) {
        int b = (k + 1) % 3;
        cairo_set_line_width(cr, 4 * p->s);
        set_rgba(cr, p->pal->shadow, 0.55);
        cairo_move_to(cr, vx[k], vy[k]);
        cairo_line_to(cr, vx[b], vy[b]);
        cairo_stroke(cr);
        cairo_set_line_width(cr, (ex->view == VIEW_EDGES && ex->edge == k ? 3 : 2) * p->s);
        set_rgb(cr, p->pal->edge[k]);
        cairo_move_to(cr, vx[k], vy[k]);
        cairo_line_to(cr, vx[b], vy[b]);
        cairo_stroke(cr);
    }
    /* edge classes of the fill rule, named at each edge's middle in the edges view */
    double gx = (vx[0] + vx[1] + vx[2]) / 3, gy = (vy[0] + vy[1] + vy[2]) / 3;
    if (ex->view == VIEW_EDGES && t->area2 > 0) {
        for (int k = 0; k < 3; k++) {
            int b = (k + 1) % 3;
            const char *cls = t->I[k] == 0 ? (t->J[k] > 0 ? "top" : "bottom")
                              : t->I[k] > 0 ? "left" : "right";
            char buf[48];
            snprintf(buf, sizeof buf, "%s %s", edge_names[k], cls);
            /* from the edge's middle along its outward normal (-I, -J), out
             * of the bounding box, whose cells may carry numbers */
            double mx = (vx[k] + vx[b]) / 2, my = (vy[k] + vy[b]) / 2;
            double dx = -(double)t->I[k], dy = -(double)t->J[k], d = hypot(dx, dy);
            if (d > 0)
                dx /= d, dy /= d;
            double tw = text_width(p, buf, 12), ks = text_px(p, 12) / (12 * p->s);
            double hw = tw / 2 + 6 * p->s, hh = 11 * ks * p->s;
            double bx0 = L->ox + t->minx * L->zoom, bx1 = L->ox + (t->maxx + 1) * L->zoom;
            double by0 = L->oy + t->miny * L->zoom, by1 = L->oy + (t->maxy + 1) * L->zoom;
            double go = HUGE_VAL;
            if (dx > 1e-9)
                go = fmin(go, (bx1 + hw - mx) / dx);
            if (dx < -1e-9)
                go = fmin(go, (bx0 - hw - mx) / dx);
            if (dy > 1e-9)
                go = fmin(go, (by1 + hh - my) / dy);
            if (dy < -1e-9)
                go = fmin(go, (by0 - hh - my) / dy);
            go = isfinite(go) ? fmax(go, 18 * p->s) : 18 * p->s;
            double cxl = mx + dx * go, cyl = my + dy * go;
            /* on the canvas, whatever the zoom */
            cxl = fmin(fmax(cxl, L->cx + hw), L->cx + L->cw - hw);
            cyl = fmin(fmax(cyl, L->cy + hh), L->cy + L->ch - hh);
            double lx = cxl - tw / 2, ly = cyl - 8 * ks * p->s;
            set_rgba(cr, p->pal->shadow, 0.7);
            cairo_rectangle(cr, lx - 4 * p->s, ly - 1 * p->s, tw + 8 * p->s, 18 * ks * p->s);
            cairo_fill(cr);
            draw_text(p, lx, ly, 0, buf, 12, p->pal->edge[k], false);
        }
    }
    /* vertex handles */
    for (int k = 0; k < 3; k++) {
        double r = (ex->hover_vertex == k ? 8 : 6) * p->s;
        if (L->zoom >= 24) {
            /* cells large enough to carry numbers: a ring around the
             * vertex's cell number rather than a disc over it */
            r = fmax(r, fmin((ex->hover_vertex == k ? 0.36 : 0.3) * L->zoom,
                             (ex->hover_vertex == k ? 19 : 16) * p->s));    /* a number's size */
            cairo_arc(cr, vx[k], vy[k], r, 0, 2 * G_PI);
            cairo_set_line_width(cr, 5 * p->s);
            set_rgb(cr, p->pal->handle_rim);
            cairo_stroke_preserve(cr);
            cairo_set_line_width(cr, 2.5 * p->s);
            set_rgb(cr, p->pal->vertex[k]);
            cairo_stroke(cr);
        } else {
            cairo_arc(cr, vx[k], vy[k], r, 0, 2 * G_PI);
            set_rgb(cr, p->pal->vertex[k]);
            cairo_fill_preserve(cr);
            cairo_set_line_width(cr, 1.5 * p->s);
            set_rgb(cr, p->pal->handle_rim);
            cairo_stroke(cr);
        }
        double dx = vx[k] - gx, dy = vy[k] - gy, d = hypot(dx, dy);
        if (d > 0)
            dx /= d, dy /= d;
        /* out of the vertex's own cell when cells are large enough to carry numbers */
        double out = 16 * p->s + (L->zoom >= 24 ? fmin(0.75 * L->zoom, 40 * p->s) : 0);
        double lx = vx[k] + dx * out - 5 * p->s, ly = vy[k] + dy * out - 10 * p->s;
        lx = fmin(fmax(lx, L->cx + 2 * p->s), L->cx + L->cw - 16 * p->s);     /* on the canvas */
        ly = fmin(fmax(ly, L->cy + 2 * p->s), L->cy + L->ch - 22 * p->s);
        set_rgba(cr, p->pal->shadow, 0.6);
        double ks = text_px(p, 15) / (15 * p->s);    /* larger on paper, if need be */
        cairo_arc(cr, lx + 5 * ks * p->s, ly + 10 * ks * p->s, 10 * ks * p->s, 0, 2 * G_PI);
        cairo_fill(cr);
        draw_text(p, lx, ly, 0, vertex_names[k], 15, p->pal->vertex[k], false);
    }
    cairo_restore(cr);
}

static void outline(struct painter *p, double x0, double y0, double x1, double y1, uint32_t colour,
                    double width)
{
    cairo_t *cr = p->cr;
    cairo_set_line_width(cr, width);
    set_rgba(cr, p->pal->shadow, 0.6);
    cell_rect(p, x0, y0, x1, y1);
    cairo_set_line_width(cr, width + 2 * p->s);
    cairo_stroke(cr);
    set_rgb(cr, colour);
    cell_rect(p, x0, y0, x1, y1);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
}

static void paint_current(struct painter *p)
{
    struct explorer *ex = p->ex;
    const struct trace_event *ev = &ex->last;
    double w = 2.5 * p->s;
    if (ex->has_last) {
        switch ((enum trace_kind)ev->kind) {
        case TRACE_PIXEL_TEST:
        case TRACE_PIXEL_WRITE:
            outline(p, ev->x, ev->y, ev->x + 1, ev->y + 1, p->pal->accent, w);
            break;
        case TRACE_ROW:
        case TRACE_SPAN:
            outline(p, ev->x, ev->y, ev->x1 + 1, ev->y + 1, p->pal->accent, w);
            break;
        case TRACE_BLOCK:
            outline(p, ev->x, ev->y, ev->x1 + 1, ev->y1 + 1, p->pal->accent, w);
            break;
        case TRACE_FRONT:
            /* the shared front end's own event (src/front/front.c narrates
             * it for every program on a 3-D scene, not lesson 06 alone): the
             * pixel of the vertex it projected or made; lesson 06's own
             * drawings of these steps are in its explorer file's overlay */
            if (ev->klass == FRONT_PROJECT || ev->klass == FRONT_NEW)
                outline(p, ev->x, ev->y, ev->x + 1, ev->y + 1, p->pal->accent, w);
            break;
        case TRACE_SETUP:
            if (!ex->tri.empty)
                outline(p, ex->tri.minx, ex->tri.miny, ex->tri.maxx + 1, ex->tri.maxy + 1,
                        p->pal->accent, w);
            break;
        case TRACE_STEP:
        case TRACE_KIND_COUNT:
            break;
        }
    }
    if (ex->pinned)
        outline(p, ex->pin_x, ex->pin_y, ex->pin_x + 1, ex->pin_y + 1, p->pal->pin, w);
}

static void paint_numbers(struct painter *p, int x0, int y0, int x1, int y1)
{
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    if (ex->numbers == NUMBERS_OFF || !mono_face())
        return;
    cairo_t *cr = p->cr;
    double size = numbers_size(p);
    if (size <= 0)
        return;
    cairo_save(cr);
    cairo_set_font_face(cr, mono_face());
    cairo_set_font_size(cr, size);
    cairo_set_font_options(cr, font_options());
    double advance = size * 0.602;   /* DejaVu Sans Mono: 1233 / 2048 em */
    cairo_text_extents_t te;
    cairo_text_extents(cr, "0", &te);
    advance = te.x_advance;
    struct glyph_batch ink[2] = { { 0 } };
    struct view_ctx v;
    view_ctx_init(&v, ex, p->pal);
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            char out[3][16];
            int n = view_numbers(&v, x, y, out);
            if (n == 0)
                continue;
            bool light = luma(view_cell(&v, x, y)) < 0.5;
            double cx = L->ox + (x + 0.5) * L->zoom, cy = L->oy + (y + 0.5) * L->zoom;
            double lh = size * 1.2;
            for (int k = 0; k < n; k++) {
                double by = cy - lh * n / 2 + lh * k + size * 0.95;
                batch_add(cr, &ink[light], cx, by, out[k], advance);
            }
        }
    for (int k = 0; k < 2; k++) {
        if (ink[k].n && ex->text_min > 0) {     /* on paper, over the edges: a halo first */
            set_rgba(cr, k ? 0x000000 : 0xffffff, 0.85);
            cairo_glyph_path(cr, ink[k].g, ink[k].n);
            cairo_set_line_width(cr, size * 0.3);
            cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
            cairo_stroke(cr);
        }
        if (ink[k].n) {
            set_rgba(cr, k ? 0xffffff : 0x000000, 0.92);
            cairo_show_glyphs(cr, ink[k].g, ink[k].n);
        }
        free(ink[k].g);
    }
    cairo_restore(cr);
}

void paint_canvas(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    cairo_save(cr);
    cairo_rectangle(cr, L->cx, L->cy, L->cw, L->ch);
    cairo_clip(cr);
    set_rgb(cr, p->pal->canvas);
    cairo_paint(cr);
    /* visible pixels */
    int x0 = (int)floor((L->cx - L->ox) / L->zoom), y0 = (int)floor((L->cy - L->oy) / L->zoom);
    int x1 = (int)ceil((L->cx + L->cw - L->ox) / L->zoom), y1 = (int)ceil((L->cy + L->ch - L->oy) / L->zoom);
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > ex->scene.w ? ex->scene.w : x1, y1 = y1 > ex->scene.h ? ex->scene.h : y1;
    if (x0 < x1 && y0 < y1) {
        paint_cells(p, x0, y0, x1, y1);
        paint_grid(p, x0, y0, x1, y1);
        paint_exhibit(p, x0, y0, x1, y1);
        if (!(ex->text_min > 0))
            paint_numbers(p, x0, y0, x1, y1);
    }
    /* the target's border */
    cairo_set_line_width(cr, 1);
    set_rgba(cr, p->pal->border, 0.25);
    cell_rect(p, 0, 0, ex->scene.w, ex->scene.h);
    cairo_stroke(cr);
    paint_current(p);
    paint_triangle(p);
    paint_overlay(p);
    if (ex->text_min > 0 && x0 < x1 && y0 < y1)
        paint_numbers(p, x0, y0, x1, y1);     /* on paper: over the edges, legible */
    if (ex->message[0]) {
        double h = 24 * p->s;
        double tw = text_width(p, ex->message, 12);
        double mw = fmin(tw + 20 * p->s, L->cw - 24 * p->s);
        set_rgba(cr, p->pal->shadow, 0.75);
        cairo_rectangle(cr, L->cx + 12 * p->s, L->cy + 12 * p->s, mw, h);
        cairo_fill(cr);
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
        draw_text(p, L->cx + 22 * p->s, L->cy + 16 * p->s, mw - 20 * p->s, ex->message, 12, p->pal->accent, false);
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    }
    cairo_restore(cr);
}

