/* lesson.h - what a lesson's algorithm file provides: its algorithm,
 * variants, narration and the costs it counts (lesson_main in src/cli/cli.h
 * turns it into a program). What the explorer adds for a lesson (views,
 * drawings, watch values) is declared apart, in lesson_explorer.h.
 * Shared machinery a lesson uses by name: src/shade/ (shading pixels). */
#ifndef TRISTEP_LESSON_H
#define TRISTEP_LESSON_H

#include <stdbool.h>
#include <stddef.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* How many parameters of its own a lesson may have (rows of its table). */
#define LESSON_PARAMS_MAX 4

struct run_place;

/* Settings a run may change without changing the algorithm: what every
 * lesson's run reads, and the values of the lesson's own parameters. */
struct raster_params {
    int checker;          /* the scene's "texture checker N", 0 = untextured */
    int subpixel_bits;    /* snapping precision of the set-up, SUBPIXEL_BITS unless an exhibit */
    int samples;          /* samples per pixel of the target, 1, 4 or 8 (0 = 1, the centre) */
    /* the lesson's own parameters, knob[i] the value of row i of its table
     * (struct lesson_param, PARAM_OWN rows); 0 = the lesson's default */
    int knob[LESSON_PARAMS_MAX];
    /* where the triangle stands in the run that draws it (struct
     * run_place), which every driver hands over, or NULL: a triangle drawn
     * alone. One pointer for every lesson, whatever a lesson reads of it */
    const struct run_place *at;
    /* the image texture of the triangle being drawn (scene_texture of its
     * `texture` number), or NULL: set by the drivers per triangle; a lesson
     * without .texturing draws in the vertex colour and never reads it */
    const struct texture *texture;
};

/* One unit of a scene-level lesson's narrated run: triangle `tri` of the
 * scene drawn inside tile `tile`, entry `bin_entry` of the tile's `bin_size`
 * triangles, in a tile that worker `thread` drew in the real run. */
struct lesson_unit {
    uint32_t tri;
    int32_t tile, bin_size, bin_entry, thread;
};

/* Where the triangle being drawn stands in its run, handed over by the
 * driver (the replay, the programs, the checks) for a lesson that tells of
 * more than its triangle: lesson 06 narrates a world triangle's front end
 * from the scene (and its depth exhibits read the camera's planes), lesson
 * 07 draws and narrates one unit of its narrated order. */
struct run_place {
    const struct scene *scene;          /* the scene being drawn, or NULL */
    /* in the narrated replay of a scene-level lesson: the unit being drawn,
     * and the whole order (for the explorer's drawings); NULL outside one */
    const struct lesson_unit *unit, *units;
    int nunits;
    /* in the explorer's drawings and watch only (NULL in every run): the
     * last event the unit told at each line of the pseudo-code up to the
     * step shown, told[line] (.kind TRACE_KIND_COUNT: none yet), so that a
     * step can be shown with the steps before it (lesson 09: a pixel's
     * filter with its quad's derivatives) */
    const struct trace_event *told;
};

/* The scene of the run p draws in, or NULL. */
static inline const struct scene *drawn_scene(const struct raster_params *p)
{
    return p->at ? p->at->scene : NULL;
}

/* The units of variant v's narrated run in their order: writes at most
 * `cap` of them to out (NULL when cap is 0) and returns how many there are,
 * or -1 when out of memory. */
struct lesson_variant;
typedef long (*lesson_units_fn)(const struct scene *s, const struct lesson_variant *v,
                                const struct raster_params *p, struct lesson_unit *out, long cap);

/* Makes a 3-D scene's screen triangles (src/front/: front_scene, or an
 * exhibit's own way); false only when out of memory. */
typedef bool (*front_fn)(struct scene *s);

typedef void (*rasterize_fn)(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr);
/* A whole scene at once, in whatever order and on whatever threads the
 * lesson likes, as long as the picture is that of drawing the triangles one
 * after another. Returns false when out of memory. */
