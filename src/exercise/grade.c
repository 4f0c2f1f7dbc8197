/* grade.c - make grade (grade.h): every submission of a class compiled,
 * linked and run in a sandbox of its own, its checks decided here, by the
 * judge, which never runs student code; every check scored on its own;
 * one CSV row per submission and a Gradescope results.json each.
 *
 * Each submission is graded by a judge process of its own (forked), so
 * that nothing a submission does, nor anything it makes the judge read,
 * can stop the run: a judge that runs past the submission's time is
 * killed, its checks so far kept (shared memory), the rest "timed out".
 * The sandbox (bubblewrap): no network, new namespaces (a process that
 * outlives the run dies with its pid namespace), read-only /usr (the
 * toolchain) and the lesson's student library, the one file, a private
 * /tmp of 64 MiB; limits on CPU time, memory, processes, file size; what
 * it prints goes through a pipe to a reader that keeps the first LOG_MAX
 * bytes. Run as root, each submission's commands run as a user id of
 * their own (so that the process limit counts its processes alone, and
 * whatever is left of them is killed by that id). The grader is its
 * processes' subreaper: whatever a submission leaves behind (even without
 * the sandbox, UNSAFE=1, in a session of its own) becomes its child when
 * its parent ends, and is killed before the next submission. */
#define _GNU_SOURCE

#include "grade.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <grp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "exercise/class.h"
#include "exercise/exercise.h"
#include "exercise/gen.h"
#include "exercise/remote.h"
#include "exercise/sandbox.h"

#define FILE_MAX (1 << 20)          /* a submission's size */
#define UID_BASE 1900000000u        /* run as root: a submission's user id, this + its judge's pid */

static struct {
    const char *dir, *lib, *out, *csv, *points, *commit, *cc, *seed_text, *variant;
    double timeout;
    bool unsafe, one;
} G = { .cc = "cc", .timeout = 60, .commit = "unknown" };

uint64_t grade_seed(const char *s)
{
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    if (*s && !*end)
        return v;
    uint64_t h = 1469598103934665603u;      /* FNV-1a of a word */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211u;
    return h;
}

/* Seconds of search for each submission, shared by the lesson's checks
 * that search (as make check's default). */
#define GRADE_SEARCH_SECONDS 1.5

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* --- one submission --------------------------------------------------------------- */

struct row {
    char result[32];            /* pass, fail, compile error, link error, timed out, ... */
    char first[240];            /* the first failure, in plain words */
    char sha[65];
    char stage[64];             /* the sandbox's files, removed after the run */
    bool judged;                /* the checks began */
    double seconds;             /* the submission's whole run */
    struct check_result r;
};

static int rm_entry(const char *p, const struct stat *st, int flag, struct FTW *f)
{
    (void)st, (void)flag, (void)f;
    return remove(p);
}

