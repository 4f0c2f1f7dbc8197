/* test_texts.c - the numbers the course's texts quote are the program's.
 *
 * Every count a lesson text or answer key quotes (exhibit pixels, operations
 * per pixel, pixels tested and covered, steps) carries a marker right after
 * it, <!--=key--> (see testlib.h). Here each key is recomputed from the
 * lessons themselves, against the exact reference where it is a count of
 * wrong pixels, so a change of code or scene that moves a number fails until
 * the text is updated. The test also fails on a marker it does not know and
 * on a known number that no text quotes any more.
 *
 * Speeds are the bench's alone: a text may quote a speed (Mpix/s, Mtri/s,
 * ms, a factor "x faster") only if BENCH.md, which `make bench` writes, has
 * that very figure.
 */
#include <criterion/criterion.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "testlib.h"
#include "util/file.h"
#include "explore/explorer.h"
#include "explore/replay.h"

extern const struct lesson lesson_01, lesson_02, lesson_03, lesson_04, lesson_05, lesson_06, lesson_08;

/* The texts whose numbers are checked: the top README, the course page, and
 * every lesson's text and answer key (built from the lessons that exist). */
#define MAX_TEXTS 64
static int text_list(char out[][128])
{
    int n = 0;
    snprintf(out[n++], 128, "README.md");
    snprintf(out[n++], 128, "lessons/README.md");
    for (int i = 0; all_lessons[i] && n + 2 <= MAX_TEXTS; i++) {
        snprintf(out[n++], 128, "lessons/%s/README.md", all_lessons[i]->id);
        snprintf(out[n++], 128, "lessons/%s/ANSWERS.md", all_lessons[i]->id);
    }
    return n;
}

static bool exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f)
        fclose(f);
    return f != NULL;
}

/* --- running lessons ------------------------------------------------------------- */

static struct scene load(const char *name)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, name, err, sizeof err), "%s", err);
    return s;
}

/* How a variant's coverage of a scene differs from the reference, per pixel. */
struct tally {
    long covered;       /* the reference's coverage, summed */
    long wrong;         /* pixels whose count differs */
    long extra_px;      /* pixels with more than the reference (the explorer's magenta) */
    long missing_px;    /* pixels with less (cyan) */
    long extra_writes;  /* coverage beyond the reference, summed */
    long missing_writes;
    long outside;       /* pixels the reference leaves empty, drawn */
    long holes;         /* pixels the reference covers, drawn fewer times */
    long doubled;       /* pixels the reference covers, drawn more times */
    long twice;         /* pixels drawn twice or more */
};

static struct tally compare(const char *scene, const struct lesson *l, const char *variant,
                            int block_size)
{
    struct scene s = load(scene);
    const struct lesson_variant *v = variant ? lesson_variant(l, variant) : &l->variants[0];
    cr_assert_not_null(v, "%s has no variant %s", l->id, variant);
    struct raster_params p = default_params();
    cr_assert(!block_size || lesson_param_set(l, &p, "block-size", block_size));
    struct target fb;
    cr_assert(render_scene(&s, v, &p, &fb));
    uint8_t *ref = reference_scene(&s);
    cr_assert_not_null(ref);
    struct tally c = { 0 };
    for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++) {
        int want = ref[i], got = fb.count[i];
        c.covered += want;
        c.wrong += got != want;
        c.extra_px += got > want;
        c.missing_px += got < want;
        c.extra_writes += got > want ? got - want : 0;
        c.missing_writes += got < want ? want - got : 0;
        c.outside += want == 0 && got > 0;
        c.holes += want > 0 && got < want;
        c.doubled += want > 0 && got > want;
        c.twice += got >= 2;
    }
    free(ref);
    target_free(&fb);
    scene_free(&s);
    return c;
}

/* Counters of a whole scene run with narration, and its events. */
static struct trace_counters narrate(const char *scene, const struct lesson *l, int block_size,
                                     struct test_events *out)
{
    struct scene s = load(scene);
    struct raster_params p = default_params();
    cr_assert(!block_size || lesson_param_set(l, &p, "block-size", block_size));
    struct target fb;
    cr_assert(target_init(&fb, s.w, s.h, scene_background(&s)));
    struct trace_counters sum = { 0 };
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        struct trace tr = { .sink = out ? test_collect : NULL, .ctx = out };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        l->variants[0].rasterize(&t, &p, &fb, &tr);
        sum.tested += tr.c.tested;
        sum.covered += tr.c.covered;
        sum.written += tr.c.written;
        sum.rows += tr.c.rows;
        sum.spans += tr.c.spans;
        sum.mul += tr.c.mul;
        sum.add += tr.c.add;
        for (int k = 0; k < BLOCK_CLASS_COUNT; k++)
            sum.blocks[k] += tr.c.blocks[k];
    }
    target_free(&fb);
    scene_free(&s);
    return sum;
}

/* --- costs per pixel, per row, per triangle, read from the narration ---------------
 *
 * The counters a lesson declares (COUNT_OPS) ride on every event. Between two
 * pixel tests of a row the difference is the cost of one tested pixel, plus
 * that of a covered one when the first was covered; between two rows it is
 * the row's pixels plus the cost of a row. What is left of the triangle's
 * total is the cost of the triangle. Each cost is the value most events
 * agree on (a row that changes edge in lesson 01 pays a setup more). */

struct costs {
    long mul_test, add_test;        /* per pixel tested (lesson 01: per pixel written) */
    long mul_cov, add_cov;          /* more per pixel covered */
    long mul_row, add_row;          /* per row */
    long mul_tri, add_tri;          /* per triangle */
};

#define MODE_MAX 64
struct mode { long v[MODE_MAX]; int n[MODE_MAX]; int k; };

static void mode_add(struct mode *m, long v)
{
    for (int i = 0; i < m->k; i++)
        if (m->v[i] == v) {
            m->n[i]++;
            return;
        }
    if (m->k < MODE_MAX) {
        m->v[m->k] = v;
        m->n[m->k++] = 1;
    }
}

static long mode_of(const struct mode *m)
{
    int best = 0;
    for (int i = 1; i < m->k; i++)
        if (m->n[i] > m->n[best])
            best = i;
    cr_assert_gt(m->k, 0, "no sample to take a cost from");
    return m->v[best];
}

