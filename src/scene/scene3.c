/* scene3.c - the lines of a 3-D scene (lessons/CONVENTIONS.md, "3-D scenes"):
 *
 *     camera  0 1 5   0 0 0   0 1 0   60  0.1 100   eye, target, up, fovy, near, far
 *     cull none                                      none (default), back or front
 *     tri3  -1 0 -1  1 0 0   1 0 -1  0 1 0   0 0 1  0 0 1     x y z r g b, three times
 *     tri3  ... with 24 numbers                      x y z r g b s t: under an image texture
 *     obj   model.obj  0.8 0.8 0.8                   path relative to the scene, colour
 *
 * scene.c reads every line and hands these four keywords over. Nothing here
 * projects: the camera and the world triangles are checked and stored, and
 * the 3-D front end (src/front/) makes screen triangles of them. */
#define _POSIX_C_SOURCE 200809L   /* fmemopen */

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "parse.h"

bool world_add(struct world *w, const struct world_tri *t)
{
    if (w->ntris == w->cap) {
        if (w->cap > (1 << 28))
            return false;
        int cap = w->cap ? w->cap * 2 : 64;
        struct world_tri *nt = realloc(w->tris, (size_t)cap * sizeof *nt);
        if (!nt)
            return false;
        w->tris = nt;
        w->cap = cap;
    }
    struct world_tri *n = &w->tris[w->ntris++];
    memset(n, 0, sizeof *n);            /* the padding too: worlds compare with memcmp */
    memcpy(n->p, t->p, sizeof n->p);
    memcpy(n->rgb, t->rgb, sizeof n->rgb);
    memcpy(n->st, t->st, sizeof n->st);
    n->texture = t->texture;
    return true;
}

bool scene3_keyword(const char *kw)
{
    return strcmp(kw, "camera") == 0 || strcmp(kw, "cull") == 0 || strcmp(kw, "tri3") == 0
        || strcmp(kw, "obj") == 0;
}

/* n numbers from tok into out. */
static bool numbers(struct parser *p, char **tok, int n, double *out)
{
    for (int i = 0; i < n; i++)
        if (!scene_number(p, tok[i], &out[i]))
            return false;
    return true;
}

/* A world point: finite (scene_number saw to that) and within 10^6. */
static bool world_point(struct parser *p, const char *what, const double v[3])
{
    for (int c = 0; c < 3; c++)
        if (!(fabs(v[c]) <= WORLD_LIMIT))
            return scene_fail(p, "%s: %c = %g is beyond the world's limit of 10^6", what, "xyz"[c], v[c]);
    return true;
}

