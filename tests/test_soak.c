/* test_soak.c - the short run of the soak (tests/soak/soak.c; `make soak`
 * runs it for 10 minutes): every lesson's window under Xvfb for a few
 * seconds of random keys, drags, clicks, wheel turns and resizes. Built
 * with the sanitizers (make test SANITIZE=1), it fails on any report. */
#define _XOPEN_SOURCE 700         /* popen */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testlib.h"

Test(soak, every_lesson_takes_random_input_under_xvfb, .timeout = 300)
{
    const char *b = test_build_dir();
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "%s/tristep-soak --build %s --seconds-per-lesson 4 2>&1", b, b);
    char exe[600];
    snprintf(exe, sizeof exe, "%s/tristep-soak", b);
    cr_assert_eq(access(exe, X_OK), 0, "%s: not built (make test builds it)", exe);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    char out[16384];
    size_t n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    int st = pclose(p);
    cr_log_info("%s", out);
    cr_assert(WIFEXITED(st) && WEXITSTATUS(st) == 0, "the soak failed:\n%s", out);
    int lessons = 0, ok = 0;
    for (int i = 0; all_lessons[i]; i++) {
        char line[80];
        snprintf(line, sizeof line, "  %-26s ok ", all_lessons[i]->id);
        lessons++;
        ok += strstr(out, line) != NULL;
    }
    cr_assert_eq(ok, lessons, "every lesson soaked without a fault:\n%s", out);
    cr_assert(strstr(out, "soak: passed") && strstr(out, " frames: median "),
              "the report gives the frame times:\n%s", out);
}
