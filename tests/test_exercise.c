/* test_exercise.c - the exercises' checks are honest:
 *
 *   - every lesson's own algorithm (each exact variant), run as an
 *     exercise, passes its lesson's check, and so does the worked answer
 *     next to each skeleton;
 *   - every untouched skeleton fails, with a counterexample scene written;
 *   - every exhibit of every lesson fails its lesson's check, and the check
 *     that fails is the one that names its mistake;
 *   - a rasterizer written for one lesson, in the exercise_rasterize form,
 *     is checked by any other lesson's check;
 *   - a counterexample opens in the explorer at the step the check names,
 *     on the first wrong pixel;
 *   - the counterexample is small (shrunk) and every check stays fast.
 */
#define _POSIX_C_SOURCE 200809L   /* open_memstream, mkdtemp */

#include <criterion/criterion.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "exercise/exercise.h"
#include "exercise/scenes.h"
#include "explore/explorer.h"
#include "shade/shade.h"
#include "front/front.h"   /* front_scene */
#include "testlib.h"

/* A whole check must finish in 30 s on the slowest machine of the course;
 * here, with the tests running two at a time, a check that
 * takes more than 10 s of CPU has grown far beyond what it was. */
#define CHECK_SECONDS 10.0

static const struct lesson *lesson_nn(const char *nn)
{
    for (int i = 0; all_lessons[i]; i++)
        if (strncmp(all_lessons[i]->id, nn, 2) == 0)
            return all_lessons[i];
    return NULL;
}

struct run {
    bool ok;
    struct check_result r;
    char *report;       /* what make check printed */
    size_t len;
    double seconds;
    char dir[64];
};

/* Lesson 06: the clipper or the whole front end the next check() runs with
 * (NULL: the lesson's own). */
static clip_fn use_clip;
static front_fn use_front;
/* The graded variant (VARIANT=) the next check() runs under, or NULL. */
static const char *use_variant;

/* Search scenes per check after the fixed ones (the search of make check,
 * bounded by a count so that the suite is repeatable): 0, none. */
static int search_scenes;

/* Check fn as lesson l's exercise; the report is kept for messages. */
static void check(struct run *run, const struct lesson *l, rasterize_fn fn,
                  const struct raster_params *params)
{
    memset(run, 0, sizeof *run);
    snprintf(run->dir, sizeof run->dir, "/tmp/tristep-check-XXXXXX");
    cr_assert_not_null(mkdtemp(run->dir));
    FILE *out = open_memstream(&run->report, &run->len);
    cr_assert_not_null(out);
    struct check_options o = {
        .file = "test.c", .out_dir = run->dir, .open_cmd = "make exercise LESSON=NN",
        .params = params ? *params : (struct raster_params){ .subpixel_bits = SUBPIXEL_BITS },
        .out = out, .seed = 1, .search_scenes = search_scenes,
    };
    exercise_use(l, fn);
    exercise_use_clip(use_clip);
    exercise_use_front(use_front);
    if (use_variant) {
        cr_assert_not_null(exercise_variant_named(l, use_variant), "lesson %s has no variant %s", l->id, use_variant);
        exercise_use_variant(exercise_variant_named(l, use_variant));
    }
    clock_t t0 = clock();
    run->ok = exercise_check(l, &o, &run->r);
    run->seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    fclose(out);
}

/* The counterexample, the folder of the checked file that holds it, and
 * the check's folder. */
static void run_free(struct run *run)
{
    if (run->r.counterexample[0]) {
        remove(run->r.counterexample);
        char *slash = strrchr(run->r.counterexample, '/');
        if (slash) {
            *slash = '\0';
            rmdir(run->r.counterexample);
        }
    }
    rmdir(run->dir);
    free(run->report);
}

/* Open run's counterexample as make exercise does: lesson l's explorer on
 * fn (and lesson 06's clipper clip) as the exercise variant, at step. */
static void open_counterexample(struct explorer *ex, struct scene *s, const struct lesson *l, rasterize_fn fn,
                                clip_fn clip, const struct run *run, uint64_t step)
{
    static struct lesson el;            /* the explorer keeps pointers to them */
    static struct lesson_variant ev[2];
    char err[512];
    cr_assert(scene_load(s, run->r.counterexample, err, sizeof err), "%s", err);
    exercise_lesson(&el, ev, l, "test.c");
    exercise_use(l, fn);
    exercise_use_clip(clip);
    cr_assert(explorer_init(ex, &(struct explorer_desc){ .lesson = &el, .scene = s, .variant = &ev[1], .step = step },
                            err, sizeof err), "%s", err);
}

/* The mutation of tests/mutations/ called name. */
static const struct exercise_mutation *mutation(const char *name)
{
    for (const struct exercise_mutation *m = all_mutations; m->lesson; m++)
        if (strcmp(m->name, name) == 0)
            return m;
    cr_assert_fail("no tests/mutations/%s.patch", name);
    return NULL;
}

/* --- what passes ------------------------------------------------------------ */

Test(exercise, every_lessons_own_algorithm_passes_its_check, .timeout = 180)
{
    int n = 0;
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        for (int v = 0; v < l->nvariants; v++) {
            if (variant_against_exact(&l->variants[v]))
                continue;
            struct run run;
            check(&run, l, l->variants[v].rasterize, NULL);
            if (strncmp(l->id, "08", 2) == 0 && (strcmp(l->variants[v].name, "ssaa") == 0
                                                 || strcmp(l->variants[v].name, "tent") == 0)) {
                /* supersampling shades every sample, the tent resolve
                 * weighs the neighbours' samples too: their coverage is
                 * the exact rule's, their resolved colour (the mean of N
                 * shades, not the centre's; a wider filter than the
                 * box) another by design */
                cr_expect_str_eq(run.r.failed, "colour and depth (perspective)", "%s", run.report);
                cr_expect_eq(run.r.passed, run.r.nchecks - 1, "%s", run.report);
            } else {
                cr_expect(run.ok, "%s/%s fails its own lesson's check:\n%s", l->id, l->variants[v].name,
                          run.report);
            }
            /* a lesson checked at several sample counts draws every scene
             * once per count: the budget is per drawing */
            int draws = 0;
            for (const int *c = l->exercise.samples; c && *c; c++)
                draws++;
            cr_expect_lt(run.seconds, CHECK_SECONDS * (draws > 1 ? draws : 1), "%s/%s: the check took %.1f s", l->id,
                         l->variants[v].name, run.seconds);
            run_free(&run);
            n++;
        }
    }
    cr_expect_geq(n, 5);
}

Test(exercise, every_worked_answer_passes_its_check)
{
    int n = 0;
    for (int i = 0; all_exercises[i].lesson; i++, n++) {
        const struct lesson *l = lesson_nn(all_exercises[i].lesson);
        cr_assert_not_null(l);
        struct run run;
        use_clip = all_exercises[i].answer_clip;
        check(&run, l, all_exercises[i].answer, NULL);
        use_clip = NULL;
        cr_expect(run.ok, "lessons/%s's answer.c fails:\n%s", l->id, run.report);
        cr_expect(strstr(run.report, "checks pass"), "no short report on success:\n%s", run.report);
        run_free(&run);
    }
    cr_expect_geq(n, 8, "a skeleton and an answer for every lesson, 01 to 08");
}

/* The exercise_rasterize form is the same for every lesson: a rasterizer
 * written for one is checked by another lesson's check like its own. The
 * linear lessons accept lesson 03's answer, the perspective ones lesson
 * 04's, but for the lessons of blocks (05, 07), which want its blocks
 * classified; and lesson 02's linear answer is told, by name, that lesson
 * 04 wants perspective. */
