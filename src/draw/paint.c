/* paint.c - the one painter: the pixel grid in the current view, the
 * triangle as exact vectors, the panels, the scrub bar and the help overlay,
 * drawn with cairo into whatever surface it is given (the window's texture,
 * a PNG, SVG or PDF file). Text: Pango with DejaVu Sans Mono. */
#define _POSIX_C_SOURCE 200809L   /* setenv, mkstemp */

#include "explorer.h"

#include <math.h>
#include <pango/pangocairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* --- fonts -------------------------------------------------------------------- */

/* Only DejaVu, with fixed rendering settings: a user's own fontconfig
 * setup must not change a figure (FACTS.md). Written to a temporary file
 * because FONTCONFIG_FILE names a file. */
static const char fonts_conf[] =
    "<?xml version=\"1.0\"?>\n"
    "<!DOCTYPE fontconfig SYSTEM \"fonts.dtd\">\n"
    "<fontconfig>\n"
    "  <dir>/usr/share/fonts/truetype/dejavu</dir>\n"
    "  <dir>/usr/share/fonts/dejavu</dir>\n"
    "  <dir>/usr/local/share/fonts/dejavu</dir>\n"
    "  <dir>/opt/homebrew/share/fonts</dir>\n"
    "  <cachedir prefix=\"xdg\">fontconfig</cachedir>\n"
    "  <config><rescan><int>0</int></rescan></config>\n"
    "  <match target=\"pattern\">\n"
    "    <edit name=\"family\" mode=\"assign\" binding=\"strong\"><string>DejaVu Sans Mono</string></edit>\n"
    "  </match>\n"
    "  <match target=\"font\">\n"
    "    <edit name=\"antialias\" mode=\"assign\"><bool>true</bool></edit>\n"
    "    <edit name=\"hinting\" mode=\"assign\"><bool>false</bool></edit>\n"
    "    <edit name=\"rgba\" mode=\"assign\"><const>none</const></edit>\n"
    "  </match>\n"
    "</fontconfig>\n";

static char fonts_path[64];

static void remove_fonts_conf(void)
{
    if (fonts_path[0])
        unlink(fonts_path);
}

void explorer_fonts(void)
{
    static bool done;
    if (done)
        return;
    done = true;
    const char *dir = getenv("TMPDIR");
    snprintf(fonts_path, sizeof fonts_path, "%s/tristep-fonts-XXXXXX",
             dir && *dir && strlen(dir) < 32 ? dir : "/tmp");
    int fd = mkstemp(fonts_path);
    if (fd < 0) {
        fonts_path[0] = '\0';
        return;
    }
    size_t n = sizeof fonts_conf - 1;
    bool ok = write(fd, fonts_conf, n) == (ssize_t)n;
    close(fd);
    if (!ok) {
        unlink(fonts_path);
        fonts_path[0] = '\0';
        return;
    }
    setenv("FONTCONFIG_FILE", fonts_path, 1);
    atexit(remove_fonts_conf);
}

static cairo_font_options_t *font_options(void)
{
    static cairo_font_options_t *o;
    if (!o) {
        o = cairo_font_options_create();
        cairo_font_options_set_antialias(o, CAIRO_ANTIALIAS_GRAY);
        cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_NONE);
        cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_OFF);
        cairo_font_options_set_subpixel_order(o, CAIRO_SUBPIXEL_ORDER_DEFAULT);
    }
    return o;
}

/* The DejaVu Sans Mono face as Pango finds it, for the numbers in cells
 * (drawn as one batch of glyphs: thousands of labels per frame). */
static cairo_font_face_t *mono_face(void)
{
    static cairo_font_face_t *face;
    if (!face) {
        explorer_fonts();
        PangoFontMap *fm = pango_cairo_font_map_get_default();
        PangoContext *ctx = pango_font_map_create_context(fm);
        pango_cairo_context_set_font_options(ctx, font_options());
        PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono 10");
        PangoFont *f = pango_font_map_load_font(fm, ctx, d);
        if (f) {
            cairo_scaled_font_t *sf = pango_cairo_font_get_scaled_font(PANGO_CAIRO_FONT(f));
            if (sf)
                face = cairo_font_face_reference(cairo_scaled_font_get_font_face(sf));
            g_object_unref(f);
        }
        pango_font_description_free(d);
        g_object_unref(ctx);
    }
    return face;
}

/* --- colours ------------------------------------------------------------------- */

struct rgb { double r, g, b; };

#define HEX(h) ((struct rgb){ ((h) >> 16 & 255) / 255.0, ((h) >> 8 & 255) / 255.0, ((h) & 255) / 255.0 })

static const uint32_t
    C_BG = 0x15171c, C_CANVAS = 0x1c1f26, C_PANEL = 0x23262e, C_RULE = 0x343946,
    C_TEXT = 0xdde3ec, C_DIM = 0x8c95a6, C_ACCENT = 0xffd166, C_HILITE = 0x3a4358,
    C_GRID = 0x000000, C_BOX = 0x88c0d0, C_PIN = 0x5ce1e6,
    C_COVERED = 0x7ec87e, C_OUTSIDE = 0x8f3b46, C_UNTESTED = 0x3a4150,
    C_EARLIER1 = 0x5b6270, C_EARLIER2 = 0x9aa3b5, C_EMPTY_PX = 0x1e2128,
    C_POS = 0x3f8fd2, C_NEG = 0xd0505a, C_ZERO = 0xffe066,
    C_BLOCK_EMPTY = 0x5a2a33, C_BLOCK_FULL = 0x4f9d69, C_BLOCK_PARTIAL = 0xd9a441,
    C_SPAN = 0x4fb3bf, C_ROW = 0x39404e,
    C_EXTRA = 0xff4fd8, C_MISSING = 0x00e5ff, C_EXHIBIT = 0xe0565b;

static const uint32_t edge_colours[3] = { 0xf5a623, 0x4fc3f7, 0xc792ea };   /* AB, BC, CA */
static const uint32_t vertex_colours[3] = { 0xff6b6b, 0x6bdc7a, 0x6b9dff };  /* A, B, C */
static const char *const edge_names[3] = { "F_ab", "F_bc", "F_ca" };
static const char *const vertex_names[3] = { "A", "B", "C" };

static void set_rgb(cairo_t *cr, uint32_t h) { struct rgb c = HEX(h); cairo_set_source_rgb(cr, c.r, c.g, c.b); }
static void set_rgba(cairo_t *cr, uint32_t h, double a) { struct rgb c = HEX(h); cairo_set_source_rgba(cr, c.r, c.g, c.b, a); }

