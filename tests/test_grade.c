/* test_grade.c - `make grade LESSON=NN DIR=folder` grades a whole folder:
 * a correct file, a wrong one, one that does not compile and one that never
 * finishes each get their row in the CSV, the run goes through all four,
 * and each counterexample lies in its own file's folder. Lesson 02's checks
 * are the cheapest; the time limit is far above what its answer needs, and
 * the file that loops is stopped by the check's own guard or by the limit,
 * a "timed out" either way. Run from the repository's top folder, as make
 * test does. */
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

/* The CSV row of the file whose name ends in `name`, copied; NULL if none. */
static char *row_of(const char *csv, const char *name, char *row, size_t n)
{
    char key[96];
    snprintf(key, sizeof key, "/sub/%s\",", name);
    const char *at = strstr(csv, key);
    if (!at)
        return NULL;
    const char *begin = at, *end = strchr(at, '\n');
    while (begin > csv && begin[-1] != '\n')
        begin--;
    size_t len = end ? (size_t)(end - begin) : strlen(begin);
    snprintf(row, n, "%.*s", (int)(len < n ? len : n - 1), begin);
    return row;
}

Test(grade, a_folder_of_four_files_gets_four_rows, .init = make_dir, .fini = test_scratch_remove, .timeout = 240)
{
    char path[256], cmd[1024];
    snprintf(path, sizeof path, "%s/sub", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    char *answer = slurp("lessons/02-barycentric/answer.c");
    snprintf(path, sizeof path, "%s/sub/good.c", dir);
    write_text(path, answer);
    /* the untouched skeleton: compiles, draws nothing */
    char *skeleton = slurp("lessons/02-barycentric/exercise.c");
    snprintf(path, sizeof path, "%s/sub/wrong.c", dir);
    write_text(path, skeleton);
    snprintf(path, sizeof path, "%s/sub/broken.c", dir);
    write_text(path, "this is not C;\n");
    /* the answer, with an endless loop at the top of its rasterizer */
    char *body = strstr(answer, "void exercise_rasterize(");
    cr_assert_not_null(body);
    body = strchr(body, '{');
    cr_assert_not_null(body);
    snprintf(path, sizeof path, "%s/sub/loop.c", dir);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fwrite(answer, 1, (size_t)(body + 1 - answer), f);
    fputs("\n    for (volatile int forever = 1; forever;)\n        ;\n", f);
    fputs(body + 1, f);
    fclose(f);
    free(answer);
    free(skeleton);

    const char *b = getenv("TRISTEP_BUILD");
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory grade "
             "B=%s LESSON=02 DIR=%s/sub OUT=%s/out CSV=%s/grade.csv TIMEOUT=60 > %s/log 2>&1",
             b ? b : "build", dir, dir, dir, dir);
    int st = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    char *log = slurp(path);
    cr_assert_eq(st, 0, "%s:\n%s", cmd, log);

    snprintf(path, sizeof path, "%s/grade.csv", dir);
    char *csv = slurp(path);
    cr_expect_not_null(strstr(csv, "file,result,passed,checks,\"single triangle\",\"fill-rule ties\","),
                       "the header names the lesson's checks:\n%s", csv);
    cr_expect_not_null(strstr(csv, ",first failure,counterexample\n"), "%s", csv);
    int lines = 0;
    for (const char *p = csv; *p; p++)
        lines += *p == '\n';
    cr_expect_eq(lines, 5, "a header and four rows:\n%s", csv);

    char row[1024];
    cr_assert_not_null(row_of(csv, "good.c", row, sizeof row), "%s", csv);
    cr_expect_not_null(strstr(row, "\"pass\",5,5,ok,ok,ok,ok,ok,\"\",\"\""), "%s", row);
    cr_assert_not_null(row_of(csv, "wrong.c", row, sizeof row), "%s", csv);
    cr_expect_not_null(strstr(row, "\"fail\",0,5,FAILED,,,,,\"single triangle\","), "%s", row);
    /* its counterexample, in the wrong file's own folder, a scene that exists */
    char want[256];
    snprintf(want, sizeof want, "\"%s/out/wrong/check/", dir);
    const char *cx = strstr(row, want);
    cr_expect_not_null(cx, "the counterexample is not in %s: %s", want, row);
    if (cx) {
        snprintf(path, sizeof path, "%.*s", (int)strcspn(cx + 1, "\""), cx + 1);
        cr_expect_eq(access(path, R_OK), 0, "no counterexample %s", path);
    }
    cr_assert_not_null(row_of(csv, "broken.c", row, sizeof row), "%s", csv);
    cr_expect_not_null(strstr(row, "\"compile error\",0,"), "%s", row);
    cr_expect_not_null(strstr(row, "error"), "the compiler's first error: %s", row);
    cr_assert_not_null(row_of(csv, "loop.c", row, sizeof row), "%s", csv);
    cr_expect_not_null(strstr(row, "\"timed out\",0,5,timed out,"), "%s", row);
    free(csv);
    free(log);
}