Test(exercise, any_lessons_check_accepts_a_whole_rasterizer)
{
    rasterize_fn linear = NULL, perspective = NULL, bary = NULL;
    for (int i = 0; all_exercises[i].lesson; i++) {
        if (strcmp(all_exercises[i].lesson, "03") == 0)
            linear = all_exercises[i].answer;
        if (strcmp(all_exercises[i].lesson, "04") == 0)
            perspective = all_exercises[i].answer;
        if (strcmp(all_exercises[i].lesson, "02") == 0)
            bary = all_exercises[i].answer;
    }
    cr_assert(linear && perspective && bary);
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        struct run run;
        check(&run, l, l->perspective ? perspective : linear, NULL);
        if (l->exercise.samples) {
            /* a lesson checked at several samples per pixel (08) rejects a
             * rasterizer of one sample, at the first scene */
            cr_expect_not(run.ok, "%s accepts a one-sample rasterizer", l->id);
            cr_expect_str_eq(run.r.failed, "single triangle", "%s", run.report);
        } else if (l->exercise.textures) {
            /* lesson 09 draws image textures: a rasterizer that draws the
             * vertex colour alone passes every untextured check and fails
             * at the first textured one (the lesson's own algorithm, a
             * whole rasterizer too, passes: above) */
            cr_expect_not(run.ok, "%s accepts a rasterizer that draws no image texture", l->id);
            cr_expect_str_eq(run.r.failed, "texels magnified", "%s", run.report);
        } else if (l->exercise.full_blocks) {
            /* a lesson of blocks (05, 07) holds a pixel to the block
             * classified before it: a rasterizer that classifies none draws
             * the right picture without the lesson's idea */
            cr_expect_not(run.ok, "%s accepts a rasterizer that classifies no block", l->id);
            cr_expect_not_null(strstr(run.report, "before it classified any block"), "%s", run.report);
        } else {
            cr_expect(run.ok, "%s rejects a correct rasterizer written for another lesson:\n%s", l->id,
                      run.report);
        }
        run_free(&run);
    }
    struct run run;
    check(&run, lesson_nn("04"), bary, NULL);
    cr_expect_not(run.ok);
    cr_expect_str_eq(run.r.failed, "colour and depth (perspective)", "%s", run.report);
    run_free(&run);
}

/* --- what fails -------------------------------------------------------------- */

Test(exercise, every_untouched_skeleton_fails_with_a_counterexample)
{
    for (int i = 0; all_exercises[i].lesson; i++) {
        const struct lesson *l = lesson_nn(all_exercises[i].lesson);
        struct run run;
        use_clip = all_exercises[i].skeleton_clip;
        check(&run, l, all_exercises[i].skeleton, NULL);
        use_clip = NULL;
        cr_expect_not(run.ok, "lesson %s's skeleton passes its check", l->id);
        cr_expect_neq(run.r.failed[0], '\0');
        cr_expect_neq(run.r.counterexample[0], '\0', "%s: no counterexample:\n%s", l->id, run.report);
        struct scene s;
        char err[512];
        cr_expect(scene_load(&s, run.r.counterexample, err, sizeof err), "%s", err);
        int ntris = s.world.camera_line ? s.world.ntris : s.ntris;     /* a 3-D scene: world triangles */
        cr_expect_eq(ntris, run.r.ntris);
        cr_expect_eq(ntris, 1, "%s: a skeleton's mistake needs one triangle, not %d", l->id, ntris);
        scene_free(&s);
        /* the report says what to run next */
        cr_expect(strstr(run.report, "SCENE=") && strstr(run.report, "STEP="), "%s", run.report);
        run_free(&run);
    }
}

/* Each exhibit and the check that names its mistake. */
static const struct {
    const char *lesson, *variant;
    bool affine;
    const char *check;
} exhibits[] = {
    { "01", "source-float", false, "single triangle" },
    { "02", "inclusive", false, "fill-rule ties" },
    { "02", "strict", false, "fill-rule ties" },
    /* the ties far out and a 1/65536 px^2 from a centre (float rounds them) */
    { "03", "float", false, "fill-rule ties" },
    { "04", NULL, true, "colour and depth (perspective)" },
    { "05", "corners-outside", false, "single triangle" },
    { "05", "or-inside", false, "single triangle" },
    { "06", "inverse", false, "colour and depth (perspective)" },
    { "06", "reversed", false, "colour and depth (perspective)" },
    { "06", "ndc24", false, "colour and depth (perspective)" },
    { "06", "no-guard-32", false, "fill-rule ties" },
    /* lesson 06's slips of the front end, checked with their own front ends */
    { "06", "project-first", false, "one vertex behind near" },
    /* a new vertex on the screen's border, snapped, moves the edge it cuts */
    { "06", "viewport", false, "one vertex behind near" },
    /* the float clippers pass: on the check's scenes no float vertex snaps
     * elsewhere than the exact one, and the walk order's cracks are rare
     * (tests/test_lesson06.c counts them on the floors the search found) */
    { "06", "walk-order", false, NULL },
    { "06", "float-canonical", false, NULL },
    /* a triangle within one tile goes into its bin untested: the first
     * triangles to lose pixels cross tiles */
    { "07", "wrong-corner", false, "random triangles" },
    /* its mistake is the order of a threaded scene run, which one triangle
     * through `rasterize` cannot show: its check must PASS (the scene run's
     * pictures are tests/test_lesson07.c's) */
    { "07", "unordered", false, NULL },
    { "08", "no-fill-rule", false, "fill-rule ties" },
    /* lesson 08's check draws at 4 samples first: the quarter points are
     * not the standard pattern's samples */
    { "08", "grid", false, "single triangle" },
    /* lesson 09, against the lesson's own picture: level 0 alone blurs
     * nothing where the minified scenes need a coarser level; (s, t) linear
     * in the screen moves texels on the first triangle whose depths differ;
     * each pixel's own derivatives choose other levels than its quad's
     * where the level of detail changes fastest, on the grazing floors (the
     * per-pixel level of detail a student might write), and the analytic
     * ones on the first receding triangle minified */
    { "09", "no-mipmaps", false, "texels minified" },
    { "09", "affine", false, "texels magnified" },
    { "09", "fine-lod", false, "grazing floors and walls" },
    { "09", "analytic-lod", false, "a texture that is not square" },
};

Test(exercise, every_exhibit_fails_the_check_that_names_its_mistake)
{
    size_t n = sizeof exhibits / sizeof exhibits[0];
    for (size_t i = 0; i < n; i++) {
        const struct lesson *l = lesson_nn(exhibits[i].lesson);
        const struct lesson_variant *v = exhibits[i].variant ? lesson_variant(l, exhibits[i].variant)
                                                             : &l->variants[0];
        cr_assert_not_null(v);
        struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS };
        cr_assert(!exhibits[i].affine || lesson_param_set(l, &p, "affine", 1));
        struct run run;
        use_front = lesson_front(l, v) != front_scene ? lesson_front(l, v) : NULL;
        check(&run, l, v->rasterize, &p);
        use_front = NULL;
        const char *name = exhibits[i].variant ? exhibits[i].variant : "affine";
        if (!exhibits[i].check) {
            cr_expect(run.ok, "%s/%s, whose mistake its check cannot show, fails it:\n%s", l->id, name, run.report);
            run_free(&run);
            continue;
        }
        cr_expect_not(run.ok, "%s/%s passes", l->id, name);
        cr_expect_str_eq(run.r.failed, exhibits[i].check, "%s/%s:\n%s", l->id, name, run.report);
        cr_expect_neq(run.r.counterexample[0], '\0');
        cr_expect_lt(run.seconds, CHECK_SECONDS);
        run_free(&run);
    }
    /* and every exhibit of every lesson is in the table, lesson 06's slips
     * of the front end too (its 3-D checks run their front ends) */
    for (int i = 0; all_lessons[i]; i++)
        for (int k = 0; k < all_lessons[i]->nvariants; k++) {
            const struct lesson_variant *v = &all_lessons[i]->variants[k];
            if (!variant_against_exact(v))
                continue;
            bool listed = false;
            for (size_t e = 0; e < n && !listed; e++)
                listed = exhibits[e].variant && strncmp(all_lessons[i]->id, exhibits[e].lesson, 2) == 0
                         && strcmp(exhibits[e].variant, v->name) == 0;
            cr_expect(listed, "the exhibit %s/%s has no expected check", all_lessons[i]->id, v->name);
        }
}

