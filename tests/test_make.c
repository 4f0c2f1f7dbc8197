/* test_make.c - the Makefile keeps its promises, seen through `make -n`
 * (what make would run, in the order it would run it) in a build folder of
 * the test's own:
 *   - the user's CFLAGS and LDFLAGS do not replace the flags tristep needs;
 *   - make test installs its packages before it compiles anything, a dry
 *     run installs nothing, and two installs never overlap (these tests
 *     never install: apt-get, apt, dpkg and sudo are stand-ins that say
 *     they were called);
 *   - make figures writes where FIGURES says, and make bench times the
 *     figures into its build folder, never over the committed figures/;
 *   - make check takes a new FILE when the one checked before is gone.
 * Run from the repository's top folder, as make test does. */
#define _POSIX_C_SOURCE 200809L   /* popen, mkdtemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "testlib.h"

/* make's build folder, in the test's scratch folder (testlib); beside it
 * bin/, the stand-ins put first on the PATH, and installs.log, where they
 * write that they were called */
static char build[80], bin[80], installs[96];

static void stand_in(const char *name, const char *body)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", bin, name);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "cannot write %s", path);
    fprintf(f, "#!/bin/sh\n%s\n", body);
    cr_assert_eq(fclose(f), 0);
    cr_assert_eq(chmod(path, 0755), 0);
}

static void make_build_dir(void)
{
    test_scratch_make();
    snprintf(build, sizeof build, "%s", test_scratch_path("build"));
    snprintf(bin, sizeof bin, "%s", test_scratch_path("bin"));
    snprintf(installs, sizeof installs, "%s", test_scratch_path("installs.log"));
    cr_assert_eq(mkdir(bin, 0755), 0);
    char body[512];
    snprintf(body, sizeof body, "echo \"$0 $*\" >> %s; echo \"$0: a stand-in of test_make.c\" >&2; exit 1",
             installs);
    const char *const installers[] = { "apt-get", "apt", "dpkg", "sudo" };
    for (size_t i = 0; i < sizeof installers / sizeof installers[0]; i++)
        stand_in(installers[i], body);
}

/* Nothing was installed: no stand-in was called. */
static void assert_no_install(const char *what)
{
    FILE *f = fopen(installs, "r");
    char line[512] = "";
    if (f) {
        if (!fgets(line, sizeof line, f))
            line[0] = '\0';
        fclose(f);
    }
    cr_assert(!f, "%s tried to install packages: %s", what, line);
}

/* `make FLAGS ARGS` in the top folder (stdout and stderr into *out,
 * NUL-terminated, malloc'ed), the stand-ins first on the PATH; its exit
 * status. Without what a calling make (make test SANITIZE=1) passes down
 * in MAKEFLAGS and in the environment, such as SANITIZE or CFLAGS. */
static int make_run(const char *flags, const char *args, char **out)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u SANITIZE -u CFLAGS -u LDFLAGS "
             "-u LDLIBS -u FIGURES -u FILE -u LESSON PATH=\"%s:$PATH\" make %s --no-print-directory BUILD=%s %s 2>&1",
             bin, flags, build, args);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p, "cannot run %s", cmd);
    size_t cap = 1 << 16, n = 0;
    char *o = malloc(cap);
    cr_assert_not_null(o);
    for (size_t got; (got = fread(o + n, 1, cap - n - 1, p)) > 0;) {
        n += got;
        if (n + 1 == cap) {
            o = realloc(o, cap *= 2);
            cr_assert_not_null(o);
        }
    }
    o[n] = '\0';
    int status = pclose(p);
    *out = o;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

/* The output of `make -n ARGS`, which must succeed and install nothing. */
static char *make(const char *args)
{
    char *out;
    int status = make_run("-n", args, &out);
    cr_assert_eq(status, 0, "make -n %s failed:\n%s", args, out);
    assert_no_install("make -n");
    return out;
}

/* The first line of `text` containing `what`, copied into line[n]; false if none. */
static bool line_with(const char *text, const char *what, char *line, size_t n)
{
    const char *at = strstr(text, what);
    if (!at)
        return false;
    const char *begin = at, *end = strchr(at, '\n');
    while (begin > text && begin[-1] != '\n')
        begin--;
    size_t len = end ? (size_t)(end - begin) : strlen(begin);
    snprintf(line, n, "%.*s", (int)(len < n ? len : n - 1), begin);
    return true;
}

