/* lesson.h - what a lesson file provides, and the one entry point that turns
 * it into a program (options, headless modes, the explorer). */
#ifndef TRISTEP_LESSON_H
#define TRISTEP_LESSON_H

#include <math.h>
#include <stdbool.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "trace/trace.h"

#define CHECKER_DARK 0.35   /* brightness of the checkerboard's dark squares */

/* Settings a run may change without changing the algorithm. */
struct raster_params {
    int checker;          /* the scene's "texture checker N", 0 = untextured */
    int block_size;       /* q for block lessons (0 = the lesson's default) */
    bool affine;          /* texture affinely, not perspective-correct (exhibit) */
    int subpixel_bits;    /* snapping precision, SUBPIXEL_BITS unless an exhibit */
};

typedef void (*rasterize_fn)(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr);

/* One way of running the lesson: the algorithm itself, a faster twin, or an
 * exhibit that reproduces a slip of the source texts. */
struct lesson_variant {
    const char *name;       /* --variant NAME */
    const char *what;       /* one line for --help and the explorer */
    rasterize_fn rasterize;
    bool exhibit;           /* deliberately not exact: shown against the exact rule */
};

struct lesson {
    const char *id;                     /* "02-barycentric", as the program's name */
    const char *title;
    const char *const *pseudocode;      /* lines, NULL-terminated; events point at them */
    const char *builtin_scene;          /* the scene opened by default */
    const char *exhibit_scene;          /* the scene its exhibits are shown on */
    bool perspective;                   /* interpolates 1/z (lesson 04 onwards) */
    const struct lesson_variant *variants;  /* variants[0] is the lesson's algorithm */
    int nvariants;
    const char *const *aux_names;       /* names of trace_event.aux[], NULL-terminated */
};

const struct lesson_variant *lesson_variant(const struct lesson *l, const char *name);

/* Colour of a covered pixel from interpolated values, shared by every lesson:
 * the Gouraud colour, darkened on the dark squares of the checkerboard when
 * the scene has "texture checker N" (texture coordinates in [0, 1]). */
static inline uint32_t shade_pixel(const struct raster_params *p, double r, double g,
                                   double b, double s, double t)
{
    if (p->checker > 0) {
        long i = (long)floor(s * p->checker), j = (long)floor(t * p->checker);
        if ((i + j) & 1) {
            r *= CHECKER_DARK;
            g *= CHECKER_DARK;
            b *= CHECKER_DARK;
        }
    }
    return pack_rgb(r, g, b);
}

/* The program: parse options, load the scene, run headless or open the
 * explorer. Returns the exit status (0 ok, 1 failure while running, 2 bad
 * command line or input). */
int lesson_main(const struct lesson *l, int argc, char **argv);

#endif