typedef bool (*rasterize_scene_fn)(const struct scene *s, const struct raster_params *p,
                                   struct target *fb);

/* What a variant is, and so how the programs treat it: the explorer's T
 * key steps through the variants drawn by the exact rule (twins and
 * alternatives), X through those shown against it; the tests hold the
 * former to the reference and expect the latter to differ from it. */
enum variant_kind {
    VARIANT_ALGORITHM,      /* variants[0]: the lesson's algorithm */
    VARIANT_TWIN,           /* the same pixels another way, faster (SIMD, block size, threads) */
    VARIANT_ALTERNATIVE,    /* another exact method: the same coverage, its own colours or
                             * clip space (lesson 08's ssaa and tent, lesson 06's clip-space-gl) */
    VARIANT_CONTRAST,       /* no slip, yet not the algorithm's picture or depth: shown against it
                             * (lesson 06's depth storages, float clipping in canonical order) */
    VARIANT_EXHIBIT,        /* a slip of the source texts, reproduced: shown against the exact rule */
    VARIANT_EXERCISE,       /* the student's code (make exercise): shown against the exact rule */
};

/* One way of running the lesson, written with designated initializers:
 * { .name = "q4", .kind = VARIANT_TWIN, .rasterize = rasterize_q4, .what = "..." }. */
struct lesson_variant {
    const char *name;       /* --variant NAME */
    const char *what;       /* one line for --help and the explorer */
    rasterize_fn rasterize;
    enum variant_kind kind;
    /* how it makes a 3-D scene's screen triangles (lesson 06's exhibits have
     * their own), or NULL: the shared front end, front_scene (src/front/) */
    front_fn front;
    /* the depth buffer keeps another quantity than z (lesson 06 stores 1/d,
     * NDC z, reversed depth): shown against the exact rule by colours alone */
    bool other_depth;
};

/* Shown against the exact rule (the explorer's diff, the X key), not held to it. */
static inline bool variant_against_exact(const struct lesson_variant *v)
{
    return v->kind >= VARIANT_CONTRAST;
}

#define LESSON_COMPARE_MAX 2

/* Every lesson, narrated (NULL-terminated): every program links them all, so
 * the explorer can run an earlier lesson on the same scene for comparison. */
extern const struct lesson *const all_lessons[];

/* Where a parameter's value lives. */
enum lesson_param_slot {
    PARAM_OWN,              /* knob[its row]: read by the lesson alone, through its row */
    PARAM_SUBPIXEL_BITS,    /* raster_params.subpixel_bits, which every lesson's set-up reads */
    PARAM_SAMPLES,          /* raster_params.samples, which the shared drivers read */
};

/* One parameter of a lesson, a row of the table in its descriptor. The
 * command line (src/cli/), the explorer's keys (src/app/params.c) and its
 * panel (src/draw/panel.c) read the table; every program accepts the
 * options of every lesson's table (the same option means the same thing in
 * each), and a lesson ignores the options of rows it does not have, except
 * that shared slots are always set. */
struct lesson_param {
    const char *option;     /* "block-size": --block-size ARG */
    const char *arg;        /* "Q", as --help shows it; NULL: a flag (--affine), which sets 1 */
    const char *help;       /* --help's line after the option */
    const char *name;       /* "block size": the panel's and the keys' word */
    /* the values by name, or NULL (numbers): a flag's two states in the panel
     * ({ "off", "on" }); with an arg, value min + i is words[i] everywhere
     * (--filter trilinear, the panel, the keys), min..max all named */
    const char *const *words;
    int key;                /* the explorer's key: the next value, wrapping; 0: none */
    int key_down;           /* with it, key_down the value before and key the one after, stopping
                             * at the ends ([ and ]); 0: key alone */
    int min, max;           /* the values allowed ... */
    const int *values;      /* ... or only these, -1-terminated (4, 8, 16) */
    int def;                /* the value without an option (may lie outside the range: threads
                             * 0, one per core) */
    enum lesson_param_slot slot;
};

