/* test_texture_input.c - textured scenes as the programs take them: every
 * input error of a texture line, a PNG or an OBJ's texture coordinates is
 * `FILE:LINE: message` (in-process, and through a program: exit 2, nothing
 * written); every lesson program reads textured 2-D and 3-D scenes and,
 * before lesson 09, draws them by its own rule (an image-textured triangle
 * in its vertex colour), which --help says. */
#define _POSIX_C_SOURCE 200809L   /* access */

#include <cairo.h>
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "testlib.h"

/* A w x h PNG, opaque grey, or with one texel of alpha `alpha` (< 255). */
static void put_png(const char *name, int w, int h, int alpha)
{
    cairo_surface_t *s = cairo_image_surface_create(alpha < 255 ? CAIRO_FORMAT_ARGB32 : CAIRO_FORMAT_RGB24, w, h);
    cairo_t *cr = cairo_create(s);
    cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
    cairo_paint(cr);
    if (alpha < 255) {
        cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
        cairo_set_source_rgba(cr, 0.2, 0.4, 0.6, alpha / 255.0);
        cairo_rectangle(cr, 0, 0, 1, 1);
        cairo_fill(cr);
    }
    cairo_destroy(cr);
    cr_assert_eq(cairo_surface_write_to_png(s, test_scratch_path(name)), CAIRO_STATUS_SUCCESS);
    cairo_surface_destroy(s);
}

/* --- input errors ---------------------------------------------------------------------- */

#define CAM "camera 0 1 5  0 0 0  0 1 0  60 0.5 100\n"
#define TRI24 "tri 1 1 1 1 1 1 0 0  30 2 1 1 1 1 1 0  3 20 1 1 1 1 0 1\n"
#define QUAD "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\n"

struct bad {
    const char *what, *scene, *obj;   /* obj: written as m.obj when not NULL */
    const char *file;                 /* the file the message names: "s.scene" or "m.obj" */
    int line;
    const char *says;                 /* part of the message */
};

static const struct bad bad[] = {
    { "missing PNG", "size 8 8\n\ntexture nothere.png\n", NULL, "s.scene", 3, "cannot open" },
    { "not a PNG", "size 8 8\ntexture text.png\n", NULL, "s.scene", 2, "not a PNG" },
    { "truncated PNG", "size 8 8\ntexture cut.png\n", NULL, "s.scene", 2, "malformed PNG" },
    { "PNG without IHDR", "size 8 8\ntexture nohdr.png\n", NULL, "s.scene", 2, "malformed PNG" },
    { "3 x 4 PNG", "size 8 8\ntexture odd.png clamp\n", NULL, "s.scene", 2, "powers of two" },
    { "8192 x 1 PNG", "size 8 8\ntexture wide.png\n", NULL, "s.scene", 2, "in 1..4096" },
    { "alpha 254", "size 8 8\ntexture glass.png\n", NULL, "s.scene", 2, "alpha 254" },
    { "alpha 0", "size 8 8\ntexture hole.png\n" TRI24, NULL, "s.scene", 2, "opaque" },
    { "bad wrap word", "size 8 8\ntexture builtin:rgby mirror\n", NULL, "s.scene", 2, "repeat or clamp" },
    { "texture alone", "size 8 8\ntexture\n", NULL, "s.scene", 2, "texture FILE.png" },
    { "four words", "size 8 8\ntexture a.png clamp x\n", NULL, "s.scene", 2, "texture FILE.png" },
    { "unknown builtin", "size 8 8\ntexture builtin:marble\n", NULL, "s.scene", 2, "no built-in texture" },
    { "checker without N", "size 8 8\ntexture checker\n", NULL, "s.scene", 2, "texture checker N" },
    { "s infinite", "size 8 8\ntri 1 1 1 1 1 1 inf 0  5 1 1 1 1 1 1 0  1 5 1 1 1 1 0 1\n", NULL,
      "s.scene", 2, "not a number" },
    { "t NaN", "size 8 8\ntri 1 1 1 1 1 1 0 nan  5 1 1 1 1 1 1 0  1 5 1 1 1 1 0 1\n", NULL,
      "s.scene", 2, "not a number" },
    { "tri3 s too large", "size 8 8\n" CAM "tri3 0 0 0 1 1 1 2e6 0  1 0 0 1 1 1 0 0  0 1 0 1 1 1 0 0\n",
      NULL, "s.scene", 3, "s = 2e+06 is outside" },
    { "tri3 t overflows", "size 8 8\n" CAM "tri3 0 0 0 1 1 1 0 0  1 0 0 1 1 1 0 1e999  0 1 0 1 1 1 0 0\n",
      NULL, "s.scene", 3, "too large" },
    { "tri3 of 21 numbers", "size 8 8\n" CAM "tri3 0 0 0 1 1 1 0  1 0 0 1 1 1 0  0 1 0 1 1 1 0\n",
      NULL, "s.scene", 3, "or 24" },
    { "vt beyond", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "f 1/1 2/2 3/3\n", "m.obj", 6,
      "texture coordinate 3 is not defined" },
    { "vt before any", "size 8 8\n" CAM "obj m.obj 1 1 1\n", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1/1 2/1 3/1\nvt 0 0\n",
      "m.obj", 4, "texture coordinate 1 is not defined" },
    { "vt -3 of 2", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "f 1/-1/1 2/-3/1 3/-1/1\n", "m.obj", 6,
      "texture coordinate -3" },
    { "vt index 0", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "f 1/0 2/1 3/1\n", "m.obj", 6, "index 0" },
    { "vt nan", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "vt nan 0\n", "m.obj", 6, "not a number" },
    { "vt inf", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "vt 0 -inf\n", "m.obj", 6, "not a number" },
    { "vt 1e300", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "vt 1e300 0\n", "m.obj", 6, "outside" },
    { "vt empty", "size 8 8\n" CAM "obj m.obj 1 1 1\n", QUAD "vt\n", "m.obj", 6, "'vt' needs" },
};

