/* export.c - the explorer's view written to PNG, SVG or PDF (the same
 * painter as the window, onto a file surface), and a target's colours as PNG. */
#include "export.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <math.h>
#include <string.h>

#include "paint.h"
#include "util/file.h"

/* Fixed dates: the same figure gives the same bytes (cairo 1.16 ignores
 * SOURCE_DATE_EPOCH). */
#define FIGURE_DATE "2024-01-01T00:00:00Z"

/* cairo's stream writer: to a FILE. */
static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int len)
{
    return fwrite(data, 1, len, closure) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

struct export_job {
    struct explorer *ex;
    const char *path;
    int w, h;
    enum paper paper;
};

/* Pages in points: A4 (210 x 297 mm) and US Letter (8.5 x 11 in), turned
 * to landscape for a view wider than tall; the view is fitted inside a
 * margin of half an inch, centred. */
static const double paper_size[PAPER_COUNT][2] = { { 0, 0 }, { 595, 842 }, { 612, 792 } };
#define PAPER_MARGIN 36.0
/* The smallest text on paper, in points: 6 pt is the usual floor of a
 * printed figure's labels (journals ask for 6 to 8 pt), and DejaVu Sans
 * Mono's digits are still clear at it. Labels and names are drawn at least
 * that large; a cell too small to hold its numbers at that size shows none
 * on paper. */
#define PAPER_TEXT_MIN_PT 6.0

/* Where the view of w x h goes on the page: its scale and offset. */
static void paper_fit(enum paper paper, int w, int h, double *pw, double *ph, double *s, double *x,
                      double *y)
{
    *pw = paper_size[paper][0], *ph = paper_size[paper][1];
    if (w > h) {
        double t = *pw;
        *pw = *ph, *ph = t;
    }
    *s = fmin((*pw - 2 * PAPER_MARGIN) / w, (*ph - 2 * PAPER_MARGIN) / h);
    *x = (*pw - w * *s) / 2, *y = (*ph - h * *s) / 2;
}

void paper_page_size(enum paper paper, int w, int h, double *pw, double *ph)
{
    double s, x, y;
    paper_fit(paper, w, h, pw, ph, &s, &x, &y);
}

void explorer_paint_page(struct explorer *ex, cairo_t *cr, int w, int h, enum paper paper)
{
    double pw, ph, s, x, y;
    paper_fit(paper, w, h, &pw, &ph, &s, &x, &y);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, s, s);
    cairo_rectangle(cr, 0, 0, w, h);
    cairo_clip(cr);
    ex->text_min = PAPER_TEXT_MIN_PT / s;
    explorer_paint(ex, cr, w, h);
    ex->text_min = 0;
    cairo_restore(cr);
}

static bool write_figure(FILE *out, void *ctx)
{
    struct export_job *job = ctx;
    cairo_surface_t *surface;
    bool png = has_suffix(job->path, ".png");
    if (png) {
        surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, job->w, job->h);
    } else if (has_suffix(job->path, ".svg")) {
        surface = cairo_svg_surface_create_for_stream(to_file, out, job->w, job->h);
    } else {
        double pw = job->w, ph = job->h;
        if (job->paper != PAPER_NONE)
            paper_page_size(job->paper, job->w, job->h, &pw, &ph);
        surface = cairo_pdf_surface_create_for_stream(to_file, out, pw, ph);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, FIGURE_DATE);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_MOD_DATE, FIGURE_DATE);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "tristep");
    }
    cairo_t *cr = cairo_create(surface);
    if (job->paper != PAPER_NONE && !png)
        explorer_paint_page(job->ex, cr, job->w, job->h, job->paper);
    else
        explorer_paint(job->ex, cr, job->w, job->h);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    if (st == CAIRO_STATUS_SUCCESS && png)
        st = cairo_surface_write_to_png_stream(surface, to_file, out);
    cairo_surface_finish(surface);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    return st == CAIRO_STATUS_SUCCESS;
}

bool explorer_export_paper(struct explorer *ex, const char *path, int w, int h, enum paper paper,
                           char *err, size_t errlen)
{
    struct export_job job = { ex, path, w, h, has_suffix(path, ".pdf") ? paper : PAPER_NONE };
    return write_file_atomic(path, write_figure, &job, err, errlen);
}

bool explorer_export(struct explorer *ex, const char *path, int w, int h, char *err, size_t errlen)
{
    return explorer_export_paper(ex, path, w, h, PAPER_NONE, err, errlen);
}

bool write_color_png(FILE *out, const struct target *fb)
{
    /* the colour buffer is already cairo's ARGB32 (opaque, so premultiplied) */
    int stride = cairo_format_stride_for_width(CAIRO_FORMAT_ARGB32, fb->w);
    if (stride != fb->w * 4)
        return false;
    cairo_surface_t *s = cairo_image_surface_create_for_data(
        (unsigned char *)fb->color, CAIRO_FORMAT_ARGB32, fb->w, fb->h, stride);
    cairo_status_t st = cairo_surface_write_to_png_stream(s, to_file, out);
    cairo_surface_destroy(s);
    return st == CAIRO_STATUS_SUCCESS;
}