/* A named cost (trace/trace.h) counted n times, in a lesson's declaration of
 * what one pixel costs: COST_TERM(3, EDGE_VALUE_COST). A list of terms ends
 * with { 0 }. */
struct cost_term {
    unsigned n;
    const char *name;
    struct op_cost cost;
};
#define COST_TERM(n, COST) { (n), #COST, COST }

/* A graded variant of a lesson's exercise (VARIANT=NAME): the same idea
 * under another pinned convention, whose answer the lesson's own source
 * does not print. Its skeleton is lessons/NN-name/exercise-NAME.c, its
 * worked answer answer-NAME.c; the check is the lesson's, every check held
 * to the exact reference under the variant's convention. */
struct exercise_variant {
    const char *name;       /* "bottom-right": VARIANT=bottom-right */
    const char *what;       /* one line: the convention */
    enum fill_convention rule; /* the rule the reference decides coverage by */
    /* the box walked from its bottom-right pixel: rows from the bottom up,
     * each from its right end to its left; the check holds the order of the
     * pixels the code tests and writes to it */
    bool from_bottom_right;
};

/* What `make exercise` and `make check` need of a lesson (src/exercise/):
 * the rest comes from the descriptor itself (perspective, pseudocode). */
struct lesson_exercise {
    /* pseudo-code line of a pixel written by the student's code without
     * narration of its own (a bare target_write): every write is a step */
    int write_line;
    /* the lesson's own property: no multiplication between two pixels of
     * a row, by the counters (lesson 03) */
    bool no_pixel_mul;
    /* ... every block narrated FULL covered in full, every block covered
     * in full narrated FULL (lesson 05; lesson 07, tiles and blocks alike) */
    bool full_blocks;
    /* which pseudo-code lines narrate a block's class, -1-terminated (lesson
     * 07: a triangle whose box fits a block is narrated as that box, tested
     * pixel by pixel, never classified); NULL: every block event */
    const int *class_lines;
    /* a check on scenes over many 64 x 64 tiles (lesson 07): triangles
     * inside one block, one tile, across many; edges through the corners of
     * tiles; the partial tiles at the screen's right and bottom */
    bool tiles;
    /* the sample counts every scene of the check is drawn at, in order,
     * 0-terminated (lesson 08: 4, 8, 1); NULL: one sample per pixel. At
     * n > 1 the exact rule decides every sample (reference_point_covered)
     * and the check compares each pixel's covered samples and resolve */
    const int *samples;
    /* the student writes lesson 06's clipper, exercise_clip() (one plane,
     * Sutherland-Hodgman, src/exercise/student.h): the check adds the 3-D
     * checks, each scene projected by the lesson's front end for the exact
     * picture and by the front end around the student's clipper for theirs */
    bool clip;
    /* the student writes parts of lesson 09's sampler, run inside the
     * lesson's own rasterizer: the check adds textured scenes (texels
     * magnified and minified, both wraps, a texture that is not square,
     * grazing floors, tiny triangles), and the exact picture is the
     * lesson's own (variants[0], held to the independent reference by its
     * tests) rather than the shared rule's */
    bool textures;
    /* ... and the pseudo-code line whose TRACE_STEP narrates a quad's level
     * of detail (0: none): aux[0..3] du/dx, dv/dx, du/dy, dv/dy in level-0
     * texels per pixel, aux[4] rho, aux[5] the lambda the code chose, flags
     * TRACE_INSIDE unless beyond the horizon. The check holds that lambda to
     * log2(rho) of those derivatives, quad by quad */
    int lod_line;
    /* its graded variants, ending with { 0 } (NULL: none) */
    const struct exercise_variant *variants;
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
    /* its parameters, rows ending with { 0 } (NULL: none); the lesson names
     * its rows by an enum and reads row i of its own as p->knob[i] */
    const struct lesson_param *params;
    /* ids of earlier lessons (at most LESSON_COMPARE_MAX, NULL-terminated)
     * that the explorer runs on the same scene, to show their counters
     * (pixels tested, arithmetic per pixel) beside this lesson's */
    const char *const *compare;
    /* What one pixel costs in the lesson's algorithm (variants[0]), in named
     * costs: every pixel tested, and on top of that every pixel covered
     * (shaded and written); NULL for none. tests/test_counters.c recounts
     * both from what the code COUNTs. */
    const struct cost_term *cost_tested, *cost_covered;
    /* Optional, one per variant (lesson 07: bins need every triangle before
     * the first pixel): what the headless modes and the bench call instead
     * of variants[i].rasterize per triangle. `rasterize` stays: one triangle
     * through the same pipeline, for the tests and the narrated replay. */
    const rasterize_scene_fn *rasterize_scene;
    /* With it, the order the narrated replay steps through (the explorer
     * keeps one count per unit instead of one per triangle), or NULL. */
    lesson_units_fn narration_units;
    /* How it draws a triangle under an image texture (`texture FILE.png`),
     * one sentence for --help, or NULL: in its vertex colour, the image
     * unread (every lesson before texture mapping) */
    const char *texturing;
    /* How it draws a scene's `line`s, one sentence for --help, or NULL:
     * it reads and checks them and draws the triangles alone (every lesson
     * but lesson 00) */
    const char *lines;