static bool colour(struct parser *p, const char *what, const double c[3])
{
    for (int i = 0; i < 3; i++)
        if (!(c[i] >= 0 && c[i] <= 1))
            return scene_fail(p, "%s: %c = %g is outside [0, 1]", what, "rgb"[i], c[i]);
    return true;
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* camera ex ey ez  tx ty tz  ux uy uz  fovy near far */
static bool parse_camera(struct parser *p, struct scene *s, char **tok, int n)
{
    struct world *w = &s->world;
    if (w->camera_line)
        return scene_fail(p, "'camera' given twice (first on line %d)", w->camera_line);
    if (n != 12)
        return scene_fail(p, "'camera' needs 12 numbers (eye x y z, target x y z, up x y z, "
                       "fovy, near, far), got %d", n);
    double v[12];
    if (!numbers(p, tok, 12, v))
        return false;
    struct camera c = {
        .eye = { v[0], v[1], v[2] }, .target = { v[3], v[4], v[5] }, .up = { v[6], v[7], v[8] },
        .fovy = v[9], .near = v[10], .far = v[11],
    };
    if (!world_point(p, "eye", c.eye) || !world_point(p, "target", c.target)
        || !world_point(p, "up", c.up))
        return false;
    if (!(c.fovy > 0 && c.fovy < 180))
        return scene_fail(p, "fovy = %g degrees is outside (0, 180)", c.fovy);
    if (!(c.near > 0))
        return scene_fail(p, "near = %g must be positive (a view depth in front of the eye)", c.near);
    if (!(c.far > c.near))
        return scene_fail(p, "far = %g must be beyond near = %g", c.far, c.near);
    /* every depth the front end makes lies in [near, far]: the range of a
     * 2-D scene's z, which keeps 1/z and z finite in every lesson's floats */
    if (!(c.near >= SCENE_Z_MIN && c.far <= SCENE_Z_MAX))
        return scene_fail(p, "near = %g and far = %g must lie in [%g, %g]", c.near, c.far,
                          SCENE_Z_MIN, SCENE_Z_MAX);
    double f[3] = { c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2] };
    if (f[0] == 0 && f[1] == 0 && f[2] == 0)
        return scene_fail(p, "eye and target are the same point (no view direction)");
    /* |f x up| against |f| |up|: the sine of the angle between them */
    double x[3] = { f[1] * c.up[2] - f[2] * c.up[1], f[2] * c.up[0] - f[0] * c.up[2],
                    f[0] * c.up[1] - f[1] * c.up[0] };
    if (!(dot(x, x) > 1e-24 * dot(f, f) * dot(c.up, c.up)))
        return scene_fail(p, "up (%g, %g, %g) is parallel to the view direction (or zero): "
                       "it cannot say which way is up", c.up[0], c.up[1], c.up[2]);
    if (s->ntris)
        return scene_fail(p, "'camera' in a scene with 2-D 'tri' lines (a 3-D scene has tri3 and obj only)");
    w->cam = c;
    w->camera_line = p->line;
    return true;
}

static bool parse_cull(struct parser *p, struct world *w, char **tok, int n)
{
    static const char *const names[] = { [CULL_NONE] = "none", [CULL_BACK] = "back",
                                         [CULL_FRONT] = "front" };
    if (w->cull_line)
        return scene_fail(p, "'cull' given twice (first on line %d)", w->cull_line);
    if (n == 1)
        for (int i = 0; i < 3; i++)
            if (strcmp(tok[0], names[i]) == 0) {
                w->cull = (enum cull)i;
                w->cull_line = p->line;
                return true;
            }
    return scene_fail(p, "'cull' needs one of none, back, front");
}

/* tri3 and obj come after size and camera. */
static bool placed(struct parser *p, const struct scene *s, const char *kw)
{
    if (!s->w)
        return scene_fail(p, "'%s' before 'size' (size and camera must come first)", kw);
    if (!s->world.camera_line)
        return scene_fail(p, "'%s' before 'camera' (size and camera must come first)", kw);
    return true;
}

static bool parse_tri3(struct parser *p, struct scene *s, char **tok, int n)
{
    if (n != 18 && n != 24)
        return scene_fail(p, "'tri3' needs 18 numbers (x y z r g b for each vertex) "
                             "or 24 (x y z r g b s t), got %d", n);
    double v[24];
    if (!numbers(p, tok, n, v))
        return false;
    int per = n / 3;
    struct world_tri t = { .texture = per == 8 ? p->texture : 0 };
    for (int i = 0; i < 3; i++) {
        char what[16];
        snprintf(what, sizeof what, "vertex %d", i + 1);
        const double *d = v + per * i;
        if (!world_point(p, what, d) || !colour(p, what, d + 3))
            return false;
        memcpy(t.p[i], d, sizeof t.p[i]);
        memcpy(t.rgb[i], d + 3, sizeof t.rgb[i]);
        for (int c = 6; c < per; c++) {
            if (!(fabs(d[c]) <= SCENE_ST_MAX))
                return scene_fail(p, "vertex %d: %c = %g is outside [-%g, %g]", i + 1, "st"[c - 6],
                                  d[c], SCENE_ST_MAX, SCENE_ST_MAX);
            t.st[i][c - 6] = d[c];
        }
    }
    if (per == 8)
        s->has_st = true;
    if (!world_add(&s->world, &t))
        return scene_fail(p, "out of memory after %d triangles", s->world.ntris);
    return true;
}

