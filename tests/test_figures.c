/* test_figures.c - the committed figures are what the programs draw today.
 *
 * Every PNG line of figures/list is drawn again by its lesson program (as
 * figures/make-figures.sh does, one process per figure) into a temporary
 * folder and compared with figures/NAME pixel for pixel. The tolerance is
 * zero on purpose: coverage is exact integer arithmetic, and the fonts are
 * pinned (explorer_fonts), so any difference is a real change of a picture.
 *
 * On a mismatch the test writes NAME_actual.png and NAME_diff.png (changed
 * pixels in magenta over a faded copy of the reference) under
 * $TRISTEP_BUILD/figures-diff/ and names the command that updates the
 * references. SVG and PDF lines are not compared here (their bytes are
 * checked by running `make figures` twice); they must exist, though.
 */
#define _POSIX_C_SOURCE 200809L   /* posix_spawn, mkdtemp, opendir */

#include <cairo.h>
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <dirent.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testlib.h"

extern char **environ;

#define LIST "figures/list"
#define MAX_FIGURES 128
#define MAX_ARGS 32

struct figure {
    char line[512];             /* the list line, split in place */
    int lineno;
    char *name, *lesson, *scene, *step, *view, *size;
    char *extra[MAX_ARGS];
    int nextra;
};

static int read_list(struct figure *f, int max)
{
    FILE *in = fopen(LIST, "r");
    cr_assert_not_null(in, LIST " not found (run the tests from the project's top folder)");
    char buf[512];
    int n = 0, lineno = 0;
    while (fgets(buf, sizeof buf, in)) {
        lineno++;
        char *p = buf + strspn(buf, " \t");
        if (*p == '#' || *p == '\n' || *p == '\0')
            continue;
        cr_assert_lt(n, max, LIST ": more than %d figures", max);
        struct figure *g = &f[n++];
        memset(g, 0, sizeof *g);
        snprintf(g->line, sizeof g->line, "%s", p);
        g->lineno = lineno;
        char *field[6 + MAX_ARGS];
        int k = 0;
        for (char *tok = strtok(g->line, " \t\n"); tok && k < 6 + MAX_ARGS; tok = strtok(NULL, " \t\n"))
            field[k++] = tok;
        cr_assert_geq(k, 6, LIST ":%d: expected output lesson scene step view size [options]", lineno);
        g->name = field[0], g->lesson = field[1], g->scene = field[2];
        g->step = field[3], g->view = field[4], g->size = field[5];
        for (int i = 6; i < k; i++)
            g->extra[g->nextra++] = field[i];
    }
    fclose(in);
    return n;
}

static bool is_png(const char *name)
{
    size_t n = strlen(name);
    return n > 4 && strcmp(name + n - 4, ".png") == 0;
}

/* Draw one figure into dir/NAME with the lesson program; returns its exit status. */
static int draw_figure(const struct figure *g, const char *dir, char *out, size_t outlen)
{
    char prog[512];
    snprintf(prog, sizeof prog, "%s/%s", test_build_dir(), g->lesson);
    snprintf(out, outlen, "%s/%s", dir, g->name);
    char *argv[16 + MAX_ARGS];
    int a = 0;
    argv[a++] = prog;
    argv[a++] = "--figure", argv[a++] = out;
    argv[a++] = "--scene", argv[a++] = g->scene;
    argv[a++] = "--step", argv[a++] = g->step;
    argv[a++] = "--view", argv[a++] = g->view;
    argv[a++] = "--size", argv[a++] = g->size;
    for (int i = 0; i < g->nextra; i++)
        argv[a++] = g->extra[i];
    argv[a] = NULL;
    pid_t pid;
    int err = posix_spawn(&pid, prog, NULL, NULL, argv, environ);
    cr_assert_eq(err, 0, "cannot run %s: %s (set TRISTEP_BUILD)", prog, strerror(err));
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

static cairo_surface_t *load_png(const char *path)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(s);
        return NULL;
    }
    cairo_surface_flush(s);
    return s;
}

static uint32_t pixel(cairo_surface_t *s, int x, int y)
{
    const unsigned char *row = cairo_image_surface_get_data(s) + (size_t)y * (size_t)cairo_image_surface_get_stride(s);
    uint32_t v;
    memcpy(&v, row + 4 * (size_t)x, 4);
    /* RGB24 leaves the top byte undefined: compare colour only then */
    return cairo_image_surface_get_format(s) == CAIRO_FORMAT_ARGB32 ? v : (v & 0xffffff);
}

/* Differing pixels, or -1 when the sizes differ. */
static long count_diff(cairo_surface_t *a, cairo_surface_t *b)
{
    int w = cairo_image_surface_get_width(a), h = cairo_image_surface_get_height(a);
    if (w != cairo_image_surface_get_width(b) || h != cairo_image_surface_get_height(b))
        return -1;
    long n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            n += pixel(a, x, y) != pixel(b, x, y);
    return n;
}

