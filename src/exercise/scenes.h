/* scenes.h - the scenes of make check's checks (check.c), drawn the same on
 * every run: one generator per check, scene number i into s (false when the
 * check has no more), with a line saying what the scene is. */
#ifndef TRISTEP_EXERCISE_SCENES_H
#define TRISTEP_EXERCISE_SCENES_H

#include <stdbool.h>
#include <stddef.h>

#include "scene/scene.h"

typedef bool (*scene_gen)(int i, struct scene *s, char *what, size_t n);

bool gen_single(int i, struct scene *s, char *what, size_t n);      /* single triangle */
bool gen_ties(int i, struct scene *s, char *what, size_t n);        /* fill-rule ties */
bool gen_meshes(int i, struct scene *s, char *what, size_t n);      /* watertight meshes */
bool gen_random(int i, struct scene *s, char *what, size_t n);      /* random triangles */
bool gen_colour(int i, struct scene *s, char *what, size_t n);      /* colour and depth */
bool gen_property(int i, struct scene *s, char *what, size_t n);    /* the lesson's property */
bool gen_tiles(int i, struct scene *s, char *what, size_t n);       /* tiles and blocks (lesson 07) */

#endif
