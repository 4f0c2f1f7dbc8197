/* cli.h - the program every lesson becomes: the options they all share
 * (lessons/CONVENTIONS.md), the headless modes, the explorer window. */
#ifndef TRISTEP_CLI_H
#define TRISTEP_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "app/app.h"
#include "lesson.h"

#define TRISTEP_VERSION "0.1.0"

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
    enum theme theme;               /* --theme dark|light (figures for print) */
    enum figure_part part;          /* --figure-part all|canvas */
    enum paper paper;               /* --paper a4|letter (PDF figures) */
    const char *keys;               /* --keys FILE: scripted explorer input */
    struct raster_params params;
};

/* Binary PGM (P5, maxval 255) of the coverage counts, row 0 at the top. */
bool write_coverage_pgm(FILE *out, const struct target *fb);

/* The program: parse options, load the scene, run headless or open the
 * explorer. Returns the exit status (EXIT_OK, EXIT_RUN, EXIT_USAGE). */
int lesson_main(const struct lesson *l, int argc, char **argv);

#endif
