/* export.c - the explorer's view written to PNG, SVG or PDF (the same
 * painter as the window, onto a file surface), and a target's colours as PNG. */
#include "export.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
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
};

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
        surface = cairo_pdf_surface_create_for_stream(to_file, out, job->w, job->h);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, FIGURE_DATE);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_MOD_DATE, FIGURE_DATE);
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "tristep");
    }
    cairo_t *cr = cairo_create(surface);
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

bool explorer_export(struct explorer *ex, const char *path, int w, int h, char *err, size_t errlen)
{
    struct export_job job = { ex, path, w, h };
    return write_file_atomic(path, write_figure, &job, err, errlen);
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