/* Lesson 03's own property fails a rasterizer that is right pixel for pixel
 * but evaluates the edge functions at every pixel: lesson 02's. */
Test(exercise, lesson03_property_finds_multiplications_per_pixel)
{
    const struct lesson *l02 = lesson_nn("02"), *l03 = lesson_nn("03");
    struct run run;
    check(&run, l03, l02->variants[0].rasterize, NULL);
    cr_expect_not(run.ok);
    cr_expect_str_eq(run.r.failed, "no multiplication per pixel", "%s", run.report);
    run_free(&run);
}

/* Lesson 05's: block rasterizers that draw the right picture, every pixel
 * tested, but call their blocks wrong: all partial (the corner test rejects
 * some, and finds some full), or every block full (not really full); and
 * one that calls each block what its four corners say, which passes. */
enum claim { CLAIM_PARTIAL, CLAIM_FULL, CLAIM_CORNERS };
static enum claim claim;

static uint8_t corner_claim(const struct tri_setup *t, int x0, int y0, int x1, int y1)
{
    if (claim != CLAIM_CORNERS)
        return claim == CLAIM_FULL ? BLOCK_FULL : BLOCK_PARTIAL;
    bool full = true;
    for (int k = 0; k < 3; k++) {
        int in = edge_inside(t, k, edge_value(t, k, x0, y0)) + edge_inside(t, k, edge_value(t, k, x1, y0))
               + edge_inside(t, k, edge_value(t, k, x0, y1)) + edge_inside(t, k, edge_value(t, k, x1, y1));
        if (in == 0)
            return BLOCK_EMPTY;
        full = full && in == 4;
    }
    return full ? BLOCK_FULL : BLOCK_PARTIAL;
}

static void blocks_tested(const struct tri_setup *t, const struct raster_params *p,
                          struct target *fb, struct trace *tr)
{
    if (t->empty)
        return;
    for (int by = t->miny; by <= t->maxy; by += 8)
        for (int bx = t->minx; bx <= t->maxx; bx += 8) {
            int x1 = bx + 7 < t->maxx ? bx + 7 : t->maxx, y1 = by + 7 < t->maxy ? by + 7 : t->maxy;
            NARRATE(tr, .kind = TRACE_BLOCK, .x = bx, .y = by, .x1 = x1, .y1 = y1,
                    .klass = corner_claim(t, bx, by, x1, y1));
            for (int y = by; y <= y1; y++)
                for (int x = bx; x <= x1; x++) {
                    bool in = true;
                    for (int k = 0; k < 3; k++)
                        in = in && edge_inside(t, k, edge_value(t, k, x, y));
                    if (!in)
                        continue;
                    double z, rgb[3], st[2];
                    reference_shade(t, x, y, true, &z, rgb, st);
                    PLOT(fb, tr, 0, x, y, (float)z, shade_pixel(p, tr, rgb[0], rgb[1], rgb[2], st[0], st[1]));
                }
        }
}

Test(exercise, lesson05_property_holds_blocks_to_their_class)
{
    const struct lesson *l05 = lesson_nn("05");
    struct run run;
    claim = CLAIM_PARTIAL;
    check(&run, l05, blocks_tested, NULL);
    cr_expect_str_eq(run.r.failed, "corner classes", "%s", run.report);
    cr_expect_not_null(strstr(run.report, "narrated PARTIAL; its corner pixel centres make it EMPTY"), "%s",
                       run.report);
    /* the printed command opens the explorer at the first misclassified
     * block's own step (the blocks view outlines it), the one the report names */
    struct scene s;
    struct explorer ex;
    open_counterexample(&ex, &s, l05, blocks_tested, NULL, &run, run.r.step);
    cr_expect(ex.has_last);
    cr_expect_eq(ex.last.kind, TRACE_BLOCK);
    cr_expect_eq(ex.last.klass, BLOCK_PARTIAL);
    char want[96];
    snprintf(want, sizeof want, "block (%d, %d)-(%d, %d) narrated PARTIAL", ex.last.x, ex.last.y, ex.last.x1,
             ex.last.y1);
    cr_expect_not_null(strstr(run.report, want), "the step shows another block than the report's:\n%s\n%s",
                       want, run.report);
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);
    claim = CLAIM_FULL;
    check(&run, l05, blocks_tested, NULL);
    cr_expect_str_eq(run.r.failed, "corner classes", "%s", run.report);
    cr_expect_not_null(strstr(run.report, "narrated FULL, but pixel"), "%s", run.report);
    run_free(&run);
    claim = CLAIM_CORNERS;
    check(&run, l05, blocks_tested, NULL);
    cr_expect(run.ok, "%s", run.report);
    run_free(&run);
    /* lesson 04 classifies no blocks: its pixels lie in no classified block */
    check(&run, l05, lesson_nn("04")->variants[0].rasterize, NULL);
    cr_expect_str_eq(run.r.failed, "corner classes", "%s", run.report);
    cr_expect_not_null(strstr(run.report, "before it classified any block"), "%s", run.report);
    run_free(&run);
}

/* The explorer of an exercise runs the student's code, one triangle at a
 * time, in every mode: lesson 07's whole-scene runs (bins, threads) and the
 * order they narrate in are the lesson's own variants', not the exercise's.
 * Lesson 07's skeleton, which draws nothing, must then give an empty
 * picture where the lesson's scene run would draw the built-in scene. */
Test(exercise, the_exercise_explorer_runs_the_students_code_per_triangle)
{
    for (int i = 0; all_lessons[i]; i++) {
        struct lesson el;
        struct lesson_variant ev[2];
        exercise_lesson(&el, ev, all_lessons[i], "test.c");
        cr_expect_null(lesson_scene_fn(&el, &ev[0]), "%s", el.id);
        cr_expect_null(lesson_scene_fn(&el, &ev[1]), "%s", el.id);
        cr_expect_null(el.narration_units, "%s", el.id);
    }
    const struct lesson *l07 = lesson_nn("07");
    rasterize_fn skeleton = NULL;
    for (int i = 0; all_exercises[i].lesson; i++)
        if (strcmp(all_exercises[i].lesson, "07") == 0)
            skeleton = all_exercises[i].skeleton;
    cr_assert_not_null(skeleton);
    struct scene s;
    char err[512];
    cr_assert(scene_builtin(&s, l07->builtin_scene, err, sizeof err), "%s", err);
    struct lesson el;
    struct lesson_variant ev[2];
    exercise_lesson(&el, ev, l07, "test.c");
    exercise_use(l07, skeleton);
    struct explorer ex;
    cr_assert(explorer_init(&ex, &(struct explorer_desc){ .lesson = &el, .scene = &s, .variant = &ev[1],
                                                         .step_end = true }, err, sizeof err), "%s", err);
    size_t covered = 0;
    for (size_t i = 0; i < (size_t)s.w * (size_t)s.h; i++)
        covered += ex.fb.count[i] != 0;
    cr_expect_eq(covered, 0, "the skeleton draws nothing, yet %zu pixels are covered", covered);
    cr_expect_gt(ex.missing, 0, "the diff marks the pixels the skeleton leaves out");
    explorer_free(&ex);
    scene_free(&s);
}

