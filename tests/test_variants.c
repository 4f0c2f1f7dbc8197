/* test_variants.c - the graded variants of the exercises (VARIANT=,
 * lesson_exercise.variants) are judged exactly like the exercises:
 *
 *   - every variant's worked answer passes its check, and its untouched
 *     skeleton fails it with a counterexample;
 *   - the lesson's own answer, the loop the lesson's source prints, fails
 *     the variant's check (a transcription does not pass), and a variant's
 *     answer under another fill rule fails the lesson's own check;
 *   - every variant of a lesson's descriptor has its skeleton, its answer,
 *     at least four mistakes in tests/mutations/ named after it (the
 *     mutation test of test_exercise.c runs them under the variant), and
 *     its place in the lesson's text and on the course page;
 *   - the committed skeleton is the one made from the answer.
 *
 * The exact rule under the bottom-right rule is tested on its own in
 * test_fillrule.c and test_mesh.c. These tests need the worked answers: a
 * student kit leaves them out (Makefile, NEED_ANSWERS).
 */
#define _POSIX_C_SOURCE 200809L   /* open_memstream, mkdtemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "exercise/exercise.h"
#include "testlib.h"

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
    char *report;
    size_t len;
};

/* Check fn as lesson l's exercise under variant v (NULL: the lesson's own
 * convention); the counterexample is removed, the report kept. */
static void check(struct run *run, const struct lesson *l, const struct exercise_variant *v, rasterize_fn fn)
{
    memset(run, 0, sizeof *run);
    char dir[64] = "/tmp/tristep-variant-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    FILE *out = open_memstream(&run->report, &run->len);
    cr_assert_not_null(out);
    struct check_options o = {
        .file = "test.c", .out_dir = dir, .open_cmd = "make exercise LESSON=NN",
        .params = { .subpixel_bits = SUBPIXEL_BITS }, .out = out,
    };
    exercise_use(l, fn);
    exercise_use_variant(v);
    run->ok = exercise_check(l, &o, &run->r);
    fclose(out);
    exercise_use_variant(NULL);
    if (run->r.counterexample[0]) {
        remove(run->r.counterexample);
        char *slash = strrchr(run->r.counterexample, '/');
        if (slash) {
            *slash = '\0';
            rmdir(run->r.counterexample);
            *slash = '/';
        }
    }
    rmdir(dir);
}

static rasterize_fn own_answer(const char *nn)
{
    for (int i = 0; all_exercises[i].lesson; i++)
        if (strcmp(all_exercises[i].lesson, nn) == 0)
            return all_exercises[i].answer;
    return NULL;
}

Test(variants, every_variants_answer_passes_and_its_skeleton_fails)
{
    int n = 0;
    for (const struct exercise_variant_code *c = all_exercise_variants; c->lesson; c++, n++) {
        const struct lesson *l = lesson_nn(c->lesson);
        cr_assert_not_null(l);
        const struct exercise_variant *v = exercise_variant_named(l, c->variant);
        cr_assert_not_null(v, "lessons/%s/exercise-%s.c: the lesson's descriptor has no variant %s", l->id,
                           c->variant, c->variant);
        cr_assert_not_null(c->answer, "lessons/%s/exercise-%s.c has no answer-%s.c beside it", l->id, c->variant,
                           c->variant);
        struct run run;
        check(&run, l, v, c->answer);
        cr_expect(run.ok, "lesson %s, variant %s: the worked answer fails:\n%s", l->id, v->name, run.report);
        cr_expect(strstr(run.report, v->name) != NULL, "the report does not name the variant:\n%s", run.report);
        free(run.report);
        check(&run, l, v, c->skeleton);
        cr_expect(!run.ok && run.r.counterexample[0], "lesson %s, variant %s: the skeleton passes, or fails "
                  "with no counterexample:\n%s", l->id, v->name, run.report);
        free(run.report);
    }
    cr_expect_geq(n, 2, "graded variants of lessons 02 and 03 at least, %d found", n);
}

/* The lesson's source prints the lesson's answer; copied, it must fail the
 * variant, which is what makes the variant worth grading. And the other
 * way: the variant's answer is not the lesson's. */
Test(variants, the_lessons_own_answer_fails_every_variant_and_back)
{
    for (const struct exercise_variant_code *c = all_exercise_variants; c->lesson; c++) {
        const struct lesson *l = lesson_nn(c->lesson);
        const struct exercise_variant *v = exercise_variant_named(l, c->variant);
        cr_assert(l && v && c->answer);
        rasterize_fn own = own_answer(c->lesson);
        cr_assert_not_null(own);
        struct run run;
        check(&run, l, v, own);
        cr_expect(!run.ok, "lesson %s: its own answer passes variant %s:\n%s", l->id, v->name, run.report);
        free(run.report);
        /* and the lesson's own algorithm, variants[0], as a whole rasterizer */
        check(&run, l, v, l->variants[0].rasterize);
        cr_expect(!run.ok, "lesson %s: its own algorithm passes variant %s:\n%s", l->id, v->name, run.report);
        free(run.report);
        if (v->rule == FILL_TOP_LEFT)
            continue;   /* another walk, the same pixels: the lesson's own check pins no order */
        check(&run, l, NULL, c->answer);
        cr_expect(!run.ok, "lesson %s: variant %s's answer passes the lesson's own check:\n%s", l->id, v->name,
                  run.report);
        free(run.report);
    }
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    int ch;
    while ((ch = fgetc(f)) != EOF)
        fputc(ch, m);
    fclose(m);
    fclose(f);
    return buf;
}

/* Each variant of a lesson's descriptor: its files, its mistakes, its text. */
Test(variants, every_variant_has_its_files_its_mistakes_and_its_text)
{
    const char *build = getenv("TRISTEP_BUILD") ? getenv("TRISTEP_BUILD") : "build";
    char *course = slurp("lessons/README.md");
    cr_assert_not_null(course);
    int nv = 0;
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        for (const struct exercise_variant *v = l->exercise.variants; v && v->name; v++, nv++) {
            char path[256], made[256], option[96];
            snprintf(path, sizeof path, "lessons/%s/exercise-%s.c", l->id, v->name);
            snprintf(made, sizeof made, "%s/skeletons/%s/exercise-%s.c", build, l->id, v->name);
            char *a = slurp(path), *b = slurp(made);
            cr_expect(a && b && strcmp(a, b) == 0,
                      "%s differs from %s, made from answer-%s.c beside it: run make skeletons", path, made, v->name);
            free(a);
            free(b);
            int found = 0;
            for (const struct exercise_mutation *m = all_mutations; m->lesson; m++)
                found += m->variant && strcmp(m->variant, v->name) == 0 && strncmp(m->lesson, l->id, 2) == 0;
            cr_expect_geq(found, 4, "lesson %s, variant %s: %d mistakes in tests/mutations/%.2s-%s--*.patch, "
                          "fewer than 4", l->id, v->name, found, l->id, v->name);
            snprintf(option, sizeof option, "VARIANT=%s", v->name);
            snprintf(path, sizeof path, "lessons/%s/README.md", l->id);
            char *text = slurp(path);
            cr_assert_not_null(text);
            cr_expect(strstr(text, option) != NULL, "%s does not give its variant's command (%s)", path, option);
            cr_expect(strstr(course, option) != NULL, "lessons/README.md does not tell which variant to give "
                      "(%s of lesson %.2s)", option, l->id);
            free(text);
        }
    }
    free(course);
    cr_expect_geq(nv, 2);
}
