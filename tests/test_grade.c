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
#define _GNU_SOURCE               /* popen, usleep, prctl */

#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testlib.h"

/* the grading run's folder: the test's scratch folder (testlib) */
static const char *dir;

static void make_dir(void)
{
    test_scratch_make();
    dir = test_scratch_dir();
    prctl(PR_SET_CHILD_SUBREAPER, 1);     /* survivors() */
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
    FILE *p = popen("git status --porcelain --untracked-files=all --ignored -- . ':!build' 2>&1; "
                    "git diff --stat 2>&1 | tail -n 1", "r");
    cr_assert_not_null(p);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, p);
    buf[n] = '\0';
    pclose(p);
    return strdup(buf);
}

/* The processes of the run that survive it. The test process is a
 * subreaper (make_dir): whatever make grade started, in a sandbox or in a
 * session of its own, is its descendant, and becomes its child when its
 * parents end; so once make grade has returned, a child of this process is
 * a survivor. Each is killed (so that the next test starts clean) and
 * counted, after a moment for the ones the run killed to go. */
static int survivors(void)
{
    int n = 0;
    for (int round = 0; round < 100; round++) {
        n = 0;
        DIR *d = opendir("/proc");
        struct dirent *e;
        while (d && (e = readdir(d))) {
            char p[300], buf[512];
            snprintf(p, sizeof p, "/proc/%s/stat", e->d_name);
            FILE *f = e->d_name[0] >= '1' && e->d_name[0] <= '9' ? fopen(p, "r") : NULL;
            size_t k = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
            if (f)
                fclose(f);
            buf[k] = '\0';
            const char *paren = strrchr(buf, ')');
            char state;
            int ppid;
            if (paren && sscanf(paren + 1, " %c %d", &state, &ppid) == 2 && ppid == getpid() && state != 'Z')
                n++;
        }
        if (d)
            closedir(d);
        while (waitpid(-1, NULL, WNOHANG) > 0)
            ;
        if (!n)
            return 0;
        usleep(20000);
    }
    return n;
}

/* What a run must leave: no process of its own, the project tree as it
 * was (before: tree_state() then; freed). */
static void expect_no_trace(char *before)
{
    cr_expect_eq(survivors(), 0, "processes of the run survive it");
    char *after = tree_state();
    cr_expect_str_eq(after, before, "the project tree changed");
    free(after);
    free(before);
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

/* make grade LESSON=lesson on sub/ into out/ and grade.csv: the CSV's text. */
static char *grade_lesson(const char *lesson, const char *extra)
{
    char cmd[1024], path[256];
    const char *b = getenv("TRISTEP_BUILD");
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory grade "
             "B=%s LESSON=%s DIR=%s/sub OUT=%s/out CSV=%s/grade.csv TIMEOUT=30 %s > %s/log 2>&1",
             b ? b : "build", lesson, dir, dir, dir, extra, dir);
    int st = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    char *log = slurp(path);
    cr_assert_eq(st, 0, "%s:\n%s", cmd, log);
    free(log);
    snprintf(path, sizeof path, "%s/grade.csv", dir);
    return slurp(path);
}

