/* scene.h - scene files (CONVENTIONS.md): parse, write, built-in scenes.
 *
 *     # comment to end of line; blank lines are ignored
 *     size 64 48
 *     background 0.1 0.1 0.1
 *     tri  10.5 4 1   1 0 0    50 20.25 2   0 1 0    20 40 1.5   0 0 1
 *
 * Extensions every lesson program accepts (lesson 04 uses them):
 *     texture checker N        a procedural checkerboard of N x N squares
 *     tri with 24 numbers      x y z r g b s t, three times
 */
#ifndef TRISTEP_SCENE_H
#define TRISTEP_SCENE_H

#include <stdbool.h>
#include <stdio.h>

#include "raster/raster.h"

struct scene_tri {
    struct vertex v[3];
};

struct scene {
    int w, h;
    double background[3];     /* default opaque black */
    int checker;              /* texture checker N; 0 = no texture */
    bool has_st;              /* some triangle gave texture coordinates */
    int ntris, cap;
    struct scene_tri *tris;
};

/* Parse a whole scene text. `name` is used in messages ("FILE:LINE: ...").
 * On error returns false, writes one line "name:LINE: message" into err
 * (without a newline) and leaves *s empty. */
bool scene_parse(struct scene *s, const char *name, const char *text, size_t len,
                 char *err, size_t errlen);
/* Read and parse a file ("-" is standard input), a chunk at a time: the
 * text is never held whole (a 2,000,000-triangle scene is some 330 MB of it). */
bool scene_load(struct scene *s, const char *path, char *err, size_t errlen);
/* Write a scene that scene_parse reads back to the same values. */
bool scene_write(const struct scene *s, FILE *out);
void scene_free(struct scene *s);
/* A copy with triangles of its own; false (dst empty) when out of memory. */
bool scene_copy(struct scene *dst, const struct scene *src);
bool scene_add(struct scene *s, const struct vertex v[3]);
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
