/* test_readme.c - the README's lesson catalogue lists exactly the lessons
 * that exist, each with its program name and title. */
#include <criterion/criterion.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"

extern const struct lesson *const all_lessons[];

static char *read_readme(void)
{
    FILE *f = fopen("README.md", "rb");
    cr_assert_not_null(f, "README.md not found (run the tests from the project's top folder)");
    static char text[1 << 16];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    return text;
}

/* The catalogue: the lines between the two markers. */
static char *catalogue(char *text)
{
    char *begin = strstr(text, "<!-- catalogue:");
    char *end = strstr(text, "<!-- end of catalogue -->");
    cr_assert(begin && end && begin < end, "README.md has no catalogue markers");
    *end = '\0';
    return begin;
}

Test(readme, catalogue_lists_every_lesson_with_its_program_and_title)
{
    char *cat = catalogue(read_readme());
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        char row[256];
        snprintf(row, sizeof row, "| [%.2s](lessons/%s/README.md) | `build/%s` | %s |",
                 l->id, l->id, l->id, l->title);
        cr_expect(strstr(cat, row) != NULL, "README catalogue lacks the row:\n%s", row);
    }
}

Test(readme, catalogue_lists_no_lesson_that_does_not_exist)
{
    char *cat = catalogue(read_readme());
    int rows = 0;
    for (char *p = strstr(cat, "\n| ["); p; p = strstr(p + 1, "\n| ["))
        rows++;
    int lessons = 0;
    while (all_lessons[lessons])
        lessons++;
    cr_expect_eq(rows, lessons, "README catalogue has %d rows for %d lessons", rows, lessons);
}

Test(readme, every_picture_it_shows_exists)
{
    char *text = read_readme();
    int pictures = 0;
    for (char *p = strstr(text, "figures/"); p; p = strstr(p + 1, "figures/")) {
        size_t n = strcspn(p, "\")> \n");
        if (n < 12 || strncmp(p + n - 4, ".png", 4) != 0)
            continue;
        char path[256];
        snprintf(path, sizeof path, "%.*s", (int)n, p);
        FILE *f = fopen(path, "rb");
        cr_expect_not_null(f, "README.md shows %s, which does not exist", path);
        if (f)
            fclose(f);
        pictures++;
    }
    cr_expect_gt(pictures, 0, "README.md shows no picture");
}

/* The top level is the design card's: the four folders, the Makefile and
 * the README, beside .ci, .gitignore and LICENSE; anything else (a table,
 * a folder of models) belongs inside one of the folders. Read from what
 * git tracks, so that a build folder does not count; in a tree git does
 * not track (a student kit, make student-kit), from the tree without its
 * build folders. */
Test(readme, the_top_level_is_the_design_cards)
{
    static const char *const allowed[] = { ".ci", ".gitignore", "LICENSE", "Makefile", "README.md",
                                           "figures", "lessons", "src", "tests" };
    FILE *p = popen("{ git ls-files 2>/dev/null | grep . || ls -A | grep -v '^build'; } | cut -d/ -f1 | sort -u", "r");
    cr_assert_not_null(p);
    char name[256];
    int seen = 0;
    while (fgets(name, sizeof name, p)) {
        name[strcspn(name, "\n")] = '\0';
        bool ok = false;
        for (size_t i = 0; i < sizeof allowed / sizeof allowed[0]; i++)
            ok = ok || strcmp(name, allowed[i]) == 0;
        cr_expect(ok, "the top level holds %s, which is not on the design card", name);
        seen++;
    }
    pclose(p);
    cr_assert_geq(seen, 6, "%d top-level entries: not the project's top folder?", seen);
}
