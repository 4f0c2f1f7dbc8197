/* scene.h - scene files (lessons/CONVENTIONS.md): parse, write, built-in scenes.
 *
 *     # comment to end of line; blank lines are ignored
 *     size 64 48
 *     background 0.1 0.1 0.1
 *     tri  10.5 4 1   1 0 0    50 20.25 2   0 1 0    20 40 1.5   0 0 1
 *
 * Extensions every lesson program accepts (lesson 04 uses them):
 *     texture checker N        a procedural checkerboard of N x N squares
 *     tri with 24 numbers      x y z r g b s t, three times
 * and image textures (texture.h; lesson 09 draws them, every other lesson
 * draws such a triangle in its vertex colour):
 *     texture FILE.png [repeat|clamp]     or texture builtin:NAME [repeat|clamp]
 * which applies to the tri lines with 24 numbers (tri3 lines with 24, obj
 * lines) that follow it, until the next texture line.
 *
 * Lines (lesson 00 draws them; lessons 01 to 09 read and ignore them):
 *     line  x0 y0 z0 r0 g0 b0   x1 y1 z1 r1 g1 b1    a segment from end 1 to end 2
 *
 * 3-D scenes (lesson 06 onward, read by scene3.c and obj.c): instead of `tri`,
 *     camera  0 1 5   0 0 0   0 1 0   60  0.1 100   eye, target, up, fovy, near, far
 *     cull none                                      none (default), back or front
 *     tri3  x y z r g b  (three times, world space)
 *     tri3  x y z r g b s t  (three times: textured, as tri with 24 numbers)
 *     obj   model.obj  0.8 0.8 0.8                   Wavefront OBJ beside the scene, colour
 * The 3-D front end (src/front/) turns them into the screen-space triangles
 * below, which is all a lesson ever rasterizes.
 */
#ifndef TRISTEP_SCENE_H
#define TRISTEP_SCENE_H

#include <stdbool.h>
#include <stdio.h>

#include "raster/raster.h"
#include "texture.h"

/* Ranges every value of a scene is checked against where it is read (beyond
 * lessons/CONVENTIONS.md's coordinates and colours): they keep every quantity a
 * lesson derives (1/z, z, colours over z, checker squares) finite and
 * representable in the floats and integers it uses. */
#define SCENE_Z_MIN 1e-6        /* z in [SCENE_Z_MIN, SCENE_Z_MAX] */
#define SCENE_Z_MAX 1e6
#define SCENE_ST_MAX 1e6        /* |s|, |t| <= SCENE_ST_MAX */

struct scene_tri {
    struct vertex v[3];
    int texture;                       /* 0: no image (the checker if the scene has one);
                                        * k > 0: scene_texture(s, k) */
};

/* A `line` (lessons/CONVENTIONS.md, "Lines"): from v[0] (A, the start) to v[1] (B). */
struct scene_line {
    struct vertex v[2];
    /* how many triangles of the file (tri, or a 3-D scene's world
     * triangles) come before it: the file's order of lines and triangles */
    int after;
};

/* --- 3-D scenes (lessons/CONVENTIONS.md, "3-D scenes") --------------------- */

#define WORLD_LIMIT 1e6     /* |world coordinate| <= 10^6 */

struct camera {
    double eye[3], target[3], up[3];   /* gluLookAt's */
    double fovy;                       /* vertical field of view, degrees, in (0, 180) */
    double near, far;                  /* clipping planes, view depths, 0 < near < far */
};

/* Which facing the front end drops; facing is decided on each drawn triangle
 * (front-facing = counter-clockwise as the viewer sees it, OpenGL's default). */
enum cull { CULL_NONE, CULL_BACK, CULL_FRONT };

struct world_tri {
    double p[3][3];                    /* world-space positions */
    double rgb[3][3];                  /* colours in [0, 1] */
    double st[3][2];                   /* texture coordinates (0 where none were given) */
    int texture;                       /* as in struct scene_tri */
};

struct world {
    int camera_line;                   /* line of `camera`; 0 = not a 3-D scene */
    struct camera cam;
    enum cull cull;
    int cull_line;                     /* line of `cull`, 0 when absent */
    int ntris, cap;
    struct world_tri *tris;
    int *from;                         /* front end output: the world triangle each
                                        * screen triangle of the scene came from */
};

struct scene {
    int w, h;
    double background[3];     /* default opaque black */
    int checker;              /* texture checker N; 0 = no texture */
    bool has_st;              /* some triangle gave texture coordinates */
    int ntris, cap;
    struct scene_tri *tris;   /* screen space; in a 3-D scene, what the front end made */
    int nlines, lines_cap;
    struct scene_line *lines; /* its `line`s, in file order (lesson 00 draws them) */
    struct world world;       /* a 3-D scene's camera and triangles (world.camera_line > 0) */
    struct scene_textures *textures;  /* its image textures, shared by its copies; NULL: none */
};

/* Parse a whole scene text. `name` is used in messages ("FILE:LINE: ...").
 * On error returns false, writes one line "name:LINE: message" into err
 * (without a newline) and leaves *s empty. */
bool scene_parse(struct scene *s, const char *name, const char *text, size_t len,
                 char *err, size_t errlen);
/* Read and parse a file ("-" is standard input), a chunk at a time: the
 * text is never held whole (a 2,000,000-triangle scene is some 330 MB of it). */
bool scene_load(struct scene *s, const char *path, char *err, size_t errlen);
/* Write a scene that scene_parse reads back to the same values (a 3-D scene
 * as its camera, culling and world triangles, an obj's triangles as tri3
 * lines: the front end makes the same screen triangles of it again). */
bool scene_write(const struct scene *s, FILE *out);
void scene_free(struct scene *s);
/* A copy with triangles (and a 3-D world) of its own; false (dst empty)
 * when out of memory. */
bool scene_copy(struct scene *dst, const struct scene *src);
bool scene_add(struct scene *s, const struct vertex v[3]);
/* The same for a triangle under image texture k (0: none). */
bool scene_add_textured(struct scene *s, const struct vertex v[3], int texture);
bool world_add(struct world *w, const struct world_tri *t);
/* Append a line from v[0] to v[1], after the triangles there are so far. */
bool scene_add_line(struct scene *s, const struct vertex v[2]);

/* What lesson 00 draws of a scene (lessons/CONVENTIONS.md, "Lines"), in file order:
 * its `line`s and the edges of its screen triangles (a 3-D scene's after
 * the front end has made them), each edge AB, BC, CA in the order the
 * triangle gives them and each edge that two triangles share once, from
 * its lexicographically smaller snapped end (x, then y). Returns a fresh
 * array of *n segments, ends v[2 i] and v[2 i + 1], to free (never NULL
 * for an empty scene); NULL when out of memory. */
struct vertex *scene_wireframe(const struct scene *s, int *n);

/* The scene's image textures, numbered from 1 as triangles name them:
 * scene_texture(s, k) for k in 1..scene_texture_count(s), NULL otherwise. */
int scene_texture_count(const struct scene *s);
const struct texture *scene_texture(const struct scene *s, int k);
uint32_t scene_background(const struct scene *s);

/* Built-in scenes, by name ("builtin:NAME" is accepted wherever a scene file is). */
struct builtin_scene {
    const char *name, *what, *text;
};
extern const struct builtin_scene builtin_scenes[];
extern const int builtin_scene_count;
const struct builtin_scene *builtin_find(const char *name);
bool scene_builtin(struct scene *s, const char *name, char *err, size_t errlen);

#endif