static void make_files(void)
{
    test_scratch_make();
    test_scratch_text("text.png", "size 8 8\n");
    static const unsigned char cut[] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                                         'I', 'H', 'D', 'R', 0, 0, 0, 4, 0, 0, 0, 4, 8, 2, 0, 0, 0 };
    test_scratch_put("cut.png", cut, sizeof cut);
    static const unsigned char nohdr[] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                                           'I', 'D', 'A', 'T', 0, 0, 0, 4, 0, 0, 0, 4, 8, 2 };
    test_scratch_put("nohdr.png", nohdr, sizeof nohdr);
    put_png("odd.png", 3, 4, 255);
    put_png("wide.png", 8192, 1, 255);
    put_png("glass.png", 4, 4, 254);
    put_png("hole.png", 2, 2, 0);
}

Test(texture_input, every_error_names_the_file_and_line, .init = make_files, .fini = test_scratch_remove)
{
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const struct bad *b = &bad[i];
        test_scratch_text("s.scene", b->scene);
        if (b->obj)
            test_scratch_text("m.obj", b->obj);
        struct scene s;
        char err[512] = "", want[300];
        cr_expect(!scene_load(&s, test_scratch_path("s.scene"), err, sizeof err), "%s: accepted", b->what);
        cr_expect(s.ntris == 0 && s.tris == NULL && scene_texture_count(&s) == 0,
                  "%s: the rejected scene keeps nothing", b->what);
        snprintf(want, sizeof want, "%s:%d: ", test_scratch_path(b->file), b->line);
        cr_expect(strncmp(err, want, strlen(want)) == 0, "%s: '%s' does not start with '%s'", b->what, err, want);
        cr_expect(strstr(err, b->says) != NULL, "%s: '%s' does not say '%s'", b->what, err, b->says);
        cr_expect(strchr(err, '\n') == NULL, "%s: one line", b->what);
    }
}

/* --- the programs ------------------------------------------------------------------------ */

/* Run a command line through the shell; its exit status. */
static int run(const char *fmt, ...)
{
    char cmd[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static int programs(char names[][300], int max)
{
    DIR *d = opendir(test_build_dir());
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < max;) {
        const char *s = e->d_name;
        if (s[0] >= '0' && s[0] <= '9' && s[1] >= '0' && s[1] <= '9' && s[2] == '-') {
            snprintf(names[n], 300, "%s/%s", test_build_dir(), s);
            struct stat st;
            n += stat(names[n], &st) == 0 && S_ISREG(st.st_mode) && access(names[n], X_OK) == 0;
        }
    }
    closedir(d);
    cr_assert_geq(n, 8, "the lesson programs in %s", test_build_dir());
    return n;
}

static bool same_file(const char *a, const char *b)
{
    return run("cmp -s '%s' '%s'", a, b) == 0;
}

Test(texture_input, a_program_refuses_a_bad_texture_and_writes_nothing, .init = make_files, .fini = test_scratch_remove)
{
    char prog[16][300];
    int n = programs(prog, 16);
    const char *cases[] = { "size 8 8\ntexture odd.png\n" TRI24, "size 8 8\ntexture glass.png\n" TRI24,
                            "size 8 8\n" CAM "obj m.obj 1 1 1\n" };
    test_scratch_text("m.obj", QUAD "f 1/1 2/2 3/3\n");
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            test_scratch_text("s.scene", cases[c]);
            cr_expect_eq(run("'%s' --scene '%s' --dump-image '%s' 2>'%s'", prog[i], test_scratch_path("s.scene"),
                             test_scratch_path("out.png"), test_scratch_path("err.txt")), 2, "%s, case %d: exit 2", prog[i], c);
            cr_expect(access(test_scratch_path("out.png"), F_OK) != 0, "%s, case %d: nothing written", prog[i], c);
            FILE *f = fopen(test_scratch_path("err.txt"), "r");
            char line[512] = "";
            cr_assert_not_null(f);
            cr_expect(fgets(line, sizeof line, f) && strstr(line, c == 2 ? "m.obj:6: " : "s.scene:2: "),
                      "%s: %s", prog[i], line);
            fclose(f);
        }
}