static struct costs costs_of(const struct lesson *l, const char *scene)
{
    struct test_events e = { 0 };
    struct trace_counters total = narrate(scene, l, 0, &e);
    /* pixel events: tests, or writes when the lesson tests nothing (01) */
    int px_kind = total.tested ? TRACE_PIXEL_TEST : TRACE_PIXEL_WRITE;
    struct mode mt = { 0 }, at = { 0 }, mc = { 0 }, ac = { 0 }, mr = { 0 }, ar = { 0 };
    struct costs c = { 0 };
    /* per pixel */
    const struct trace_event *prev = NULL;
    for (size_t i = 0; i < e.n; i++) {
        const struct trace_event *ev = &e.ev[i];
        if (ev->kind == TRACE_ROW || ev->kind == TRACE_SETUP || ev->kind == TRACE_SPAN)
            prev = NULL;
        if (ev->kind != px_kind)
            continue;
        if (prev && prev->tri == ev->tri && !(prev->flags & TRACE_INSIDE))
            mode_add(&mt, (long)(ev->mul - prev->mul)), mode_add(&at, (long)(ev->add - prev->add));
        prev = ev;
    }
    c.mul_test = mode_of(&mt);
    c.add_test = mode_of(&at);
    if (px_kind == TRACE_PIXEL_WRITE) {
        /* lesson 01 writes without testing: every pixel is a covered one */
        mc.k = ac.k = 1;
        mc.v[0] = ac.v[0] = 0;
        mc.n[0] = ac.n[0] = 1;
    }
    prev = NULL;
    for (size_t i = 0; i < e.n && px_kind == TRACE_PIXEL_TEST; i++) {
        const struct trace_event *ev = &e.ev[i];
        if (ev->kind == TRACE_ROW || ev->kind == TRACE_SETUP)
            prev = NULL;
        if (ev->kind != TRACE_PIXEL_TEST)
            continue;
        if (prev && prev->tri == ev->tri && (prev->flags & TRACE_INSIDE)) {
            mode_add(&mc, (long)(ev->mul - prev->mul) - c.mul_test);
            mode_add(&ac, (long)(ev->add - prev->add) - c.add_test);
        }
        prev = ev;
    }
    c.mul_cov = mode_of(&mc);
    c.add_cov = mode_of(&ac);
    /* per row: from one row event to the next, less the row's pixels */
    const struct trace_event *row = NULL;
    long pixels = 0, covered = 0;
    for (size_t i = 0; i < e.n; i++) {
        const struct trace_event *ev = &e.ev[i];
        if (ev->kind == TRACE_SETUP)
            row = NULL;
        if (ev->kind == TRACE_ROW) {
            if (row && row->tri == ev->tri) {
                long px_mul = pixels * c.mul_test + covered * c.mul_cov;
                long px_add = pixels * c.add_test + covered * c.add_cov;
                mode_add(&mr, (long)(ev->mul - row->mul) - px_mul);
                mode_add(&ar, (long)(ev->add - row->add) - px_add);
            }
            row = ev;
            pixels = covered = 0;
        }
        if (ev->kind == px_kind) {
            pixels++;
            covered += px_kind == TRACE_PIXEL_TEST && (ev->flags & TRACE_INSIDE);
        }
    }
    c.mul_row = mode_of(&mr);
    c.add_row = mode_of(&ar);
    long npx = (long)(px_kind == TRACE_PIXEL_TEST ? total.tested : total.written);
    struct scene s = load(scene);
    c.mul_tri = ((long)total.mul - npx * c.mul_test - (long)total.covered * c.mul_cov
                 - (long)total.rows * c.mul_row) / s.ntris;
    c.add_tri = ((long)total.add - npx * c.add_test - (long)total.covered * c.add_cov
                 - (long)total.rows * c.add_row) / s.ntris;
    scene_free(&s);
    free(e.ev);
    return c;
}

/* --- the keys ------------------------------------------------------------------------ */

static double strip_triangles(void)
{
    struct scene s = load("offgrid-strip");
    int n = s.ntris;
    scene_free(&s);
    return n;
}

static double l01_strip_covered(void) { return compare("offgrid-strip", &lesson_01, NULL, 0).covered; }
static double l01_float_differ(void) { return compare("offgrid-strip", &lesson_01, "source-float", 0).wrong; }
static double l01_float_outside(void) { return compare("offgrid-strip", &lesson_01, "source-float", 0).outside; }
static double l01_float_holes(void) { return compare("offgrid-strip", &lesson_01, "source-float", 0).holes; }
static double l01_float_doubled(void) { return compare("offgrid-strip", &lesson_01, "source-float", 0).doubled; }
static double l01_float_extra(void) { return compare("offgrid-strip", &lesson_01, "source-float", 0).extra_px; }
static double l01_add_pixel(void) { return costs_of(&lesson_01, "cases-a-b").add_test; }
static double l01_mul_row(void) { return costs_of(&lesson_01, "cases-a-b").mul_row; }
static double l01_add_row(void) { return costs_of(&lesson_01, "cases-a-b").add_row; }

static double l02_square(void) { return compare("shared-edge", &lesson_02, NULL, 0).covered; }
static double l02_incl_wrong(void) { return compare("shared-edge", &lesson_02, "inclusive", 0).wrong; }
static double l02_incl_writes(void) { return compare("shared-edge", &lesson_02, "inclusive", 0).extra_writes; }
static double l02_incl_doubled(void) { return compare("shared-edge", &lesson_02, "inclusive", 0).twice; }
static double l02_strict_missing(void) { return compare("shared-edge", &lesson_02, "strict", 0).missing_writes; }

/* Strict: the crack on the diagonal x == y, pixels no triangle draws. */
static double l02_strict_diagonal(void)
{
    struct scene s = load("shared-edge");
    struct raster_params p = default_params();
    struct target fb;
    cr_assert(render_scene(&s, lesson_variant(&lesson_02, "strict"), &p, &fb));
    uint8_t *ref = reference_scene(&s);
    cr_assert_not_null(ref);
    long n = 0;
    for (int i = 0; i < s.w && i < s.h; i++) {
        size_t k = (size_t)i * (size_t)s.w + (size_t)i;
        n += ref[k] > fb.count[k];
    }
    free(ref);
    target_free(&fb);
    scene_free(&s);
    return n;
}

static double l02_mul_test(void) { return costs_of(&lesson_02, "triangle").mul_test; }
static double l02_add_test(void) { return costs_of(&lesson_02, "triangle").add_test; }
static double l02_mul_cov(void) { return costs_of(&lesson_02, "triangle").mul_cov; }
static double l02_add_cov(void) { return costs_of(&lesson_02, "triangle").add_cov; }

static double l03_mul_test(void) { return costs_of(&lesson_03, "edge-steps").mul_test; }
static double l03_add_test(void) { return costs_of(&lesson_03, "edge-steps").add_test; }
static double l03_mul_cov(void) { return costs_of(&lesson_03, "edge-steps").mul_cov; }
static double l03_add_cov(void) { return costs_of(&lesson_03, "edge-steps").add_cov; }
static double l03_mul_row(void) { return costs_of(&lesson_03, "edge-steps").mul_row; }
static double l03_add_row(void) { return costs_of(&lesson_03, "edge-steps").add_row; }
static double l03_mul_tri(void) { return costs_of(&lesson_03, "edge-steps").mul_tri; }
static double l03_add_tri(void) { return costs_of(&lesson_03, "edge-steps").add_tri; }

