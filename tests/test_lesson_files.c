/* test_lesson_files.c - a lesson folder holds the lesson: its algorithm file
 * (what a student reads: algorithm, narration, variants) and, apart, what the
 * explorer adds for it (NAME_explorer.c, compiled only in the narrated
 * build). Neither draws with cairo: the explorer side uses the canvas verbs
 * of lesson_explorer.h.
 *
 * Read from the sources, as test_layers.c reads src/: every .c and .h file
 * of every lessons/NN-name/ folder. */
#define _POSIX_C_SOURCE 200809L   /* opendir */

#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* The first line of path containing `needle`, or 0. */
static int line_with(const char *path, const char *needle)
{
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f, "cannot read %s", path);
    char line[1024];
    int n = 0, found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        n++;
        if (strstr(line, needle))
            found = n;
    }
    fclose(f);
    return found;
}

Test(lesson_files, algorithm_and_explorer_side_apart_and_no_cairo)
{
    DIR *top = opendir("lessons");
    cr_assert_not_null(top, "run from the repository's top folder");
    int algorithms = 0, sides = 0;
    struct dirent *d;
    while ((d = readdir(top))) {
        if (!(d->d_name[0] >= '0' && d->d_name[0] <= '9'))
            continue;
        char dir[300];
        snprintf(dir, sizeof dir, "lessons/%s", d->d_name);
        DIR *lesson = opendir(dir);
        cr_assert_not_null(lesson, "%s", dir);
        struct dirent *f;
        while ((f = readdir(lesson))) {
            if (!ends_with(f->d_name, ".c") && !ends_with(f->d_name, ".h"))
                continue;
            char path[700];
            snprintf(path, sizeof path, "%s/%s", dir, f->d_name);
            int at;
            cr_expect_eq(at = line_with(path, "cairo"), 0, "%s:%d: cairo in a lesson file", path, at);
            if (ends_with(f->d_name, "_explorer.c")) {
                sides++;
                cr_expect_neq(line_with(path, "#include \"lesson_explorer.h\""), 0,
                              "%s: an explorer side is written against lesson_explorer.h", path);
                continue;
            }
            if (!line_with(path, "const struct lesson lesson_"))
                continue;           /* not an algorithm file (an exercise, a helper) */
            algorithms++;
            /* the algorithm file knows nothing of the explorer */
            cr_expect_eq(at = line_with(path, "lesson_explorer"), 0,
                         "%s:%d: the explorer's side in the algorithm file", path, at);
            cr_expect_eq(at = line_with(path, "snprintf"), 0,
                         "%s:%d: panel text in the algorithm file", path, at);
        }
        closedir(lesson);
    }
    closedir(top);
    cr_expect_geq(algorithms, 5);
    cr_expect_geq(sides, 4);
}