static uint32_t mix(uint32_t a, uint32_t b, double t)   /* a*(1-t) + b*t */
{
    uint32_t out = 0;
    for (int sh = 0; sh <= 16; sh += 8) {
        double v = (a >> sh & 255) * (1 - t) + (b >> sh & 255) * t;
        out |= (uint32_t)(v + 0.5) << sh;
    }
    return out;
}

static uint32_t from_rgb(double r, double g, double b)
{
    return pack_rgb(r, g, b) & 0xffffff;
}

static double luma(uint32_t c)
{
    return (0.299 * (c >> 16 & 255) + 0.587 * (c >> 8 & 255) + 0.114 * (c & 255)) / 255;
}

/* --- text ------------------------------------------------------------------------ */

struct painter {
    cairo_t *cr;
    struct explorer *ex;
    struct explorer_layout L;
    PangoLayout *layout;
    double s;
};

/* Draw text (Pango markup when markup) at (x, y) top-left, at most `width`
 * wide (0: no limit); returns its height. */
static double text(struct painter *p, double x, double y, double width, const char *str,
                   double size, uint32_t colour, bool markup)
{
    PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono");
    pango_font_description_set_absolute_size(d, size * p->s * PANGO_SCALE);
    pango_layout_set_font_description(p->layout, d);
    pango_font_description_free(d);
    pango_layout_set_width(p->layout, width > 0 ? (int)(width * PANGO_SCALE) : -1);
    pango_layout_set_wrap(p->layout, PANGO_WRAP_WORD_CHAR);
    if (markup)
        pango_layout_set_markup(p->layout, str, -1);
    else {
        pango_layout_set_attributes(p->layout, NULL);
        pango_layout_set_text(p->layout, str, -1);
    }
    set_rgb(p->cr, colour);
    cairo_move_to(p->cr, x, y);
    pango_cairo_show_layout(p->cr, p->layout);
    /* forget the current point, or the next cairo_arc would start with a
     * line from here (a stray line from a label to a vertex handle) */
    cairo_new_path(p->cr);
    int w, h;
    pango_layout_get_size(p->layout, &w, &h);
    return (double)h / PANGO_SCALE;
}

static double text_width(struct painter *p, const char *str, double size)
{
    PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono");
    pango_font_description_set_absolute_size(d, size * p->s * PANGO_SCALE);
    pango_layout_set_font_description(p->layout, d);
    pango_font_description_free(d);
    pango_layout_set_width(p->layout, -1);
    pango_layout_set_attributes(p->layout, NULL);
    pango_layout_set_text(p->layout, str, -1);
    int w, h;
    pango_layout_get_size(p->layout, &w, &h);
    return (double)w / PANGO_SCALE;
}

/* Numbers in cells: glyphs collected over the frame, shown in two batches
 * (dark and light ink). */
struct glyph_batch {
    cairo_glyph_t *g;
    int n, cap;
};

static void batch_add(cairo_t *cr, struct glyph_batch *b, double cx, double cy, const char *str,
                      double advance)
{
    int len = (int)strlen(str);
    if (b->n + len > b->cap) {
        int cap = b->cap ? b->cap * 2 : 4096;
        while (cap < b->n + len)
            cap *= 2;
        cairo_glyph_t *g = realloc(b->g, (size_t)cap * sizeof *g);
        if (!g)
            return;
        b->g = g;
        b->cap = cap;
    }
    cairo_glyph_t *glyphs = NULL;
    int n = 0;
    double x = cx - advance * len / 2;
    cairo_scaled_font_t *sf = cairo_get_scaled_font(cr);
    if (cairo_scaled_font_text_to_glyphs(sf, x, cy, str, len, &glyphs, &n, NULL, NULL, NULL)
        == CAIRO_STATUS_SUCCESS) {
        for (int i = 0; i < n && b->n < b->cap; i++)
            b->g[b->n++] = glyphs[i];
    }
    cairo_glyph_free(glyphs);
}

/* --- cells ------------------------------------------------------------------------ */

static const struct cell *cur_cell(const struct explorer *ex, int x, int y)
{
    return ex->cur >= 0 ? explorer_cell(ex, x, y) : NULL;
}

static bool in_box(const struct explorer *ex, int x, int y)
{
    return ex->cur >= 0 && !ex->tri.empty && x >= ex->tri.minx && x <= ex->tri.maxx
        && y >= ex->tri.miny && y <= ex->tri.maxy;
}

static void depth_range(const struct explorer *ex, double *zmin, double *zmax)
{
    *zmin = INFINITY, *zmax = -INFINITY;
    int n = ex->scene.ntris < 4096 ? ex->scene.ntris : 4096;   /* enough for a scale */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            *zmin = fmin(*zmin, ex->scene.tris[i].v[k].z);
            *zmax = fmax(*zmax, ex->scene.tris[i].v[k].z);
        }
    if (!(*zmax > *zmin))
        *zmax = *zmin + 1;
}