/* The search's scenes, for every lesson's aim: each one has triangles, and
 * written as a counterexample is written it reads back to as many (every
 * s and t, every coordinate and texture within the format), the same
 * scene for the same seed. */
Test(exercise, the_search_scenes_are_scenes_the_format_reads_back)
{
    static const search_gen gens[] = { search_ties, search_coverage, search_colour, search_textures, search_world };
    static const struct search_for aims[] = { { 0 }, { .tiles = true }, { .samples = true }, { .perspective = true } };
    for (size_t g = 0; g < sizeof gens / sizeof gens[0]; g++)
        for (size_t a = 0; a < sizeof aims / sizeof aims[0]; a++)
            for (uint64_t seed = 0; seed < 150; seed++) {
                struct scene s, again, back;
                char what[256], what2[256], err[256];
                cr_assert(gens[g](&aims[a], seed * 7919 + a, &s, what, sizeof what));
                cr_assert(gens[g](&aims[a], seed * 7919 + a, &again, what2, sizeof what2));
                cr_expect_str_eq(what, what2);
                int n = s.world.camera_line ? s.world.ntris : s.ntris;
                cr_expect_gt(n, 0, "%s", what);
                cr_expect_eq(again.ntris, s.ntris, "%s", what);
                char *text = NULL;
                size_t len = 0;
                FILE *f = open_memstream(&text, &len);
                cr_assert(f && scene_write(&s, f));
                fclose(f);
                cr_assert(scene_parse(&back, "back.scene", text, len, err, sizeof err), "%s: %s", what, err);
                cr_expect_eq(back.world.camera_line ? back.world.ntris : back.ntris, n, "%s", what);
                free(text);
                scene_free(&back);
                scene_free(&again);
                scene_free(&s);
            }
}

/* Lesson 09's textured scenes: every triangle under an image texture, and
 * each scene written as a counterexample is written reads back to the same
 * triangles under the same textures (builtin:NAME, the same wrap). */
Test(exercise, the_textured_scenes_are_textured_and_read_back)
{
    static const scene_gen gens[] = { gen_tex_magnify, gen_tex_wrap, gen_tex_nonsquare,
                                      gen_tex_minify, gen_tex_floor, gen_tex_tiny };
    int n = 0;
    for (size_t g = 0; g < sizeof gens / sizeof gens[0]; g++)
        for (int i = 0;; i++, n++) {
            struct scene s, back;
            char what[256], err[256];
            if (!gens[g](i, &s, what, sizeof what))
                break;
            cr_expect_gt(s.ntris, 0, "%s", what);
            char *text = NULL;
            size_t len = 0;
            FILE *f = open_memstream(&text, &len);
            cr_assert(f && scene_write(&s, f));
            fclose(f);
            cr_assert(scene_parse(&back, "back.scene", text, len, err, sizeof err), "%s: %s", what, err);
            cr_assert_eq(back.ntris, s.ntris, "%s", what);
            for (int k = 0; k < s.ntris; k++) {
                const struct texture *a = scene_texture(&s, s.tris[k].texture),
                                     *b = scene_texture(&back, back.tris[k].texture);
                cr_assert(a && b, "%s: triangle %d has no image texture", what, k + 1);
                cr_expect_str_eq(a->name, b->name, "%s", what);
                cr_expect_eq(a->wrap, b->wrap, "%s", what);
            }
            free(text);
            scene_free(&back);
            scene_free(&s);
        }
    cr_expect_geq(n, 25);
}

/* --- the counterexample in the explorer --------------------------------------- */

/* Open the counterexample as make exercise does, at the step the check
 * printed: the last event is on the first wrong pixel (an extra pixel's
 * write), or the triangle is finished and the diff marks the pixel (a
 * missing one). */
static void open_at_step(const struct lesson *l, rasterize_fn fn, const struct run *run, bool extra)
{
    struct scene s;
    char err[512];
    cr_assert(scene_load(&s, run->r.counterexample, err, sizeof err), "%s", err);
    struct lesson el;
    struct lesson_variant ev[2];
    exercise_lesson(&el, ev, l, "test.c");
    exercise_use(l, fn);
    struct explorer ex;
    cr_assert(explorer_init(&ex, &(struct explorer_desc){ .lesson = &el, .scene = &s, .variant = &ev[1],
                                                         .step = run->r.step }, err, sizeof err), "%s", err);
    cr_expect_eq(ex.step, run->r.step);
    if (extra) {
        cr_expect(ex.has_last);
        cr_expect_eq(ex.last.kind, TRACE_PIXEL_WRITE);
        cr_expect_eq(ex.last.x, run->r.x);
        cr_expect_eq(ex.last.y, run->r.y);
        /* marked extra at the very step that writes it, the triangle unfinished */
        cr_assert_not_null(ex.diff);
        cr_expect_eq(ex.diff[(size_t)run->r.y * (size_t)s.w + (size_t)run->r.x], EXHIBIT_EXTRA);
    } else {
        cr_assert_not_null(ex.diff);
        cr_expect_eq(ex.diff[(size_t)run->r.y * (size_t)s.w + (size_t)run->r.x], EXHIBIT_MISSING,
                     "pixel (%d, %d) not marked missing at step %llu", run->r.x, run->r.y,
                     (unsigned long long)run->r.step);
    }
    explorer_free(&ex);
    scene_free(&s);
}

Test(exercise, a_counterexample_opens_at_the_step_it_names)
{
    const struct lesson *l02 = lesson_nn("02");
    const struct lesson_variant *inclusive = lesson_variant(l02, "inclusive");
    struct run run;
    check(&run, l02, inclusive->rasterize, NULL);
    cr_assert_not_null(strstr(run.report, "an extra pixel"), "%s", run.report);
    cr_expect_not_null(strstr(run.report, "leaves it to the triangle on the other side"), "%s", run.report);
    cr_expect_eq(run.r.ntris, 1, "one triangle shows it: its own right edge");
    open_at_step(l02, inclusive->rasterize, &run, true);
    run_free(&run);

    for (int i = 0; all_exercises[i].lesson; i++)
        if (strcmp(all_exercises[i].lesson, "02") == 0) {
            check(&run, l02, all_exercises[i].skeleton, NULL);
            cr_assert_not_null(strstr(run.report, "a missing pixel"), "%s", run.report);
            open_at_step(l02, all_exercises[i].skeleton, &run, false);
            run_free(&run);
        }
}

/* Lesson 06: the skeleton's 3-D counterexample, opened as make exercise
 * opens it (the exercise's front end around the same clipper), at the step
 * the check printed: the end of the run, where the diff view marks the
 * pixels the untouched clipper draws wrong, with as many pixels marked as
 * the exact front end and the check disagree on. */
