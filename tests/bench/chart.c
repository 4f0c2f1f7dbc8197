/* chart.c - the bench's chart, drawn with cairo: one panel per scene, a
 * horizontal bar per program, llvmpipe in its own colour, the memory limit
 * as a dashed line. The same painter writes the SVG and the PNG. */
#include <stdio.h>
#include <string.h>

#include <cairo.h>
#include <cairo-svg.h>

#include "bench.h"

#define CHART_W 960
#define BAR_H 18
#define BAR_GAP 4
#define LABEL_W 190
#define PANEL_HEAD 34
#define PANEL_FOOT 26
#define TITLE_H 40
#define FONT "DejaVu Sans"

static double panel_height(const struct chart_panel *p)
{
    return PANEL_HEAD + p->nbars * (BAR_H + BAR_GAP) + PANEL_FOOT;
}

static double chart_height(const struct chart_panel *p, int n)
{
    double h = TITLE_H;
    for (int i = 0; i < n; i++)
        h += panel_height(&p[i]);
    return h;
}

static void text(cairo_t *cr, double x, double y, const char *s, double size, bool right)
{
    cairo_set_font_size(cr, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, right ? x - e.x_advance : x, y);
    cairo_show_text(cr, s);
}

static void draw_panel(cairo_t *cr, const struct chart_panel *p, double y)
{
    double max = p->limit;
    for (int i = 0; i < p->nbars; i++)
        max = p->bars[i].value > max ? p->bars[i].value : max;
    max = max > 0 ? max * 1.12 : 1;
    double x0 = LABEL_W, width = CHART_W - LABEL_W - 30;

    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_select_font_face(cr, FONT, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    char head[128];
    snprintf(head, sizeof head, "%s (%s, higher is better)", p->title, p->unit);
    text(cr, 12, y + 22, head, 14, false);
    cairo_select_font_face(cr, FONT, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

    double by = y + PANEL_HEAD;
    for (int i = 0; i < p->nbars; i++, by += BAR_H + BAR_GAP) {
        const struct chart_bar *b = &p->bars[i];
        cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
        text(cr, x0 - 8, by + BAR_H - 5, b->label, 11.5, true);
        if (b->peer)
            cairo_set_source_rgb(cr, 0.85, 0.45, 0.15);
        else
            cairo_set_source_rgb(cr, 0.20, 0.45, 0.75);
        cairo_rectangle(cr, x0, by, width * b->value / max, BAR_H);
        cairo_fill(cr);
        char v[32];
        snprintf(v, sizeof v, b->value >= 100 ? "%.0f" : "%.2f", b->value);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        text(cr, x0 + width * b->value / max + 4, by + BAR_H - 5, v, 11, false);
    }
    if (p->limit > 0) {
        double lx = x0 + width * p->limit / max;
        double dash[] = { 5, 4 };
        cairo_set_dash(cr, dash, 2, 0);
        cairo_set_source_rgb(cr, 0.75, 0.1, 0.1);
        cairo_set_line_width(cr, 1.5);
        cairo_move_to(cr, lx, y + PANEL_HEAD - 4);
        cairo_line_to(cr, lx, by);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
        char v[64];
        snprintf(v, sizeof v, "%s %.0f", p->limit_label, p->limit);
        text(cr, lx - 4, by + 14, v, 11, true);
    }
}

static void draw_chart(cairo_t *cr, const struct chart_panel *p, int n, const char *title)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_select_font_face(cr, FONT, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    text(cr, 12, 26, title, 15, false);
    double y = TITLE_H;
    for (int i = 0; i < n; i++) {
        draw_panel(cr, &p[i], y);
        y += panel_height(&p[i]);
    }
}

/* Draw, check cairo's sticky status once, rename the finished file in place. */
static bool finish(cairo_surface_t *s, cairo_t *cr, const char *tmp, const char *path,
                   bool png, char *err, size_t errlen)
{
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    if (st == CAIRO_STATUS_SUCCESS && png)
        st = cairo_surface_write_to_png(s, tmp);
    cairo_surface_finish(s);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    if (st != CAIRO_STATUS_SUCCESS || rename(tmp, path) != 0) {
        snprintf(err, errlen, "%s: %s", path,
                 st != CAIRO_STATUS_SUCCESS ? cairo_status_to_string(st) : "cannot rename");
        remove(tmp);
        return false;
    }
    return true;
}

bool chart_write(const struct chart_panel *p, int npanels, const char *title,
                 const char *svg_path, const char *png_path, char *err, size_t errlen)
{
    double h = chart_height(p, npanels);
    char tmp[1100];

    snprintf(tmp, sizeof tmp, "%s.tmp", svg_path);
    cairo_surface_t *s = cairo_svg_surface_create(tmp, CHART_W, h);
    cairo_t *cr = cairo_create(s);
    draw_chart(cr, p, npanels, title);
    if (!finish(s, cr, tmp, svg_path, false, err, errlen))
        return false;

    snprintf(tmp, sizeof tmp, "%s.tmp", png_path);
    s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, CHART_W, (int)h);
    cr = cairo_create(s);
    draw_chart(cr, p, npanels, title);
    return finish(s, cr, tmp, png_path, true, err, errlen);
}