/* Colour of pixel (x, y) in the current view. */
static uint32_t cell_colour(const struct explorer *ex, int x, int y, double zmin, double zmax)
{
    size_t i = (size_t)y * (size_t)ex->scene.w + (size_t)x;
    uint32_t col = ex->fb.color[i] & 0xffffff;
    uint32_t dim = mix(col, C_CANVAS, 0.72);
    const struct cell *c = cur_cell(ex, x, y);
    int f = c ? c->flags : 0;
    switch (ex->view) {
    case VIEW_COLOR:
        return col;
    case VIEW_COVERAGE:
        if (f & CELL_INSIDE)
            return C_COVERED;
        if (f & CELL_TESTED)
            return C_OUTSIDE;
        if (in_box(ex, x, y))
            return C_UNTESTED;
        return ex->fb.count[i] == 0 ? C_EMPTY_PX : ex->fb.count[i] == 1 ? C_EARLIER1 : C_EARLIER2;
    case VIEW_EDGES:
        if (!(f & CELL_TESTED))
            return dim;
        if (ex->edge >= 0) {
            int64_t F = c->e[ex->edge];
            if (F == 0)
                return C_ZERO;
            double t = sqrt(fmin(1.0, fabs((double)F) / (double)(ex->tri.area2 ? ex->tri.area2 : 1)));
            return mix(C_CANVAS, F > 0 ? C_POS : C_NEG, 0.25 + 0.75 * t);
        } else {
            int fails = 0;
            for (int k = 0; k < 3; k++)
                fails += !edge_inside(&ex->tri, k, c->e[k]);
            return (f & CELL_INSIDE) ? C_COVERED : fails == 1 ? 0xc0605f : 0x7a3440;
        }
    case VIEW_BARY:
        if (!(f & CELL_TESTED))
            return dim;
        {
            uint32_t b = from_rgb(c->bary[0], c->bary[1], c->bary[2]);
            return (f & CELL_INSIDE) ? b : mix(b, C_CANVAS, 0.65);
        }
    case VIEW_DEPTH: {
        float z = ex->fb.depth[i];
        if (!isfinite(z))
            return C_EMPTY_PX;
        double t = 1 - (z - zmin) / (zmax - zmin);
        t = 0.2 + 0.8 * fmin(fmax(t, 0), 1);
        return from_rgb(t, t, t * 0.95 + 0.05);
    }
    case VIEW_BLOCKS:
        if (f & CELL_BLOCK) {
            if (c->klass == BLOCK_FULL)
                return C_BLOCK_FULL;
            if (c->klass == BLOCK_PARTIAL)
                return (f & CELL_INSIDE) ? 0xf0c674 : (f & CELL_TESTED) ? 0x8a6d2c : C_BLOCK_PARTIAL;
            return C_BLOCK_EMPTY;
        }
        return dim;
    case VIEW_SPANS:
        if (f & CELL_SPAN)
            return C_SPAN;
        if (f & CELL_ROW)
            return C_ROW;
        return dim;
    default: {
        const struct lesson_view *v = &ex->lesson->views[ex->view - VIEW_BUILTIN_COUNT];
        if (!c || !(f & (CELL_TESTED | CELL_WRITTEN)))
            return dim;
        struct trace_event test = { .kind = TRACE_PIXEL_TEST, .x = x, .y = y,
                                    .flags = (f & CELL_INSIDE) ? TRACE_INSIDE : 0 };
        memcpy(test.e, c->e, sizeof test.e);
        memcpy(test.bary, c->bary, sizeof test.bary);
        memcpy(test.aux, c->aux, sizeof test.aux);
        struct trace_event write = { .kind = TRACE_PIXEL_WRITE, .x = x, .y = y, .z = c->z,
                                     .rgba = c->rgba,
                                     .flags = (f & CELL_DEPTH_PASS) ? TRACE_DEPTH_PASS : 0 };
        double rgb[3];
        if (!v->cell(&ex->tri, (f & CELL_TESTED) ? &test : NULL, (f & CELL_WRITTEN) ? &write : NULL, rgb))
            return dim;
        return from_rgb(rgb[0], rgb[1], rgb[2]);
    }
    }
}

static void format_edge(char *buf, size_t n, int64_t F)
{
    double v = (double)F / (SUBPIXEL_ONE * SUBPIXEL_ONE);
    if (F == 0)
        snprintf(buf, n, "0");
    else if (fabs(v) < 10)
        snprintf(buf, n, "%.2f", v);
    else if (fabs(v) < 100)
        snprintf(buf, n, "%.1f", v);
    else
        snprintf(buf, n, "%.0f", v);
}

/* The numbers shown in a cell (up to 3 lines); returns the line count. */
static int cell_numbers(const struct explorer *ex, int x, int y, char out[3][16])
{
    size_t i = (size_t)y * (size_t)ex->scene.w + (size_t)x;
    const struct cell *c = cur_cell(ex, x, y);
    int f = c ? c->flags : 0;
    switch (ex->view) {
    case VIEW_COLOR:
        if (ex->fb.count[i] == 0)
            return 0;
        for (int k = 0; k < 3; k++)
            snprintf(out[k], 16, "%u", (unsigned)(ex->fb.color[i] >> (16 - 8 * k) & 255));
        return 3;
    case VIEW_COVERAGE:
        if (ex->fb.count[i] == 0)
            return 0;
        snprintf(out[0], 16, "%u", (unsigned)ex->fb.count[i]);
        return 1;
    case VIEW_EDGES:
        if (!(f & CELL_TESTED))
            return 0;
        if (ex->edge >= 0) {
            format_edge(out[0], 16, c->e[ex->edge]);
            return 1;
        }
        for (int k = 0; k < 3; k++)
            format_edge(out[k], 16, c->e[k]);
        return 3;
    case VIEW_BARY:
        if (!(f & CELL_TESTED))
            return 0;
        for (int k = 0; k < 3; k++)
            snprintf(out[k], 16, "%.2f", c->bary[k]);
        return 3;
    case VIEW_DEPTH:
        if (!isfinite(ex->fb.depth[i]))
            return 0;
        snprintf(out[0], 16, "%.3g", ex->fb.depth[i]);
        return 1;
    default:
        return 0;
    }
}

/* --- the canvas ------------------------------------------------------------------- */

static void cell_rect(const struct painter *p, double x0, double y0, double x1, double y1)
{
    const struct explorer_layout *L = &p->L;
    cairo_rectangle(p->cr, L->ox + x0 * L->zoom, L->oy + y0 * L->zoom, (x1 - x0) * L->zoom,
                    (y1 - y0) * L->zoom);
}

static void paint_cells(struct painter *p, int x0, int y0, int x1, int y1)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double zmin, zmax;
    depth_range(ex, &zmin, &zmax);
    int w = x1 - x0, h = y1 - y0;
    bool raster = cairo_surface_get_type(cairo_get_target(cr)) == CAIRO_SURFACE_TYPE_IMAGE;
    if (raster) {
        /* one image pixel per scene pixel, scaled up without smoothing */
        cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
        uint32_t *px = (uint32_t *)cairo_image_surface_get_data(img);
        int stride = cairo_image_surface_get_stride(img) / 4;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++)
                px[(y - y0) * stride + (x - x0)] = cell_colour(ex, x, y, zmin, zmax);
        cairo_surface_mark_dirty(img);
        cairo_save(cr);
        cairo_translate(cr, L->ox + x0 * L->zoom, L->oy + y0 * L->zoom);
        cairo_scale(cr, L->zoom, L->zoom);
        cairo_set_source_surface(cr, img, 0, 0);
        cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
        cairo_rectangle(cr, 0, 0, w, h);
        cairo_fill(cr);
        cairo_restore(cr);
        cairo_surface_destroy(img);
        return;
    }
    /* vector surfaces: runs of one colour as rectangles */
    for (int y = y0; y < y1; y++) {
        int x = x0;
        while (x < x1) {
            uint32_t c = cell_colour(ex, x, y, zmin, zmax);
            int e = x + 1;
            while (e < x1 && cell_colour(ex, e, y, zmin, zmax) == c)
                e++;
            set_rgb(cr, c);
            cell_rect(p, x, y, e, y + 1);
            cairo_fill(cr);
            x = e;
        }
    }
}

/* The font size of the numbers in cells, or 0 when they are not shown:
 * the widest label is about 5 characters of 0.6 em. */
