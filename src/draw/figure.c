/* figure.c - the explorer's view written to PNG, SVG or PDF: the same
 * painter as the window, onto a file surface. */
#include "figure.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <string.h>

#include "draw/explorer.h"

/* Fixed dates: the same figure gives the same bytes (cairo 1.16 ignores
 * SOURCE_DATE_EPOCH). */
#define FIGURE_DATE "2024-01-01T00:00:00Z"

struct export_job {
    struct explorer *ex;
    const char *path;
    int w, h;
};

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int len)
{
    return fwrite(data, 1, len, closure) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

static bool write_figure(FILE *out, void *ctx)
{
    struct export_job *job = ctx;
    cairo_surface_t *surface;
    bool png = ends_with(job->path, ".png");
    if (png) {
        surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, job->w, job->h);
    } else if (ends_with(job->path, ".svg")) {
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

int explorer_desc_from_cli(const struct lesson *l, const struct cli_options *o,
                           const struct scene *s, char *name, size_t n,
                           struct explorer_desc *d)
{
    if (o->scene_path)
        snprintf(name, n, "%s", o->scene_path);
    else
        snprintf(name, n, "builtin:%s", l->builtin_scene);
    *d = (struct explorer_desc){
        .lesson = l, .scene = s, .scene_name = name, .scene_is_default = !o->scene_path,
        .variant = o->variant, .params = o->params, .step = o->step, .step_end = o->step_end,
        .zoom = o->zoom, .scale = o->scale,
    };
    if (o->view) {
        /* check the name first: a bad view is a usage error */
        struct explorer probe = { .lesson = l, .edge = -1 };
        if (!explorer_set_view_name(&probe, o->view)) {
            fprintf(stderr, "%s: --view '%s': no such view; views:", l->id, o->view);
            for (int i = 0; i < explorer_view_count(&probe); i++)
                fprintf(stderr, " %s", explorer_view_name(&probe, i));
            fprintf(stderr, " edge-ab edge-bc edge-ca\n");
            return EXIT_USAGE;
        }
        d->view = o->view;
    }
    return -1;
}

int figure_export(const struct lesson *l, const struct cli_options *o, const struct scene *s)
{
    char name[160];
    struct explorer ex;
    struct explorer_desc d;
    int status = explorer_desc_from_cli(l, o, s, name, sizeof name, &d);
    if (status >= 0)
        return status;
    explorer_fonts();
    if (!explorer_init(&ex, &d)) {
        fprintf(stderr, "%s: out of memory for the scene\n", l->id);
        return EXIT_RUN;
    }
    int w = o->width ? o->width : 1280, h = o->height ? o->height : 800;
    char err[512];
    status = EXIT_OK;
    if (!explorer_export(&ex, o->figure, w, h, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = EXIT_RUN;
    }
    explorer_free(&ex);
    return status;
}