Test(exercise, a_3d_counterexample_opens_at_the_end_with_the_diff)
{
    const struct lesson *l06 = lesson_nn("06");
    const struct exercise_code *code = NULL;
    for (int i = 0; all_exercises[i].lesson; i++)
        if (strcmp(all_exercises[i].lesson, "06") == 0)
            code = &all_exercises[i];
    cr_assert(code && code->skeleton_clip);
    struct run run;
    use_clip = code->skeleton_clip;
    check(&run, l06, code->skeleton, NULL);
    use_clip = NULL;
    cr_assert_str_eq(run.r.failed, "one vertex behind near", "%s", run.report);
    cr_expect_not_null(strstr(run.report, "behind the plane"), "%s", run.report);
    cr_expect_not_null(strstr(run.report, "view depths d = "), "%s", run.report);
    struct scene s;
    char err[512];
    cr_assert(scene_load(&s, run.r.counterexample, err, sizeof err), "%s", err);
    cr_assert_gt(s.world.camera_line, 0);
    struct lesson el;
    struct lesson_variant ev[2];
    exercise_lesson(&el, ev, l06, "test.c");
    exercise_use(l06, code->skeleton);
    exercise_use_clip(code->skeleton_clip);
    struct explorer ex;
    cr_assert(explorer_init(&ex, &(struct explorer_desc){ .lesson = &el, .scene = &s, .variant = &ev[1],
                                                         .step = run.r.step }, err, sizeof err), "%s", err);
    cr_expect_eq(ex.step, run.r.step);
    cr_expect_eq(ex.step, ex.replay.total, "the end of the run");
    cr_expect_gt(ex.extra + ex.missing, 0, "the diff view marks nothing");
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);
}

/* --- code that crashes --------------------------------------------------------- */

/* Right until the third pixel of a wide row, then a crash. */
static void crash_on_wide_rows(const struct tri_setup *t, const struct raster_params *p,
                               struct target *fb, struct trace *tr)
{
    (void)p, (void)tr;
    if (t->empty)
        return;
    for (int y = t->miny; y <= t->maxy; y++)
        for (int x = t->minx; x <= t->maxx; x++) {
            if (x - t->minx > 2 && t->maxx - t->minx > 12)
                raise(SIGSEGV);     /* what a wild write does, without undefined behaviour */
            target_write(fb, x, y, 1, 0xffffffffu);
        }
}

/* Check the code given to exercise_use as lesson l's exercise in a process
 * of its own (exercise_check_guarded), into dir; the report into report. */
static bool check_guarded(const struct lesson *l, const char *program, const char *dir, char *report,
                          size_t len, struct check_result *r)
{
    FILE *out = tmpfile();
    cr_assert_not_null(out);
    struct check_options o = { .file = "crash.c", .out_dir = dir, .open_cmd = "make exercise",
                               .params = { .subpixel_bits = SUBPIXEL_BITS }, .out = out,
                               .program = program };
    bool ok = exercise_check_guarded(l, &o, r);
    rewind(out);
    size_t n = fread(report, 1, len - 1, out);
    report[n] = '\0';
    fclose(out);
    return ok;
}

Test(exercise, a_crash_is_reported_with_the_scene_that_crashes, .timeout = 60)
{
    const struct lesson *l02 = lesson_nn("02");
    char dir[] = "/tmp/tristep-crash-XXXXXX", report[8192];
    cr_assert_not_null(mkdtemp(dir));
    exercise_use(l02, crash_on_wide_rows);
    struct check_result r;
    cr_expect_not(check_guarded(l02, "build/exercise-02", dir, report, sizeof report, &r));
    cr_expect_not_null(strstr(report, "CRASHED"), "%s", report);
    cr_expect_not_null(strstr(report, "gdb -ex run --args build/exercise-02"), "%s", report);
    cr_expect_str_eq(r.failed, "single triangle");
    struct scene s;
    char err[512];
    cr_assert(scene_load(&s, r.counterexample, err, sizeof err), "%s", err);
    cr_expect_eq(s.ntris, 1);
    scene_free(&s);
    remove(r.counterexample);
    rmdir(dir);
}

/* Lesson 06: a clipper that crashes on a vertex behind the eye. */
static void crash_behind_the_eye(struct poly *out, const struct poly *in, const struct plane *pl)
{
    for (int i = 0; i < in->n; i++)
        if (in->v[i].pos[2] < 0)
            raise(SIGSEGV);
    clip_polygon(out, in, pl, NULL);
}

Test(exercise, a_crashing_clipper_is_reported_with_one_world_triangle, .timeout = 60)
{
    const struct lesson *l06 = lesson_nn("06");
    char dir[] = "/tmp/tristep-crash-XXXXXX", report[8192];
    cr_assert_not_null(mkdtemp(dir));
    exercise_use(l06, l06->variants[0].rasterize);
    exercise_use_clip(crash_behind_the_eye);
    struct check_result r;
    cr_expect_not(check_guarded(l06, "build/exercise-06", dir, report, sizeof report, &r));
    cr_expect_not_null(strstr(report, "CRASHED"), "%s", report);
    cr_expect_str_eq(r.failed, "one vertex behind near", "%s", report);
    struct scene s;
    char err[512];
    cr_assert(scene_load(&s, r.counterexample, err, sizeof err), "%s", err);
    cr_expect_gt(s.world.camera_line, 0, "written as a 3-D scene");
    cr_expect_eq(s.world.ntris, 1, "%s", report);
    scene_free(&s);
    remove(r.counterexample);
    rmdir(dir);
}

/* --- a scene of the student's own (SCENE=) ------------------------------------- */

static bool write_builtin(FILE *out, void *ctx)
{
    struct scene s;
    char err[256];
    if (!scene_builtin(&s, ctx, err, sizeof err))
        return false;
    bool ok = scene_write(&s, out);
    scene_free(&s);
    return ok;
}