static void rm_tree(const char *p)
{
    nftw(p, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static bool copy_file(const char *from, const char *to, const char **why)
{
    int in = open(from, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (in < 0) {
        *why = "cannot be read";
        return false;
    }
    char *buf = malloc(FILE_MAX + 1);
    ssize_t n = 0, k;
    while (buf && n <= FILE_MAX && (k = read(in, buf + n, (size_t)(FILE_MAX + 1 - n))) > 0)
        n += k;
    close(in);
    if (!buf || n > FILE_MAX) {
        free(buf);
        *why = "larger than 1 MiB";
        return false;
    }
    int out = open(to, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    bool ok = out >= 0 && write(out, buf, (size_t)n) == n;
    if (out >= 0)
        close(out);
    free(buf);
    if (!ok)
        *why = "cannot be copied";
    return ok;
}

static void sha256(const char *path, char out[65])
{
    snprintf(out, 65, "unknown");
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "sha256sum < '%s'", path);     /* our own path: OUT/<safe>/src/exercise.c */
    FILE *p = popen(cmd, "r");
    if (!p)
        return;
    char buf[100] = "";
    if (fgets(buf, sizeof buf, p) && strlen(buf) >= 64 && strspn(buf, "0123456789abcdef") >= 64)
        snprintf(out, 65, "%.64s", buf);
    pclose(p);
}

/* The compiler's or linker's messages, in plain words: the first name
 * the student library does not give, the first include the sandbox does
 * not hold, else the first error. */
static void summarise(const char *log, const struct lesson *l, char *out, size_t n)
{
    FILE *f = fopen(log, "r");
    char line[600];
    snprintf(out, n, "see compile.txt");
    bool found = false;
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        char *p;
        if ((p = strstr(line, "attempt to use poisoned \""))) {
            p += strlen("attempt to use poisoned \"");
            snprintf(out, n, "uses %.*s, which lesson %.2s's exercise does not give (it is the exercise)",
                     (int)strcspn(p, "\""), p, l->id);
            found = true;
        } else if ((p = strstr(line, "undefined reference to `"))) {
            p += strlen("undefined reference to `");
            snprintf(out, n, "uses %.*s, which lesson %.2s's exercise does not give (src/exercise/student-library.txt)",
                     (int)strcspn(p, "'"), p, l->id);
            found = true;
        } else if ((p = strstr(line, "multiple definition of `"))) {
            p += strlen("multiple definition of `");
            snprintf(out, n, "defines %.*s, which the runner defines: a file defines the exercise's functions only",
                     (int)strcspn(p, "'"), p);
            found = true;
        } else if ((p = strstr(line, "fatal error: ")) && strstr(line, "No such file")) {
            p += strlen("fatal error: ");
            snprintf(out, n, "includes %.*s, which is not there: a submission is compiled alone, with its lesson's headers",
                     (int)strcspn(p, ":"), p);
            found = true;
        } else if (!found && (p = strstr(line, "error: "))) {
            snprintf(out, n, "%s", p);
            found = true;
            continue;
        }
        if (found && strstr(line, "error"))
            break;
    }
    if (f)
        fclose(f);
}

static void grade_one(const struct lesson *l, const struct sub *s, struct row *row)
{
    char dir[1200], src[1300], build[1300], log[1300], clog[1300], chk[1300];
    snprintf(dir, sizeof dir, "%s/%s", G.out, s->safe);
    rm_tree(dir);
    snprintf(src, sizeof src, "%s/src", dir);
    if (mkdir(dir, 0755) != 0 || mkdir(src, 0755) != 0) {
        snprintf(row->result, sizeof row->result, "not graded");
        snprintf(row->first, sizeof row->first, "cannot create its folder under OUT");
        return;
    }
    snprintf(src + strlen(src), sizeof src - strlen(src), "/exercise.c");
    const char *why = s->problem;
    if (why || !copy_file(s->file, src, &why)) {
        snprintf(row->result, sizeof row->result, "no file");
        snprintf(row->first, sizeof row->first, "%s", why);
        return;
    }
    sha256(src, row->sha);
    snprintf(clog, sizeof clog, "%s/compile.txt", dir);
    double start = now();
    if (getuid() == 0 && !G.unsafe)
        sandbox_uid = UID_BASE + (uid_t)getpid();
    /* CPU time above the wall time: a compile that takes too long is
     * "timed out" whatever the machine's load, never a compiler killed */
    struct limits cl = { .cpu = (rlim_t)(2 * G.timeout) + 1, .as = (rlim_t)2 << 30, .fsize = (rlim_t)64 << 20,
                         .nproc = sandbox_processes(0) + 64 };
    /* what the sandbox binds, staged where its user may read it (a private
     * folder of the grader's may not be): the headers, the library, the
     * file, and the folder it builds in */
    char *stage = row->stage;
    snprintf(stage, sizeof row->stage, "/tmp/tristep-grade-XXXXXX");
    char inc[1300], lib[1300], obj[1400], runner[1400], cmd[4000];
    if (!mkdtemp(stage) || chmod(stage, 0711) != 0) {
        snprintf(row->result, sizeof row->result, "not graded");
        snprintf(row->first, sizeof row->first, "cannot create a folder in /tmp");
        return;
    }
    snprintf(inc, sizeof inc, "%s/include", stage);
    snprintf(lib, sizeof lib, "%s/library.o", stage);
    snprintf(cmd, sizeof cmd, "cp -R '%s/include' '%s' && cp '%s/library.o' '%s' && cp '%s' '%s/exercise.c' && chmod -R a+rX '%s'",
             G.lib, stage, G.lib, stage, src, stage, stage);
    snprintf(src, sizeof src, "%s/exercise.c", stage);
    snprintf(build, sizeof build, "%s/build", stage);
    if (strchr(G.lib, '\'') || system(cmd) != 0 || mkdir(build, 0755) != 0
        || (getuid() == 0 && !G.unsafe && chown(build, sandbox_uid, sandbox_uid) != 0)) {
        snprintf(row->result, sizeof row->result, "not graded");
        snprintf(row->first, sizeof row->first, "cannot stage its files in /tmp");
        return;
    }
    snprintf(obj, sizeof obj, "%s/file.o", build);
    snprintf(runner, sizeof runner, "%s/runner", build);
    const char *in_inc = G.unsafe ? inc : "/student/include", *in_src = G.unsafe ? src : "/sub/exercise.c";
    const char *in_obj = G.unsafe ? obj : "/out/file.o", *in_lib = G.unsafe ? lib : "/student/library.o";
    const char *in_runner = G.unsafe ? runner : "/out/runner";
    char incflag[1400];
    snprintf(incflag, sizeof incflag, "-I%s", in_inc);
    const char *binds[] = { "--ro-bind", inc, "/student/include", "--ro-bind", src, "/sub/exercise.c",
                            "--ro-bind", lib, "/student/library.o", "--bind", build, "/out", NULL };
    const char *compile[] = { G.cc, "-O2", "-std=c17", "-Wall", "-Wextra", "-pedantic", "-pthread",
                              "-DTRISTEP_NARRATE", incflag, "-include", "exercise/student.h", "-include",
                              "forbid.h", "-c", in_src, "-o", in_obj, NULL };
    char *argv[96];
    sandbox_argv(argv, binds, compile);
    pid_t reader;
    int logfd = sandbox_log(clog, &reader);
    int st = sandbox_run(argv, logfd, &cl, G.timeout);
    if (st != 0) {
        sandbox_log_done(logfd, reader);
        snprintf(row->result, sizeof row->result, st < 0 ? "timed out" : "compile error");
        if (st < 0)
            snprintf(row->first, sizeof row->first, "compiling took more than %g s", G.timeout);
        else
            summarise(clog, l, row->first, sizeof row->first);
        return;
    }
    const char *link[] = { G.cc, "-Wl,--gc-sections", "-s", in_obj, in_lib, "-lm", "-pthread", "-o", in_runner, NULL };
    sandbox_argv(argv, binds, link);
    st = sandbox_run(argv, logfd, &cl, G.timeout - (now() - start));
    sandbox_log_done(logfd, reader);
    if (st != 0) {
        snprintf(row->result, sizeof row->result, st < 0 ? "timed out" : "link error");
        if (st < 0)
            snprintf(row->first, sizeof row->first, "linking took more than %g s", G.timeout);
        else
            summarise(clog, l, row->first, sizeof row->first);
        return;
    }

    /* the checks: the judge here, the runner in the sandbox */
    snprintf(log, sizeof log, "%s/log.txt", dir);
    snprintf(chk, sizeof chk, "%s/check.txt", dir);
    static struct limits rl;
    rl = (struct limits){ .cpu = (rlim_t)G.timeout + 1, .as = (rlim_t)1 << 30, .fsize = (rlim_t)1 << 20,
                          .nproc = sandbox_processes(0) + 32 };
    const char *rbinds[] = { "--ro-bind", runner, "/runner", NULL };
    const char *rcmd[] = { G.unsafe ? runner : "/runner", NULL };
    static char *rargv[96];
    sandbox_argv(rargv, rbinds, rcmd);
    int runlog = sandbox_log(log, &reader);
    remote_configure(&(struct remote_config){ .argv = rargv, .log = log, .log_fd = runlog, .limits = sandbox_limits,
                                              .limits_ctx = &rl, .scene_seconds = 10, .start_seconds = 10 });
    FILE *out = fopen(chk, "w");
    if (!out) {
        sandbox_log_done(runlog, reader);
        return;
    }
    char open_cmd[600];
    snprintf(open_cmd, sizeof open_cmd, "make exercise LESSON=%.2s%s%s FILE=<the file>", l->id,
             G.variant ? " VARIANT=" : "", G.variant ? G.variant : "");
    /* the search as make check's, seeded by SEED= (hidden scenes) or as
     * the students' own runs were */
    struct check_options o = { .file = "exercise.c", .out_dir = dir, .open_cmd = open_cmd,
                               .params = { .subpixel_bits = SUBPIXEL_BITS }, .out = out, .all = true,
                               .program = "build/exercise-NN", .seed = check_seed ? check_seed : 1,
                               .search_seconds = GRADE_SEARCH_SECONDS };
    row->judged = true;
    bool ok = exercise_check(l, &o, &row->r);
    remote_shutdown();
    sandbox_log_done(runlog, reader);
    fclose(out);
    int failed_by_time = 0;
    for (int i = 0; i < row->r.nchecks; i++)
        failed_by_time += row->r.check[i].runner == RUNNER_TIMEOUT;
    snprintf(row->result, sizeof row->result, "%s", ok ? "pass" : failed_by_time ? "fail (timed out)" : "fail");
    snprintf(row->first, sizeof row->first, "%s", row->r.failed);
}

/* --- scores and the outputs ------------------------------------------------------- */

struct points {
    char name[48];
    double value;
};
static struct points table[CHECKS_MAX * 2];
static int ntable;

static double default_points(const char *name)
{
    static const struct { const char *name; double p; } d[] = {
        { "single triangle", 1 }, { "fill-rule ties", 2 }, { "watertight meshes", 2 },
        { "random triangles", 2 }, { "tiles and blocks", 2 }, { "no multiplication per pixel", 2 },
        { "corner classes", 2 }, { "colour and depth", 2 },
    };
    for (size_t i = 0; i < sizeof d / sizeof d[0]; i++)
        if (!strncmp(name, d[i].name, strlen(d[i].name)))
            return d[i].p;
    return 1;
}

static double points_of(const char *name)
{
    for (int i = 0; i < ntable; i++)
        if (!strcmp(table[i].name, name))
            return table[i].value;
    return ntable ? 0 : default_points(name);
}

static bool read_points(const char *path, const struct check_result *plan)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "POINTS=%s: %s\n", path, strerror(errno));
        return false;
    }
    char line[200];
    for (int ln = 1; fgets(line, sizeof line, f); ln++) {
        line[strcspn(line, "\r\n")] = '\0';
        char *p = line + strspn(line, " \t");
        if (!*p || *p == '#')
            continue;
        char *end;
        double v = strtod(p, &end);
        end += strspn(end, " \t");
        bool known = false;
        for (int i = 0; i < plan->nchecks && !known; i++)
            known = !strcmp(plan->check[i].name, end);
        if (end == p || !(v >= 0 && v <= 1e6) || !known || ntable == (int)(sizeof table / sizeof table[0])) {
            fprintf(stderr, "%s:%d: expected \"POINTS check name\" with a check of this lesson:", path, ln);
            for (int i = 0; i < plan->nchecks; i++)
                fprintf(stderr, "%s \"%s\"", i ? "," : "", plan->check[i].name);
            fprintf(stderr, "\n");
            fclose(f);
            return false;
        }
        snprintf(table[ntable].name, sizeof table[ntable].name, "%s", end);
        table[ntable++].value = v;
    }
    fclose(f);
    return true;
}