static double numbers_size(const struct painter *p)
{
    const struct explorer *ex = p->ex;
    if (ex->numbers == NUMBERS_OFF)
        return 0;
    int lines = ex->view == VIEW_COLOR || ex->view == VIEW_BARY || (ex->view == VIEW_EDGES && ex->edge < 0) ? 3 : 1;
    double size = fmin(fmin(p->L.zoom * 0.86 / (lines * 1.2), p->L.zoom * 0.86 / (5.2 * 0.602)), 13 * p->s);
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
    set_rgba(cr, C_GRID, 0.45);
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
        set_rgba(cr, 0xffffff, 0.55);
        bool numbers = numbers_size(p) > 0;
        char out[3][16];
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                if (numbers && cell_numbers(p->ex, x, y, out) > 0)
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
    if (!ex->diff || !ex->lesson->variants[ex->variant].exhibit)
        return;
    cairo_t *cr = p->cr;
    const struct explorer_layout *L = &p->L;
    double lw = fmax(2 * p->s, L->zoom * 0.12);
    for (int kind = EXHIBIT_EXTRA; kind <= EXHIBIT_MISSING; kind++) {
        set_rgb(cr, kind == EXHIBIT_EXTRA ? C_EXTRA : C_MISSING);
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
        set_rgba(cr, C_BOX, 0.9);
        cell_rect(p, t->minx, t->miny, t->maxx + 1, t->maxy + 1);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
    }
    /* the edges, exactly where the snapped vertices are */
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int k = 0; k < 3; k++) {
        int b = (k + 1) % 3;
        cairo_set_line_width(cr, 4 * p->s);
        set_rgba(cr, 0x000000, 0.55);
        cairo_move_to(cr, vx[k], vy[k]);
        cairo_line_to(cr, vx[b], vy[b]);
        cairo_stroke(cr);
        cairo_set_line_width(cr, (ex->view == VIEW_EDGES && ex->edge == k ? 3 : 2) * p->s);
        set_rgb(cr, edge_colours[k]);
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
            double mx = (vx[k] + vx[b]) / 2, my = (vy[k] + vy[b]) / 2;
            double dx = mx - gx, dy = my - gy, d = hypot(dx, dy);
            if (d > 0)
                dx /= d, dy /= d;
            double tw = text_width(p, buf, 12);
            double lx = mx + dx * 22 * p->s - tw / 2, ly = my + dy * 18 * p->s - 8 * p->s;
            set_rgba(cr, 0x000000, 0.7);
            cairo_rectangle(cr, lx - 4 * p->s, ly - 1 * p->s, tw + 8 * p->s, 18 * p->s);
            cairo_fill(cr);
            text(p, lx, ly, 0, buf, 12, edge_colours[k], false);
        }
    }
    /* vertex handles */
    for (int k = 0; k < 3; k++) {
        double r = (ex->hover_vertex == k ? 8 : 6) * p->s;
        cairo_arc(cr, vx[k], vy[k], r, 0, 2 * G_PI);
        set_rgb(cr, vertex_colours[k]);
        cairo_fill_preserve(cr);
        cairo_set_line_width(cr, 1.5 * p->s);
        set_rgb(cr, 0x101014);
        cairo_stroke(cr);
        double dx = vx[k] - gx, dy = vy[k] - gy, d = hypot(dx, dy);
        if (d > 0)
            dx /= d, dy /= d;
        double lx = vx[k] + dx * 16 * p->s - 5 * p->s, ly = vy[k] + dy * 16 * p->s - 10 * p->s;
        set_rgba(cr, 0x000000, 0.6);
        cairo_arc(cr, lx + 5 * p->s, ly + 10 * p->s, 10 * p->s, 0, 2 * G_PI);
        cairo_fill(cr);
        text(p, lx, ly, 0, vertex_names[k], 15, vertex_colours[k], false);
    }
    cairo_restore(cr);
}

static void outline(struct painter *p, double x0, double y0, double x1, double y1, uint32_t colour,
                    double width)
{
    cairo_t *cr = p->cr;
    cairo_set_line_width(cr, width);
    set_rgba(cr, 0x000000, 0.6);
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
            outline(p, ev->x, ev->y, ev->x + 1, ev->y + 1, C_ACCENT, w);
            break;
        case TRACE_ROW:
        case TRACE_SPAN:
            outline(p, ev->x, ev->y, ev->x1 + 1, ev->y + 1, C_ACCENT, w);
            break;
        case TRACE_BLOCK:
            outline(p, ev->x, ev->y, ev->x1 + 1, ev->y1 + 1, C_ACCENT, w);
            break;
        case TRACE_SETUP:
            if (!ex->tri.empty)
                outline(p, ex->tri.minx, ex->tri.miny, ex->tri.maxx + 1, ex->tri.maxy + 1,
                        C_ACCENT, w);
            break;
        case TRACE_KIND_COUNT:
            break;
        }
    }
    if (ex->pinned)
        outline(p, ex->pin_x, ex->pin_y, ex->pin_x + 1, ex->pin_y + 1, C_PIN, w);
}

/* --- the lesson's own drawings ------------------------------------------------ */

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
    cairo_set_source_rgb(cr, (rgb >> 16 & 255) / 255.0, (rgb >> 8 & 255) / 255.0,
                         (rgb & 255) / 255.0);
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
    set_rgba(p->cr, 0x000000, 0.7);
    cairo_rectangle(p->cr, sx - 2 * p->s, sy, tw + 4 * p->s, th);
    cairo_fill(p->cr);
    text(p, sx, sy, 0, str, size, rgb, false);
    cairo_restore(p->cr);
}

static void paint_overlay(struct painter *p)
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
        c.edge_rgb[k] = edge_colours[k];
    cairo_save(p->cr);
    cairo_translate(p->cr, L->ox, L->oy);
    cairo_scale(p->cr, L->zoom, L->zoom);
    cairo_new_path(p->cr);
    ex->lesson->overlay(&c, &ex->tri, &ex->params, ex->has_last ? &ex->last : NULL);
    cairo_restore(p->cr);
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
    double zmin, zmax;
    depth_range(ex, &zmin, &zmax);
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            char out[3][16];
            int n = cell_numbers(ex, x, y, out);
            if (n == 0)
                continue;
            bool light = luma(cell_colour(ex, x, y, zmin, zmax)) < 0.5;
            double cx = L->ox + (x + 0.5) * L->zoom, cy = L->oy + (y + 0.5) * L->zoom;
            double lh = size * 1.2;
            for (int k = 0; k < n; k++) {
                double by = cy - lh * n / 2 + lh * k + size * 0.95;
                batch_add(cr, &ink[light], cx, by, out[k], advance);
            }
        }
    for (int k = 0; k < 2; k++) {
        if (ink[k].n) {
            set_rgba(cr, k ? 0xffffff : 0x000000, 0.92);
            cairo_show_glyphs(cr, ink[k].g, ink[k].n);
        }
        free(ink[k].g);
    }
    cairo_restore(cr);
}

