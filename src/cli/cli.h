/* cli.h - the options every lesson program shares (CONVENTIONS.md), and the
 * careful writing of output files. */
#ifndef TRISTEP_CLI_H
#define TRISTEP_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "lesson.h"

#define TRISTEP_VERSION "0.1.0"

enum { EXIT_OK = 0, EXIT_RUN = 1, EXIT_USAGE = 2 };

struct cli_options {
    const char *scene_path;         /* NULL: the lesson's built-in scene */
    const struct lesson_variant *variant;
    const char *dump_coverage;      /* FILE.pgm */
    const char *dump_image;         /* FILE.png */
    const char *figure;             /* FILE.png, .svg or .pdf */
    bool step_end;                  /* --step end */
    uint64_t step;                  /* --step N */
    const char *view;               /* --view NAME */
    int width, height;              /* --size WxH (figure or window), 0 = default */
    double zoom;                    /* --zoom PX: screen pixels per scene pixel, 0 = fit */
    double scale;                   /* --scale F: interface scale, 0 = 1 */
    const char *keys;               /* --keys FILE: scripted explorer input */
    struct raster_params params;
};

/* Write a file all or nothing: `write` produces the bytes into a temporary
 * file beside `path`, which is renamed over `path` only when everything
 * succeeded. On failure nothing is left behind and err says why. */
bool write_file_atomic(const char *path, bool (*write)(FILE *out, void *ctx), void *ctx,
                       char *err, size_t errlen);

/* Binary PGM (P5, maxval 255) of the coverage counts, row 0 at the top. */
bool write_coverage_pgm(FILE *out, const struct target *fb);
/* PNG of the colour buffer through cairo. */
bool write_color_png(FILE *out, const struct target *fb);

#endif
