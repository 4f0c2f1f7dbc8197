/* test_kit.c - a student kit (make student-kit) is the course without its
 * answers, and works:
 *
 *   - it holds no worked answer, no answer key, no mutation suite and no
 *     test that needs them, and says which tests it left out;
 *   - in it, make check passes a worked answer copied in from outside the
 *     kit (as a student's own file), and fails the kit's own skeleton, for
 *     an exercise and for a graded variant.
 *
 * To keep it short the kit is built with lesson 02 alone, on the objects
 * this build has already compiled from the same sources (copied with their
 * times, so the kit's make finds them up to date and compiles only what a
 * one-lesson tree changes); `make student-kit-test` builds a whole kit from
 * nothing and runs its make test. This test needs the worked answers: a
 * kit leaves it out.
 */
#define _POSIX_C_SOURCE 200809L

#include <criterion/criterion.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "testlib.h"

/* Run a command line in sh; its output in *log (static); its exit status.
 * Not the test run's own make: no jobserver, no inherited flags. */
static int run(char **log, const char *fmt, ...)
{
    char cmd[4096], line[4400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    const char *out = test_scratch_path("log");
    snprintf(line, sizeof line, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u SANITIZE -u BUILD sh -c '%s' > %s 2>&1",
             cmd, out);
    int st = system(line);
    FILE *f = fopen(out, "rb");
    cr_assert_not_null(f);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    *log = buf;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

Test(kit, a_student_kit_checks_a_worked_answer_brought_in_from_outside, .init = test_scratch_make,
     .fini = test_scratch_remove, .timeout = 240)
{
    const char *build = getenv("TRISTEP_BUILD") ? getenv("TRISTEP_BUILD") : "build";
    cr_assert(strspn(build, "abcdefghijklmnopqrstuvwxyz0123456789_-./") == strlen(build) && build[0] != '/',
              "TRISTEP_BUILD=%s: expected a folder of the tree, such as build", build);
    const char *sanitize = strstr(build, "sanitize") ? "SANITIZE=1" : "";
    char kit[300], *log;
    snprintf(kit, sizeof kit, "%s/kit", test_scratch_dir());
    cr_assert_eq(run(&log, "make -s student-kit KIT=%s", kit), 0, "make student-kit:\n%s", log);
    cr_expect_not_null(strstr(log, "student kit in"), "%s", log);

    /* nothing that gives an answer away */
    cr_assert_eq(run(&log, "cd %s && find . -name \"answer*.c\" -o -name ANSWERS.md -o -path ./tests/mutations", kit), 0);
    cr_expect_str_eq(log, "", "the kit holds answers:\n%s", log);
    cr_expect_eq(run(&log, "cd %s && test -f lessons/02-barycentric/exercise.c && test -f lessons/02-barycentric/exercise-bottom-right.c"
                     " && test ! -e tests/test_exercise.c && ! grep -l \"^#if !TRISTEP_NO_ANSWERS\" tests/*.c", kit), 0,
                 "the kit's skeletons, or the tests it leaves out:\n%s", log);
    cr_expect_eq(run(&log, "grep -c . %s/tests/left-out.txt && grep -q \"tests/test_exercise.c\" %s/tests/left-out.txt", kit, kit), 0,
                 "tests/left-out.txt does not name what the kit left out:\n%s", log);

    /* lesson 02 alone, on this build's objects (src/, lesson 02, the library,
     * and the student library's objects where the build has them) */
    cr_assert_eq(run(&log, "rm -rf %s/lessons/01-* %s/lessons/0[3-9]-* && mkdir -p %s/%s && "
                     "tar -cf - %s/config.mk %s/cc.flag %s/lib.list %s/libtristep.a %s/obj/src %s/obj/lessons/02-* "
                     "%s/fast/lessons/02-* $(ls -d %s/student/obj 2>/dev/null) | tar -xf - -C %s && touch %s",
                     kit, kit, kit, build, build, build, build, build, build, build, build, build, kit,
                     test_scratch_path("copied")), 0, "%s", log);
    /* the kit's compiler and flags are this build's (cc.flag, which every
     * object depends on, rewritten by the kit's make in its own spacing,
     * keeps the time of the copy) */
    cr_assert_eq(run(&log, "cd %s && cp -p %s/cc.flag cc.copied && make -s %s B=%s %s/cc.flag && "
                     "tr -s \" \" < %s/cc.flag | sed \"s/ *$//\" > a && tr -s \" \" < cc.copied | sed \"s/ *$//\" > b && "
                     "cmp a b && touch -r cc.copied %s/cc.flag && rm a b cc.copied",
                     kit, build, sanitize, build, build, build, build), 0,
                 "the kit's compiler flags are not this build's:\n%s", log);

    /* a worked answer from outside the kit passes; the kit's skeleton fails */
    char answer[400];
    snprintf(answer, sizeof answer, "%s/mine.c", kit);
    cr_assert_eq(run(&log, "cp lessons/02-barycentric/answer.c %s", answer), 0, "%s", log);
    cr_expect_eq(run(&log, "cd %s && make -j2 %s B=%s check LESSON=02 FILE=%s", kit, sanitize, build, answer), 0,
                 "make check on an answer in the kit:\n%s", log);
    cr_expect_not_null(strstr(log, "all 5 checks pass"), "%s", log);
    cr_expect_neq(run(&log, "cd %s && make -j2 %s B=%s check LESSON=02", kit, sanitize, build), 0,
                  "make check passes the kit's untouched skeleton:\n%s", log);
    cr_expect_not_null(strstr(log, "FAILED"), "%s", log);

    /* the graded variant, likewise */
    snprintf(answer, sizeof answer, "%s/mine-bottom-right.c", kit);
    cr_assert_eq(run(&log, "cp lessons/02-barycentric/answer-bottom-right.c %s", answer), 0, "%s", log);
    cr_expect_eq(run(&log, "cd %s && make -j2 %s B=%s check LESSON=02 VARIANT=bottom-right FILE=%s", kit, sanitize,
                     build, answer), 0, "make check VARIANT=bottom-right on its answer in the kit:\n%s", log);
    cr_expect_neq(run(&log, "cd %s && make -j2 %s B=%s check LESSON=02 VARIANT=bottom-right", kit, sanitize, build), 0,
                  "make check VARIANT=bottom-right passes the kit's untouched skeleton:\n%s", log);

    /* only what a one-lesson tree changes was compiled: no library source */
    cr_expect_eq(run(&log, "find %s/%s/obj/src -newer %s -name \"*.o\"", kit, build, test_scratch_path("copied")), 0);
    cr_expect_str_eq(log, "", "the kit recompiled the library's sources:\n%s", log);
}