/* The model of an obj line: a file, or builtin:NAME of models.c. */
static bool read_model(struct parser *p, struct scene *s, const char *file, const double rgb[3])
{
    if (strncmp(file, "builtin:", 8) == 0) {
        char *text;
        size_t len;
        if (!builtin_model(file + 8, &text, &len))
            return scene_fail(p, "no built-in model '%s' (there are builtin:torus.obj and builtin:sheet.obj)", file);
        FILE *f = fmemopen(text, len, "rb");
        bool ok = f ? obj_read(s, f, file, rgb, p->err, p->errlen)
                    : scene_fail(p, "out of memory");
        if (f)
            fclose(f);
        free(text);
        return ok;
    }
    char *path = scene_relative_path(p, file);
    if (!path)
        return scene_fail(p, "out of memory");
    FILE *f = fopen(path, "rb");
    bool ok = f ? obj_read(s, f, path, rgb, p->err, p->errlen)
                : scene_fail(p, "cannot open '%s': %s", path, strerror(errno));
    if (f)
        fclose(f);
    free(path);
    return ok;
}

/* obj PATH r g b: PATH relative to the scene file's folder (as given: to the
 * current folder for standard input and built-in scenes); builtin:NAME is a
 * model of models.c. Its triangles take the image texture in force. */
static bool parse_obj(struct parser *p, struct scene *s, char **tok, int n)
{
    if (n != 4)
        return scene_fail(p, "'obj' needs a file and a colour (obj model.obj r g b), got %d values", n);
    double rgb[3];
    if (!numbers(p, tok + 1, 3, rgb) || !colour(p, "obj colour", rgb))
        return false;
    int first = s->world.ntris;
    bool ok = read_model(p, s, tok[0], rgb);
    for (int i = first; ok && i < s->world.ntris; i++)
        s->world.tris[i].texture = p->texture;      /* the image texture in force, if any */
    return ok;
}

bool scene3_line(struct parser *p, struct scene *s, char **tok, int n)
{
    const char *kw = tok[0];
    if (strcmp(kw, "camera") == 0)
        return parse_camera(p, s, tok + 1, n - 1);
    if (strcmp(kw, "cull") == 0)
        return parse_cull(p, &s->world, tok + 1, n - 1);
    if (!placed(p, s, kw))
        return false;
    if (strcmp(kw, "tri3") == 0)
        return parse_tri3(p, s, tok + 1, n - 1);
    return parse_obj(p, s, tok + 1, n - 1);
}

/* The projection divides by the depth and multiplies by g = 1 / tan(fovy / 2):
 * a tiny near plane with a tiny field of view could send a world point of
 * 10^6 beyond the range of a double. Far beyond any real camera, but input. */
#define MAGNIFICATION_LIMIT 1e280

bool scene3_finish(struct parser *p, struct scene *s)
{
    const struct world *w = &s->world;
    if (w->cull_line && !w->camera_line) {
        p->line = w->cull_line;
        return scene_fail(p, "'cull' in a scene without a camera (culling is for 3-D scenes)");
    }
    if (!w->camera_line)
        return true;
    const double pi = 3.14159265358979323846;
    double g = 1.0 / tan(w->cam.fovy * pi / 360.0), a = (double)s->w / s->h;
    if (!(g / (fmin(a, 1.0) * w->cam.near) <= MAGNIFICATION_LIMIT)) {
        p->line = w->camera_line;
        return scene_fail(p, "fovy = %g with near = %g magnifies beyond what double precision "
                       "can project", w->cam.fovy, w->cam.near);
    }
    return true;
}