/* The reference faded to a quarter, changed pixels in magenta. */
static void write_diff(cairo_surface_t *ref, cairo_surface_t *act, const char *path)
{
    int w = cairo_image_surface_get_width(ref), h = cairo_image_surface_get_height(ref);
    cairo_surface_t *d = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *data = cairo_image_surface_get_data(d);
    int stride = cairo_image_surface_get_stride(d);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t r = pixel(ref, x, y), v;
            if (pixel(act, x, y) != r)
                v = 0xff00ff;
            else
                v = ((r >> 2) & 0x3f3f3f);
            memcpy(data + (size_t)y * (size_t)stride + 4 * (size_t)x, &v, 4);
        }
    cairo_surface_mark_dirty(d);
    cairo_surface_write_to_png(d, path);
    cairo_surface_destroy(d);
}

static void copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    char buf[1 << 14];
    size_t n;
    while (out && (n = fread(buf, 1, sizeof buf, in)) > 0)
        fwrite(buf, 1, n, out);
    if (out)
        fclose(out);
    if (in)
        fclose(in);
}

Test(figures, every_png_in_the_list_is_drawn_as_committed, .timeout = 120)
{
    static struct figure list[MAX_FIGURES];
    int n = read_list(list, MAX_FIGURES);
    cr_assert_gt(n, 0, LIST " names no figure");
    char tmp[] = "/tmp/tristep-figures-XXXXXX";
    cr_assert_not_null(mkdtemp(tmp));
    char diffdir[512];
    snprintf(diffdir, sizeof diffdir, "%s/figures-diff", test_build_dir());

    int compared = 0, failed = 0;
    for (int i = 0; i < n; i++) {
        const struct figure *g = &list[i];
        if (!is_png(g->name))
            continue;
        char out[600], ref[600];
        int status = draw_figure(g, tmp, out, sizeof out);
        snprintf(ref, sizeof ref, "figures/%s", g->name);
        if (status != 0) {
            cr_log_error(LIST ":%d: %s: the program exited with status %d", g->lineno, g->name, status);
            failed++;
            continue;
        }
        cairo_surface_t *want = load_png(ref), *got = load_png(out);
        compared++;
        long d = !want || !got ? -2 : count_diff(want, got);
        if (d != 0) {
            failed++;
            mkdir(diffdir, 0777);
            char stem[600], path[700];
            snprintf(stem, sizeof stem, "%s/%.*s", diffdir, (int)(strlen(g->name) - 4), g->name);
            snprintf(path, sizeof path, "%s_actual.png", stem);
            copy_file(out, path);
            if (d > 0) {
                snprintf(path, sizeof path, "%s_diff.png", stem);
                write_diff(want, got, path);
            }
            cr_log_error("%s: %s; wrote %s_actual.png%s", ref,
                         d == -2 ? "cannot read the committed or the new PNG"
                         : d == -1 ? "the size changed"
                         : "pixels differ",
                         stem, d > 0 ? " and _diff.png" : "");
            if (d > 0)
                cr_log_error("%s: %ld pixels differ", ref, d);
        }
        if (want)
            cairo_surface_destroy(want);
        if (got)
            cairo_surface_destroy(got);
        unlink(out);
    }
    rmdir(tmp);
    if (failed)
        cr_log_error("if the change is intended, update the references with: make figures"
                     " (then look at every changed figure before committing it)");
    cr_expect_eq(failed, 0, "%d of %d figures differ from figures/ (see above)", failed, compared);
    cr_expect_gt(compared, 0, LIST " names no PNG figure");
}

Test(figures, the_list_and_the_folder_agree)
{
    static struct figure list[MAX_FIGURES];
    int n = read_list(list, MAX_FIGURES);
    /* every line's output exists, and no name is listed twice */
    for (int i = 0; i < n; i++) {
        char path[600];
        snprintf(path, sizeof path, "figures/%s", list[i].name);
        struct stat st;
        cr_expect(stat(path, &st) == 0, LIST ":%d: %s is not in figures/ (run make figures)",
                  list[i].lineno, list[i].name);
        cr_expect(strchr(list[i].name, '/') == NULL, LIST ":%d: %s: a plain file name, please",
                  list[i].lineno, list[i].name);
        for (int j = 0; j < i; j++)
            cr_expect_neq(strcmp(list[i].name, list[j].name), 0, LIST ":%d: %s is listed twice",
                          list[i].lineno, list[i].name);
    }
    /* every figure in the folder is in the list: no orphan keeps an old picture */
    DIR *dir = opendir("figures");
    cr_assert_not_null(dir, "no figures/ folder");
    const char *kinds[] = { ".png", ".svg", ".pdf" };
    for (struct dirent *e; (e = readdir(dir)) != NULL;) {
        size_t len = strlen(e->d_name);
        bool figure = false;
        for (int k = 0; k < 3; k++)
            figure |= len > 4 && strcmp(e->d_name + len - 4, kinds[k]) == 0;
        if (!figure)
            continue;
        bool listed = false;
        for (int i = 0; i < n; i++)
            listed |= strcmp(list[i].name, e->d_name) == 0;
        cr_expect(listed, "figures/%s is not in " LIST " (an orphan: remove it or list it)", e->d_name);
    }
    closedir(dir);
}
