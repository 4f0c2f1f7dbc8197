/* testlib.h - what every test file shares: a seeded random generator,
 * random triangles by category, running one triangle through a lesson,
 * the reference coverage and a comparison that draws the first difference.
 *
 * Replaying a failure: every randomised test prints its seed and case number
 * when it fails; run the suite again with TRISTEP_SEED set to that seed
 *
 *     TRISTEP_SEED=0x1234 build/tristep-tests --filter 'property/all'
 *
 * and the same triangles come out in the same order.
 *
 * The API is small on purpose, and stable: lesson tests use it too.
 */
#ifndef TRISTEP_TESTLIB_H
#define TRISTEP_TESTLIB_H

#include <stdbool.h>
#include <stdint.h>

#include "lesson.h"

/* Every lesson, narrated and fast; NULL-terminated (generated build/lessons.c). */
extern const struct lesson *const all_lessons[], *const all_lessons_fast[];

/* --- seeded random numbers (splitmix64) --------------------------------------- */

#define TEST_DEFAULT_SEED 0x7457e9u   /* used when TRISTEP_SEED is not set */

struct rng {
    uint64_t state;
};

/* The run's seed: TRISTEP_SEED (decimal or 0x hex) or TEST_DEFAULT_SEED. */
uint64_t test_seed(void);
/* A generator for one test: the run's seed mixed with a per-test salt, so
 * tests do not draw the same triangles yet all replay from one seed. */
struct rng rng_for(uint64_t salt);
uint64_t rng_next(struct rng *r);
double rng_unit(struct rng *r);                        /* [0, 1) */
double rng_range(struct rng *r, double lo, double hi); /* [lo, hi) */
int rng_int(struct rng *r, int lo, int hi);            /* lo..hi inclusive */
bool rng_chance(struct rng *r, double p);

/* --- random triangles by category -------------------------------------------- */

enum tri_category {
    CAT_GENERIC,      /* a few pixels to a few tens of pixels */
    CAT_SLIVER,       /* long and thin: two vertices close, or all nearly collinear */
    CAT_TINY,         /* smaller than a pixel */
    CAT_LARGE,        /* larger than the target */
    CAT_OFFSCREEN,    /* partly (or wholly) outside the target */
    CAT_DEGENERATE,   /* collinear or a repeated vertex: covers nothing */
    CAT_CENTRES,      /* vertices on pixel centres: edges through centres */
    CAT_AXIS,         /* at least one horizontal or vertical edge */
    CAT_COUNT
};

const char *tri_category_name(enum tri_category c);

/* Three vertices of category c for a w x h target, in random winding.
 * Coordinates are chosen at random on the 1/256 grid, off it, exactly half
 * way between two grid points (a snapping tie) or on a pixel centre. Depths
 * are positive and colours in [0, 1], so the triangle is a valid scene line. */
void random_tri(struct rng *r, enum tri_category c, int w, int h, struct vertex v[3]);

/* A vertex at (x, y) with depth 1 and a grey colour. */
struct vertex test_vertex(double x, double y);

/* --- running lessons -------------------------------------------------------- */

/* One variant of one lesson in one build. */
struct test_variant {
    const struct lesson *lesson;
    const struct lesson_variant *variant;
    bool narrated;              /* the narrated build (else the fast one) */
};

enum { BUILD_NARRATED = 1, BUILD_FAST = 2, BUILD_BOTH = 3 };

/* Every NON-exhibit variant of every lesson in the chosen builds. Writes at
 * most max entries and returns how many there are. */
int exact_variants(struct test_variant *out, int max, int builds);
#define MAX_TEST_VARIANTS 128

/* "02-barycentric/top-left (narrated)", written into buf; returns buf. */
const char *variant_label(const struct test_variant *tv, char *buf, size_t len);

/* The parameters a plain run uses (exact sub-pixel bits, default block size). */
struct raster_params default_params(void);