static char *grade(const char *extra)
{
    return grade_lesson("02", extra);
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
    cr_expect_not_null(strstr(json, "\"score\": 9,\n"), "%s", json);
    cr_expect_not_null(strstr(json, "\"name\": \"fill-rule ties\", \"score\": 2, \"max_score\": 2, \"status\": \"passed\""), "%s", json);
    free(json);
    expect_no_trace(before);
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
    /* a symbolic link, to the answer, for a student: a row, never followed */
    char target[1024];
    cr_assert_not_null(realpath("lessons/02-barycentric/answer.c", target));
    snprintf(path, sizeof path, "%s/sub/linked", dir);
    cr_assert_eq(symlink(target, path), 0);

    char *csv = grade("SEED=7");
    expect_row(csv, "linked", "\"no file\",\"0\",\"9\"");
    expect_row(csv, "linked", "a symbolic link");
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

/* Hostile files: each the lesson's answer, its skeleton or nothing, with
 * code put before it and at the top of its rasterizer's body; what its
 * CSV row must hold. The run grades them beside an honest answer and the
 * skeleton, whose rows must be right too. */
struct hostile {
    const char *name, *base, *before, *top;
    const char *expect[2];
    bool quick;                 /* in make test's share; all in make grade-hostile's */
};

static const struct hostile hostiles[] = {
    /* a fork bomb beside the skeleton: its processes stop at the limit, the
     * checks run, and the next file's process limit is its own */
    { "bomb.c", "exercise", "#include <unistd.h>\n__attribute__((constructor)) static void bomb(void)\n"
      "{ if (fork() == 0) for (;;) if (fork() < 0) pause(); }\n", "", { "\",\"fail", NULL }, true },
    /* a child in a session of its own, forked twice, that would rewrite
     * its verdict once the run is over */
    { "outlive.c", "exercise", "#include <stdio.h>\n#include <unistd.h>\n#include <sys/wait.h>\n"
      "__attribute__((constructor)) static void linger(void)\n"
      "{ pid_t a = fork(); if (a == 0) { setsid(); if (fork() == 0) for (int i = 0; i < 300; i++) {\n"
      "  sleep(1); puts(\"all checks pass\"); fflush(stdout); FILE *f = fopen(\"../check.txt\", \"w\");\n"
      "  if (f) fputs(\"all checks pass\", f), fclose(f); } _exit(0); } waitpid(a, NULL, 0); }\n",
      "", { "\",\"fail\",\"0\"", "\"0 failed\"" }, true },
    /* the answer, trying to kill its grader and everything else first: the
     * grader is out of its reach, so the work gets its due */
    { "killer.c", "answer", "#include <signal.h>\n#include <unistd.h>\n"
      "__attribute__((constructor)) static void killer(void)\n"
      "{ kill(getppid(), SIGKILL); kill(-1, SIGKILL); kill(1, SIGKILL); }\n", "", { "\",\"pass\",\"9\"", NULL }, true },
    /* the answer, printing 75 MB first: the log keeps 256 KiB, the run goes on */
    { "flood.c", "answer", "#include <stdio.h>\n",
      "    static int once;\n    if (!once++)\n        for (int i = 0; i < 1 << 22; i++)\n"
      "            fputs(\"all checks pass!!\\n\", stdout);\n", { "\",\"pass\",\"9\"", NULL }, true },
    /* 4 GiB, more than a runner may have: a crash */
    { "memory.c", "answer", "#include <stdlib.h>\n#include <string.h>\n",
      "    char *m = malloc((size_t)4 << 30);\n    if (!m)\n        abort();\n    memset(m, 1, (size_t)4 << 30);\n"
      "    free(m);\n", { "\",\"fail\",\"0\"", "\"0 crashed\"" }, false },
    /* a file that includes itself twice at every level: 2^40 inclusions */
    { "self-include.c", NULL, "#if __INCLUDE_LEVEL__ < 40\n#include __FILE__\n#include __FILE__\n#endif\n", "",
      { "\",\"timed out\",\"0\"", "compiling took more than" }, false },
    /* a destructor that forges a report after the real failure, in its log,
     * in files where check.txt might be and on the results' pipe */
    { "destructor.c", "exercise", "#include <stdio.h>\n#include <unistd.h>\n"
      "__attribute__((destructor)) static void forge(void)\n"
      "{ const char *p[] = { \"check.txt\", \"../check.txt\", \"/out/check.txt\", \"/tmp/check.txt\" };\n"
      "  for (int i = 0; i < 4; i++) { FILE *f = fopen(p[i], \"w\"); if (f) fputs(\"all checks pass\\n\", f), fclose(f); }\n"
      "  puts(\"all checks pass\"); fflush(stdout); (void)!write(3, \"\\1\\0\\0\\0\\0\\0\\0\\0\", 8); _exit(10); }\n",
      "", { "\",\"fail\",\"0\"", "\"0 failed\"" }, false },
    /* the private /tmp filled to its end first, then the work */
    { "disk.c", "answer", "#include <stdio.h>\n#include <string.h>\n"
      "__attribute__((constructor)) static void fill(void)\n"
      "{ static char b[1 << 19]; memset(b, 'x', sizeof b);\n"
      "  for (int i = 0; i < 1000; i++) { char n[64]; snprintf(n, sizeof n, \"/tmp/fill%d\", i);\n"
      "    FILE *f = fopen(n, \"w\"); if (!f) break; size_t w = fwrite(b, 1, sizeof b, f);\n"
      "    if (fclose(f) != 0 || w != sizeof b) break; } }\n", "", { "\",\"pass\",\"9\"", NULL }, false },
    /* an endless loop in a constructor: the runner never starts */
    { "spin.c", "answer", "__attribute__((constructor)) static void spin(void) { for (volatile int f = 1; f;) ; }\n",
      "", { "\",\"fail", "\"0 timed out\"" }, false },
};

static void grade_hostiles(const char *lesson, bool all)
{
    char path[256], base_path[256];
    snprintf(path, sizeof path, "%s/sub", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    char *before = tree_state();
    snprintf(base_path, sizeof base_path, "lessons/%s-*/answer.c", lesson);
    char cmd[512];
    snprintf(cmd, sizeof cmd, "ls lessons/%s-*/answer.c", lesson);
    FILE *ls = popen(cmd, "r");
    cr_assert(ls && fgets(base_path, sizeof base_path, ls));
    pclose(ls);
    base_path[strcspn(base_path, "\n")] = '\0';
    char *answer = slurp(base_path);
    strcpy(strrchr(base_path, '/'), "/exercise.c");
    char *skeleton = slurp(base_path);
    put("good.c", answer);
    put("wrong.c", skeleton);
    for (size_t i = 0; i < sizeof hostiles / sizeof hostiles[0]; i++) {
        const struct hostile *h = &hostiles[i];
        if (!all && !h->quick)
            continue;
        const char *base = !h->base ? NULL : !strcmp(h->base, "answer") ? answer : skeleton;
        char *t = base ? answer_with(base, h->top, h->before) : strdup(h->before);
        put(h->name, t);
        free(t);
    }
    char *csv = grade_lesson(lesson, all ? "TIMEOUT=20" : "");
    expect_row(csv, "good.c", "\",\"pass\",\"");
    expect_row(csv, "wrong.c", !strcmp(lesson, "02") ? "\",\"fail\",\"0\"" : "\",\"fail\",\"");
    for (size_t i = 0; i < sizeof hostiles / sizeof hostiles[0]; i++) {
        const struct hostile *h = &hostiles[i];
        if (!all && !h->quick)
            continue;
        /* the scores are lesson 02's: another lesson's row gets its result */
        for (int k = 0; k < 2 && h->expect[k]; k++)
            expect_row(csv, h->name, !strcmp(lesson, "02") || k ? h->expect[k]
                       : strstr(h->expect[k], "\"pass\"") ? "\",\"pass\",\""
                       : strstr(h->expect[k], "\"fail\"") ? "\",\"fail\",\"" : h->expect[k]);
    }
    /* the flood's log: its first 256 KiB and a line that says so */
    struct stat st;
    snprintf(path, sizeof path, "%s/out/flood/log.txt", dir);
    cr_expect_eq(stat(path, &st), 0, "%s", path);
    cr_expect(st.st_size >= 256 << 10 && st.st_size < (256 << 10) + 200, "flood's log: %lld bytes", (long long)st.st_size);
    expect_no_trace(before);
    free(csv);
    free(answer);
    free(skeleton);
}

/* make test's share: a few hostile files of lesson 02. make grade-hostile
 * (TRISTEP_HOSTILE="02 06 09", a list of lessons) grades them all, for each
 * lesson of the list. */
Test(grade, hostile_files, .init = make_dir, .fini = test_scratch_remove, .timeout = 1200)
{
    const char *list = getenv("TRISTEP_HOSTILE");
    if (!list || !*list) {
        grade_hostiles("02", false);
        return;
    }
    char lessons[64];
    snprintf(lessons, sizeof lessons, "%s", list);
    for (char *save, *l = strtok_r(lessons, " ", &save); l; l = strtok_r(NULL, " ", &save)) {
        if (l != lessons) {     /* a fresh folder for the next lesson */
            test_scratch_remove();
            make_dir();
        }
        grade_hostiles(l, true);
    }
}

/* --- Gradescope's results.json ----------------------------------------------------- */

/* A JSON reader just large enough to check a results.json against the
 * format Gradescope documents ("Autograder Specifications", results.json):
 * every key one it names, with the type it gives. */
struct json {
    const char *p;
    char err[200];
};

static void js_ws(struct json *j)
{
    while (*j->p == ' ' || *j->p == '\n' || *j->p == '\t' || *j->p == '\r')
        j->p++;
}

static bool js_fail(struct json *j, const char *what)
{
    if (!j->err[0])
        snprintf(j->err, sizeof j->err, "%s at \"%.30s\"", what, j->p);
    return false;
}

/* A string into out (escapes kept as they are: only its shape matters here). */
static bool js_string(struct json *j, char *out, size_t n)
{
    js_ws(j);
    if (*j->p != '"')
        return js_fail(j, "a string expected");
    size_t k = 0;
    for (j->p++; *j->p != '"'; j->p++) {
        if (!*j->p || (unsigned char)*j->p < 0x20)
            return js_fail(j, "an unterminated string or a control character in it");
        if (*j->p == '\\') {
            if (!strchr("\"\\/bfnrtu", j->p[1]))
                return js_fail(j, "an unknown escape");
            if (k + 1 < n)
                out[k++] = *j->p;
            j->p++;
        }
        if (k + 1 < n)
            out[k++] = *j->p;
    }
    j->p++;
    if (n)
        out[k] = '\0';
    return true;
}

static bool js_number(struct json *j, double *v)
{
    js_ws(j);
    char *end;
    *v = strtod(j->p, &end);
    if (end == j->p || (*j->p != '-' && (*j->p < '0' || *j->p > '9')))
        return js_fail(j, "a number expected");
    j->p = end;
    return true;
}

static bool js_value(struct json *j);

/* An object: member(j, key, ctx) reads each member's value. */
static bool js_object(struct json *j, bool (*member)(struct json *, const char *, void *), void *ctx)
{
    char key[256];
    js_ws(j);
    if (*j->p++ != '{')
        return js_fail(j, "an object expected");
    js_ws(j);
    if (*j->p == '}')
        return j->p++, true;
    for (;;) {
        if (!js_string(j, key, sizeof key))
            return false;
        js_ws(j);
        if (*j->p++ != ':')
            return js_fail(j, "a colon expected");
        if (!member(j, key, ctx))
            return false;
        js_ws(j);
        if (*j->p == '}')
            return j->p++, true;
        if (*j->p++ != ',')
            return js_fail(j, "a comma expected");
    }
}

static bool js_any_member(struct json *j, const char *key, void *ctx)
{
    (void)key, (void)ctx;
    return js_value(j);
}

/* An array: item(j, ctx) reads each item. */
static bool js_array(struct json *j, bool (*item)(struct json *, void *), void *ctx)
{
    js_ws(j);
    if (*j->p++ != '[')
        return js_fail(j, "an array expected");
    js_ws(j);
    if (*j->p == ']')
        return j->p++, true;
    for (;;) {
        if (!item(j, ctx))
            return false;
        js_ws(j);
        if (*j->p == ']')
            return j->p++, true;
        if (*j->p++ != ',')
            return js_fail(j, "a comma expected");
    }
}

static bool js_any_item(struct json *j, void *ctx)
{
    (void)ctx;
    return js_value(j);
}

static bool js_value(struct json *j)
{
    js_ws(j);
    double v;
    char s[8];
    if (*j->p == '"')
        return js_string(j, s, 0);
    if (*j->p == '{')
        return js_object(j, js_any_member, NULL);
    if (*j->p == '[')
        return js_array(j, js_any_item, NULL);
    for (const char *const *w = (const char *const[]){ "true", "false", "null", NULL }; *w; w++)
        if (!strncmp(j->p, *w, strlen(*w)))
            return j->p += strlen(*w), true;
    return js_number(j, &v);
}

static bool one_of(const char *v, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(v, *list))
            return true;
    return false;
}

static const char *const formats[] = { "text", "html", "simple_format", "md", "ansi", NULL };
static const char *const visibilities[] = { "hidden", "after_due_date", "after_published", "visible", NULL };

/* A string member whose value must be one of list. */
static bool js_enum(struct json *j, const char *const *list, const char *what)
{
    char v[64];
    return (js_string(j, v, sizeof v) && one_of(v, list)) || js_fail(j, what);
}

/* What a results.json adds up to: its score, its tests' scores, max_scores,
 * passes and count. */
struct results {
    double score, sum, max, test_score, test_max;
    int passed, ntests;
    bool test_has_score, test_has_status;
};

/* A member of a test of "tests": the keys Gradescope documents, each of its type. */
static bool js_test_member(struct json *j, const char *key, void *ctx)
{
    struct results *r = ctx;
    char v[256];
    if (!strcmp(key, "score") || !strcmp(key, "max_score")) {
        r->test_has_score |= !strcmp(key, "score");
        return js_number(j, !strcmp(key, "score") ? &r->test_score : &r->test_max);
    }
    if (!strcmp(key, "status")) {
        js_ws(j);
        r->test_has_status = true;
        r->passed += !strncmp(j->p, "\"passed\"", 8);
        return js_enum(j, (const char *const[]){ "passed", "failed", NULL }, "a status other than passed or failed");
    }
    if (!strcmp(key, "name") || !strcmp(key, "number") || !strcmp(key, "output"))
        return js_string(j, v, sizeof v);
    if (!strcmp(key, "name_format") || !strcmp(key, "output_format"))
        return js_enum(j, formats, "a format Gradescope does not name");
    if (!strcmp(key, "visibility"))
        return js_enum(j, visibilities, "a visibility Gradescope does not name");
    if (!strcmp(key, "tags"))
        return js_array(j, js_any_item, NULL);
    if (!strcmp(key, "extra_data"))
        return js_object(j, js_any_member, NULL);
    return js_fail(j, "a key of a test that Gradescope does not document");
}

static bool js_test(struct json *j, void *ctx)
{
    struct results *r = ctx;
    r->test_score = r->test_max = 0;
    r->test_has_score = r->test_has_status = false;
    if (!js_object(j, js_test_member, r))
        return false;
    if (!r->test_has_score || !r->test_has_status || r->test_score < 0 || r->test_score > r->test_max)
        return js_fail(j, "a test without its score and status, or scoring above its max_score");
    r->sum += r->test_score, r->max += r->test_max, r->ntests++;
    return true;
}

/* A member of the top: the keys Gradescope documents, each of its type. */
static bool js_top_member(struct json *j, const char *key, void *ctx)
{
    struct results *r = ctx;
    char v[256];
    double x;
    if (!strcmp(key, "score"))
        return js_number(j, &r->score);
    if (!strcmp(key, "execution_time"))
        return js_number(j, &x);
    if (!strcmp(key, "output"))
        return js_string(j, v, sizeof v);
    if (!strcmp(key, "output_format") || !strcmp(key, "test_output_format") || !strcmp(key, "test_name_format"))
        return js_enum(j, formats, "a format Gradescope does not name");
    if (!strcmp(key, "visibility") || !strcmp(key, "stdout_visibility"))
        return js_enum(j, visibilities, "a visibility Gradescope does not name");
    if (!strcmp(key, "extra_data"))
        return js_object(j, js_any_member, NULL);
    if (!strcmp(key, "leaderboard"))
        return js_array(j, js_any_item, NULL);
    if (!strcmp(key, "tests"))
        return js_array(j, js_test, r);
    return js_fail(j, "a key Gradescope does not document");
}

static bool js_results(struct json *j, struct results *r)
{
    *r = (struct results){ .score = -1 };
    if (!js_object(j, js_top_member, r))
        return false;
    js_ws(j);
    return *j->p ? js_fail(j, "text after the object") : true;
}

/* results.json: the documented format, its score the sum of its tests',
 * how many of them passed, out of how many. */
static void expect_results(const char *path, double score, double max, int passed, int ntests)
{
    char *text = slurp(path);
    struct json j = { .p = text };
    struct results r;
    cr_expect(js_results(&j, &r), "%s: %s\n%s", path, j.err, text);
    cr_expect(r.score == score && r.sum == score && r.max == max && r.passed == passed && r.ntests == ntests,
              "%s: score %g (tests' sum %g) of %g, %d of %d tests passed; expected %g of %g, %d of %d\n%s", path,
              r.score, r.sum, r.max, r.passed, r.ntests, score, max, passed, ntests, text);
    free(text);
}

/* make gradescope's zip unpacked as Gradescope unpacks it (into
 * /autograder/source, run_autograder copied to /autograder), a submission
 * in submission/, and run_autograder run with AUTOGRADER_ROOT, a scratch
 * root: its results/results.json in Gradescope's format. (The build is
 * this one's, named by BUILD, as setup.sh's make grade-build would make
 * it; the unpacked files dated before it, so that make takes it as it is.)
 * The answer scores everything, the skeleton nothing. */
Test(grade, gradescope_zip_in_a_scratch_root, .init = make_dir, .fini = test_scratch_remove, .timeout = 300)
{
    const char *b = getenv("TRISTEP_BUILD");
    char build[1024], cmd[4096], path[1200];
    cr_assert_not_null(realpath(b ? b : "build", build));
    /* BUILD names the build run_autograder's make uses: with SANITIZE (make
     * test SANITIZE=1 exports it) make adds /sanitize itself */
    char base[1024];
    snprintf(base, sizeof base, "%s", build);
    const char *san = getenv("SANITIZE");
    size_t k = strlen(base);
    if (san && *san && k > 9 && !strcmp(base + k - 9, "/sanitize"))
        base[k - 9] = '\0';
    char *before = tree_state();
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory gradescope "
             "B=%s LESSON=02 > %s/log 2>&1 && unzip -Z1 %s/gradescope-02.zip > %s/list && mkdir -p %s/ag/source "
             "%s/ag/submission && cd %s/ag/source && unzip -q %s/gradescope-02.zip && cp run_autograder .. && "
             "find . -exec touch -h -d 2000-01-01 {} +",     /* older than the build it shares */
             build, dir, build, dir, dir, dir, dir, build);
    int st = system(cmd);
    snprintf(path, sizeof path, "%s/log", dir);
    cr_assert_eq(st, 0, "%s\n%s", cmd, test_read_text(path));
    snprintf(path, sizeof path, "%s/list", dir);
    char *list = slurp(path);
    /* Gradescope's two files at the zip's top, the source beside them */
    cr_expect(!strncmp(list, "setup.sh\n", 9) || strstr(list, "\nsetup.sh\n"), "%s", list);
    cr_expect(!strncmp(list, "run_autograder\n", 15) || strstr(list, "\nrun_autograder\n"), "%s", list);
    cr_expect_not_null(strstr(list, "\nMakefile\n"), "%s", list);
    cr_expect_null(strstr(list, "build/"), "%s", list);
    free(list);

    const char *files[] = { "lessons/02-barycentric/answer.c", "lessons/02-barycentric/exercise.c" };
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/ag/submission/exercise.c", dir);
        char *text = slurp(files[k]);
        write_text(path, text);
        free(text);
        snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL AUTOGRADER_ROOT=%s/ag "
                 "BUILD=%s %s/ag/run_autograder > %s/log 2>&1", dir, base, dir, dir);
        st = system(cmd);
        snprintf(path, sizeof path, "%s/log", dir);
        cr_expect_eq(st, 0, "%s\n%s", cmd, test_read_text(path));
        snprintf(path, sizeof path, "%s/ag/results/results.json", dir);
        expect_results(path, k ? 0 : 9, 9, k ? 0 : 5, 5);
        char *json = slurp(path);
        cr_expect_not_null(strstr(json, k ? "\"output\": \"fail: " : "\"output\": \"pass\""), "%s", json);
        cr_expect_not_null(strstr(json, "\"name\": \"fill-rule ties\""), "%s", json);
        free(json);
    }
    expect_no_trace(before);
}

/* Without the sandbox (UNSAFE=1) too, nothing a submission starts outlives
 * its run: a child in a session of its own, forked twice, is killed (the
 * grader is its subreaper), and the CSV says the run was not isolated. */
Test(grade, unsafe_leaves_no_process, .init = make_dir, .fini = test_scratch_remove, .timeout = 240)
{
    char path[256];
    snprintf(path, sizeof path, "%s/sub", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    char *skeleton = slurp("lessons/02-barycentric/exercise.c");
    const struct hostile *h = &hostiles[1];
    cr_assert_str_eq(h->name, "outlive.c");
    char *t = answer_with(skeleton, h->top, h->before);
    put(h->name, t);
    free(t);
    free(skeleton);
    char *csv = grade("UNSAFE=1");
    expect_row(csv, "outlive.c", "\",\"fail\",\"0\"");
    expect_row(csv, "outlive.c", "\"UNSAFE: no sandbox\"");
    cr_expect_eq(survivors(), 0, "processes of the run survive it");
    free(csv);
}