static char *slurp(const char *path, size_t *len)
{
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *b = malloc((size_t)4 << 20);
    if (b)
        *len = fread(b, 1, ((size_t)4 << 20) - 1, f);
    fclose(f);
    return b;
}

static const char *verdict_of(const struct row *row, const struct check_outcome *c)
{
    if (!row->judged)
        return row->result;
    if (!c->ran)
        return "timed out";
    if (c->passed)
        return "ok";
    if (c->runner == RUNNER_TIMEOUT || c->to == 0)
        return "timed out";
    return c->runner == RUNNER_CRASHED ? "crashed" : c->runner == RUNNER_GARBAGE ? "garbage" : "failed";
}

/* OUT/<safe>/results.json in Gradescope's documented format: the score,
 * the time, a summary as the output, and a test per check with its own
 * score, max_score, status and output (its part of check.txt); the
 * possible total in extra_data (Gradescope takes it from the assignment). */
static void write_results(const struct sub *s, const struct row *row, const struct check_result *plan,
                          double *score, double *max)
{
    char path[1300], chk[1300];
    snprintf(path, sizeof path, "%s/%s/results.json", G.out, s->safe);
    snprintf(chk, sizeof chk, "%s/%s/check.txt", G.out, s->safe);
    size_t len;
    char *text = row->judged ? slurp(chk, &len) : NULL;
    FILE *f = fopen(path, "w");
    *score = *max = 0;
    for (int i = 0; i < plan->nchecks; i++) {
        double p = points_of(plan->check[i].name);
        *max += p;
        if (row->judged && row->r.check[i].passed)
            *score += p;
    }
    if (!f) {
        free(text);
        return;
    }
    char summary[600];
    snprintf(summary, sizeof summary, "%s%s%s", row->result, row->first[0] ? ": " : "", row->first);
    fprintf(f, "{\n  \"score\": %g,\n  \"execution_time\": %.0f,\n  \"output\": ", *score, ceil(row->seconds));
    json_string(f, summary, strlen(summary));
    fprintf(f, ",\n  \"output_format\": \"text\",\n  \"stdout_visibility\": \"hidden\",\n"
            "  \"extra_data\": {\"max_score\": %g, \"sha256\": \"%s\", \"seed\": \"%llu\"},\n  \"tests\": [\n",
            *max, row->sha[0] ? row->sha : "", (unsigned long long)check_seed);
    for (int i = 0; i < plan->nchecks; i++) {
        const struct check_outcome *c = &row->r.check[i];
        double p = points_of(plan->check[i].name);
        bool passed = row->judged && c->passed;
        fprintf(f, "    {\"number\": \"%d\", \"name\": ", i + 1);
        json_string(f, plan->check[i].name, strlen(plan->check[i].name));
        fprintf(f, ", \"score\": %g, \"max_score\": %g, \"status\": \"%s\", \"visibility\": \"visible\", "
                "\"output_format\": \"text\", \"output\": ", passed ? p : 0, p, passed ? "passed" : "failed");
        if (text && c->ran && c->from >= 0 && c->to > c->from && (size_t)c->to <= len)
            json_string(f, text + c->from, (size_t)(c->to - c->from));
        else
            json_string(f, verdict_of(row, c), strlen(verdict_of(row, c)));
        fprintf(f, "}%s\n", i + 1 < plan->nchecks ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    fclose(f);
    free(text);
}

int exercise_grade_main(const struct lesson *l, int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool v = i + 1 < argc;
        if (!strcmp(a, "--grade"))
            continue;
        else if (!strcmp(a, "--dir") && v)
            G.dir = argv[++i];
        else if (!strcmp(a, "--lib") && v)
            G.lib = argv[++i];
        else if (!strcmp(a, "--out") && v)
            G.out = argv[++i];
        else if (!strcmp(a, "--csv") && v)
            G.csv = argv[++i];
        else if (!strcmp(a, "--points") && v)
            G.points = argv[++i];
        else if (!strcmp(a, "--commit") && v)
            G.commit = argv[++i];
        else if (!strcmp(a, "--cc") && v)
            G.cc = argv[++i];
        else if (!strcmp(a, "--seed") && v)
            G.seed_text = argv[++i];
        else if (!strcmp(a, "--timeout") && v)
            G.timeout = atof(argv[++i]);
        else if (!strcmp(a, "--unsafe"))
            G.unsafe = sandbox_unsafe = true;
        else if (!strcmp(a, "--one"))
            G.one = true;
        else if (!strcmp(a, "--exercise-variant") && v)
            G.variant = argv[++i];
        else {
            fprintf(stderr, "%s --grade: unknown option %s (grade.h lists them)\n", argv[0], a);
            return 2;
        }
    }
    if (!G.dir || !G.lib || !G.out || !G.csv || !(G.timeout > 0)) {
        fprintf(stderr, "%s --grade: --dir, --lib, --out and --csv are needed, and a timeout above 0\n", argv[0]);
        return 2;
    }
    struct stat st;
    if (stat(G.dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "DIR=%s: no such folder\n", G.dir);
        return 2;
    }
    prctl(PR_SET_CHILD_SUBREAPER, 1);       /* what a submission leaves behind becomes ours */
    if (!G.unsafe && system("bwrap --unshare-all --die-with-parent --ro-bind /usr /usr --symlink usr/bin /bin "
                            "--symlink usr/lib /lib --symlink usr/lib64 /lib64 true >/dev/null 2>&1") != 0) {
        fprintf(stderr, "make grade: bubblewrap (bwrap) cannot make a sandbox here (not installed, or no user\n"
                "namespaces): students' code would run with the grader's rights. Install bubblewrap\n"
                "(src/deps.sh grade), or grade without isolation with UNSAFE=1 (the CSV then says so).\n");
        return 2;
    }
    if (G.seed_text)
        check_seed = grade_seed(G.seed_text);
    if (G.variant) {        /* the graded variant (VARIANT=): its rule is the one judged */
        const struct exercise_variant *ev = exercise_variant_named(l, G.variant);
        if (!ev) {
            fprintf(stderr, "VARIANT=%s: lesson %.2s has no such variant\n", G.variant, l->id);
            return 2;
        }
        exercise_use_variant(ev);
    }
    /* the compiler by its real path: /usr/bin/cc is a link through /etc,
     * which the sandbox does not hold */
    static char cc_path[4096];
    const char *path = getenv("PATH");
    for (const char *p = strchr(G.cc, '/') ? "" : path ? path : "/usr/bin"; p;) {
        const char *colon = strchr(p, ':');
        char cand[4096];
        snprintf(cand, sizeof cand, "%s%.*s%s%s", "", colon ? (int)(colon - p) : (int)strlen(p), p,
                 *p ? "/" : "", G.cc);
        if (realpath(cand, cc_path) && access(cc_path, X_OK) == 0) {
            G.cc = cc_path;
            break;
        }
        p = colon ? colon + 1 : NULL;
    }
    /* the lesson's checks, by name, from a plan with nothing run */
    struct check_result plan;
    {
        FILE *null = fopen("/dev/null", "w");
        struct check_options o = { .file = "plan", .out = null, .all = false, .out_dir = "/nonexistent" };
        memset(&plan, 0, sizeof plan);
        exercise_check_plan(l, &o, &plan);
        if (null)
            fclose(null);
    }
    if (G.points && !read_points(G.points, &plan))
        return 2;
    mkdir(G.out, 0755);
    int n;
    struct sub *subs = list_class(G.dir, G.one, &n);      /* freed at every return from here on */
    if (!subs || n == 0) {
        fprintf(stderr, "DIR=%s holds no .c file and no folder\n", G.dir);
        free_class(subs, n);
        return 2;
    }
    struct row *rows = mmap(NULL, sizeof *rows * (size_t)n, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (rows == MAP_FAILED) {
        free_class(subs, n);
        return 1;
    }
    memset(rows, 0, sizeof *rows * (size_t)n);
    double t0 = now();
    for (int i = 0; i < n; i++) {
        struct row *row = &rows[i];
        char shown[300];
        clean_text(subs[i].entry, shown, sizeof shown);
        printf("grade %s: ", shown);
        fflush(stdout);
        double started = now();
        pid_t pid = fork();
        if (pid == 0) {
            setpgid(0, 0);
            grade_one(l, &subs[i], row);
            _exit(0);
        }
        if (pid > 0) {
            setpgid(pid, pid);
            /* compile and link, then the checks: each within the timeout */
            double end = now() + 3 * G.timeout + 10;
            int status;
            while (waitpid(pid, &status, WNOHANG) != pid) {
                if (now() > end) {
                    kill(-pid, SIGKILL);
                    kill(pid, SIGKILL);
                    waitpid(pid, &status, 0);
                    snprintf(row->result, sizeof row->result, "timed out");
                    break;
                }
                nanosleep(&(struct timespec){ 0, 10000000 }, NULL);
            }
            kill(-pid, SIGKILL);
            /* what it left behind: its user id's processes (root), the
             * orphans that became ours (any) */
            if (getuid() == 0 && !G.unsafe)
                sandbox_kill_user(UID_BASE + (uid_t)pid);
            sandbox_kill_children();
        }
        if (row->stage[0] && !strncmp(row->stage, "/tmp/tristep-grade-", 19))
            rm_tree(row->stage);
        if (!row->result[0])
            snprintf(row->result, sizeof row->result, "judge failed");
        row->seconds = now() - started;
        printf("%s\n", row->result);
    }
    /* the table */
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s.tmp", G.csv);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        fprintf(stderr, "CSV=%s: %s\n", G.csv, strerror(errno));
        free_class(subs, n);
        return 1;
    }
    const char *head[] = { "student", "folder", "file", "result", "score", "max" };
    for (int k = 0; k < 6; k++)
        csv_field(f, head[k], k == 0);
    for (int c = 0; c < plan.nchecks; c++) {
        char h[80];
        snprintf(h, sizeof h, "%s (%g)", plan.check[c].name, points_of(plan.check[c].name));
        csv_field(f, h, false);
    }
    const char *tail[] = { "first failure", "sha256", "seed", "grader", "sandbox" };
    for (int k = 0; k < 5; k++)
        csv_field(f, tail[k], false);
    fputc('\n', f);
    char seed[32];
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)check_seed);
    for (int i = 0; i < n; i++) {
        const struct row *row = &rows[i];
        double score, max;
        write_results(&subs[i], row, &plan, &score, &max);
        const char *file = subs[i].file ? subs[i].file + strlen(G.dir) : "";
        csv_field(f, subs[i].entry, true);
        csv_field(f, subs[i].safe, false);
        csv_field(f, *file == '/' ? file + 1 : file, false);
        csv_field(f, row->result, false);
        char num[32];
        snprintf(num, sizeof num, "%g", score);
        csv_field(f, num, false);
        snprintf(num, sizeof num, "%g", max);
        csv_field(f, num, false);
        for (int c = 0; c < plan.nchecks; c++) {
            const struct check_outcome *co = &row->r.check[c];
            if (row->judged && co->passed)
                snprintf(num, sizeof num, "%g", points_of(plan.check[c].name));
            else
                snprintf(num, sizeof num, "0 %s", verdict_of(row, co));
            csv_field(f, num, false);
        }
        csv_field(f, row->first, false);
        csv_field(f, row->sha[0] ? row->sha : "", false);
        csv_field(f, seed, false);
        csv_field(f, G.commit, false);
        csv_field(f, G.unsafe ? "UNSAFE: no sandbox" : "bubblewrap", false);
        fputc('\n', f);
    }
    if (fclose(f) != 0 || rename(tmp, G.csv) != 0) {
        fprintf(stderr, "CSV=%s: %s\n", G.csv, strerror(errno));
        free_class(subs, n);
        return 1;
    }
    printf("grade: %d submission%s in %.1f s, the table in %s%s\n", n, n == 1 ? "" : "s", now() - t0, G.csv,
           G.unsafe ? " (UNSAFE=1: graded without a sandbox)" : "");
    free_class(subs, n);
    return 0;
}