static double l03_steps_tested(void) { return (double)narrate("edge-steps", &lesson_03, 0, NULL).tested; }
static double l03_steps_covered(void) { return (double)narrate("edge-steps", &lesson_03, 0, NULL).covered; }
static double l03_steps_rows(void) { return (double)narrate("edge-steps", &lesson_03, 0, NULL).rows; }
static double l03_steps_l02_mul(void) { return (double)narrate("edge-steps", &lesson_02, 0, NULL).mul; }
static double l03_steps_l02_add(void) { return (double)narrate("edge-steps", &lesson_02, 0, NULL).add; }
static double l03_steps_l03_mul(void) { return (double)narrate("edge-steps", &lesson_03, 0, NULL).mul; }
static double l03_steps_l03_add(void) { return (double)narrate("edge-steps", &lesson_03, 0, NULL).add; }
static double l03_drift_l02_mul(void) { return (double)narrate("float-drift", &lesson_02, 0, NULL).mul; }
static double l03_drift_l03_mul(void) { return (double)narrate("float-drift", &lesson_03, 0, NULL).mul; }

/* The float exhibit, one triangle at a time against the reference: wrong
 * decisions of triangle `which` (-1: all), and the centres exactly on its
 * right and bottom edges (where the -1 bias is what rounds away). */
struct float_tally { long wrong, extra, on_dropped; };

static struct float_tally float_exhibit(int which)
{
    struct scene s = load("float-drift");
    const struct lesson_variant *fl = lesson_variant(&lesson_03, "float");
    cr_assert_not_null(fl);
    struct raster_params p = default_params();
    struct float_tally c = { 0 };
    for (int i = 0; i < s.ntris; i++) {
        if (which >= 0 && i != which)
            continue;
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        struct target fb;
        cr_assert(target_init(&fb, s.w, s.h, 0));
        fl->rasterize(&t, &p, &fb, NULL);
        uint8_t *ref = calloc((size_t)s.w * (size_t)s.h, 1);
        cr_assert_not_null(ref);
        reference_mask(&t, ref);
        for (int y = t.miny; y <= t.maxy; y++)
            for (int x = t.minx; x <= t.maxx; x++) {
                size_t k = (size_t)y * (size_t)s.w + (size_t)x;
                c.wrong += fb.count[k] != ref[k];
                c.extra += fb.count[k] > ref[k];
                bool dropped = false;
                for (int e = 0; e < 3; e++)
                    dropped |= edge_value(&t, e, x, y) == 0 && t.bias[e] == -1;
                c.on_dropped += dropped;
            }
        free(ref);
        target_free(&fb);
    }
    scene_free(&s);
    return c;
}

static double l03_float_wrong(void) { return float_exhibit(-1).wrong; }
static double l03_float_first(void) { return float_exhibit(0).extra; }
static double l03_float_first_edges(void) { return float_exhibit(0).on_dropped; }
static double l03_float_second(void) { return float_exhibit(1).extra; }
static double l03_float_pixels(void) { return compare("float-drift", &lesson_03, "float", 0).wrong; }
static double l03_float_extra_px(void) { return compare("float-drift", &lesson_03, "float", 0).extra_px; }
static double l03_float_twice(void) { return compare("float-drift", &lesson_03, "float", 0).twice; }

static double l05_corners_missing(void)
{
    return compare("blocks-exhibits", &lesson_05, "corners-outside", 0).missing_px;
}
static double l05_or_extra(void) { return compare("blocks-exhibits", &lesson_05, "or-inside", 0).extra_px; }

static double blocks_of(int q, int klass)
{
    return (double)narrate("blocks", &lesson_05, q, NULL).blocks[klass];
}
static double l05_q4_empty(void) { return blocks_of(4, BLOCK_EMPTY); }
static double l05_q4_full(void) { return blocks_of(4, BLOCK_FULL); }
static double l05_q4_partial(void) { return blocks_of(4, BLOCK_PARTIAL); }
static double l05_q8_empty(void) { return blocks_of(8, BLOCK_EMPTY); }
static double l05_q8_full(void) { return blocks_of(8, BLOCK_FULL); }
static double l05_q8_partial(void) { return blocks_of(8, BLOCK_PARTIAL); }
static double l05_q16_empty(void) { return blocks_of(16, BLOCK_EMPTY); }
static double l05_q16_full(void) { return blocks_of(16, BLOCK_FULL); }
static double l05_q16_partial(void) { return blocks_of(16, BLOCK_PARTIAL); }
static double blocks_all(int q)
{
    return blocks_of(q, BLOCK_EMPTY) + blocks_of(q, BLOCK_FULL) + blocks_of(q, BLOCK_PARTIAL);
}
static double l05_q4_blocks(void) { return blocks_all(4); }
static double l05_q8_blocks(void) { return blocks_all(8); }
static double l05_q16_blocks(void) { return blocks_all(16); }
static double l05_q4_tested(void) { return (double)narrate("blocks", &lesson_05, 4, NULL).tested; }
static double l05_q8_tested(void) { return (double)narrate("blocks", &lesson_05, 8, NULL).tested; }
static double l05_q16_tested(void) { return (double)narrate("blocks", &lesson_05, 16, NULL).tested; }
static double l05_blocks_covered(void) { return (double)narrate("blocks", &lesson_05, 8, NULL).covered; }
static double l05_l02_tested(void) { return (double)narrate("blocks", &lesson_02, 0, NULL).tested; }

static double l01_mul_tri(void) { return costs_of(&lesson_01, "cases-a-b").mul_tri; }
static double l01_add_tri(void) { return costs_of(&lesson_01, "cases-a-b").add_tri; }

static double l03_drift_tested(void) { return (double)narrate("float-drift", &lesson_03, 0, NULL).tested; }
static double l03_drift_covered(void) { return (double)narrate("float-drift", &lesson_03, 0, NULL).covered; }
/* additions saved by stepping the attributes only over covered pixels:
 * the attribute steps (all but the three edge steps) of every pixel not covered */
static double l03_drift_saved(void)
{
    struct trace_counters c = narrate("float-drift", &lesson_03, 0, NULL);
    return (double)((c.tested - c.covered) * (uint64_t)(costs_of(&lesson_03, "edge-steps").add_test - 3));
}

/* Lesson 04's floor: pixels in the bounding boxes (the source's layout
 * computes four lanes for each), lanes of the row4 layout (groups of four
 * from minX, the last one past maxX masked), pixels covered. */
struct floor_lanes { long box, row4_lanes, covered; };

static struct floor_lanes floor_lanes(void)
{
    struct scene s = load("floor");
    struct floor_lanes f = { 0 };
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        long w = t.maxx - t.minx + 1, h = t.maxy - t.miny + 1;
        f.box += w * h;
        f.row4_lanes += 4 * ((w + 3) / 4) * h;
    }
    scene_free(&s);
    f.covered = (long)narrate("floor", &lesson_04, 0, NULL).covered;
    return f;
}
static double l04_floor_box(void) { return floor_lanes().box; }
static double l04_floor_box_lanes(void) { return 4.0 * floor_lanes().box; }
static double l04_floor_row4(void) { return floor_lanes().row4_lanes; }
static double l04_floor_covered(void) { return floor_lanes().covered; }

