/* exercise.h - a student's rasterizer run as a lesson variant, and the
 * checks of `make check` (lessons/CONVENTIONS.md, "Exercises").
 *
 * The student's file defines exercise_rasterize(), compiled with
 * student.h in front of it. Here it becomes a variant of the lesson
 * ("exercise"), shown in the explorer beside the exact rule and checked
 * against it: coverage by the reference rasterizer of src/raster,
 * colour and depth by reference_shade(), linear or perspective-correct as
 * the lesson interpolates.
 *
 * A lesson gets its exercise from its own data, nothing here names it:
 *   - lessons/NN-name/exercise.c, the skeleton: the lesson's scaffolding
 *     with the heart left as TODOs; it compiles, runs and fails the check;
 *   - lessons/NN-name/answer.c beside it, the skeleton with its TODOs
 *     written (the Makefile lists both for the tests, build/exercises.c);
 *   - `.exercise` in the lesson's descriptor (struct lesson_exercise,
 *     lesson.h): the pseudo-code line of a bare write, and the lesson's own
 *     property among those the check knows (no_pixel_mul, full_blocks,
 *     clip, textures with lod_line);
 *   - the lesson's exhibits each name the check they fail in
 *     tests/test_exercise.c (the test fails on an exhibit it does not know);
 *   - the "Write it yourself" section that ends the lesson's README. */
#ifndef TRISTEP_EXERCISE_H
#define TRISTEP_EXERCISE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "lesson.h"

/* The code the exercise variant runs from now on (the student's
 * exercise_rasterize, or any rasterizer: a lesson's own, an exhibit) and the
 * lesson it is an exercise of. */
void exercise_use(const struct lesson *l, rasterize_fn fn);
/* ... or, with draw, the results of the runner, a process of its own
 * (remote.h; NULL: the code in this process again). */
void exercise_use_remote(bool (*draw)(struct target *fb, struct trace *tr));

/* The graded variant (VARIANT=, lesson_exercise.variants) that the exact
 * rule and the checks follow from now on; NULL, and exercise_use, return
 * to the lesson's own convention. */
void exercise_use_variant(const struct exercise_variant *v);
const struct exercise_variant *exercise_current_variant(void);
/* The fill rule the exact rule decides by now: the variant's, else top-left. */
enum fill_convention exercise_rule(void);
/* Lesson l's graded variant called name, or NULL. */
const struct exercise_variant *exercise_variant_named(const struct lesson *l, const char *name);

/* Lesson 06's exercise (lesson_exercise.clip): the student's clipper against
 * one plane, exercise_clip() (student.h), and the front end around it. */
struct poly;
struct plane;
typedef void (*clip_fn)(struct poly *out, const struct poly *in, const struct plane *pl);

/* The clipper the exercise's front end runs from now on (NULL: the
 * lesson's own, clip_polygon), or a whole front end of another making (a
 * lesson 06 exhibit's; NULL: none). exercise_use resets both. */
void exercise_use_clip(clip_fn clip);
void exercise_use_front(front_fn front);

/* The exercise variant's front end: a 3-D scene's screen triangles made
 * by the front end given to exercise_use_front, else by lesson 06's front
 * end with the clipper given to exercise_use_clip in place of its own for
 * near and far, else by front_scene. */
bool exercise_front(struct scene *s);

/* What the student's clipper did wrong since exercise_fault_clear(): the
 * first world triangle whose polygon came out of it with a vertex on the
 * wrong side of the plane, not finite, or too many vertices (the front end
 * then draws what it can: depths held to at least near, as a projection
 * before clipping would; a polygon it cannot use is dropped). */
enum clip_wrong { CLIP_OK, CLIP_OUTSIDE, CLIP_NOT_FINITE, CLIP_TOO_MANY, CLIP_ORDER };
struct clip_fault {
    enum clip_wrong what;
    int tri;                    /* the world triangle */
    int plane;                  /* enum plane_id: PLANE_NEAR or PLANE_FAR */
    double at;                  /* the plane's depth */
    int n_in, n;                /* vertices in and out */
    int vertex;                 /* CLIP_OUTSIDE, CLIP_NOT_FINITE: which (0-based) */
    double d;                   /* CLIP_OUTSIDE: its depth */
    double made[3];             /* CLIP_ORDER: a new vertex one walk made and the other did not */
    bool reversed;              /* ... made walking the polygon the other way */
};
const struct clip_fault *exercise_clip_fault(void);
/* The fault as the runner reports it (the judge's copy, remote.c). */
void exercise_clip_fault_set(const struct clip_fault *f);