Test(exercise, a_scene_of_ones_own_is_checked_first)
{
    char dir[] = "/tmp/tristep-own-XXXXXX", path[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/mine.scene", dir);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    cr_assert(write_builtin(f, "shared-edge"));
    fclose(f);
    const struct lesson *l02 = lesson_nn("02");
    const char *scenes[] = { path, NULL };
    struct check_result r;
    for (int pass = 0; pass < 2; pass++) {
        char *report = NULL;
        size_t len = 0;
        FILE *out = open_memstream(&report, &len);
        struct check_options o = { .file = "t.c", .scenes = scenes, .out_dir = dir, .open_cmd = "make exercise",
                                   .params = { .subpixel_bits = SUBPIXEL_BITS }, .out = out };
        exercise_use(l02, pass == 0 ? lesson_variant(l02, "strict")->rasterize : l02->variants[0].rasterize);
        bool ok = exercise_check(l02, &o, &r);
        fclose(out);
        cr_expect_eq(ok, pass == 1, "%s", report);
        cr_expect_not_null(strstr(report, "1/6 your scene"), "%s", report);
        if (pass == 0) {
            cr_expect_str_eq(r.failed, "your scene", "%s", report);
            remove(r.counterexample);
        }
        free(report);
    }
    remove(path);
    rmdir(dir);
}

/* --- make check from a clean clone ----------------------------------------------- */

/* Run a shell command line; its output into `log` (read back); exit status. */
static int shell(const char *cmd, char **log)
{
    char line[2048], path[] = "/tmp/tristep-log-XXXXXX";
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    close(fd);
    /* not the test run's own make: no jobserver, no inherited flags, and
     * the plain build a student makes (make test SANITIZE=1 exports it) */
    snprintf(line, sizeof line, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u SANITIZE -u BUILD -u CFLAGS "
             "-u LDFLAGS -u LDLIBS sh -c '%s' > %s 2>&1", cmd, path);
    int st = system(line);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    remove(path);
    *log = buf;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

/* What a student does after cloning: make check on the answer (passes,
 * short report), on the untouched skeleton (fails within 30 s, with a
 * counterexample and the command to open it), and the program that command
 * runs opens the counterexample at its step (headless here: --figure). The
 * clone is of the last commit. */
Test(exercise, make_check_works_from_a_clean_clone, .timeout = 280)
{
    char *log;
    cr_assert_eq(shell("git rev-parse --show-toplevel", &log), 0, "not a git checkout: %s", log);
    char top[1024];
    snprintf(top, sizeof top, "%s", log);
    top[strcspn(top, "\n")] = '\0';
    char dir[] = "/tmp/tristep-clone-XXXXXX", cmd[1536];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(cmd, sizeof cmd, "git clone -q %s %s/t", top, dir);
    cr_assert_eq(shell(cmd, &log), 0, "%s", log);

    snprintf(cmd, sizeof cmd, "cd %s/t && make -j2 check LESSON=02 FILE=lessons/02-barycentric/answer.c", dir);
    int st = shell(cmd, &log);
    cr_expect_eq(st, 0, "make check on the answer:\n%s", log);
    cr_expect_not_null(strstr(log, "all 5 checks pass"), "%s", log);

    snprintf(cmd, sizeof cmd, "cd %s/t && make check LESSON=02", dir);
    time_t t0 = time(NULL);
    st = shell(cmd, &log);
    cr_expect_neq(st, 0, "make check passes the untouched skeleton:\n%s", log);
    cr_expect_leq(time(NULL) - t0, 30, "make check on a wrong answer took %lld s", (long long)(time(NULL) - t0));
    const char *open = strstr(log, "make exercise LESSON=02 SCENE=");
    cr_assert_not_null(open, "%s", log);
    char scene[256];
    unsigned long long step;
    cr_assert_eq(sscanf(open, "make exercise LESSON=02 SCENE=%255s STEP=%llu", scene, &step), 2, "%s", open);
    /* (make exercise builds the explorer that make check's command opens) */
    snprintf(cmd, sizeof cmd, "cd %s/t && make -s LESSON=02 build/exercise-02 && "
             "build/exercise-02 --scene %s --step %llu --figure f.png && test -s f.png", dir, scene, step);
    cr_expect_eq(shell(cmd, &log), 0, "%s", log);
    /* the counterexample lies in a folder of the checked file's own */
    cr_expect_not_null(strstr(scene, "/lessons-02-barycentric-exercise/02-"), "%s", scene);
    /* --help names the exercise's options beside the lesson program's */
    snprintf(cmd, sizeof cmd, "cd %s/t && build/exercise-02 --help", dir);
    cr_expect_eq(shell(cmd, &log), 0, "%s", log);
    cr_expect(strstr(log, "--file NAME") && strstr(log, "--check ") && strstr(log, "--check-scene FILE")
              && strstr(log, "--out DIR") && strstr(log, "--scene FILE"), "%s", log);

    /* lesson 09: the student's stages inside the lesson's own rasterizer,
     * its textured counterexample opened where the check says */
    snprintf(cmd, sizeof cmd, "cd %s/t && make check LESSON=09 FILE=lessons/09-textures/answer.c", dir);
    st = shell(cmd, &log);
    cr_expect_eq(st, 0, "make check on lesson 09's answer:\n%s", log);
    cr_expect_not_null(strstr(log, "all 13 checks pass"), "%s", log);
    snprintf(cmd, sizeof cmd, "cd %s/t && make check LESSON=09", dir);
    st = shell(cmd, &log);
    cr_expect_neq(st, 0, "make check passes lesson 09's untouched skeleton:\n%s", log);
    open = strstr(log, "make exercise LESSON=09 SCENE=");
    cr_assert_not_null(open, "%s", log);
    cr_assert_eq(sscanf(open, "make exercise LESSON=09 SCENE=%255s STEP=%llu", scene, &step), 2, "%s", open);
    snprintf(cmd, sizeof cmd, "cd %s/t && make -s LESSON=09 build/exercise-09 && "
             "build/exercise-09 --scene %s --step %llu --figure f.png && test -s f.png", dir, scene, step);
    cr_expect_eq(shell(cmd, &log), 0, "%s", log);

    /* the mistakes the lesson texts name: tests/mutations/, in-process (every_mistake_...) */

    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    shell(cmd, &log);
}

/* --- the common mistakes the lesson texts name ("Write it yourself") ---------------- */

void exercise_write(struct target *fb, int x, int y, float z, uint32_t rgba);

/* Lesson 02's loop with one mistake at a time, as a student makes it. */
enum mistake { M_NONE, M_CORNER, M_STRICT, M_INCLUSIVE, M_BOTTOM_RIGHT, M_WEIGHTS, M_UNCLIPPED };
static enum mistake mistake;

static void bary_with_mistake(const struct tri_setup *t, const struct raster_params *p,
                              struct target *fb, struct trace *tr)
{
    if (t->area2 <= 0)
        return;
    int x0 = t->minx, x1 = t->maxx, y0 = t->miny, y1 = t->maxy;
    if (mistake == M_UNCLIPPED) {       /* the box of the vertices, not clamped to the target */
        x0 = y0 = INT32_MAX, x1 = y1 = INT32_MIN;
        for (int i = 0; i < 3; i++) {
            int vx = (int)floor((double)t->x[i] / SUBPIXEL_ONE), vy = (int)floor((double)t->y[i] / SUBPIXEL_ONE);
            x0 = vx < x0 ? vx : x0, x1 = vx > x1 ? vx : x1, y0 = vy < y0 ? vy : y0, y1 = vy > y1 ? vy : y1;
        }
    }
    int64_t half = mistake == M_CORNER ? 0 : SUBPIXEL_HALF;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            int64_t F[3];
            bool in = true;
            for (int k = 0; k < 3; k++) {
                F[k] = t->I[k] * ((int64_t)x * SUBPIXEL_ONE + half) + t->J[k] * ((int64_t)y * SUBPIXEL_ONE + half) + t->K[k];
                bool top = t->I[k] == 0 && t->J[k] > 0, left = t->I[k] > 0;
                if (mistake == M_BOTTOM_RIGHT)
                    top = t->I[k] == 0 && t->J[k] < 0, left = t->I[k] < 0;
                in = in && (mistake == M_STRICT ? F[k] > 0 : mistake == M_INCLUSIVE ? F[k] >= 0
                                                 : F[k] > 0 || (F[k] == 0 && (top || left)));
            }
            if (x >= 0 && y >= 0 && x < fb->w && y < fb->h)
                NARRATE(tr, .kind = TRACE_PIXEL_TEST, .x = x, .y = y, .e = { F[0], F[1], F[2] },
                        .flags = in ? TRACE_INSIDE : 0);
            if (!in)
                continue;
            double a = (double)F[1] / (double)t->area2, b = (double)F[2] / (double)t->area2,
                   c = (double)F[0] / (double)t->area2;
            if (mistake == M_WEIGHTS) {     /* alpha = F_ab / area2: the edge AT A, not opposite */
                double tmp = a;
                a = c, c = b, b = tmp;
            }
            const struct vertex *A = &t->v[0], *B = &t->v[1], *C = &t->v[2];
            /* as a student's target_write becomes (exercise/student.h) */
            exercise_write(fb, x, y, (float)(a * A->z + b * B->z + c * C->z),
                         shade_pixel(p, tr, a * A->r + b * B->r + c * C->r, a * A->g + b * B->g + c * C->g,
                                     a * A->b + b * B->b + c * C->b, 0, 0));
        }
}

Test(exercise, the_common_mistakes_fail_as_the_texts_say)
{
    static const struct {
        enum mistake m;
        const char *lesson, *check, *says;
    } cases[] = {
        { M_NONE, "02", "", "all 5 checks pass" },
        { M_CORNER, "02", "single triangle", "the exact edge values at its centre" },
        { M_STRICT, "02", "fill-rule ties", "the top-left rule covers it" },
        { M_INCLUSIVE, "02", "fill-rule ties", "leaves it to the triangle on the other side" },
        { M_BOTTOM_RIGHT, "02", "fill-rule ties", "a missing pixel" },
        { M_WEIGHTS, "02", "colour and depth (linear)", "the exact weights of A, B, C" },
        { M_UNCLIPPED, "01", "fill-rule ties", "outside the" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        mistake = cases[i].m;
        struct run run;
        check(&run, lesson_nn(cases[i].lesson), bary_with_mistake, NULL);
        cr_expect_str_eq(run.r.failed, cases[i].check, "mistake %d:\n%s", (int)cases[i].m, run.report);
        cr_expect_not_null(strstr(run.report, cases[i].says), "mistake %d: no \"%s\" in\n%s",
                           (int)cases[i].m, cases[i].says, run.report);
        run_free(&run);
    }
}

/* --- code that narrates nothing --------------------------------------------------- */

/* Every covered pixel written with a bare target_write, as student.h turns
 * it into exercise_write: no NARRATE anywhere. */
static void silent(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                   struct trace *tr)
{
    (void)p, (void)tr;
    for (int y = t->miny; y <= t->maxy && !t->empty; y++)
        for (int x = t->minx; x <= t->maxx; x++) {
            bool in = true;
            for (int k = 0; k < 3; k++)
                in = in && edge_inside(t, k, edge_value(t, k, x, y));
            if (in)
                exercise_write(fb, x, y, 1.0f, 0xffffffffu);
        }
}

static void count_cover(void *ctx, int x, int y)
{
    (void)x, (void)y;
    ++*(int *)ctx;
}

Test(exercise, code_that_narrates_nothing_still_shows_every_pixel_written)
{
    const struct lesson *l02 = lesson_nn("02");
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "triangle", err, sizeof err), "%s", err);
    struct lesson el;
    struct lesson_variant ev[2];
    exercise_lesson(&el, ev, l02, "silent.c");
    exercise_use(l02, silent);
    struct explorer ex;
    cr_assert(explorer_init(&ex, &(struct explorer_desc){ .lesson = &el, .scene = &s, .variant = &ev[1],
                                                         .step = 1 }, err, sizeof err), "%s", err);
    int covered = 0;
    for (int i = 0; i < s.ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s.tris[i].v, s.w, s.h);
        reference_coverage(&t, count_cover, &covered);
    }
    cr_expect_eq(ex.replay.total, (uint64_t)covered, "one step per pixel written");
    cr_expect(ex.has_last);
    cr_expect_eq(ex.last.kind, TRACE_PIXEL_WRITE);
    cr_expect_eq(ex.last.line, l02->exercise.write_line, "lit on the lesson's write line");
    cr_assert(explorer_set_step(&ex, ex.replay.total));
    cr_expect_eq(ex.extra + ex.missing, 0, "the diff finds nothing to say");
    explorer_free(&ex);
    scene_free(&s);
}