/* Each program before texture mapping draws a triangle under an image
 * texture in its vertex colour: the picture of a textured scene is that of
 * the same scene without its texture lines, byte for byte, in 2-D and in
 * 3-D. A lesson that textures (.texturing) draws the image: the pictures
 * differ. */
Test(texture_input, every_program_reads_textured_scenes_and_draws_them_by_its_rule,
     .init = make_files, .fini = test_scratch_remove)
{
    char prog[16][300];
    int n = programs(prog, 16);
    put_png("wall.png", 16, 8, 255);
    test_scratch_text("torus.obj", "");
    const char *scenes[2][2] = {
        { "size 40 30\ntexture wall.png clamp\n"
          "tri 2 2 1 1 0.5 0.2 0 0  38 4 2 0.2 1 0.5 4 0  6 28 1.5 0.3 0.4 1 0 4\n"
          "texture builtin:bricks\n"
          "tri 20 10 1 0.9 0.9 0.9 0 0  39 29 1 0.9 0.9 0.9 1 1  10 29 1 0.9 0.9 0.9 0 1\n",
          "size 40 30\n"
          "tri 2 2 1 1 0.5 0.2 0 0  38 4 2 0.2 1 0.5 4 0  6 28 1.5 0.3 0.4 1 0 4\n"
          "tri 20 10 1 0.9 0.9 0.9 0 0  39 29 1 0.9 0.9 0.9 1 1  10 29 1 0.9 0.9 0.9 0 1\n" },
        { "size 48 32\ncamera 2.2 1.8 2.6  0 -0.1 0  0 1 0  45 0.5 20\ntexture builtin:grid\n"
          "obj builtin:torus.obj 0.85 0.6 0.3\ntexture wall.png\n"
          "tri3 -3 -1 -3 1 1 1 0 0  3 -1 -3 1 1 1 8 0  0 -1 3 1 1 1 0 8\n",
          "size 48 32\ncamera 2.2 1.8 2.6  0 -0.1 0  0 1 0  45 0.5 20\n"
          "obj builtin:torus.obj 0.85 0.6 0.3\n"
          "tri3 -3 -1 -3 1 1 1 0 0  3 -1 -3 1 1 1 8 0  0 -1 3 1 1 1 0 8\n" },
    };
    for (int d = 0; d < 2; d++) {
        test_scratch_text("tex.scene", scenes[d][0]);
        test_scratch_text("plain.scene", scenes[d][1]);
        for (int i = 0; i < n; i++) {
            cr_expect_eq(run("'%s' --scene '%s' --dump-image '%s'", prog[i], test_scratch_path("tex.scene"),
                             test_scratch_path("tex.png")), 0, "%s reads the textured %d-D scene", prog[i], d + 2);
            cr_expect_eq(run("'%s' --scene '%s' --dump-image '%s'", prog[i], test_scratch_path("plain.scene"),
                             test_scratch_path("plain.png")), 0);
            const struct lesson *l = NULL;
            for (int k = 0; all_lessons[k]; k++)
                if (strcmp(strrchr(prog[i], '/') + 1, all_lessons[k]->id) == 0)
                    l = all_lessons[k];
            cr_assert_not_null(l, "%s is a lesson's program", prog[i]);
            cr_expect(same_file(test_scratch_path("tex.png"), test_scratch_path("plain.png")) == !l->texturing,
                      "%s: the textured %d-D scene drawn by its rule (%s)", prog[i], d + 2,
                      l->texturing ? "the image" : "the vertex colour");
        }
    }
    for (int i = 0; i < n; i++)
        cr_expect_eq(run("'%s' --help | grep -q 'texture FILE.png'", prog[i]), 0,
                     "%s --help says how it draws image textures", prog[i]);
}