/* The explorer's own count of an exhibit's pixels covered as the exact rule
 * says but with a colour or depth off (what its panel and figure show), at
 * the end of the scene s (its screen triangles). */
static double explorer_wrong_colour(const struct lesson *l, struct scene *s, const char *name,
                                    const struct lesson_variant *v)
{
    struct raster_params prm = default_params();
    prm.at = &(struct run_place){ .scene = s };
    struct explorer ex;
    char err[256];
    struct explorer_desc d = { .lesson = l, .scene = s, .scene_name = name, .variant = v,
                               .params = &prm, .step_end = true };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    double n = (double)ex.wrong_colour;
    explorer_free(&ex);
    return n;
}

static double l01_float_colour(void)
{
    struct scene s = load("offgrid-strip");
    double n = explorer_wrong_colour(&lesson_01, &s, "offgrid-strip", lesson_variant(&lesson_01, "source-float"));
    scene_free(&s);
    return n;
}

/* The sample counts lesson 08's make check draws at, in order. */
static double l08_check_first(void)
{
    return lesson_08.exercise.samples ? lesson_08.exercise.samples[0] : NAN;
}

static double l08_check_second(void)
{
    return lesson_08.exercise.samples && lesson_08.exercise.samples[0] ? lesson_08.exercise.samples[1] : NAN;
}

/* Lesson 06: a 3-D scene through the lesson's front end (variant `variant`),
 * its screen triangles; the world triangles stay in s.world. */
static struct scene load06(const char *name, const char *variant, const struct lesson_variant **out)
{
    struct scene s = load(name);
    const struct lesson_variant *v = lesson_variant(&lesson_06, variant);
    cr_assert_not_null(v, "lesson 06 has no variant %s", variant);
    cr_assert(lesson_front(&lesson_06, v)(&s));
    if (out)
        *out = v;
    return s;
}

/* Pixels of the closed room that a variant does not cover exactly once
 * (missing_only: those it does not cover at all). */
static double l06_room_not_once(const char *variant, bool missing_only)
{
    const struct lesson_variant *v;
    struct scene s = load06("room", variant, &v);
    struct raster_params p = default_params();
    p.at = &(struct run_place){ .scene = &s };
    struct target fb;
    cr_assert(render_scene(&s, v, &p, &fb));
    long n = 0;
    for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++)
        n += missing_only ? fb.count[i] == 0 : fb.count[i] != 1;
    target_free(&fb);
    scene_free(&s);
    return (double)n;
}

static double l06_count(const char *name, int what)
{
    struct scene s = load06(name, "clip", NULL);
    double n = what == 0 ? s.world.ntris : what == 1 ? s.ntris : (double)s.w * s.h;
    scene_free(&s);
    return n;
}
static double l06_room_world(void) { return l06_count("room", 0); }
static double l06_room_screen(void) { return l06_count("room", 1); }
static double l06_room_pixels(void) { return l06_count("room", 2); }
static double l06_model_world(void) { return l06_count("model", 0); }
static double l06_model_screen(void) { return l06_count("model", 1); }
static double l06_pair_pixels(void) { return l06_count("depth-pair", 2); }
static double l06_project_first(void) { return l06_room_not_once("project-first", false); }
static double l06_no_guard_missing(void) { return l06_room_not_once("no-guard-32", true); }

/* The explorer's count of wrong colours at the end of the exhibit ndc24 on
 * builtin:depth-pair. */
static double l06_wrong(const char *scene, const char *variant)
{
    const struct lesson_variant *v;
    struct scene s = load06(scene, variant, &v);
    double n = explorer_wrong_colour(&lesson_06, &s, scene, v);
    scene_free(&s);
    return n;
}
static double l06_ndc24_wrong(void) { return l06_wrong("depth-pair", "ndc24"); }
/* ... and of no-guard-32 on builtin:room */
static double l06_no_guard_wrong(void) { return l06_wrong("room", "no-guard-32"); }

/* Lesson 08's exercise 4: the pixels of builtin:samples where a triangle
 * covers a sample at N = 4 but not the centre (where centroid shading
 * moves the point the colour is taken at), per triangle; a pixel of a
 * shared edge counts for each triangle. */
static double l08_centroid_pixels(void)
{
    struct scene s = load("samples");
    const struct sample_pattern *sp = sample_pattern(4);
    cr_assert_not_null(sp);
    long n = 0;
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        if (!tri_setup(&t, s.tris[i].v, s.w, s.h))
            continue;
        for (int y = 0; y < s.h; y++)
            for (int x = 0; x < s.w; x++) {
                bool any = false;
                for (int k = 0; k < sp->n; k++)
                    any |= reference_point_covered(&t, 256 * (int64_t)x + sp->x[k], 256 * (int64_t)y + sp->y[k]);
                n += any && !reference_point_covered(&t, 256 * (int64_t)x + 128, 256 * (int64_t)y + 128);
            }
    }
    scene_free(&s);
    return (double)n;
}

struct key {
    const char *key;
    double (*compute)(void);    /* NULL: checked by the test file named in `where` */
    const char *where;
};

