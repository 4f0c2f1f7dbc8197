/* test_make.c - the Makefile keeps its promises, seen through `make -n`
 * (what make would run, in the order it would run it) in a build folder of
 * the test's own:
 *   - the user's CFLAGS and LDFLAGS do not replace the flags tristep needs;
 *   - make test installs its packages before it compiles anything;
 *   - make figures writes where FIGURES says, and make bench times the
 *     figures into its build folder, never over the committed figures/.
 * Run from the repository's top folder, as make test does. */
#define _POSIX_C_SOURCE 200809L   /* popen, mkdtemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

/* make's build folder: the test's scratch folder (testlib) */
static const char *build;

static void make_build_dir(void)
{
    test_scratch_make();
    build = test_scratch_dir();
}

/* The output of `make -n ARGS` (stdout and stderr), NUL-terminated,
 * malloc'ed; without what a calling make (make test SANITIZE=1) passes
 * down in MAKEFLAGS and in the environment, such as SANITIZE or CFLAGS. */
static char *make(const char *args)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u SANITIZE -u CFLAGS -u LDFLAGS "
             "-u LDLIBS -u FIGURES make -n --no-print-directory BUILD=%s %s 2>&1", build, args);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p, "cannot run %s", cmd);
    size_t cap = 1 << 16, n = 0;
    char *out = malloc(cap);
    cr_assert_not_null(out);
    for (size_t got; (got = fread(out + n, 1, cap - n - 1, p)) > 0;) {
        n += got;
        if (n + 1 == cap) {
            out = realloc(out, cap *= 2);
            cr_assert_not_null(out);
        }
    }
    out[n] = '\0';
    int status = pclose(p);
    cr_assert_eq(status, 0, "%s failed:\n%s", cmd, out);
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
    char target[128], line[4096];
    snprintf(target, sizeof target, "-B CFLAGS=-O0 LDFLAGS=-Wl,-O1 SANITIZE=1 %s/sanitize/01-scanline", build);
    char *out = make(target);
    cr_assert(line_with(out, "-c src/lesson.c", line, sizeof line), "no compile of src/lesson.c:\n%s", out);
    cr_assert(strstr(line, " -O0 ") && !strstr(line, " -O2 "), "the user's CFLAGS are not used: %s", line);
    cr_assert(strstr(line, "-Isrc") && strstr(line, "-std=c17") && strstr(line, "-Wall"),
              "CFLAGS=-O0 dropped the required flags: %s", line);
    cr_assert(strstr(line, "-fsanitize=address,undefined"), "SANITIZE lost with CFLAGS given: %s", line);
    char link[160];
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