/* Run one triangle through a variant (params NULL = default_params()). */
void rasterize_one(const struct lesson_variant *v, const struct raster_params *p,
                   const struct tri_setup *t, struct target *fb, struct trace *tr);

/* Add reference_coverage() of t to a w x h mask of counts (saturating at 255). */
void reference_mask(const struct tri_setup *t, uint8_t *mask);
/* Coverage counts of a whole scene by the exact reference, triangle after
 * triangle (a fresh w x h array to free; NULL when out of memory). */
uint8_t *reference_scene(const struct scene *s);
/* Does every pixel fb covers have the reference's perspective-correct
 * colour of triangle t within `tolerance` levels per channel, and its depth
 * within depth_rel of it? The number of pixels compared, or -1 with the
 * first that is not in why. */
int reference_shading_check(const struct target *fb, const struct tri_setup *t, int tolerance,
                            double depth_rel, char *why, size_t n);

/* What a failure message says about the case. */
struct case_info {
    const char *what;           /* e.g. the variant label and the category */
    uint64_t seed, index;       /* replay: TRISTEP_SEED and the case number */
    const struct vertex *v;     /* the triangle(s), may be NULL */
    int nv;                     /* number of vertices in v (3 per triangle) */
};

/* Compare coverage counts with the expected ones. On a difference prints the
 * case (seed, number, vertices with %.17g) and the neighbourhood of the
 * first differing pixel as ASCII art, expected beside actual, then returns
 * false. Use it as cr_assert(coverage_equal(...)). */
bool coverage_equal(const uint8_t *expected, const uint8_t *actual, int w, int h,
                    const struct case_info *info);

/* Print the case alone (for failures that are not a picture). */
void print_case(const struct case_info *info);

/* --- narration ------------------------------------------------------------------ */

/* Every event of a run, kept: a trace sink (`.sink = test_collect,
 * .ctx = &events`); free(events.ev) after. */
struct test_events {
    struct trace_event *ev;
    size_t n, cap;
};
void test_collect(void *ctx, const struct trace_event *ev);

/* --- numbers the texts quote ---------------------------------------------------
 *
 * A count a lesson text quotes carries a marker right after it, invisible
 * in the rendered page:
 *
 *     differs from the exact coverage on **97**<!--=l01.float.differ--> pixels
 *
 * The number is what stands before the marker (bold or code marks skipped,
 * thousands separated by commas). tests/test_texts.c recomputes every marked
 * number of every text from the program and fails when one disagrees. */

/* A whole text file, NUL-terminated (static storage, valid until the next
 * call); fails the test when it cannot be read. */
const char *test_read_text(const char *path);
/* The number quoted before the first marker `key` in `path` (aborting the
 * test when there is none); *tol (if not NULL) gets half a unit of its last
 * digit, the rounding it was quoted with. */
double text_number(const char *path, const char *key, double *tol);
/* The number written right before position m of text (bold and code marks
 * skipped, commas dropped), NAN when there is none; *tol as above. */
double number_before(const char *text, const char *m, double *tol);

/* --- programs ----------------------------------------------------------------- */

/* The build directory ($TRISTEP_BUILD, "build" when unset). */
const char *test_build_dir(void);

/* --- a scratch folder ---------------------------------------------------------
 *
 * A fresh folder /tmp/tristep-test-XXXXXX for one test, made and removed
 * around it: Test(suite, name, .init = test_scratch_make, .fini = test_scratch_remove).
 * Failures abort the test. */
void test_scratch_make(void);
void test_scratch_remove(void);
/* the folder itself */
const char *test_scratch_dir(void);
/* folder/name (static storage, four buffers used in turn) */
const char *test_scratch_path(const char *name);
/* Write n bytes (or a text, test_scratch_text) to folder/name. */
void test_scratch_put(const char *name, const void *data, size_t n);
void test_scratch_text(const char *name, const char *text);

#endif