static const struct key keys[] = {
    { "l01.strip.triangles", strip_triangles, NULL },
    { "l01.strip.covered", l01_strip_covered, NULL },
    { "l01.float.differ", l01_float_differ, NULL },
    { "l01.float.outside", l01_float_outside, NULL },
    { "l01.float.holes", l01_float_holes, NULL },
    { "l01.float.doubled", l01_float_doubled, NULL },
    { "l01.float.extra", l01_float_extra, NULL },
    { "l01.float.colour", l01_float_colour, NULL },
    { "l01.add-per-pixel", l01_add_pixel, NULL },
    { "l01.mul-per-row", l01_mul_row, NULL },
    { "l01.add-per-row", l01_add_row, NULL },
    { "l01.mul-per-triangle", l01_mul_tri, NULL },
    { "l01.add-per-triangle", l01_add_tri, NULL },

    { "l02.square.covered", l02_square, NULL },
    { "l02.inclusive.wrong", l02_incl_wrong, NULL },
    { "l02.inclusive.writes", l02_incl_writes, NULL },
    { "l02.inclusive.doubled", l02_incl_doubled, NULL },
    { "l02.strict.missing", l02_strict_missing, NULL },
    { "l02.strict.diagonal", l02_strict_diagonal, NULL },
    { "l02.mul-per-test", l02_mul_test, NULL },
    { "l02.add-per-test", l02_add_test, NULL },
    { "l02.mul-per-covered", l02_mul_cov, NULL },
    { "l02.add-per-covered", l02_add_cov, NULL },

    { "l03.mul-per-test", l03_mul_test, NULL },
    { "l03.add-per-test", l03_add_test, NULL },
    { "l03.mul-per-covered", l03_mul_cov, NULL },
    { "l03.add-per-covered", l03_add_cov, NULL },
    { "l03.mul-per-row", l03_mul_row, NULL },
    { "l03.add-per-row", l03_add_row, NULL },
    { "l03.mul-per-triangle", l03_mul_tri, NULL },
    { "l03.add-per-triangle", l03_add_tri, NULL },
    { "l03.steps.tested", l03_steps_tested, NULL },
    { "l03.steps.covered", l03_steps_covered, NULL },
    { "l03.steps.rows", l03_steps_rows, NULL },
    { "l03.steps.l02-mul", l03_steps_l02_mul, NULL },
    { "l03.steps.l02-add", l03_steps_l02_add, NULL },
    { "l03.steps.l03-mul", l03_steps_l03_mul, NULL },
    { "l03.steps.l03-add", l03_steps_l03_add, NULL },
    { "l03.drift.l02-mul", l03_drift_l02_mul, NULL },
    { "l03.drift.l03-mul", l03_drift_l03_mul, NULL },
    { "l03.float.wrong", l03_float_wrong, NULL },
    { "l03.float.first", l03_float_first, NULL },
    { "l03.float.first-edges", l03_float_first_edges, NULL },
    { "l03.float.second", l03_float_second, NULL },
    { "l03.float.pixels", l03_float_pixels, NULL },
    { "l03.float.extra-px", l03_float_extra_px, NULL },
    { "l03.float.twice", l03_float_twice, NULL },
    { "l03.drift.tested", l03_drift_tested, NULL },
    { "l03.drift.covered", l03_drift_covered, NULL },
    { "l03.drift.saved-adds", l03_drift_saved, NULL },
    { "l03.large.extra", NULL, "tests/test_lesson03.c" },
    { "l03.large.missing", NULL, "tests/test_lesson03.c" },

    { "l04.affine.worst", NULL, "tests/test_lesson04.c" },
    { "l04.floor.box", l04_floor_box, NULL },
    { "l04.floor.box-lanes", l04_floor_box_lanes, NULL },
    { "l04.floor.row4-lanes", l04_floor_row4, NULL },
    { "l04.floor.covered", l04_floor_covered, NULL },
    { "l04.perspective.worst", NULL, "tests/test_lesson04.c" },

    { "l05.corners-outside.missing", l05_corners_missing, NULL },
    { "l05.or-inside.extra", l05_or_extra, NULL },
    { "l05.q4.empty", l05_q4_empty, NULL },
    { "l05.q4.full", l05_q4_full, NULL },
    { "l05.q4.partial", l05_q4_partial, NULL },
    { "l05.q8.empty", l05_q8_empty, NULL },
    { "l05.q8.full", l05_q8_full, NULL },
    { "l05.q8.partial", l05_q8_partial, NULL },
    { "l05.q16.empty", l05_q16_empty, NULL },
    { "l05.q16.full", l05_q16_full, NULL },
    { "l05.q16.partial", l05_q16_partial, NULL },
    { "l05.q4.blocks", l05_q4_blocks, NULL },
    { "l05.q8.blocks", l05_q8_blocks, NULL },
    { "l05.q16.blocks", l05_q16_blocks, NULL },
    { "l05.q4.tested", l05_q4_tested, NULL },
    { "l05.q8.tested", l05_q8_tested, NULL },
    { "l05.q16.tested", l05_q16_tested, NULL },
    { "l05.blocks.covered", l05_blocks_covered, NULL },
    { "l05.l02.tested", l05_l02_tested, NULL },
    { "l07.wrong-corner.missing", NULL, "tests/test_lesson07.c" },
    { "l07.exhibits.covered", NULL, "tests/test_lesson07.c" },
    { "l07.unordered.diff2", NULL, "tests/test_lesson07.c" },
    { "l07.unordered.diff3", NULL, "tests/test_lesson07.c" },
    { "l07.unordered.diff23", NULL, "tests/test_lesson07.c" },
    { "l08.mul.msaa1", NULL, "tests/test_lesson08.c" },
    { "l08.mul.msaa4", NULL, "tests/test_lesson08.c" },
    { "l08.mul.msaa8", NULL, "tests/test_lesson08.c" },
    { "l08.mul.ssaa4", NULL, "tests/test_lesson08.c" },
    { "l08.mul.ssaa8", NULL, "tests/test_lesson08.c" },
    { "l08.sliver.off1", NULL, "tests/test_lesson08.c" },
    { "l08.horizontal.off1", NULL, "tests/test_lesson08.c" },
    { "l08.sliver.worst1", NULL, "tests/test_lesson08.c" },
    { "l08.sliver.off8n", NULL, "tests/test_lesson08.c" },
    { "l08.horizontal.odd", NULL, "tests/test_lesson08.c" },
    { "l08.vertical.odd", NULL, "tests/test_lesson08.c" },
    { "l08.grid.off", NULL, "tests/test_lesson08.c" },
    { "l08.grid.worst", NULL, "tests/test_lesson08.c" },
    { "l08.fill.doubled", NULL, "tests/test_lesson08.c" },
    { "l08.fill.scene", NULL, "tests/test_lesson08.c" },
    { "l08.full1", NULL, "tests/test_lesson08.c" },
    { "l08.tent.changed", NULL, "tests/test_lesson08_resolve.c" },
    { "l08.tent.pixels", NULL, "tests/test_lesson08_resolve.c" },
    { "l08.check.first", l08_check_first, NULL },
    { "l08.centroid.pixels", l08_centroid_pixels, NULL },
    { "l08.check.second", l08_check_second, NULL },
    { "l06.room.world", l06_room_world, NULL },
    { "l06.room.screen", l06_room_screen, NULL },
    { "l06.room.pixels", l06_room_pixels, NULL },
    { "l06.model.world", l06_model_world, NULL },
    { "l06.model.screen", l06_model_screen, NULL },
    { "l06.depth-pair.pixels", l06_pair_pixels, NULL },
    { "l06.project-first.wrong", l06_project_first, NULL },
    { "l06.no-guard-32.missing", l06_no_guard_missing, NULL },
    { "l06.no-guard-32.wrong", l06_no_guard_wrong, NULL },
    { "l06.ndc24.wrong", l06_ndc24_wrong, NULL },
    { "l06.cracks.found", NULL, "tests/test_lesson06.c" },
    { "l06.cracks.first-seed", NULL, "tests/test_lesson06.c" },
    { "l06.cracks.doubled", NULL, "tests/test_lesson06.c" },
    { "l06.cracks.missed", NULL, "tests/test_lesson06.c" },
    { "l06.cracks.canonical", NULL, "tests/test_lesson06.c" },
    { "l08.full4", NULL, "tests/test_lesson08.c" },
    { "l08.full8", NULL, "tests/test_lesson08.c" },
    { "l08.tested1", NULL, "tests/test_lesson08.c" },
    { "l08.tested4", NULL, "tests/test_lesson08.c" },
    { "l09.floor.pixels", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.nomip.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.nomip.off16", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.floor.trilinear.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.floor.trilinear.off16", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.floor.aniso.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.affine.model.worst", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.affine.model.differ", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.affine.model.pixels", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.affine.floor.worst", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.affine.floor.differ", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.perpixel.level", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.perpixel.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.fine.level", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.wall.pixels", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.wall.trilinear.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.wall.aniso.error", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.wall.trilinear.off16", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.wall.aniso.off16", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.helpers.64", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.helpers.16", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.helpers.8", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.helpers.4", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.helpers.2", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.tiny.helpers", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.floor.helpers", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square3.shaded", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square3.helpers", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square4.shaded", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square4.helpers", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square4off.shaded", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.square4off.helpers", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.trilinear.lambda", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.aniso16.taps", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.aniso16.lambda", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.aniso4.taps", NULL, "tests/test_lesson09_exhibits.c" },
    { "l09.ans.aniso4.lambda", NULL, "tests/test_lesson09_exhibits.c" },
};

