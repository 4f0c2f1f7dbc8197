/* test_scene3.c - reading 3-D scenes and OBJ files (lessons/CONVENTIONS.md, "3-D
 * scenes"): every keyword and every OBJ form read to the right values, and
 * every kind of bad input refused with FILE:LINE (the scene's, or the OBJ
 * file's own) and nothing left in the scene. The same bad input through the
 * lesson programs (exit 2, nothing written) is in test_cli.c. */
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "front/front.h"
#include "testlib.h"

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/tristep-scene3-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (dir[0] && system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

/* Write text to dir/name; returns the path (static buffer per slot). */
static const char *put(const char *name, const char *text, size_t len)
{
    static char paths[4][256];
    static int slot;
    char *path = paths[slot++ % 4];
    snprintf(path, 256, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(text, 1, len, f), len);
    cr_assert_eq(fclose(f), 0);
    return path;
}

static struct scene load_ok(const char *scene_text)
{
    const char *path = put("ok.scene", scene_text, strlen(scene_text));
    struct scene s;
    char err[512] = "";
    cr_assert(scene_load(&s, path, err, sizeof err), "rejected: %s\n%s", err, scene_text);
    return s;
}

#define CAMERA "camera 0 1 5  0 0 0  0 1 0  60 0.1 100\n"
#define TRI3 "tri3 -1 0 -1 1 0 0  1 0 -1 0 1 0  0 0 1 0 0 1\n"

Test(scene3, every_keyword, .init = make_dir, .fini = remove_dir)
{
    struct scene s = load_ok("size 320 240\nbackground 0.1 0.2 0.3\n"
                             "camera 0 1 5   0 0 0   0 1 0   60  0.1 100   # a comment\n"
                             "cull back\n" TRI3 "tri3 1 2 3 0.5 0.5 0.5  4 5 6 0 0 0  -7 -8 -9 1 1 1\n");
    cr_expect_eq(s.w, 320);
    cr_expect_eq(s.world.camera_line, 3);
    const struct camera *c = &s.world.cam;
    const double want[12] = { 0, 1, 5, 0, 0, 0, 0, 1, 0, 60, 0.1, 100 };
    const double got[12] = { c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2],
                             c->up[0], c->up[1], c->up[2], c->fovy, c->near, c->far };
    for (int i = 0; i < 12; i++)
        cr_expect_eq(got[i], want[i], "camera value %d: %g", i, got[i]);
    cr_expect_eq(s.world.cull, CULL_BACK);
    cr_assert_eq(s.world.ntris, 2);
    cr_expect_eq(s.ntris, 0, "nothing projected before the front end runs");
    cr_expect_eq(s.world.tris[1].p[2][2], -9.0);
    cr_expect_eq(s.world.tris[1].rgb[0][1], 0.5);
    cr_expect_eq(s.world.tris[0].rgb[2][2], 1.0);
    scene_free(&s);

    s = load_ok("size 8 8\ncamera 0 0 5 0 0 0 0 1 0 90 1 10\n");
    cr_expect_eq(s.world.cull, CULL_NONE, "cull none by default");
    cr_expect_eq(s.world.ntris, 0);
    scene_free(&s);
    /* cull may come before camera, size after it */
    s = load_ok("cull front\ncamera 0 0 5 0 0 0 0 1 0 90 1 10\nsize 8 8\n" TRI3);
    cr_expect_eq(s.world.cull, CULL_FRONT);
    scene_free(&s);
}

