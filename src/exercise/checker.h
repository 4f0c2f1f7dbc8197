/* checker.h - what the parts of make check share (check.c runs the checks,
 * evaluate.c draws and compares, shrink.c shrinks a counterexample,
 * report.c says what went wrong). Private to src/exercise/. */
#ifndef TRISTEP_EXERCISE_CHECKER_H
#define TRISTEP_EXERCISE_CHECKER_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "exercise/exercise.h"

/* Pictures of other sizes kept for the next scenes. */
#define CHECK_SPARES 6
/* Shrinking tries at most this many candidate scenes. */
#define SHRINK_BUDGET 4000
/* A scene that takes longer than this is an endless loop: no scene of the
 * checks needs a hundredth of it. */
#define SCENE_SECONDS 10
/* Shrinking a crash runs each candidate in a process of its own. */
#define CRASH_BUDGET 600

/* Where a guarded check is (exercise_check_guarded): shared with the
 * process that runs it, so a crash still says which scene did it. */
struct guard {
    int check, scene, tri;
    bool searching;             /* scene is the search's, made from search_seed */
    uint64_t search_seed;
    struct check_result result;
};
extern struct guard *check_guard;     /* NULL unless guarded */

/* CK_ORDER: the property is the order of the pixels tested and written (a
 * graded variant's from_bottom_right) */
enum check_kind { CK_COVERAGE, CK_COLOUR, CK_PROPERTY, CK_ALL, CK_ORDER };

/* What went wrong, at the first triangle after which the pictures differ. */
enum wrong {
    WRONG_NONE, WRONG_COUNT, WRONG_COLOUR, WRONG_DEPTH, WRONG_OUTSIDE, WRONG_MUL,
    WRONG_BLOCK_CLASS, WRONG_MASK, WRONG_CLIP, WRONG_LOD, WRONG_TEXEL, WRONG_ORDER, WRONG_TILES,
    WRONG_READS, WRONG_RUNNER, WRONG_UNBLOCKED,
};

struct verdict {
    enum wrong what;
    int tri;                    /* the triangle that went wrong */
    int x, y;                   /* its first wrong pixel */
    int want_n, got_n;          /* coverage counts there */
    uint32_t want_c, got_c;     /* colours */
    float want_z, got_z;
    int bx, by, bx1, by1;       /* a block, for the block properties */
    int want_class, got_class;  /* WRONG_BLOCK_CLASS: enum block_class, the corners' and the narrated */
    int edge;                   /* ... an edge all four corners lie outside (want EMPTY), else -1 */
    uint64_t mul;               /* multiplications between two pixels */
    int before_x, before_y;     /* WRONG_ORDER: the pixel tested or written before (x, y) */
    int samples;                /* samples per pixel it was drawn at (1: the pixel centre) */
    unsigned want_mask, got_mask;   /* WRONG_MASK: the samples holding a depth */
    /* a 3-D scene: tri is a world triangle; the screen triangles made of it */
    bool world;
    int want_tris, got_tris;
    struct clip_fault clip;         /* WRONG_CLIP: what the clipper did */
    /* WRONG_LOD: the quad (x, y), its derivatives (du/dx, dv/dx, du/dy,
     * dv/dy in level-0 texels), lambda = log2(rho) and the code's */
    double deriv[4], want_lambda, got_lambda;
    struct texel_fault texel;       /* WRONG_TEXEL: the texel read outside its level */
    /* WRONG_TILES: the tile (bx, by)-(bx1, by1) narrated outside the
     * triangle's box of want_n tiles;
     * WRONG_READS: got_n texels of got_class levels read for pixel (x, y),
     * levels the bits of got_mask, where want_n (4 per level read) and
     * two adjacent levels at most are the filter's */
    int box[4];                     /* WRONG_TILES: the triangle's box, x0, y0, x1, y1 */
    struct runner_fault runner;     /* WRONG_RUNNER: the runner crashed, hung or sent garbage */
};

