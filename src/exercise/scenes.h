/* scenes.h - the scenes of make check's checks (check.c), drawn the same on
 * every run: one generator per check, scene number i into s (false when the
 * check has no more), with a line saying what the scene is. */
#ifndef TRISTEP_EXERCISE_SCENES_H
#define TRISTEP_EXERCISE_SCENES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scene/scene.h"

typedef bool (*scene_gen)(int i, struct scene *s, char *what, size_t n);

bool gen_single(int i, struct scene *s, char *what, size_t n);      /* single triangle */
bool gen_ties(int i, struct scene *s, char *what, size_t n);        /* fill-rule ties */
bool gen_meshes(int i, struct scene *s, char *what, size_t n);      /* watertight meshes */
bool gen_random(int i, struct scene *s, char *what, size_t n);      /* random triangles */
bool gen_colour(int i, struct scene *s, char *what, size_t n);      /* colour and depth */
bool gen_property(int i, struct scene *s, char *what, size_t n);    /* the lesson's property */
bool gen_tiles(int i, struct scene *s, char *what, size_t n);       /* tiles and blocks (lesson 07) */

/* 3-D scenes for lesson 06's clipper, simplest first */
bool gen_no_clip(int i, struct scene *s, char *what, size_t n);         /* between near and far */
bool gen_behind_one(int i, struct scene *s, char *what, size_t n);      /* one vertex behind near */
bool gen_behind_two(int i, struct scene *s, char *what, size_t n);      /* two behind */
bool gen_crossing_far(int i, struct scene *s, char *what, size_t n);    /* beyond far, or both */
bool gen_shared_edge(int i, struct scene *s, char *what, size_t n);     /* shared edges cut */
bool gen_box_inside(int i, struct scene *s, char *what, size_t n);      /* a closed box, inside */
bool gen_floor(int i, struct scene *s, char *what, size_t n);           /* past the guard band */
bool gen_random_cameras(int i, struct scene *s, char *what, size_t n);  /* anything */

/* textured 2-D scenes for lesson 09's sampler, simplest first (scenes9.c) */
bool gen_tex_magnify(int i, struct scene *s, char *what, size_t n);     /* texels magnified */
bool gen_tex_wrap(int i, struct scene *s, char *what, size_t n);        /* repeat, clamp, s and t < 0 */
bool gen_tex_nonsquare(int i, struct scene *s, char *what, size_t n);   /* a 32 x 8 texture */
bool gen_tex_minify(int i, struct scene *s, char *what, size_t n);      /* levels of detail chosen */
bool gen_tex_floor(int i, struct scene *s, char *what, size_t n);       /* grazing floors and walls */
bool gen_tex_tiny(int i, struct scene *s, char *what, size_t n);        /* helper pixels */
bool gen_tex_world(int i, struct scene *s, char *what, size_t n);       /* 3-D: OBJ vt, clipped s and t */

/* The search (search.c): scene `seed` of a generator aimed at what a lesson
 * decides, made from the seed alone (true: always a scene). */
struct search_for {
    bool tiles, samples, perspective;       /* the lesson's (struct lesson_exercise, lesson.h) */
};
typedef bool (*search_gen)(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);

bool search_ties(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);
bool search_coverage(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);
bool search_colour(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);
bool search_textures(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);  /* lesson 09 */
bool search_world(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n);     /* lesson 06 */

#endif
