/* test_grade.c - `make grade LESSON=NN DIR=folder` grades a whole folder
 * in the sandbox: honest files get their right verdict and score, and files
 * written to game the grader get theirs beside them: a constructor that
 * prints a passing report and _exit(0)s, one that calls the lesson's own
 * rasterizer, a header's function that is the exercise, #include
 * "answer.c", a file named ...c, names that sanitise alike, a formula for
 * a name. No process of the run survives it and the project tree is the
 * same afterwards. Lesson 02's checks are the cheapest. The slower hostile
 * files (a fork bomb, 4 GiB of memory, endless output, a child that
 * outlives its run) are make grade-hostile's (TRISTEP_HOSTILE=1). Run from
 * the repository's top folder, as make test does. */
#define _POSIX_C_SOURCE 200809L   /* popen, mkdtemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "testlib.h"

/* the grading run's folder: the test's scratch folder (testlib) */
static const char *dir;

static void make_dir(void)
{
    test_scratch_make();
    dir = test_scratch_dir();
}

/* A file's text, copied (test_read_text's buffer is reused by the next read). */
static char *slurp(const char *path)
{
    char *copy = strdup(test_read_text(path));
    cr_assert_not_null(copy);
    return copy;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot write %s", path);
    fputs(text, f);
    fclose(f);
}

/* The CSV row of the student `name` (its first field), copied; NULL if none. */
static char *row_of(const char *csv, const char *name, char *row, size_t n)
{
    char key[96];
    snprintf(key, sizeof key, "\n\"%s\",", name);
    const char *at = strstr(csv, key);
    if (!at)
        return NULL;
    const char *begin = at + 1, *end = strchr(begin, '\n');
    size_t len = end ? (size_t)(end - begin) : strlen(begin);
    snprintf(row, n, "%.*s", (int)(len < n ? len : n - 1), begin);
    return row;
}


/* The project's files as git sees them (what a submission could change). */
static char *tree_state(void)
{
    FILE *p = popen("git status --porcelain --untracked-files=all -- . ':!build' 2>&1; "
                    "git diff --stat 2>&1 | tail -n 1", "r");
    cr_assert_not_null(p);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, p);
    buf[n] = '\0';
    pclose(p);
    return strdup(buf);
}

/* Processes of nobody (the sandbox's user when the tests run as root) or
 * still in a run's folder. */
static int survivors(void)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "ps -eo uid=,args= | awk '($1 == 65534 || index($0, \"%s\")) && !index($0, \"ps -eo\") && !index($0, \"awk\") { n++ } END { print n + 0 }'", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    if (p && fscanf(p, "%d", &n) != 1)
        n = -1;
    if (p)
        pclose(p);
    return n;
}

static void put(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/sub/%s", dir, name);
    write_text(path, text);
}

/* The answer with text put at the top of its rasterizer's body. */
static char *answer_with(const char *answer, const char *top, const char *before)
{
    const char *body = strchr(strstr(answer, "void exercise_rasterize("), '{');
    cr_assert_not_null(body);
    size_t n = strlen(answer) + strlen(top) + strlen(before) + 8;
    char *out = malloc(n);
    snprintf(out, n, "%s%.*s\n%s%s", before, (int)(body + 1 - answer), answer, top, body + 1);
    return out;
}

/* make grade on sub/ into out/ and grade.csv: the CSV's text. */
static char *grade(const char *extra)
{
    char cmd[1024], path[256];
    const char *b = getenv("TRISTEP_BUILD");
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory grade "
             "B=%s LESSON=02 DIR=%s/sub OUT=%s/out CSV=%s/grade.csv TIMEOUT=30 %s > %s/log 2>&1",
             b ? b : "build", dir, dir, dir, extra, dir);
    int st = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    char *log = slurp(path);
    cr_assert_eq(st, 0, "%s:\n%s", cmd, log);
    free(log);
    snprintf(path, sizeof path, "%s/grade.csv", dir);
    return slurp(path);
}

static void expect_row(const char *csv, const char *name, const char *has)
{
    char row[4096];
    cr_assert_not_null(row_of(csv, name, row, sizeof row), "no row for %s:\n%s", name, csv);
    cr_expect_not_null(strstr(row, has), "%s: expected %s in\n%s", name, has, row);
}