#define NKEYS (sizeof keys / sizeof keys[0])

static const struct key *find_key(const char *name, size_t len)
{
    for (size_t i = 0; i < NKEYS; i++)
        if (strlen(keys[i].key) == len && strncmp(keys[i].key, name, len) == 0)
            return &keys[i];
    return NULL;
}

/* Every marked number of every text equals the program's value (to the
 * precision it is quoted with); every marker names a known key. */
Test(texts, every_quoted_count_is_what_the_program_computes, .timeout = 120)
{
    static double value[NKEYS];
    static bool computed[NKEYS];
    int checked = 0;
    static char texts[MAX_TEXTS][128];
    int ntexts = text_list(texts);
    for (int t = 0; t < ntexts; t++) {
        if (!exists(texts[t]))
            continue;
        /* copy: text_number() reads the file again into the same buffer */
        const char *orig = test_read_text(texts[t]);
        char *text = malloc(strlen(orig) + 1);
        cr_assert_not_null(text);
        strcpy(text, orig);
        for (char *m = strstr(text, "<!--="); m; m = strstr(m + 1, "<!--=")) {
            char *name = m + 5, *end = strstr(name, "-->");
            cr_assert_not_null(end, "%s: unclosed marker", texts[t]);
            const struct key *k = find_key(name, (size_t)(end - name));
            cr_expect_not_null(k, "%s: unknown marker <!--=%.*s--> (add it to tests/test_texts.c)",
                               texts[t], (int)(end - name), name);
            if (!k || !k->compute)
                continue;
            size_t i = (size_t)(k - keys);
            if (!computed[i]) {
                value[i] = k->compute();
                computed[i] = true;
            }
            char key[128];
            snprintf(key, sizeof key, "%.*s", (int)(end - name), name);
            double tol;
            double quoted = number_before(text, m, &tol);
            cr_expect(!isnan(quoted), "%s: no number before <!--=%s-->", texts[t], key);
            cr_expect(fabs(quoted - value[i]) <= tol,
                      "%s quotes %g for %s, the program computes %.17g", texts[t], quoted, key,
                      value[i]);
            checked++;
        }
        free(text);
    }
    cr_expect_gt(checked, 40, "only %d quoted numbers found", checked);
}

#if !TRISTEP_NO_ANSWERS
/* A number worth quoting stays quoted: every key is in some text.
 * TRISTEP_PRINT_NUMBERS=1 prints every computable key's value (for writing
 * a text). */
Test(texts, every_known_number_is_quoted_somewhere, .timeout = 120)
{
    bool print = getenv("TRISTEP_PRINT_NUMBERS") != NULL;
    for (size_t i = 0; i < NKEYS; i++) {
        if (print && keys[i].compute)
            fprintf(stderr, "%-32s %.17g\n", keys[i].key, keys[i].compute());
        char marker[128];
        snprintf(marker, sizeof marker, "<!--=%s-->", keys[i].key);
        bool found = false;
        static char texts[MAX_TEXTS][128];
        int ntexts = text_list(texts);
        for (int t = 0; t < ntexts && !found; t++)
            found = exists(texts[t]) && strstr(test_read_text(texts[t]), marker) != NULL;
        cr_expect(found, "no text quotes %s any more: drop it from tests/test_texts.c", marker);
    }
}
#endif

/* --- one template for every lesson text ---------------------------------------------- */

/* The level-2 headings of a text, in order, each without its "## ". */
static int headings(const char *text, char out[][96], int max)
{
    int n = 0;
    bool code = false;
    for (const char *line = text; *line && n < max;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        if (len >= 3 && strncmp(line, "```", 3) == 0)
            code = !code;
        if (!code && len > 3 && strncmp(line, "## ", 3) == 0)
            snprintf(out[n++], 96, "%.*s", (int)(len - 3), line + 3);
        line += len + (end != NULL);
    }
    return n;
}

/* Goals, Run it, numbered sections 1, 2, ... , Exhibits, Exercises
 * (the "write it yourself" part may have a heading of its own), References. */
Test(texts, every_lesson_text_follows_the_template)
{
    int lessons = 0;
    for (int i = 0; all_lessons[i]; i++) {
        char path[256], answers[256];
        snprintf(path, sizeof path, "lessons/%s/README.md", all_lessons[i]->id);
        snprintf(answers, sizeof answers, "lessons/%s/ANSWERS.md", all_lessons[i]->id);
        static char h[64][96];
        int n = headings(test_read_text(path), h, 64), k = 0;
        cr_assert_geq(n, 6, "%s has %d sections", path, n);
        cr_expect_str_eq(h[k], "Goals", "%s: the first section is \"%s\", not Goals", path, h[k]);
        k++;
        cr_expect_str_eq(h[k], "Run it", "%s: the second section is \"%s\", not Run it", path, h[k]);
        k++;
        int number = 1;
        for (; k < n && isdigit((unsigned char)h[k][0]); k++, number++)
            cr_expect_eq(atoi(h[k]), number, "%s: section \"%s\" should be numbered %d", path,
                         h[k], number);
        cr_expect_gt(number, 2, "%s has fewer than two numbered sections", path);
        const char *rest[] = { "Exhibits", "Exercises", "References" };
        for (int r = 0; r < 3; r++) {
            if (r == 2 && k < n && strcmp(h[k], "Write it yourself") == 0)
                k++;
            cr_expect(k < n && strcmp(h[k], rest[r]) == 0, "%s: expected section %s, found \"%s\"",
                      path, rest[r], k < n ? h[k] : "(end)");
            k++;
        }
        cr_expect_eq(k, n, "%s: References must be the last section", path);
        /* the answer key sits beside it and the text links it */
#if !TRISTEP_NO_ANSWERS
        cr_expect(exists(answers), "%s has no answer key %s", all_lessons[i]->id, answers);
#endif
        cr_expect(strstr(test_read_text(path), "(ANSWERS.md)") != NULL, "%s does not link its "
                  "answer key", path);
        lessons++;
    }
    cr_expect_gt(lessons, 0);
}

