/* bigscene.h - very large scene files for `make bench` and the memory test:
 * n small triangles at 1920 x 1080 written as scene text (about 170 bytes a
 * triangle: 2,000,000 of them make a 330 MB file), generated on the spot
 * and never committed. */
#ifndef TRISTEP_BIGSCENE_H
#define TRISTEP_BIGSCENE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#define BIG_SCENE_W 1920
#define BIG_SCENE_H 1080
#define BIG_SCENE_TRIS 2000000      /* the size the issue names */

/* Write "size 1920 1080" and n triangles of 4 to 30 square pixels, each
 * wholly on the screen, both windings, Gouraud colours, depths in
 * [1.5, 99.5], from a seed. Returns false when the writing failed. */
bool big_scene_write(FILE *out, long n, uint64_t seed);

/* The same into a file at path (removed again if the writing failed). */
bool big_scene_file(const char *path, long n, uint64_t seed);

#endif