Test(make, user_flags_keep_the_required_ones, .init = make_build_dir, .fini = test_scratch_remove)
{
    char target[256], line[4096];
    snprintf(target, sizeof target, "-B CFLAGS=-O0 LDFLAGS=-Wl,-O1 SANITIZE=1 %s/sanitize/01-scanline", build);
    char *out = make(target);
    cr_assert(line_with(out, "-c src/lesson.c", line, sizeof line), "no compile of src/lesson.c:\n%s", out);
    cr_assert(strstr(line, " -O0 ") && !strstr(line, " -O2 "), "the user's CFLAGS are not used: %s", line);
    cr_assert(strstr(line, "-Isrc") && strstr(line, "-std=c17") && strstr(line, "-Wall"),
              "CFLAGS=-O0 dropped the required flags: %s", line);
    cr_assert(strstr(line, "-fsanitize=address,undefined"), "SANITIZE lost with CFLAGS given: %s", line);
    char link[256];
    snprintf(link, sizeof link, "-o %s/sanitize/01-scanline", build);
    cr_assert(line_with(out, link, line, sizeof line), "no link of the program:\n%s", out);
    cr_assert(strstr(line, "-Wl,-O1") && strstr(line, "-fsanitize=address,undefined")
                  && strstr(line, "-lcairo"),
              "LDFLAGS given dropped what the link needs: %s", line);
    free(out);
}

/* Asked for an object and `test` at once, make must still install the test
 * packages first: every compile waits for them (make -j2 test compiled
 * while apt-get was still installing Criterion). */
Test(make, test_installs_its_packages_before_compiling, .init = make_build_dir,
     .fini = test_scratch_remove)
{
    char args[256];
    snprintf(args, sizeof args, "-j2 %s/obj/src/lesson.o test", build);
    char *out = make(args);
    char *deps = strstr(out, "deps.sh test"), *cc = strstr(out, "-c src/lesson.c");
    cr_assert(deps && cc, "make -n %s printed neither step:\n%s", args, out);
    cr_assert(deps < cc, "make test compiles before it installs its packages:\n%s", out);
    free(out);
}

/* make -n test, with Criterion missing, installs nothing, and says so: not
 * in the build folder's own configuration (make remakes it even under -n),
 * nor in the sub-makes of the aarch64 and SIMDe tests (make -n runs them). */
Test(make, a_dry_run_installs_nothing, .init = make_build_dir, .fini = test_scratch_remove)
{
    /* pkg-config as it is, except that Criterion is missing */
    stand_in("pkg-config", "for a; do [ \"$a\" = criterion ] && exit 1; done\n"
                           "PATH=${PATH#*:} exec pkg-config \"$@\"");
    char *out = make("test");
    cr_assert(strstr(out, "missing criterion") && strstr(out, "a dry run (make -n) installs nothing"),
              "make -n test did not see Criterion missing:\n%s", out);
    char exact[300];
    snprintf(exact, sizeof exact, "qemu-aarch64 %s/aarch64/exact", build);
    cr_assert(strstr(out, exact), "make -n test did not go through the aarch64 sub-make:\n%s", out);
    free(out);
}

Test(make, figures_go_where_figures_says, .init = make_build_dir, .fini = test_scratch_remove)
{
    char args[256], want[256], line[4096];
    snprintf(args, sizeof args, "FIGURES=%s/elsewhere figures", build);
    char *out = make(args);
    snprintf(want, sizeof want, "make-figures.sh %s %s/elsewhere", build, build);
    cr_assert(line_with(out, "make-figures.sh", line, sizeof line), "no figures step:\n%s", out);
    cr_assert(strstr(line, want), "figures not written to FIGURES: %s", line);
    free(out);
    /* make bench's timed command: its own folder, under the build folder
     * (read from make's database: `make -n bench` would run the bench) */
    out = make("-p -q Makefile");
    cr_assert(line_with(out, "--figures-cmd", line, sizeof line), "no bench recipe:\n%.2000s", out);
    cr_assert(strstr(line, "FIGURES=$(B)/"), "make bench times figures into figures/: %s", line);
    free(out);
}