/* Since the last exercise_front(): did every polygon the student's clipper
 * made of world triangle tri equal the lesson's clipper's, vertex for
 * vertex, as a cyclic sequence (perhaps starting at another vertex)? */
bool exercise_clip_as_lesson(int tri);
/* The same flags as a runner found them, one byte per world triangle (remote.c). */
void exercise_clip_as_lesson_set(const unsigned char *flags, int n);

/* Clip every polygon walked both ways, (v0, v1, ..., v(n-1)) and (v0,
 * v(n-1), ..., v1), as the two triangles sharing an edge walk it, and
 * count a new vertex made one way and not, to the last bit, the other as
 * a fault (CLIP_ORDER): the canonical order's promise, checked on the
 * vertices themselves. */
void exercise_clip_both_ways(bool on);

/* The variant that runs the code given to exercise_use: every write checked,
 * a bare target_write narrated as a step of its own. */
extern const struct lesson_variant exercise_variant;

/* The exact rule as a variant: the reference coverage, and colour and depth
 * from reference_shade (1/z perspective-correct when `perspective`). */
const struct lesson_variant *exercise_exact(bool perspective);

/* The lesson the explorer shows for an exercise: l's descriptor with two
 * variants, the exact rule (variants[0], what the diff view compares with,
 * under the graded variant in use) and the exercise (an exhibit of the
 * student's making). */
void exercise_lesson(struct lesson *out, struct lesson_variant variants[2], const struct lesson *l,
                     const char *file);

/* A write outside the target since the last exercise_fault_clear(): the
 * first one, which the write skipped. */
struct exercise_fault {
    bool any;
    int x, y, w, h;
};
const struct exercise_fault *exercise_fault(void);
void exercise_fault_clear(void);

/* A texel read outside its level since the last exercise_fault_clear()
 * (lesson 09: exercise_texel, student.h): the first one, read as opaque
 * black. level >= nlevels, or < 0: a level the texture does not have. */
struct texel_fault {
    bool any;
    int level, nlevels;
    long long i, j;
    int w, h;                       /* the level's size (0 x 0: no such level) */
};
const struct texel_fault *exercise_texel_fault(void);
/* Both faults as the runner reports them (the judge's copy, remote.c). */
void exercise_fault_set(const struct exercise_fault *f, const struct texel_fault *t);

/* What went wrong with the runner, the process that runs the student's
 * code when the judge is another (remote.h), since the scene began: it
 * crashed or ended, drew for too long, or sent what no drawing sends. */
enum runner_wrong { RUNNER_OK, RUNNER_CRASHED, RUNNER_TIMEOUT, RUNNER_GARBAGE };
struct runner_fault {
    enum runner_wrong what;
    int signal;                     /* RUNNER_CRASHED by a signal: which */
    char why[200];                  /* in plain words */
};
const struct runner_fault *exercise_runner_fault(void);

/* The texels read through exercise_texel() since exercise_texel_reads_clear()
 * (or exercise_fault_clear()): how many, and the levels read (bit k: level
 * k; a level the texture does not have is not a bit). Lesson 09's check
 * holds them, per written pixel, to the filter's taps. */
struct texel_reads {
    uint64_t n;
    uint32_t levels;
};
const struct texel_reads *exercise_texel_reads(void);
void exercise_texel_reads_clear(void);
/* The reads a runner counted before an event it sent (remote.c), added to these. */
void exercise_texel_reads_add(const struct texel_reads *r);

/* --- make check ---------------------------------------------------------------- */

/* The search draws at least this many scenes of each check that searches
 * (when it searches at all), however long they take: the mistakes that the
 * first scenes of a seed show fail on every machine alike (the mutation
 * suite holds every classic mistake to this many). */
#define SEARCH_FLOOR 64