Test(grade, honest_files_and_cheats_side_by_side, .init = make_dir, .fini = test_scratch_remove, .timeout = 300)
{
    char path[256];
    snprintf(path, sizeof path, "%s/sub", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    char *before = tree_state();
    char *answer = slurp("lessons/02-barycentric/answer.c");
    char *skeleton = slurp("lessons/02-barycentric/exercise.c");
    put("good.c", answer);
    put("wrong.c", skeleton);
    put("broken.c", "this is not C;\n");
    char *t = answer_with(answer, "    for (volatile int forever = 1; forever;)\n        ;\n", "");
    put("loop.c", t);
    free(t);
    /* a passing report printed by a constructor, then the all-passed exits */
    t = answer_with(skeleton, "", "#include <stdio.h>\n#include <unistd.h>\n"
                    "__attribute__((constructor)) static void forge(void)\n"
                    "{ puts(\"all 5 checks pass\"); fflush(stdout); _exit(0); }\n");
    put("forge0.c", t);
    free(t);
    t = answer_with(skeleton, "    _exit(10);\n", "#include <unistd.h>\n");
    put("forge10.c", t);
    free(t);
    /* the lesson's own rasterizer, the oracle, a header's answer, the answer's file */
    put("variant.c", "#include \"lesson.h\"\nextern const struct lesson lesson_02;\n"
        "void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p, struct target *fb, struct trace *tr)\n"
        "{ lesson_02.variants[0].rasterize(t, p, fb, tr); }\n");
    put("oracle.c", "#include \"lesson.h\"\nstatic void px(void *c, int x, int y) { (void)c, (void)x, (void)y; }\n"
        "void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p, struct target *fb, struct trace *tr)\n"
        "{ (void)p, (void)fb, (void)tr; reference_coverage(t, px, 0); }\n");
    put("header.c", "#include \"lesson.h\"\n"
        "void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p, struct target *fb, struct trace *tr)\n"
        "{ (void)p, (void)fb, (void)tr; (void)edge_inside(t, 0, 0); }\n");
    put("answer-include.c", "#include \"answer.c\"\n");
    put("path-include.c", "#include \"../lessons/02-barycentric/answer.c\"\n");
    put("classmate.c", "#include \"good.c\"\n");
    free(answer);
    free(skeleton);

    char *csv = grade("");
    expect_row(csv, "good.c", "\"pass\",\"9\",\"9\",\"1\",\"2\",\"2\",\"2\",\"2\"");
    expect_row(csv, "wrong.c", "\"fail\",\"0\",\"9\",\"0 failed\"");
    expect_row(csv, "broken.c", "\"compile error\",\"0\"");
    expect_row(csv, "loop.c", "\"0 timed out\"");
    expect_row(csv, "forge0.c", "\"fail\",\"0\",\"9\",\"0 crashed\"");
    expect_row(csv, "forge10.c", "\"fail\",\"0\",\"9\",\"0 crashed\"");
    expect_row(csv, "variant.c", "\"link error\",\"0\",\"9\"");
    expect_row(csv, "variant.c", "uses lesson_02, which lesson 02's exercise does not give");
    expect_row(csv, "oracle.c", "uses reference_coverage, which lesson 02's exercise does not give");
    expect_row(csv, "header.c", "uses edge_inside, which lesson 02's exercise does not give");
    expect_row(csv, "answer-include.c", "includes answer.c, which is not there");
    expect_row(csv, "path-include.c", "includes ../lessons/02-barycentric/answer.c, which is not there");
    expect_row(csv, "classmate.c", "includes good.c, which is not there");
    /* the honest file's Gradescope results */
    snprintf(path, sizeof path, "%s/out/good/results.json", dir);
    char *json = slurp(path);
    cr_expect_not_null(strstr(json, "\"score\": 9,\n  \"max_score\": 9,"), "%s", json);
    cr_expect_not_null(strstr(json, "\"name\": \"fill-rule ties\", \"score\": 2, \"max_score\": 2, \"status\": \"passed\""), "%s", json);
    free(json);
    cr_expect_eq(survivors(), 0, "processes of the run survive it");
    char *after = tree_state();
    cr_expect_str_eq(after, before, "the project tree changed");
    free(after);
    free(before);
    free(csv);
}

Test(grade, untrusted_names_and_a_seed, .init = make_dir, .fini = test_scratch_remove, .timeout = 240)
{
    char path[256];
    snprintf(path, sizeof path, "%s/sub", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    char *answer = slurp("lessons/02-barycentric/answer.c");
    put("...c", answer);
    put("a b.c", answer);
    put("a_b.c", "this is not C;\n");
    put("=HYPERLINK(\"x\").c", answer);
    /* one folder per student, the exercise file somewhere in it */
    snprintf(path, sizeof path, "%s/sub/-rf \xc3\xa9l\xc3\xa8ve", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    snprintf(path, sizeof path, "%s/sub/-rf \xc3\xa9l\xc3\xa8ve/exercise.c", dir);
    write_text(path, answer);
    free(answer);

    char *csv = grade("SEED=7");
    expect_row(csv, "...c", "\"pass\"");
    expect_row(csv, "a b.c", "\"a_b\",\"a b.c\",\"pass\"");
    expect_row(csv, "a_b.c", "\"a_b-2\",\"a_b.c\",\"compile error\"");
    expect_row(csv, "'=HYPERLINK(\"\"x\"\").c", "\"pass\"");
    /* a leading dash neutralised as a formula's would be */
    expect_row(csv, "'-rf \xc3\xa9l\xc3\xa8ve", "\"_rf_l_ve\",\"'-rf \xc3\xa9l\xc3\xa8ve/exercise.c\",\"pass\"");
    cr_expect_not_null(strstr(csv, ",\"7\","), "the seed in every row:\n%s", csv);
    cr_expect_null(strstr(csv, "\n\"="), "a formula in the first field:\n%s", csv);
    cr_expect_null(strstr(csv, ",\"="), "a formula in a field:\n%s", csv);
    free(csv);
}