/* The tolerances the texts quote: colour within 2 of 255 levels per
 * channel, depth within 0.1 % of z. */
Test(exercise, the_quoted_tolerances_are_the_checks)
{
    cr_expect(pixel_close(0xff102030u, 2.0f, 0xff122232u, 2.0f), "2 levels in every channel");
    cr_expect_not(pixel_close(0xff102030u, 2.0f, 0xff102033u, 2.0f), "3 levels in blue");
    cr_expect_not(pixel_close(0xff102030u, 2.0f, 0xff0d2030u, 2.0f), "3 levels in red");
    cr_expect(pixel_close(0xff102030u, 2.0f, 0xff102030u, 2.0019f), "0.095 %% of z");
    cr_expect_not(pixel_close(0xff102030u, 2.0f, 0xff102030u, 2.0021f), "0.105 %% of z");
    cr_expect_not(pixel_close(0xff102030u, 2.0f, 0xff102030u, 1.9979f), "0.105 %% nearer");
}

/* --- the mutation suite ------------------------------------------------------------ */

/* Every classic mistake of tests/mutations/ (a patch to a worked answer,
 * compiled under its own name: build/mutations.c) fails, and the check
 * that fails first is the one its patch names: at least 8 per lesson.
 *
 * A mistake of your own: copy lessons/NN-name/answer.c, make the mistake in
 * the copy, and keep `diff -u` of the two as tests/mutations/NN-what.patch
 * (a graded variant V's answer-V.c: NN-V--what.patch, checked under V),
 * under a first line that says the mistake and a line "check: NAME" naming
 * the check that must fail first on it (make check on the copy says which).
 * A patch whose check is "none (a correct design)" is a correct solution of
 * another making than the answer's: it must pass every check. */
#define MUTATION_SEARCH SEARCH_FLOOR   /* search scenes per check: the first, fixed by seed 1, as on any machine */
Test(exercise, every_mistake_of_the_mutation_suite_fails_the_check_that_names_it, .timeout = 240)
{
    int n = 0, caught = 0, per_lesson[10] = { 0 }, designs = 0, accepted = 0;
    for (const struct exercise_mutation *m = all_mutations; m->lesson; m++, n++) {
        const struct lesson *l = lesson_nn(m->lesson);
        cr_assert_not_null(l, "%s: no lesson %s", m->name, m->lesson);
        struct run run;
        use_clip = m->clip;
        use_variant = m->variant;
        search_scenes = MUTATION_SEARCH;
        check(&run, l, m->fn, NULL);
        search_scenes = 0;
        use_clip = NULL;
        use_variant = NULL;
        if (strncmp(m->check, "none", 4) == 0) {       /* a correct design: every check passes */
            cr_expect(run.ok, "tests/mutations/%s.patch: a correct design, failed %s:\n%s", m->name, run.r.failed,
                      run.report);
            designs++;
            accepted += run.ok;
            n--;
            run_free(&run);
            continue;
        }
        bool ok = !run.ok && strcmp(run.r.failed, m->check) == 0 && run.r.counterexample[0];
        cr_expect(ok, "tests/mutations/%s.patch: expected the check \"%s\" to fail first, %s:\n%s", m->name,
                  m->check, run.ok ? "all passed" : run.r.failed, run.report);
        caught += ok;
        per_lesson[m->lesson[1] - '0'] += ok;
        run_free(&run);
    }
    fprintf(stderr, "mistakes caught %d of %d, correct designs accepted %d of %d\n", caught, n, accepted, designs);
    cr_expect_eq(caught, n, "mistakes caught %d of %d", caught, n);
    cr_expect_eq(accepted, designs, "correct designs accepted %d of %d", accepted, designs);
    for (int i = 0; all_exercises[i].lesson; i++) {
        int k = all_exercises[i].lesson[1] - '0';
        cr_expect_geq(per_lesson[k], 8, "lesson %s: %d mistakes caught, fewer than 8", all_exercises[i].lesson,
                      per_lesson[k]);
    }
}

/* The search is seeded: the same seed finds the same counterexample, the
 * report prints the seed, and the fixed scenes alone (no search) miss the
 * mistakes only the search is there for. */