static void paint_canvas(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    cairo_save(cr);
    cairo_rectangle(cr, L->cx, L->cy, L->cw, L->ch);
    cairo_clip(cr);
    set_rgb(cr, C_CANVAS);
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
        paint_numbers(p, x0, y0, x1, y1);
    }
    /* the target's border */
    cairo_set_line_width(cr, 1);
    set_rgba(cr, 0xffffff, 0.25);
    cell_rect(p, 0, 0, ex->scene.w, ex->scene.h);
    cairo_stroke(cr);
    paint_current(p);
    paint_triangle(p);
    paint_overlay(p);
    if (ex->message[0]) {
        double h = 24 * p->s;
        double tw = text_width(p, ex->message, 12);
        double mw = fmin(tw + 20 * p->s, L->cw - 24 * p->s);
        set_rgba(cr, 0x000000, 0.75);
        cairo_rectangle(cr, L->cx + 12 * p->s, L->cy + 12 * p->s, mw, h);
        cairo_fill(cr);
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
        text(p, L->cx + 22 * p->s, L->cy + 16 * p->s, mw - 20 * p->s, ex->message, 12, C_ACCENT, false);
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    }
    cairo_restore(cr);
}

/* --- the scrub bar -------------------------------------------------------------- */

static void paint_bar(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    set_rgb(cr, C_PANEL);
    cairo_rectangle(cr, L->cx, L->bar_y, L->cw, L->bar_h);
    cairo_fill(cr);
    set_rgb(cr, C_RULE);
    cairo_rectangle(cr, L->cx, L->bar_y, L->cw, 1);
    cairo_fill(cr);
    double tx = L->cx + 14 * s, tw = L->cw - 28 * s, ty = L->bar_y + 9 * s, th = 6 * s;
    uint64_t total = ex->replay.total;
    double f = total ? (double)ex->step / (double)total : 0;
    set_rgb(cr, 0x3a4150);
    cairo_rectangle(cr, tx, ty, tw, th);
    cairo_fill(cr);
    set_rgb(cr, C_ACCENT);
    cairo_rectangle(cr, tx, ty, tw * f, th);
    cairo_fill(cr);
    if (ex->replay.ntris > 1 && ex->replay.ntris <= 400 && total) {   /* triangle boundaries */
        set_rgba(cr, 0x000000, 0.8);
        for (int i = 1; i < ex->replay.ntris; i++) {
            double x = tx + tw * (double)ex->replay.start[i] / (double)total;
            cairo_rectangle(cr, floor(x), ty, 1, th);
        }
        cairo_fill(cr);
    }
    cairo_arc(cr, tx + tw * f, ty + th / 2, 6 * s, 0, 2 * G_PI);
    set_rgb(cr, C_TEXT);
    cairo_fill(cr);
    char buf[256];
    int n = ex->replay.ntris;
    uint64_t ev = ex->cur >= 0 ? ex->local + 1 : 0;
    uint64_t evn = ex->cur >= 0 ? ex->replay.start[ex->cur + 1] - ex->replay.start[ex->cur] : 0;
    double e = pow(2, ex->speed / 2.0);
    snprintf(buf, sizeof buf, "%s  step %llu / %llu   triangle %d / %d   event %llu / %llu   %s%.4g/s",
             ex->playing ? "\u25b6" : "\u275a\u275a", (unsigned long long)ex->step,
             (unsigned long long)total, ex->cur + 1, n, (unsigned long long)ev,
             (unsigned long long)evn, "speed ", e);
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
    text(p, tx, ty + th + 7 * s, tw, buf, 12, C_TEXT, false);
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
}

/* --- the panel ----------------------------------------------------------------------- */

static const char *const kind_names[TRACE_KIND_COUNT] = {
    "setup", "row", "span", "block", "pixel test", "pixel write",
};
static const char *const class_names[BLOCK_CLASS_COUNT] = { "empty", "full", "partial" };

static double heading(struct painter *p, double x, double y, double w, const char *title)
{
    set_rgb(p->cr, C_RULE);
    cairo_rectangle(p->cr, x, y + 9 * p->s, w, 1);
    cairo_fill(p->cr);
    double tw = text_width(p, title, 11);
    set_rgb(p->cr, C_PANEL);
    cairo_rectangle(p->cr, x, y, tw + 8 * p->s, 18 * p->s);
    cairo_fill(p->cr);
    text(p, x, y + 1 * p->s, 0, title, 11, C_DIM, false);
    return 20 * p->s;
}

static double swatch(struct painter *p, double x, double y, uint32_t colour, const char *label)
{
    set_rgb(p->cr, colour);
    cairo_rectangle(p->cr, x, y + 3 * p->s, 12 * p->s, 12 * p->s);
    cairo_fill(p->cr);
    set_rgba(p->cr, 0xffffff, 0.3);
    cairo_set_line_width(p->cr, 1);
    cairo_rectangle(p->cr, x + 0.5, y + 3 * p->s + 0.5, 12 * p->s - 1, 12 * p->s - 1);
    cairo_stroke(p->cr);
    return text(p, x + 18 * p->s, y, 0, label, 11.5, C_TEXT, false);
}