    struct lesson_exercise exercise;    /* lessons/NN-name/exercise.c */
};

/* Params p as triangle i of scene s is drawn with: its image texture set
 * (what every driver hands `rasterize`, triangle by triangle). */
static inline struct raster_params lesson_params_tri(const struct raster_params *p,
                                                     const struct scene *s, int i)
{
    struct raster_params out = *p;
    out.texture = scene_texture(s, s->tris[i].texture);
    return out;
}

/* The scene-level twin of variant v of lesson l, or NULL. */
static inline rasterize_scene_fn lesson_scene_fn(const struct lesson *l,
                                                 const struct lesson_variant *v)
{
    if (!l->rasterize_scene || v < l->variants || v >= l->variants + l->nvariants)
        return NULL;
    return l->rasterize_scene[v - l->variants];
}
/* The front end variant v of lesson l runs on a 3-D scene: v->front, or
 * front_scene. */
front_fn lesson_front(const struct lesson *l, const struct lesson_variant *v);

const struct lesson_variant *lesson_variant(const struct lesson *l, const char *name);

/* The row of lesson l with option `option` (its index in *row when row is
 * not NULL), or NULL. */
const struct lesson_param *lesson_param(const struct lesson *l, const char *option, int *row);
/* Where row `row` of lesson l keeps its value in p. */
int *lesson_param_slot(const struct lesson *l, int row, struct raster_params *p);
/* Sets the parameter named by option to v, if lesson l has it; false if not. */
bool lesson_param_set(const struct lesson *l, struct raster_params *p, const char *option, int v);
/* Every parameter of lesson l at its default, SUBPIXEL_BITS bits unless the lesson says. */
struct raster_params lesson_params_default(const struct lesson *l);
/* Params p of lesson `from` as lesson `to` reads them: every field shared
 * by all lessons as in p, and each parameter of `to`'s own at the value of
 * `from`'s row with the same option (the same option means the same
 * thing), else at its default. */
struct raster_params lesson_params_as(const struct lesson *to, const struct lesson *from,
                                      const struct raster_params *p);
/* Whether v is a value row r allows. */
bool lesson_param_allows(const struct lesson_param *r, int v);
/* The name of value v of row r (a named row's, a flag's state), or NULL: a number. */
const char *lesson_param_word(const struct lesson_param *r, int v);
/* The value of named row r called `word`, or -1 (none, or r is not named). */
int lesson_param_named(const struct lesson_param *r, const char *word);
/* Row r's values in words, "4, 8 or 16", "0..8" or "nearest, ... or aniso", into buf[0..n). */
void lesson_param_range(const struct lesson_param *r, char *buf, size_t n);

#endif