Test(exercise, the_search_is_seeded_and_repeatable, .timeout = 120)
{
    const struct exercise_mutation *m = mutation("03-bias-twice");
    const struct lesson *l = lesson_nn("03");
    struct run a, b, none;
    char *text[2] = { NULL, NULL };
    search_scenes = MUTATION_SEARCH;
    check(&a, l, m->fn, NULL);
    check(&b, l, m->fn, NULL);
    search_scenes = 0;
    check(&none, l, m->fn, NULL);
    cr_expect(none.ok, "the fixed scenes alone find it:\n%s", none.report);
    struct run *runs[2] = { &a, &b };
    for (int i = 0; i < 2; i++) {
        cr_assert_not(runs[i]->ok, "%s", runs[i]->report);
        cr_expect_str_eq(runs[i]->r.failed, "fill-rule ties");
        cr_expect(runs[i]->r.found_by_search);
        cr_expect_not_null(strstr(runs[i]->report, "make check SEED=1 "), "%s", runs[i]->report);
        text[i] = strdup(test_read_text(runs[i]->r.counterexample));
        cr_assert_not_null(text[i]);
    }
    cr_expect_str_eq(text[0], text[1], "two runs of one seed, two counterexamples");
    free(text[0]);
    free(text[1]);
    run_free(&a);
    run_free(&b);
    run_free(&none);
}

/* A wrong colour is marked by the diff at the very step that writes it,
 * the triangle unfinished: the printed command opens on a marked pixel. */
Test(exercise, a_wrong_colour_is_marked_at_the_step_that_writes_it)
{
    const struct exercise_mutation *m = mutation("02-weights-rotated");
    const struct lesson *l = lesson_nn("02");
    struct run run;
    check(&run, l, m->fn, NULL);
    cr_assert_str_eq(run.r.failed, "colour and depth (linear)", "%s", run.report);
    struct scene s;
    struct explorer ex;
    open_counterexample(&ex, &s, l, m->fn, NULL, &run, run.r.step);
    cr_expect(ex.has_last);
    cr_expect_eq(ex.last.kind, TRACE_PIXEL_WRITE);
    cr_expect_eq(ex.last.x, run.r.x);
    cr_expect_eq(ex.last.y, run.r.y);
    cr_expect_lt(ex.step, ex.replay.total, "the triangle is not finished yet");
    cr_assert_not_null(ex.diff);
    cr_expect_eq(ex.diff[(size_t)run.r.y * (size_t)s.w + (size_t)run.r.x], EXHIBIT_COLOUR,
                 "pixel (%d, %d) not marked at step %llu", run.r.x, run.r.y, (unsigned long long)run.r.step);
    cr_expect_gt(ex.wrong_colour, 0);
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);
}

/* Lesson 09: a level of detail that is not log2(rho) is named at its quad,
 * with the derivatives, rho and both lambdas, and the printed command opens
 * the explorer on the step that narrates that quad's level of detail, the
 * student's lambda on show; a texel read outside its level is named with
 * its level and size, and opens on a pixel the diff marks. */
Test(exercise, lesson09_names_the_quad_and_the_texel)
{
    const struct lesson *l = lesson_nn("09");
    cr_assert(l && l->exercise.textures && l->exercise.lod_line > 0);
    const struct exercise_mutation *m = mutation("09-log2-rho-squared");
    struct run run;
    check(&run, l, m->fn, NULL);
    cr_assert_not(run.ok);
    cr_expect_not_null(strstr(run.report, "and lambda = log2(rho) = "), "%s", run.report);
    cr_expect_not_null(strstr(run.report, "your level of detail gave lambda = "), "%s", run.report);
    cr_expect_not_null(strstr(run.report, "at the quad's level of detail (step"), "%s", run.report);
    struct scene s;
    struct explorer ex;
    open_counterexample(&ex, &s, l, m->fn, NULL, &run, run.r.step);
    cr_expect(ex.has_last);
    cr_expect_eq(ex.last.kind, TRACE_STEP);
    cr_expect_eq(ex.last.line, l->exercise.lod_line);
    cr_expect_eq(ex.last.x, run.r.x);
    cr_expect_eq(ex.last.y, run.r.y);
    /* the lambda narrated there is the code's own: log2 of rho squared */
    cr_expect_float_eq(ex.last.aux[5], 2 * log2f(ex.last.aux[4]), 1e-3, "%g, rho %g", ex.last.aux[5],
                       ex.last.aux[4]);
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);

    m = mutation("09-wrap-c-mod");
    check(&run, l, m->fn, NULL);
    cr_assert_not(run.ok);
    cr_expect_not_null(strstr(run.report, "of level 0, outside its 2 x 2 texels"), "%s", run.report);
    open_counterexample(&ex, &s, l, m->fn, NULL, &run, run.r.step);
    cr_expect(ex.has_last);
    cr_expect_eq(ex.last.kind, TRACE_PIXEL_WRITE);
    cr_assert_not_null(ex.diff);
    cr_expect_eq(ex.diff[(size_t)run.r.y * (size_t)s.w + (size_t)run.r.x], EXHIBIT_COLOUR,
                 "pixel (%d, %d) not marked at step %llu", run.r.x, run.r.y, (unsigned long long)run.r.step);
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);
}

/* Lesson 06: a clipper that leaves nothing of a triangle. The report sends
 * the student to no empty step, and the explorer around the same clipper
 * (as make exercise and --figure run it) marks the pixels it misses. */
Test(exercise, a_clipper_that_draws_nothing_opens_on_the_missing_pixels)
{
    const struct exercise_mutation *m = mutation("06-outside-kept");
    cr_assert_not_null(m->clip, "06-outside-kept has no clipper");
    const struct lesson *l06 = lesson_nn("06");
    struct run run;
    use_clip = m->clip;
    check(&run, l06, m->fn, NULL);
    use_clip = NULL;
    cr_assert_not(run.ok);
    cr_expect_eq(run.r.step, 0, "%s", run.report);
    cr_expect_null(strstr(run.report, "STEP="), "a command that opens an empty step:\n%s", run.report);
    cr_expect_not_null(strstr(run.report, "SCENE="), "%s", run.report);
    struct scene s;
    struct explorer ex;
    open_counterexample(&ex, &s, l06, m->fn, m->clip, &run, 0);
    cr_expect_eq(ex.replay.total, 0, "the student's clipper made screen triangles");
    cr_expect_gt(ex.missing, 0, "the diff marks nothing");
    cr_expect_eq(ex.extra, 0);
    explorer_free(&ex);
    scene_free(&s);
    run_free(&run);
}

/* --- the skeleton and the answer, one source ------------------------------------- */

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    size_t cap = 0, n = 0, got;
    do {
        if (n + 4096 > cap && !(text = realloc(text, cap = 2 * cap + 4096)))
            break;
        n += got = fread(text + n, 1, cap - n, f);
    } while (got > 0);
    fclose(f);
    *len = n;
    return text;
}

/* Every committed skeleton is what the build makes from the answer beside
 * it (src/exercise/skeleton.awk, into build/skeletons/): the answer is the
 * one source, and the skeleton never drifts from it. */
Test(exercise, every_committed_skeleton_is_made_from_its_answer)
{
    const char *build = getenv("TRISTEP_BUILD") ? getenv("TRISTEP_BUILD") : "build";
    int n = 0;
    for (int i = 0; all_lessons[i]; i++) {
        char committed[512], made[512];
        snprintf(committed, sizeof committed, "lessons/%s/exercise.c", all_lessons[i]->id);
        snprintf(made, sizeof made, "%s/skeletons/%s/exercise.c", build, all_lessons[i]->id);
        size_t a, b;
        char *x = slurp(committed, &a);
        if (!x)
            continue;   /* a lesson without an exercise */
        char *y = slurp(made, &b);
        cr_expect_not_null(y, "%s: not made by the build", made);
        cr_expect(y && a == b && memcmp(x, y, a) == 0,
                  "%s differs from %s, made from the answer beside it: run make skeletons", committed, made);
        free(x);
        free(y);
        n++;
    }
    cr_expect_geq(n, 8);
}