static double legend(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    double y0 = y, s = p->s;
    struct item { uint32_t c; const char *label; } items[8];
    int n = 0;
    switch (ex->view) {
    case VIEW_COLOR:
        items[n++] = (struct item){ ex->fb.background & 0xffffff, "background (nothing drawn)" };
        break;
    case VIEW_COVERAGE:
        items[n++] = (struct item){ C_COVERED, "covered by this triangle" };
        items[n++] = (struct item){ C_OUTSIDE, "tested, outside" };
        items[n++] = (struct item){ C_UNTESTED, "in the box, not tested yet" };
        items[n++] = (struct item){ C_EARLIER1, "covered once before" };
        items[n++] = (struct item){ C_EARLIER2, "covered twice or more" };
        break;
    case VIEW_EDGES:
        if (ex->edge >= 0) {
            items[n++] = (struct item){ C_POS, "F > 0: inner side" };
            items[n++] = (struct item){ C_NEG, "F < 0: outer side" };
            items[n++] = (struct item){ C_ZERO, "F = 0: centre on the edge" };
        } else {
            items[n++] = (struct item){ C_COVERED, "inside all three (fill rule)" };
            items[n++] = (struct item){ 0xc0605f, "outside one edge" };
            items[n++] = (struct item){ 0x7a3440, "outside two edges" };
        }
        break;
    case VIEW_BARY:
        items[n++] = (struct item){ 0xff0000, "alpha: weight of A (red)" };
        items[n++] = (struct item){ 0x00ff00, "beta: weight of B (green)" };
        items[n++] = (struct item){ 0x0000ff, "gamma: weight of C (blue)" };
        break;
    case VIEW_DEPTH:
        items[n++] = (struct item){ 0xffffff, "near (small z)" };
        items[n++] = (struct item){ 0x333333, "far" };
        break;
    case VIEW_BLOCKS:
        items[n++] = (struct item){ C_BLOCK_EMPTY, "empty block: skipped" };
        items[n++] = (struct item){ C_BLOCK_FULL, "full block: filled, no tests" };
        items[n++] = (struct item){ C_BLOCK_PARTIAL, "partial block: tested per pixel" };
        break;
    case VIEW_SPANS:
        items[n++] = (struct item){ C_SPAN, "span: filled from left to right edge" };
        items[n++] = (struct item){ C_ROW, "row walked" };
        break;
    default:
        break;
    }
    if (ex->view >= VIEW_BUILTIN_COUNT)
        y += text(p, x, y, w, ex->lesson->views[ex->view - VIEW_BUILTIN_COUNT].legend, 11.5, C_TEXT, false);
    for (int i = 0; i < n; i++)
        y += swatch(p, x, y, items[i].c, items[i].label) + 1 * s;
    if ((ex->view == VIEW_BLOCKS && ex->replay.sums[ex->replay.ntris].blocks[0]
                                     + ex->replay.sums[ex->replay.ntris].blocks[1]
                                     + ex->replay.sums[ex->replay.ntris].blocks[2] == 0)
        || (ex->view == VIEW_SPANS && ex->replay.sums[ex->replay.ntris].spans == 0))
        y += text(p, x, y, w, "(this lesson narrates none: they come in later lessons)", 11, C_DIM, false);
    if (ex->lesson->variants[ex->variant].exhibit) {
        y += swatch(p, x, y, C_EXTRA, "extra: more than the exact rule") + s;
        y += swatch(p, x, y, C_MISSING, "missing: a crack") + s;
    }
    y += swatch(p, x, y, C_ACCENT, "the current step") + s;
    return y - y0;
}

static double pseudocode(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    double y0 = y, lh = 17 * p->s;
    int lit = ex->has_last ? ex->last.line : -1;
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
    for (int i = 0; ex->lesson->pseudocode && ex->lesson->pseudocode[i]; i++) {
        if (i == lit) {
            set_rgb(p->cr, C_HILITE);
            cairo_rectangle(p->cr, x - 4 * p->s, y, w + 8 * p->s, lh);
            cairo_fill(p->cr);
            set_rgb(p->cr, C_ACCENT);
            cairo_rectangle(p->cr, x - 4 * p->s, y, 3 * p->s, lh);
            cairo_fill(p->cr);
        }
        char buf[160];
        snprintf(buf, sizeof buf, "%2d %s", i + 1, ex->lesson->pseudocode[i]);
        text(p, x, y + 1 * p->s, w, buf, 11.5, i == lit ? C_ACCENT : C_TEXT, false);
        y += lh;
    }
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    return y - y0;
}