/* The course page leads to every lesson and its answer key. */
Test(texts, the_course_page_lists_every_lesson_and_its_answer_key)
{
    const char *page = test_read_text("lessons/README.md");
    char *copy = malloc(strlen(page) + 1);
    cr_assert_not_null(copy);
    strcpy(copy, page);
    for (int i = 0; all_lessons[i]; i++) {
        char link[256];
        snprintf(link, sizeof link, "(%s/README.md)", all_lessons[i]->id);
        cr_expect(strstr(copy, link) != NULL, "lessons/README.md does not list %s", link);
        snprintf(link, sizeof link, "(%s/ANSWERS.md)", all_lessons[i]->id);
        cr_expect(strstr(copy, link) != NULL, "lessons/README.md does not link %s", link);
    }
    free(copy);
}

/* The top README leads to the course page and to every answer key. */
Test(texts, the_top_readme_links_the_course_page_and_the_answer_keys)
{
    const char *readme = test_read_text("README.md");
    cr_expect(strstr(readme, "(lessons/README.md)") != NULL, "README.md does not link the course page");
    char *copy = malloc(strlen(readme) + 1);
    cr_assert_not_null(copy);
    strcpy(copy, readme);
    for (int i = 0; all_lessons[i]; i++) {
        char link[256];
        snprintf(link, sizeof link, "(lessons/%s/ANSWERS.md)", all_lessons[i]->id);
        cr_expect(strstr(copy, link) != NULL, "README.md does not link %s", link);
    }
    free(copy);
}

/* --- speeds come from the bench alone ------------------------------------------------ */

/* Units a speed is quoted in (as a lesson text would write them). */
static const char *const speed_units[] = {
    "Mpix/s", "Mpixels/s", "Mtri/s", "Mtriangles/s", "GB/s", "Gpix/s", "ms", "ns",
    "x faster", "x slower", "times faster", "times slower", "x llvmpipe", "x lesson",
    "fps", "frames per second",
};

/* Every number quoted with a unit of speed in a text appears in BENCH.md,
 * which only `make bench` writes. */
Test(texts, every_speed_a_text_quotes_is_the_benchs)
{
    cr_assert(exists("tests/bench/BENCH.md"), "BENCH.md is missing: run make bench");
    const char *orig = test_read_text("tests/bench/BENCH.md");
    char *bench = malloc(strlen(orig) + 1);
    cr_assert_not_null(bench);
    strcpy(bench, orig);
    cr_expect(strstr(bench, "written by `make bench`") != NULL, "BENCH.md was not written by the bench");
    cr_expect(strstr(bench, "quick mode") == NULL, "BENCH.md is a quick run, not a measurement");
    int quoted = 0;
    static char texts[MAX_TEXTS][128];
    int ntexts = text_list(texts);
    for (int t = 0; t < ntexts; t++) {
        if (!exists(texts[t]))
            continue;
        const char *text = test_read_text(texts[t]);
        for (size_t u = 0; u < sizeof speed_units / sizeof speed_units[0]; u++) {
            const char *unit = speed_units[u];
            size_t ul = strlen(unit);
            for (const char *p = strstr(text, unit); p; p = strstr(p + 1, unit)) {
                /* a unit on its own: not inside a word ("items", "msg") */
                if (isalnum((unsigned char)p[ul]) || (p > text && isalpha((unsigned char)p[-1])
                                                      && !(unit[0] == 'x' && isdigit((unsigned char)p[-1]))))
                    continue;
                const char *e = p;
                while (e > text && e[-1] == ' ')
                    e--;
                const char *b = e;
                while (b > text && strchr("0123456789.,", b[-1]))
                    b--;
                if (b == e)
                    continue;       /* no number before the unit: a column name, a word */
                char num[32];
                snprintf(num, sizeof num, "%.*s", (int)(e - b), b);
                /* a whole cell or word of BENCH.md, not a part of a longer number */
                bool found = false;
                size_t nl = strlen(num);
                for (const char *q = strstr(bench, num); q && !found; q = strstr(q + 1, num))
                    found = (q == bench || !strchr("0123456789.", q[-1]))
                            && !strchr("0123456789", q[nl]) && !(q[nl] == '.' && isdigit((unsigned char)q[nl + 1]));
                cr_expect(found, "%s quotes the speed \"%s %s\", which BENCH.md does not have",
                          texts[t], num, unit);
                quoted++;
            }
        }
    }
    free(bench);
    cr_log_info("%d speeds quoted, all from BENCH.md", quoted);
}

/* --- lengths ------------------------------------------------------------------------- */

/* Words as `wc -w` counts them: runs of characters other than white space. */
static long words_of(const char *text)
{
    long n = 0;
    bool in = false;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) {
        bool space = *p == ' ' || *p == '\t' || *p == '\n' || *p == '\r' || *p == '\v' || *p == '\f';
        n += !space && !in;
        in = !space;
    }
    return n;
}

/* The later lessons stay lessons a class can read before the lecture. */
Test(texts, lessons_06_to_09_keep_to_their_length)
{
    static const struct { const char *path; long most; } limits[] = {
        { "lessons/06-clipping/README.md", 2800 },
        { "lessons/07-tiles/README.md", 2800 },
        { "lessons/08-multisampling/README.md", 2200 },
        { "lessons/09-textures/README.md", 2800 },
    };
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        long n = words_of(test_read_text(limits[i].path));
        cr_log_info("%s: %ld words", limits[i].path, n);
        cr_expect_leq(n, limits[i].most, "%s has %ld words, more than %ld", limits[i].path, n,
                      limits[i].most);
        cr_expect_gt(n, 500, "%s: only %ld words read", limits[i].path, n);
    }
}

/* --- every file a text names is in the repository -------------------------------------- */

/* A whole file, or NULL; the caller frees it. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    char *s = malloc(cap);
    for (size_t got; s && (got = fread(s + n, 1, cap - n - 1, f)) > 0;) {
        n += got;
        if (n + 1 == cap)
            s = realloc(s, cap *= 2);
    }
    fclose(f);
    if (s)
        s[n] = '\0';
    return s;
}

static bool is_path_char(char c)
{
    return isalnum((unsigned char)c) || c == '_' || c == '.' || c == '-' || c == '/';
}

/* A path written as a pattern rather than a file: lessons/NN-name,
 * figures/NAME, tests/%s.c, a star for any lesson, src/... */
static bool is_pattern(const char *p)
{
    if (strstr(p, "NN") || strchr(p, '%') || strchr(p, '*') || strstr(p, "..."))
        return true;
    for (const char *c = p; *c;) {          /* a component in capitals: a placeholder */
        size_t n = strcspn(c, "/");
        bool caps = n > 1;
        for (size_t i = 0; i < n; i++)
            caps = caps && (isupper((unsigned char)c[i]) || c[i] == '_');
        if (caps)
            return true;
        c += n + (c[n] == '/');
    }
    return false;
}