struct check_options {
    const char *file;               /* the code checked, as the report names it */
    const char *const *scenes;      /* scenes of the student's own (SCENE=), NULL-terminated */
    const char *out_dir;            /* where a counterexample is written */
    const char *open_cmd;           /* how to open a scene: "make exercise LESSON=02 FILE=x.c" */
    struct raster_params params;    /* subpixel_bits and the lesson's own (lesson.h) */
    FILE *out;                      /* the report (stdout) */
    bool progress;                  /* show progress on long checks (a terminal) */
    const char *program;            /* the exercise program, for the debugger command */
    /* the search after each check's fixed scenes: scenes made from seed,
     * until one fails, search_seconds (for the whole lesson, shared by its
     * checks) are spent or search_scenes (per check) are drawn; no search
     * when both are 0 */
    uint64_t seed;
    double search_seconds;
    int search_scenes;
    bool all;                       /* run every check, not only up to the first failure (grading) */
};

/* One check's outcome, for a score (make grade). */
#define CHECKS_MAX 24
struct check_outcome {
    char name[48];
    bool ran, passed;
    enum runner_wrong runner;       /* failed because the runner crashed, hung or sent garbage */
    long from, to;                  /* its part of the report: ftell(out) before and after */
};

struct check_result {
    int nchecks, passed;            /* checks run, checks passed */
    char failed[64];                /* name of the failed check, "" when all passed */
    char counterexample[512];       /* the scene written, "" when none */
    int x, y;                       /* its first wrong pixel */
    uint64_t step;                  /* the step that shows it in the explorer */
    int ntris;                      /* triangles in the counterexample */
    uint64_t searched;              /* scenes the search drew */
    bool found_by_search;           /* the counterexample's scene is the search's */
    struct check_outcome check[CHECKS_MAX];     /* every check planned, in order */
};

/* Run every check of lesson l on the code given to exercise_use, in order,
 * stopping at the first failure. Returns true when all pass. False also for
 * an unreadable SCENE file or an unwritable counterexample (said on o->out). */
bool exercise_check(const struct lesson *l, const struct check_options *o, struct check_result *r);
/* The checks exercise_check would run, by name (r->nchecks, r->check[i].name). */
bool exercise_check_plan(const struct lesson *l, const struct check_options *o, struct check_result *r);
/* The same in a process of its own: code that crashes, or loops for
 * SCENE_SECONDS on one scene, fails with the scene it was drawing (shrunk
 * when it crashes) and the command that shows where under a debugger. */
bool exercise_check_guarded(const struct lesson *l, const struct check_options *o,
                            struct check_result *r);

/* The skeletons and answers compiled into the tests (generated
 * build/exercises.c), each under its own name. */
struct exercise_code {
    const char *lesson;             /* "02" */
    rasterize_fn skeleton;          /* lessons/NN-name/exercise.c as given */
    rasterize_fn answer;            /* lessons/NN-name/answer.c */
    clip_fn skeleton_clip, answer_clip;     /* their exercise_clip (lesson 06), or NULL */
};
extern const struct exercise_code all_exercises[];     /* ends with lesson == NULL */

/* The graded variants' skeletons and answers (lessons/NN-name/exercise-V.c
 * and answer-V.c, generated build/exercise-variants.c). */
struct exercise_variant_code {
    const char *lesson;             /* "02" */
    const char *variant;            /* "bottom-right" */
    rasterize_fn skeleton, answer;  /* answer NULL where the answers are left out */
};
extern const struct exercise_variant_code all_exercise_variants[];  /* ends with lesson == NULL */

/* The mutation suite (tests/mutations/NN-name.patch, generated
 * build/mutations.c): classic mistakes, each made in a worked answer, and
 * the check that must fail first on each. */
struct exercise_mutation {
    const char *lesson;             /* "02" */
    const char *name;               /* "02-float-edges", the patch's name */
    const char *check;              /* the check that names the mistake */
    rasterize_fn fn;
    clip_fn clip;                   /* lesson 06's exercise_clip, or NULL */
    const char *variant;            /* the graded variant whose answer it mutates (NN-V--what), or NULL */
};
extern const struct exercise_mutation all_mutations[];  /* ends with lesson == NULL */

#endif