static size_t cat(char *buf, size_t n, size_t at, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
#include <stdarg.h>
static size_t cat(char *buf, size_t n, size_t at, const char *fmt, ...)
{
    if (at >= n)
        return at;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(buf + at, n - at, fmt, ap);
    va_end(ap);
    return k < 0 ? at : at + (size_t)k;
}

static size_t watch_values(const struct explorer *ex, char *buf, size_t n, size_t at,
                           const struct trace_event *ev)
{
    switch ((enum trace_kind)ev->kind) {
    case TRACE_SETUP:
        at = cat(buf, n, at, "box x %d..%d, y %d..%d\n", ev->x, ev->x1, ev->y, ev->y1);
        at = cat(buf, n, at, "area2 = %lld (%.4g px\u00b2)%s\n", (long long)ex->tri.area2,
                 (double)ex->tri.area2 / 65536, ex->tri.swapped ? "  B, C swapped" : "");
        break;
    case TRACE_ROW:
        at = cat(buf, n, at, "row y = %d, x %d..%d\n", ev->y, ev->x, ev->x1);
        break;
    case TRACE_SPAN:
        at = cat(buf, n, at, "span y = %d, x %d..%d\n", ev->y, ev->x, ev->x1);
        break;
    case TRACE_BLOCK:
        at = cat(buf, n, at, "block (%d, %d)..(%d, %d): %s\n", ev->x, ev->y, ev->x1, ev->y1,
                 ev->klass < BLOCK_CLASS_COUNT ? class_names[ev->klass] : "?");
        at = cat(buf, n, at, "corner masks %x %x %x\n", ev->mask[0], ev->mask[1], ev->mask[2]);
        break;
    case TRACE_PIXEL_TEST:
        at = cat(buf, n, at, "pixel (%d, %d): %s\n", ev->x, ev->y,
                 (ev->flags & TRACE_INSIDE) ? "inside" : "outside");
        for (int k = 0; k < 3; k++) {
            char v[24];
            format_edge(v, sizeof v, ev->e[k]);
            at = cat(buf, n, at, "%s = %lld (%s px\u00b2)\n", edge_names[k], (long long)ev->e[k], v);
        }
        at = cat(buf, n, at, "alpha %.4f beta %.4f gamma %.4f\n", ev->bary[0], ev->bary[1], ev->bary[2]);
        break;
    case TRACE_PIXEL_WRITE:
        at = cat(buf, n, at, "write (%d, %d): z %.5g, depth %s\n", ev->x, ev->y, ev->z,
                 (ev->flags & TRACE_DEPTH_PASS) ? "pass" : "fail");
        at = cat(buf, n, at, "colour #%06x\n", (unsigned)(ev->rgba & 0xffffff));
        break;
    case TRACE_KIND_COUNT:
        break;
    }
    if (ex->lesson->aux_names && (ev->kind == TRACE_PIXEL_TEST || ev->kind == TRACE_ROW
                                  || ev->kind == TRACE_SPAN || ev->kind == TRACE_BLOCK)) {
        for (int k = 0; k < 6 && ex->lesson->aux_names[k]; k++)
            at = cat(buf, n, at, "%s%s %.6g", k ? ", " : "", ex->lesson->aux_names[k], ev->aux[k]);
        if (ex->lesson->aux_names[0])
            at = cat(buf, n, at, "\n");
    }
    return at;
}

static double watch(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    char buf[2048];
    size_t at = 0, n = sizeof buf;
    buf[0] = '\0';
    if (!ex->has_last) {
        at = cat(buf, n, at, "nothing has happened yet: step forward (Right)\n");
    } else {
        at = cat(buf, n, at, "%s, line %d, triangle %d\n",
                 ex->last.kind < TRACE_KIND_COUNT ? kind_names[ex->last.kind] : "?",
                 ex->last.line + 1, ex->cur + 1);
        at = watch_values(ex, buf, n, at, &ex->last);
    }
    if (ex->pinned) {
        int px = ex->pin_x, py = ex->pin_y;
        size_t i = (size_t)py * (size_t)ex->scene.w + (size_t)px;
        at = cat(buf, n, at, "\npinned (%d, %d): colour #%06x, covered %u\u00d7", px, py,
                 (unsigned)(ex->fb.color[i] & 0xffffff), (unsigned)ex->fb.count[i]);
        if (isfinite(ex->fb.depth[i]))
            at = cat(buf, n, at, ", z %.5g", ex->fb.depth[i]);
        at = cat(buf, n, at, "\n");
        const struct cell *c = cur_cell(ex, px, py);
        if (c && (c->flags & CELL_TESTED)) {
            for (int k = 0; k < 3; k++) {
                char v[24];
                format_edge(v, sizeof v, c->e[k]);
                at = cat(buf, n, at, "%s = %lld (%s)%s", edge_names[k], (long long)c->e[k], v,
                         k < 2 ? ", " : "\n");
            }
            at = cat(buf, n, at, "alpha %.4f beta %.4f gamma %.4f: %s\n", c->bary[0], c->bary[1],
                     c->bary[2], (c->flags & CELL_INSIDE) ? "inside" : "outside");
        } else if (!c || !(c->flags & CELL_INSIDE)) {
            at = cat(buf, n, at, "not reached by this triangle yet\n");
        }
    }
    while (at > 0 && at <= n && buf[at - 1] == '\n')
        buf[--at] = '\0';
    return text(p, x, y, w, buf, 11.5, C_TEXT, false);
}

/* The lesson beside earlier ones on the triangles finished so far: pixels
 * tested, and arithmetic per tested pixel. */
static double compare_lines(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    int done = ex->cur < 0 ? 0 : ex->cur;
    if (ex->cur >= 0 && ex->local + 1 >= ex->replay.start[ex->cur + 1] - ex->replay.start[ex->cur])
        done = ex->cur + 1;     /* the current triangle has finished too */
    char buf[1024];
    size_t at = 0, n = sizeof buf;
    at = cat(buf, n, at, "same %d triangle%s finished:\n", done, done == 1 ? "" : "s");
    at = cat(buf, n, at, "%-18s %9s %7s %7s\n", "", "tested", "mul/px", "add/px");
    for (int i = -1; i < ex->ncompare; i++) {
        const struct replay *r = i < 0 ? &ex->replay : &ex->compare_replay[i];
        const struct trace_counters *c = &r->sums[done];
        double px = c->tested ? (double)c->tested : 1;
        at = cat(buf, n, at, "%-18s %9llu %7.1f %7.1f\n", i < 0 ? "this lesson" : ex->compare[i]->id,
                 (unsigned long long)c->tested, (double)c->mul / px, (double)c->add / px);
    }
    while (at > 0 && at <= n && buf[at - 1] == '\n')
        buf[--at] = '\0';
    return text(p, x, y, w, buf, 11.5, C_DIM, false);
}

static double counters(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    struct trace_counters c = { 0 };
    int before = ex->cur >= 0 ? ex->cur : 0;
    const struct trace_counters *a = &ex->replay.sums[before];
    c.tested = a->tested + ex->tri_c.tested;
    c.covered = a->covered + ex->tri_c.covered;
    c.written = a->written + ex->tri_c.written;
    for (int k = 0; k < BLOCK_CLASS_COUNT; k++)
        c.blocks[k] = a->blocks[k] + ex->tri_c.blocks[k];
    c.rows = a->rows + ex->tri_c.rows;
    c.spans = a->spans + ex->tri_c.spans;
    /* the last event carries the arithmetic done before it in its triangle */
    c.mul = a->mul + (ex->has_last ? ex->last.mul : 0);
    c.add = a->add + (ex->has_last ? ex->last.add : 0);
    char buf[1024];
    size_t at = 0, n = sizeof buf;
    at = cat(buf, n, at, "pixels tested  %10llu   covered %10llu\n", (unsigned long long)c.tested,
             (unsigned long long)c.covered);
    at = cat(buf, n, at, "pixels written %10llu   rows    %10llu\n", (unsigned long long)c.written,
             (unsigned long long)c.rows);
    const struct trace_counters *all = &ex->replay.sums[ex->replay.ntris];
    if (all->blocks[0] + all->blocks[1] + all->blocks[2])
        at = cat(buf, n, at, "blocks empty %llu  full %llu  partial %llu\n",
                 (unsigned long long)c.blocks[0], (unsigned long long)c.blocks[1],
                 (unsigned long long)c.blocks[2]);
    if (all->spans)
        at = cat(buf, n, at, "spans %llu\n", (unsigned long long)c.spans);
    at = cat(buf, n, at, "multiplications %9llu   adds %10llu", (unsigned long long)c.mul,
             (unsigned long long)c.add);
    double h = text(p, x, y, w, buf, 11.5, C_TEXT, false);
    if (ex->ncompare > 0)
        h += compare_lines(p, x, y + h + 4 * p->s, w) + 4 * p->s;
    if (ex->lesson->variants[ex->variant].exhibit) {
        char e[256];
        snprintf(e, sizeof e, "vs %s, %d triangle%s finished:\nextra %llu   missing (cracks) %llu",
                 ex->lesson->variants[0].name, ex->diff_done, ex->diff_done == 1 ? "" : "s",
                 (unsigned long long)ex->extra, (unsigned long long)ex->missing);
        h += 4 * p->s;
        h += text(p, x, y + h, w, e, 11.5, ex->extra + ex->missing ? C_EXTRA : C_COVERED, false);
    }
    return h;
}

static void paint_panel(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    set_rgb(cr, C_PANEL);
    cairo_rectangle(cr, L->px, 0, L->pw, L->h);
    cairo_fill(cr);
    set_rgb(cr, C_RULE);
    cairo_rectangle(cr, L->px, 0, 1, L->h);
    cairo_fill(cr);
    cairo_save(cr);
    cairo_rectangle(cr, L->px, 0, L->pw, L->h);
    cairo_clip(cr);
    double x = L->px + 16 * s, w = L->pw - 32 * s, y = 12 * s;
    y += text(p, x, y, w, ex->lesson->id, 15, C_ACCENT, false);
    y += text(p, x, y, w, ex->lesson->title, 11.5, C_DIM, false) + 6 * s;

    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    char buf[512];
    if (v->exhibit) {
        double bw = text_width(p, "EXHIBIT", 11) + 10 * s;
        set_rgb(cr, C_EXHIBIT);
        cairo_rectangle(cr, x, y + 1 * s, bw, 17 * s);
        cairo_fill(cr);
        text(p, x + 5 * s, y + 2 * s, 0, "EXHIBIT", 11, 0xffffff, false);
        snprintf(buf, sizeof buf, "%s: %s", v->name, v->what);
        y += text(p, x + bw + 8 * s, y + 1 * s, w - bw - 8 * s, buf, 11.5, C_TEXT, false) + 4 * s;
    } else {
        snprintf(buf, sizeof buf, "variant %s%s", v->name, ex->variant ? " (faster twin)" : "");
        y += text(p, x, y, w, buf, 11.5, C_TEXT, false);
    }
    snprintf(buf, sizeof buf, "scene %s, %dx%d, %d triangle%s", ex->scene_name, ex->scene.w,
             ex->scene.h, ex->scene.ntris, ex->scene.ntris == 1 ? "" : "s");
    y += text(p, x, y, w, buf, 11.5, C_TEXT, false);
    unsigned prm = ex->lesson->params;
    if (prm) {
        size_t at = 0;
        buf[0] = '\0';
        if (prm & LESSON_PARAM_SUBPIXEL)
            at = cat(buf, sizeof buf, at, "sub-pixel bits %d  ", ex->params.subpixel_bits);
        if (prm & LESSON_PARAM_BLOCK)
            at = cat(buf, sizeof buf, at, "block %d  ", ex->params.block_size ? ex->params.block_size : 8);
        if (prm & LESSON_PARAM_AFFINE)
            at = cat(buf, sizeof buf, at, "%s", ex->params.affine ? "affine" : "perspective");
        y += text(p, x, y, w, buf, 11.5, C_TEXT, false);
    }
    y += 8 * s;

    snprintf(buf, sizeof buf, "VIEW: %s", explorer_view_name(ex, ex->view));
    y += heading(p, x, y, w, buf);
    y += legend(p, x, y, w) + 8 * s;
    y += heading(p, x, y, w, "PSEUDO-CODE");
    y += pseudocode(p, x, y, w) + 8 * s;
    y += heading(p, x, y, w, "WATCH");
    y += watch(p, x, y, w) + 8 * s;
    if (ex->lesson->constants && ex->scene.ntris > 0 && !ex->tri.empty) {
        buf[0] = '\0';
        ex->lesson->constants(&ex->tri, &ex->params, buf, sizeof buf);
        for (size_t e = strlen(buf); e > 0 && buf[e - 1] == '\n'; e--)
            buf[e - 1] = '\0';
        y += heading(p, x, y, w, "TRIANGLE");
        y += text(p, x, y, w, buf, 11.5, C_TEXT, false) + 8 * s;
    }
    y += heading(p, x, y, w, "SO FAR");
    y += counters(p, x, y, w) + 8 * s;
    (void)y;
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
    text(p, x, L->h - 24 * s, w, "H help  V view  \u2190\u2192 step  E export  Q quit", 11, C_DIM, false);
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    cairo_restore(cr);
}

/* --- help ------------------------------------------------------------------------------ */

static void paint_help(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    char keys[2048];
    size_t at = 0, n = sizeof keys;
    at = cat(keys, n, at,
        "Right / Left         one event forward / back\n"
        "Shift+Right / Left   to the next / previous row or block\n"
        "Ctrl+Right / Left    to the next / previous triangle\n"
        "Home / End           to the start / the end\n"
        "PgDn / PgUp          one event (presentation clickers)\n"
        "Space                play / pause\n"
        "+ / -                play faster / slower\n"
        "V / Shift+V          next / previous view\n"
        "0 1 2 3              edges view: all three, F_ab, F_bc, F_ca\n"
        "N                    numbers in cells: auto, always, off\n");
    bool exhibits = false, twins = false;
    for (int i = 1; i < ex->lesson->nvariants; i++)
        exhibits |= ex->lesson->variants[i].exhibit, twins |= !ex->lesson->variants[i].exhibit;
    if (exhibits)
        at = cat(keys, n, at, "X                    next exhibit (against the exact rule)\n");
    if (twins)
        at = cat(keys, n, at, "T                    next faster twin\n");
    if (ex->lesson->params & LESSON_PARAM_SUBPIXEL)
        at = cat(keys, n, at, "[ / ]                fewer / more sub-pixel bits (0..8)\n");
    if (ex->lesson->params & LESSON_PARAM_BLOCK)
        at = cat(keys, n, at, "B                    block size 4, 8, 16\n");
    if (ex->lesson->params & LESSON_PARAM_AFFINE)
        at = cat(keys, n, at, "P                    affine / perspective-correct\n");
    at = cat(keys, n, at,
        "E                    export the view (PNG and SVG)\n"
        "F                    fit the scene to the window\n"
        "H / F1               this help\n"
        "Q / Esc              quit\n"
        "\n"
        "mouse: drag a vertex A, B, C (snaps to 1/256 px)\n"
        "       wheel to zoom, drag the background to pan\n"
        "       click a pixel to pin its values in the watch");
    double tw = fmin(L->w - 40 * s, 600 * s);
    double x = (L->w - tw) / 2, y = 40 * s;
    /* the text first, into a group, so the box can be as tall as it is */
    cairo_push_group(cr);
    double h = text(p, x + 20 * s, y + 16 * s, tw - 40 * s, "Keys", 15, C_ACCENT, false);
    h += text(p, x + 20 * s, y + 24 * s + h, tw - 40 * s, keys, 12, C_TEXT, false);
    cairo_pattern_t *words = cairo_pop_group(cr);
    set_rgba(cr, 0x000000, 0.55);
    cairo_paint(cr);
    set_rgb(cr, C_PANEL);
    cairo_rectangle(cr, x, y, tw, fmin(L->h - 2 * y, h + 44 * s));
    cairo_fill_preserve(cr);
    set_rgb(cr, C_ACCENT);
    cairo_set_line_width(cr, 1.5 * s);
    cairo_stroke(cr);
    cairo_set_source(cr, words);
    cairo_paint(cr);
    cairo_pattern_destroy(words);
}

/* --- the frame --------------------------------------------------------------------- */

void explorer_paint(struct explorer *ex, cairo_t *cr, double w, double h)
{
    mono_face();        /* pins the fonts before Pango starts */
    struct painter p = { .cr = cr, .ex = ex };
    explorer_layout(ex, w, h, &p.L);
    p.s = p.L.s;
    p.layout = pango_cairo_create_layout(cr);
    pango_cairo_context_set_font_options(pango_layout_get_context(p.layout), font_options());
    pango_layout_context_changed(p.layout);
    cairo_save(cr);
    set_rgb(cr, C_BG);
    cairo_paint(cr);
    paint_canvas(&p);
    paint_bar(&p);
    paint_panel(&p);
    if (ex->help)
        paint_help(&p);
    cairo_restore(cr);
    g_object_unref(p.layout);
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