/* Two installs at once (two makes, or the sub-makes of one) never overlap:
 * the second waits until the first is done, and says that it waits. The
 * stand-in apt-get here succeeds slowly and writes when it starts and ends;
 * Criterion stays missing, so both runs install. */
Test(make, a_second_install_waits_for_the_first, .init = make_build_dir, .fini = test_scratch_remove,
     .timeout = 60)
{
    stand_in("pkg-config", "for a; do [ \"$a\" = criterion ] && exit 1; done\n"
                           "PATH=${PATH#*:} exec pkg-config \"$@\"");
    char body[512], cmd[1024];
    snprintf(body, sizeof body, "echo \"start $1\" >> %s.order; sleep 0.5; echo \"end $1\" >> %s.order", installs,
             installs);
    stand_in("apt-get", body);
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u TRISTEP_DRY_RUN -u TRISTEP_DEPS_LOCKED PATH=\"%s:$PATH\" sh -c "
             "'sh src/deps.sh test > %s.1 2>&1 & sleep 0.2; sh src/deps.sh test > %s.2 2>&1; wait'",
             bin, installs, installs);
    cr_assert_neq(system(cmd), -1);
    char path[128];
    snprintf(path, sizeof path, "%s.order", installs);
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f, "apt-get was never called");
    char line[64];
    int depth = 0, calls = 0;
    while (fgets(line, sizeof line, f)) {
        depth += strncmp(line, "start", 5) == 0 ? 1 : -1;
        calls += strncmp(line, "start", 5) == 0;
        cr_assert(depth == 0 || depth == 1, "two apt-get runs at once (%s)", path);
    }
    fclose(f);
    cr_assert_eq(calls, 4, "apt-get ran %d times, not update and install twice", calls);
    snprintf(path, sizeof path, "%s.2", installs);
    char *second = NULL;
    f = fopen(path, "r");
    cr_assert_not_null(f);
    size_t cap = 0;
    cr_assert_gt(getdelim(&second, &cap, '\0', f), 0);
    fclose(f);
    cr_assert(strstr(second, "waiting for it"), "the second install did not say that it waits:\n%s", second);
    free(second);
}

/* A student checks a.c, deletes it, checks b.c: the second check runs (a
 * dependency file of the first named a.c, and make stopped: "No rule to
 * make target 'a.c'"). The build folder starts as a copy of the test run's
 * own, so that only the student's program is compiled. */
Test(make, check_takes_a_new_file_when_the_old_one_is_gone, .init = make_build_dir,
     .fini = test_scratch_remove, .timeout = 240)
{
    const char *from = test_build_dir();
    size_t n = strlen(from);
    bool sanitized = n >= 9 && strcmp(from + n - 9, "/sanitize") == 0;
    char cmd[1536], *out;
    snprintf(cmd, sizeof cmd, "mkdir -p %s%s && cd %s && cp -a obj fast config.mk cc.flag lessons.c libtristep.a %s%s",
             build, sanitized ? "/sanitize" : "", from, build, sanitized ? "/sanitize" : "");
    cr_assert_eq(system(cmd), 0, "cannot copy the build folder %s: %s", from, cmd);
    const char *answer = "lessons/05-block-classification/answer.c";
    struct stat st;
    cr_assert_eq(stat(answer, &st), 0, "no %s", answer);
    const char *files[] = { "a.c", "b.c" };
    for (int i = 0; i < 2; i++) {
        char path[300];
        snprintf(path, sizeof path, "%s", test_scratch_path(files[i]));
        snprintf(cmd, sizeof cmd, "cp %s %s", answer, path);
        cr_assert_eq(system(cmd), 0, "%s", cmd);
        if (i)
            cr_assert_eq(remove(test_scratch_path(files[0])), 0);
        char args[512];
        snprintf(args, sizeof args, "%scheck LESSON=05 FILE=%s", sanitized ? "SANITIZE=1 " : "", path);
        int status = make_run("-s", args, &out);
        cr_assert_eq(status, 0, "make %s%s:\n%s", args, i ? ", a.c deleted" : "", out);
        cr_assert(strstr(out, "checks pass"), "make %s:\n%s", args, out);
        free(out);
    }
    assert_no_install("make check");
}