/* The names of the Markdown links and pictures in a text (relative to its
 * folder), the repository paths (src/, lessons/, tests/, figures/) in a
 * text or a source file, and the capitalised Markdown files it names
 * (CONVENTIONS.md, BENCH.md): each must be in the repository, so that no
 * text sends a student to a file that is not there. Paths of other
 * projects (Mesa's src/gallium/...) are named after "Mesa" or "llvmpipe". */
Test(texts, every_file_a_text_or_comment_names_is_in_the_repository)
{
    FILE *ls = popen("git ls-files -co --exclude-standard 2>/dev/null", "r");
    cr_assert_not_null(ls);
    static char names[4096][160];
    int nfiles = 0;
    while (nfiles < 4096 && fgets(names[nfiles], sizeof names[0], ls)) {
        names[nfiles][strcspn(names[nfiles], "\n")] = '\0';
        nfiles++;
    }
    pclose(ls);
    cr_assert_gt(nfiles, 100, "git ls-files listed %d files: not a git checkout?", nfiles);
    static const char *const exempt[] = {
        "tests/test_texts.c",       /* this test's own examples */
        "tests/test_layers.c",      /* made-up folders are what it tests */
    };
    int links = 0, paths = 0, named = 0;
    for (int f = 0; f < nfiles; f++) {
        const char *name = names[f];
        bool md = has_suffix(name, ".md");
        bool source = has_suffix(name, ".c") || has_suffix(name, ".h") || has_suffix(name, ".sh")
                      || has_suffix(name, ".dict") || strcmp(name, "Makefile") == 0
                      || strcmp(name, "figures/list") == 0;
        for (size_t e = 0; e < sizeof exempt / sizeof exempt[0]; e++)
            source = source && strcmp(name, exempt[e]) != 0;
        if (!md && !source)
            continue;
        char *text = slurp(name);
        if (!text)
            continue;               /* listed but deleted in the work tree */
        char dir[sizeof names[0]];
        memcpy(dir, name, strlen(name) + 1);
        char *slash = strrchr(dir, '/');
        if (slash)
            slash[1] = '\0';
        else
            dir[0] = '\0';
        for (const char *p = text; md && *p; p++) {
            const char *target = NULL;
            size_t n = 0;
            if (p[0] == ']' && p[1] == '(') {
                target = p + 2;
                n = strcspn(target, ") \n#");
            } else if (strncmp(p, "src=\"", 5) == 0) {
                target = p + 5;
                n = strcspn(target, "\"#");
            } else if (strncmp(p, "`../", 4) == 0) {    /* a relative path named in code */
                target = p + 1;
                n = strcspn(target, "`#");
            }
            if (!target || n == 0 || memchr(target, ':', n))
                continue;           /* no link, an anchor alone, or a URL */
            char path[512];
            snprintf(path, sizeof path, "%s%.*s", dir, (int)n, target);
            cr_expect(exists(path) || access(path, F_OK) == 0, "%s links %.*s, which does not exist",
                      name, (int)n, target);
            links++;
        }
        static const char *const roots[] = { "src/", "lessons/", "tests/", "figures/" };
        for (const char *p = text; *p; p++) {
            if (p > text && is_path_char(p[-1]))
                continue;
            bool root = false;
            for (size_t r = 0; r < sizeof roots / sizeof roots[0]; r++)
                root = root || strncmp(p, roots[r], strlen(roots[r])) == 0;
            if (!root)
                continue;
            size_t n = 0;
            while (is_path_char(p[n]))
                n++;
            while (n > 0 && strchr("./-", p[n - 1]))
                n--;                /* the sentence's full stop, a folder's slash */
            char path[512];
            snprintf(path, sizeof path, "%.*s", (int)n, p);
            size_t back = (size_t)(p - text) < 80 ? (size_t)(p - text) : 80;
            char before[96];
            snprintf(before, sizeof before, "%.*s", (int)back, p - back);
            /* files the build writes where it runs, never committed */
            static const char *const generated[] = {
                "tests/left-out.txt",   /* a student kit's list of the tests it left out */
            };
            bool made = false;
            for (size_t g = 0; g < sizeof generated / sizeof generated[0]; g++)
                made = made || strcmp(path, generated[g]) == 0;
            if (made || is_pattern(path) || strstr(before, "Mesa") || strstr(before, "llvmpipe"))
                continue;
            cr_expect(access(path, F_OK) == 0, "%s names %s, which is not in the repository", name, path);
            paths++;
        }
        for (const char *p = strstr(text, ".md"); p; p = strstr(p + 1, ".md")) {
            const char *b = p;
            while (b > text && (isupper((unsigned char)b[-1]) || b[-1] == '_'))
                b--;
            if (p - b < 2 || (b > text && is_path_char(b[-1])) || isalnum((unsigned char)p[3]))
                continue;           /* not a bare capitalised name: lessons/README.md, x.mdx */
            char base[64];
            snprintf(base, sizeof base, "/%.*s.md", (int)(p - b), b);
            bool found = false;
            for (int g = 0; g < nfiles && !found; g++)
                found = strcmp(names[g], base + 1) == 0 || has_suffix(names[g], base);
            cr_expect(found, "%s names %s, which is not in the repository", name, base + 1);
            named++;
        }
        free(text);
    }
    cr_log_info("%d links, %d paths, %d file names checked", links, paths, named);
    cr_expect_gt(links, 50, "only %d links found", links);
    cr_expect_gt(paths, 50, "only %d paths found", paths);
    cr_expect_gt(named, 20, "only %d capitalised file names found", named);
}

/* The course's conventions page is in the repository, holds the sections
 * the texts and comments name, and every lesson text links it. */
Test(texts, every_lesson_links_the_conventions_page)
{
    const char *page = test_read_text("lessons/CONVENTIONS.md");
    static const char *const sections[] = { "## Screen space", "## Snapping", "## The fill rule",
                                            "## Scene files", "## 3-D scenes", "## Samples",
                                            "## Textures", "## Lines", "## Exercises",
                                            "## Figures for print" };
    for (size_t i = 0; i < sizeof sections / sizeof sections[0]; i++)
        cr_expect(strstr(page, sections[i]) != NULL, "lessons/CONVENTIONS.md has no \"%s\"", sections[i]);
    for (int i = 0; all_lessons[i]; i++) {
        char path[160];
        snprintf(path, sizeof path, "lessons/%s/README.md", all_lessons[i]->id);
        cr_expect(strstr(test_read_text(path), "](../CONVENTIONS.md)") != NULL,
                  "%s does not link ../CONVENTIONS.md", path);
    }
    cr_expect(strstr(test_read_text("lessons/README.md"), "](CONVENTIONS.md)") != NULL,
              "the course page does not link CONVENTIONS.md");
    cr_expect(strstr(test_read_text("README.md"), "](lessons/CONVENTIONS.md)") != NULL,
              "README.md does not link lessons/CONVENTIONS.md");
}