/* Everything one check run needs. */
struct checker {
    const struct lesson *l;
    const struct check_options *o;
    struct raster_params p;
    enum check_kind kind;
    struct target want, got;
    /* a 3-D scene: the exact rule on the code's own screen triangles (its
     * clipper's polygons, fanned its way), which compare() accepts where
     * it differs from want by the snapping of another fan alone */
    struct target own;
    bool use_own;
    /* pictures of other sizes and sample counts, the most recent first,
     * kept between scenes: lesson 08 draws each scene at 4, 8 and 1
     * samples, and random scenes change size (no reallocation each time) */
    struct target spare_want[CHECK_SPARES], spare_got[CHECK_SPARES];
    uint8_t *mask;              /* the exact coverage of the triangle being run */
    /* the property watch, fed by the narration */
    struct verdict *prop;
    const struct tri_setup *t;  /* the triangle being drawn */
    bool in_row;
    int last_x, last_y;
    uint64_t pixel_mul;         /* mul counted when the last pixel began */
    bool both_ways;             /* lesson 06: clip every polygon walked both ways */
    /* CK_ORDER: the last pixel tested or written */
    bool order_any;
    int order_x, order_y;
    /* a lesson of blocks (full_blocks): the block narrated last, which
     * holds the pixels written after it */
    bool block_any;
    int block[4];
    int only_count;             /* > 0: draw at this sample count alone (lesson 08's random scenes) */
    uint8_t *tie;               /* pixels whose nearest surface two triangles tie for (either colour is right) */
    double *zexact;             /* the exact depth of the surface nearest at each pixel */
    double search_share;        /* seconds of search for each check that searches */
    uint64_t evaluations;       /* scenes drawn, for the report */
    uint64_t triangles;
};

/* The picture the code is held to (evaluate.c). */
const struct lesson_variant *check_exact(const struct lesson *l);

/* Draw scene s both ways, triangle by triangle; false (and v) at the first
 * triangle after which they differ in what C->kind compares. */
bool evaluate(struct checker *C, const struct scene *s, struct verdict *v);

/* A 3-D scene's screen triangles as the exercise's front end makes them
 * (exercise_front), in a copy of s; false when out of memory. */
bool exercise_projected(const struct checker *C, struct scene *out, const struct scene *s);

/* The seam where the student's code draws (evaluate.c): in the runner, a
 * process of its own, when one is configured (remote.h), ask for
 * triangles first .. first + count - 1 of s (trace: enum wire_trace), then
 * draw each through exercise_variant in order; student_end when done.
 * In this process both do nothing. */
bool student_begin(const struct checker *C, const struct scene *s, const struct raster_params *p,
                   int first, int count, int trace);
void student_end(void);

/* x, then y, of each vertex of the scene in order: coordinate k. */
double *scene_coord(struct scene *s, int k);
/* Fewest triangles, then the smallest, roundest coordinates, while the
 * check still fails. */
void shrink(struct checker *C, struct scene *s);

/* What the code's own narration said about the first wrong pixel. */
struct trail {
    int x, y;
    bool by_rect;               /* the block or tile that is exactly rect, not the one holding (x, y) */
    int lod_line;               /* > 0: the quad's level of detail narrated at (x, y) on this line */
    int rect[4];
    bool written, tested, held;
    struct trace_event write, test, hold;
};
void say_verdict(const struct checker *C, FILE *out, const struct verdict *v, const struct scene *s);
/* The step at which the explorer shows the first wrong pixel (and the trail). */
uint64_t step_of(const struct checker *C, const struct scene *s, const struct verdict *v,
                 struct trail *f);
void explain(const struct checker *C, FILE *out, const struct verdict *v, const struct scene *s,
             const struct trail *f);
/* Write s to path, all or nothing, with a header naming the check. */
bool write_counterexample(const char *path, const struct scene *s, const char *check,
                          const struct lesson *l, const char *file, const struct verdict *v,
                          char *err, size_t errlen);
bool make_dirs(const char *dir);

#endif