Test(scene3, obj_forms_indices_and_ignored_statements, .init = make_dir, .fini = remove_dir)
{
    const char *obj =
        "# every form\r\n"
        "mtllib x.mtl\no thing\ng group\ns 1\nusemtl red\n"
        "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvn 0 0 1\n"
        "f 1 2 3\n"
        "f 1/1 3/2 4/1\n"
        "f 1//1 2//1 3//1   # comment\n"
        "f 1/1/1 2/2/1 3/1/1\n"
        "f -4 -3 -2\n"
        "l 1 2\n"
        "v 0.5 0.5 2\n"
        "f 1 2 3 5 4\n";        /* a pentagon: (1 2 3) (1 3 5) (1 5 4) */
    put("m.obj", obj, strlen(obj));
    struct scene s = load_ok("size 8 8\n" CAMERA "obj m.obj 0.25 0.5 1\n");
    cr_assert_eq(s.world.ntris, 8);
    const struct world_tri *t = s.world.tris;
    cr_expect(t[1].p[1][0] == 1 && t[1].p[1][1] == 1 && t[1].p[2][0] == 0, "f 1/1 3/2 4/1");
    cr_expect(t[4].p[0][0] == 0 && t[4].p[1][0] == 1 && t[4].p[2][1] == 1, "f -4 -3 -2 is 1 2 3");
    cr_expect(t[6].p[2][2] == 2, "the pentagon's second triangle ends at vertex 5");
    cr_expect(t[7].p[0][0] == 0 && t[7].p[1][2] == 2 && t[7].p[2][1] == 1 && t[7].p[2][0] == 0,
              "fanned from its first vertex");
    for (int i = 0; i < 8; i++)
        cr_expect(t[i].rgb[1][0] == 0.25 && t[i].rgb[2][2] == 1, "the obj line's colour");
    scene_free(&s);
    /* in a folder: relative to the scene, not to the current directory */
    char sub[128];
    snprintf(sub, sizeof sub, "%s/sub", dir);
    cr_assert_eq(mkdir(sub, 0755), 0);
    put("sub/m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 32);
    const char *path = put("sub/in.scene", "size 8 8\n" CAMERA "obj m.obj 1 1 1\nobj ../m.obj 1 1 1\n",
                           strlen("size 8 8\n" CAMERA "obj m.obj 1 1 1\nobj ../m.obj 1 1 1\n"));
    char err[512];
    cr_assert(scene_load(&s, path, err, sizeof err), "%s", err);
    cr_expect_eq(s.world.ntris, 9);
    scene_free(&s);
}

/* --- bad input ---------------------------------------------------------------- */

struct bad3 {
    const char *name;
    const char *scene;
    const char *obj;        /* written as bad.obj when not NULL */
    const char *where;      /* "scene" or "obj": whose line the message names */
    int line;
};

#define OBJ_LINE "obj bad.obj 1 1 1\n"
#define QUAD_V "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"

static const struct bad3 bad[] = {
    { "up parallel to the view direction", "size 8 8\ncamera 0 0 5  0 0 0  0 0 1  60 0.1 100\n", NULL, "scene", 2 },
    { "up against the view direction", "size 8 8\ncamera 0 0 5  0 0 0  0 0 -3  60 0.1 100\n", NULL, "scene", 2 },
    { "up zero", "size 8 8\n\ncamera 0 0 5  0 0 0  0 0 0  60 0.1 100\n", NULL, "scene", 3 },
    { "near = 0", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0 100\n", NULL, "scene", 2 },
    { "near < 0", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 -1 100\n", NULL, "scene", 2 },
    { "far = near", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 2 2\n", NULL, "scene", 2 },
    { "far < near", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 2 1\n", NULL, "scene", 2 },
    { "eye = target", "size 8 8\ncamera 1 2 3  1 2 3  0 1 0  60 0.1 100\n", NULL, "scene", 2 },
    { "fovy 0", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  0 0.1 100\n", NULL, "scene", 2 },
    { "fovy 180", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  180 0.1 100\n", NULL, "scene", 2 },
    { "fovy negative", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  -60 0.1 100\n", NULL, "scene", 2 },
    { "camera with 11 numbers", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0.1\n", NULL, "scene", 2 },
    { "camera with 13 numbers", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0.1 100 1\n", NULL, "scene", 2 },
    { "eye beyond 10^6", "size 8 8\ncamera 2e6 0 5  0 0 0  0 1 0  60 0.1 100\n", NULL, "scene", 2 },
    { "target nan", "size 8 8\ncamera 0 0 5  nan 0 0  0 1 0  60 0.1 100\n", NULL, "scene", 2 },
    { "up inf", "size 8 8\ncamera 0 0 5  0 0 0  0 inf 0  60 0.1 100\n", NULL, "scene", 2 },
    { "camera twice", "size 8 8\n" CAMERA CAMERA, NULL, "scene", 3 },
    /* regression: any near > 0 was taken; clipped vertices at d = near = 1e-9
     * reached lesson 04's float 1/z as 1e9 and 1e-30 as infinity */
    { "near_tiny_overflowed_inverse_depth", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 1e-30 100\n", NULL, "scene", 2 },
    { "near below 1e-6", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 9.9e-7 100\n", NULL, "scene", 2 },
    { "far beyond 1e6", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0.1 1.1e6\n", NULL, "scene", 2 },
    { "magnified beyond doubles", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  1e-200 1e-200 100\n", NULL, "scene", 2 },
    { "tri3 before camera", "size 8 8\n" TRI3 CAMERA, NULL, "scene", 2 },
    { "tri3 before size", CAMERA TRI3 "size 8 8\n", NULL, "scene", 2 },
    { "obj before camera", "size 8 8\n" OBJ_LINE CAMERA, NULL, "scene", 2 },
    { "tri3 with 17 numbers", "size 8 8\n" CAMERA "tri3 -1 0 -1 1 0 0  1 0 -1 0 1 0  0 0 1 0 0\n", NULL, "scene", 3 },
    { "tri3 beyond 10^6", "size 8 8\n" CAMERA "tri3 -1 0 -1 1 0 0  1 0 -1e7 0 1 0  0 0 1 0 0 1\n", NULL, "scene", 3 },
    { "tri3 at -1000001", "size 8 8\n" CAMERA "#\ntri3 -1000001 0 -1 1 0 0  1 0 -1 0 1 0  0 0 1 0 0 1\n", NULL, "scene", 4 },
    { "tri3 colour 2", "size 8 8\n" CAMERA "tri3 -1 0 -1 1 0 2  1 0 -1 0 1 0  0 0 1 0 0 1\n", NULL, "scene", 3 },
    { "tri3 infinity", "size 8 8\n" CAMERA "tri3 -1 0 -1 1 0 0  infinity 0 -1 0 1 0  0 0 1 0 0 1\n", NULL, "scene", 3 },
    { "2-D tri in a 3-D scene", "size 8 8\n" CAMERA "tri 1 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", NULL, "scene", 3 },
    { "camera after a 2-D tri", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n" CAMERA, NULL, "scene", 3 },
    { "cull sideways", "size 8 8\n" CAMERA "cull sideways\n", NULL, "scene", 3 },
    { "cull twice", "size 8 8\n" CAMERA "cull back\ncull none\n", NULL, "scene", 4 },
    { "cull without a camera", "size 8 8\ncull back\n# no camera\n", NULL, "scene", 2 },
    { "missing OBJ", "size 8 8\n" CAMERA "obj no-such-file.obj 1 1 1\n", NULL, "scene", 3 },
    { "obj without a colour", "size 8 8\n" CAMERA "obj bad.obj\n", "v 0 0 0\n", "scene", 3 },
    { "obj colour > 1", "size 8 8\n" CAMERA "obj bad.obj 1 1.5 1\n", "v 0 0 0\n", "scene", 3 },
    { "OBJ v with 2 numbers", "size 8 8\n" CAMERA OBJ_LINE, "v 0 0 0\nv 1 2\n", "obj", 2 },
    { "OBJ v with a word", "size 8 8\n" CAMERA OBJ_LINE, "# c\nv 0 zero 0\n", "obj", 2 },
    { "OBJ v nan", "size 8 8\n" CAMERA OBJ_LINE, "v nan 0 0\n", "obj", 1 },
    { "OBJ v beyond 10^6", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "v 0 1e7 0\n", "obj", 5 },
    { "OBJ v extra word", "size 8 8\n" CAMERA OBJ_LINE, "v 0 0 0 red\n", "obj", 1 },
    { "OBJ face of 2", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1 2\n", "obj", 5 },
    { "OBJ index 0", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 0 1 2\n", "obj", 5 },
    { "OBJ index out of range", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1 2 3\nf 2 3 5\n", "obj", 6 },
    { "OBJ negative index out of range", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f -1 -2 -5\n", "obj", 5 },
    { "OBJ face before its vertices", "size 8 8\n" CAMERA OBJ_LINE, "v 0 0 0\nf 1 2 3\n" QUAD_V, "obj", 2 },
    { "OBJ corner 1/2/3/4", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1/2/3/4 2 3\n", "obj", 5 },
    { "OBJ corner 1/", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1/ 2 3\n", "obj", 5 },
    { "OBJ corner /1", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f /1 2 3\n", "obj", 5 },
    { "OBJ corner 1.5", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1.5 2 3\n", "obj", 5 },
    { "OBJ corner word", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f one 2 3\n", "obj", 5 },
    { "OBJ index too long", "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 99999999999 2 3\n", "obj", 5 },
    { "OBJ NUL byte", "size 8 8\n" CAMERA OBJ_LINE, "v 0 0 0\nv 1 \0 0\n", "obj", 2 },
    { "error after the OBJ", "size 8 8\n" CAMERA OBJ_LINE "tri3 1 2\n", QUAD_V "f 1 2 3\n", "scene", 4 },
};

Test(scene3, bad_input_names_the_file_and_line_and_leaves_nothing, .init = make_dir, .fini = remove_dir)
{
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const struct bad3 *b = &bad[i];
        const char *scene = put("bad.scene", b->scene, strlen(b->scene));
        char obj[256];
        snprintf(obj, sizeof obj, "%s/bad.obj", dir);
        unlink(obj);
        if (b->obj) {
            /* the NUL case: its text runs to the second newline */
            size_t len = strlen(b->obj);
            if (strcmp(b->name, "OBJ NUL byte") == 0)
                len = 16;
            put("bad.obj", b->obj, len);
        }
        struct scene s;
        char err[512] = "";
        cr_assert(!scene_load(&s, scene, err, sizeof err), "'%s' was accepted", b->name);
        char prefix[300];
        snprintf(prefix, sizeof prefix, "%s:%d: ", strcmp(b->where, "obj") == 0 ? obj : scene, b->line);
        cr_expect(strncmp(err, prefix, strlen(prefix)) == 0 && strlen(err) > strlen(prefix) + 5,
                  "%s: expected '%s...', got '%s'", b->name, prefix, err);
        cr_expect(!strchr(err, '\n'), "%s: one line: %s", b->name, err);
        cr_expect(s.ntris == 0 && !s.tris && s.world.ntris == 0 && !s.world.tris && !s.world.camera_line,
                  "%s: the scene is left empty", b->name);
    }
}

Test(scene3, messages_say_what_is_wrong, .init = make_dir, .fini = remove_dir)
{
    struct { const char *scene, *obj, *says; } cases[] = {
        { "size 8 8\ncamera 0 0 5  0 0 0  0 0 1  60 0.1 100\n", NULL, "parallel" },
        { "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0 100\n", NULL, "near" },
        { "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 2 1\n", NULL, "far" },
        { "size 8 8\ncamera 1 2 3  1 2 3  0 1 0  60 0.1 100\n", NULL, "same point" },
        { "size 8 8\n" CAMERA "obj missing.obj 1 1 1\n", NULL, "missing.obj" },
        { "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "f 1 2 9\n", "vertex 9" },
        { "size 8 8\n" CAMERA OBJ_LINE, QUAD_V "v 0 1e7 0\n", "10^6" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *scene = put("m.scene", cases[i].scene, strlen(cases[i].scene));
        if (cases[i].obj)
            put("bad.obj", cases[i].obj, strlen(cases[i].obj));
        struct scene s;
        char err[512] = "";
        cr_assert(!scene_load(&s, scene, err, sizeof err));
        cr_expect(strstr(err, cases[i].says), "'%s' does not say '%s'", err, cases[i].says);
    }
}

/* A 3-D scene is written as a 3-D scene: its camera, culling and world
 * triangles (an obj's as tri3 lines), which read back to the very same
 * values and project to the very same screen triangles; and a copy is a
 * deep copy. */
static void round_trip(struct scene *s, const char *what)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    cr_assert(scene_write(s, f));
    fclose(f);
    cr_expect_not_null(strstr(text, "camera "), "%s", what);
    cr_expect_null(strstr(text, "\ntri "), "%s: written as screen triangles", what);
    struct scene b;
    char err[512];
    cr_assert(scene_parse(&b, "written.scene", text, len, err, sizeof err), "%s: %s\n%s", what, err, text);
    cr_expect_gt(b.world.camera_line, 0, "%s", what);
    cr_expect_eq(b.w, s->w);
    cr_expect_eq(b.h, s->h);
    cr_expect_eq(memcmp(b.background, s->background, sizeof b.background), 0, "%s", what);
    cr_expect_eq(b.world.cull, s->world.cull, "%s", what);
    cr_expect_eq(memcmp(&b.world.cam, &s->world.cam, sizeof b.world.cam), 0, "%s: the camera", what);
    cr_assert_eq(b.world.ntris, s->world.ntris, "%s", what);
    cr_expect_eq(memcmp(b.world.tris, s->world.tris, (size_t)b.world.ntris * sizeof *b.world.tris), 0,
                 "%s: the world triangles", what);
    cr_assert(front_scene(s) && front_scene(&b));
    cr_assert_eq(b.ntris, s->ntris, "%s", what);
    cr_expect_eq(memcmp(b.tris, s->tris, (size_t)b.ntris * sizeof *b.tris), 0, "%s: the screen triangles", what);
    scene_free(&b);
    free(text);
}

Test(scene3, written_as_a_3d_scene_and_read_back_the_same)
{
    struct scene s = load_ok("size 40 30\nbackground 0.1 0.2 0.3\n"
                             "camera 0.3 0.2 0.1  2 0.5 -1  0 1 0  90 0.01 100\ncull back\n"
                             "tri3 -1 -1 -1 1 0 0  1 -1 -1 0 1 0  1 1 -1 0 0 1\n"
                             "tri3 -1 -1 -1 1 0 0  1 1 -1 0 0 1  -1 1 -1 0 1 0\n"
                             "tri3 -1 -1 3 1 0 0  1 -1 -3 0 1 0  1 1 -3 0.1 0.7 0.3333333333333333\n");
    round_trip(&s, "three triangles");
    cr_assert_gt(s.ntris, 2, "the third triangle is cut by the near plane");
    struct scene c;
    cr_assert(scene_copy(&c, &s));
    scene_free(&s);
    cr_expect_eq(c.world.ntris, 3);
    cr_expect_eq(c.world.tris[2].p[0][2], 3.0);
    scene_free(&c);
    /* the built-in 3-D scenes, the obj model's triangles among them */
    static const char *const names[] = { "room", "horizon", "model", "depth-pair" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char err[256];
        cr_assert(scene_builtin(&s, names[i], err, sizeof err), "%s", err);
        round_trip(&s, names[i]);
        scene_free(&s);
    }
}

/* --- the built-in model and the built-in 3-D scenes ------------------------------ */

bool builtin_model(const char *name, char **text, size_t *len);   /* src/scene/models.c */

Test(scene3, the_shipped_models_are_what_the_code_makes)
{
    static const char *const names[] = { "torus.obj", "sheet.obj" };
    for (int i = 0; i < 2; i++) {
        char *text, path[64];
        size_t len;
        cr_assert(builtin_model(names[i], &text, &len));
        snprintf(path, sizeof path, "src/scene/models/%s", names[i]);
        FILE *f = fopen(path, "rb");
        cr_assert_not_null(f, "%s is missing (run the tests from the repository)", path);
        char *file = malloc(len + 2);
        size_t got = fread(file, 1, len + 1, f);
        fclose(f);
        cr_expect_eq(got, len, "%s has %zu bytes, the generator makes %zu", path, got, len);
        cr_expect(got == len && memcmp(file, text, len) == 0,
                  "%s differs from what src/scene/models.c makes", path);
        free(file);
        free(text);
    }
    char *text;
    size_t len;
    cr_expect(!builtin_model("no-such.obj", &text, &len));
    cr_expect_null(text);
}

Test(scene3, builtin_model_loads_and_a_missing_one_is_named, .init = make_dir, .fini = remove_dir)
{
    struct scene s = load_ok("size 8 8\n" CAMERA "obj builtin:torus.obj 0.5 0.5 0.5\n");
    cr_expect_eq(s.world.ntris, 24 * 12 * 2, "24 x 12 quads, fanned");
    scene_free(&s);
    const char *path = put("m.scene", "size 8 8\n" CAMERA "obj builtin:teapot.obj 1 1 1\n",
                           strlen("size 8 8\n" CAMERA "obj builtin:teapot.obj 1 1 1\n"));
    char err[512];
    cr_assert(!scene_load(&s, path, err, sizeof err));
    char prefix[300];
    snprintf(prefix, sizeof prefix, "%s:3: ", path);
    cr_expect(strncmp(err, prefix, strlen(prefix)) == 0 && strstr(err, "teapot"), "%s", err);
}

/* Each built-in 3-D scene shows what its description promises. */
Test(scene3, builtin_3d_scenes_show_what_they_say)
{
    static const char *const names[] = { "room", "horizon", "model", "depth-pair" };
    for (int i = 0; i < 4; i++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, names[i], err, sizeof err), "%s", err);
        cr_assert_gt(s.world.camera_line, 0, "builtin:%s is a 3-D scene", names[i]);
        cr_assert(front_scene(&s));
        uint8_t *count = calloc((size_t)s.w * s.h, 1);
        for (int k = 0; k < s.ntris; k++) {
            struct tri_setup t;
            tri_setup(&t, s.tris[k].v, s.w, s.h);
            reference_mask(&t, count);
        }
        int hist[4] = { 0 };
        for (int k = 0; k < s.w * s.h; k++)
            hist[count[k] < 3 ? count[k] : 3]++;
        if (i == 0) {
            cr_expect_eq(hist[1], s.w * s.h, "room: every pixel sees exactly one wall");
            cr_expect_gt(s.ntris, s.world.ntris, "room: the near plane cut walls");
        } else if (i == 1) {
            cr_expect_eq(hist[2] + hist[3], 0, "horizon: no pixel twice");
            cr_expect(hist[0] > s.w * s.h / 4 && hist[1] > s.w * s.h / 4, "horizon: sky and floor");
        } else if (i == 2) {
            cr_expect_eq(s.world.cull, CULL_BACK);
            cr_expect_gt(hist[1], 500, "model: the torus is seen");
        } else {
            cr_expect_eq(hist[2], s.w * s.h, "depth-pair: both walls fill the screen");
        }
        free(count);
        scene_free(&s);
    }
}
