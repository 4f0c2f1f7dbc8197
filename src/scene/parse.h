/* parse.h - what the readers of the scene folder share (private to it):
 * where a message points, numbers read one way, and the 3-D lines and OBJ
 * files that scene.c hands over to scene3.c and obj.c. */
#ifndef TRISTEP_SCENE_PARSE_H
#define TRISTEP_SCENE_PARSE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "scene.h"

/* The file being read and the line reached: messages are "name:LINE: ...". */
struct parser {
    const char *name;
    int line;
    char *err;
    size_t errlen;
    int texture;        /* the image texture the next tri, tri3 or obj takes (0: none) */
};

/* Write "name:LINE: message" (printf's format) into p->err; returns false. */
bool scene_fail(struct parser *p, const char *fmt, ...);
/* A decimal number (no nan, inf or hexadecimal), finite. */
bool scene_number(struct parser *p, const char *tok, double *out);

/* scene3.c: is kw one of camera, cull, tri3, obj; read such a line (tok[0]
 * is the keyword); check what only the whole scene shows (called after the
 * last line, p->line past it). */
bool scene3_keyword(const char *kw);
bool scene3_line(struct parser *p, struct scene *s, char **tok, int n);
bool scene3_finish(struct parser *p, struct scene *s);

/* obj.c: append the triangles of the Wavefront OBJ file open as f, each in
 * colour rgb, with no texture (texture 0), to s->world (s->has_st set when
 * a face gives texture coordinates). Errors name the OBJ file (`name`) and
 * its line. */
bool obj_read(struct scene *s, FILE *f, const char *name, const double rgb[3], char *err,
              size_t errlen);

/* scene_texture.c: a texture line (tok[0] is the keyword); a file named
 * in a scene, relative to the scene's folder (malloc'ed; NULL when out of
 * memory); before a triangle of a written scene, the texture line it needs
 * (if any), returning how many numbers per vertex to write (6 or 8). */
bool scene_texture_line(struct parser *p, struct scene *s, char **tok, int n);
char *scene_relative_path(const struct parser *p, const char *file);
void scene_texture_share(struct scene *dst, const struct scene *src);
void scene_textures_release(struct scene *s);
void scene_write_textures(const struct scene *s, FILE *out, int *current);
int scene_write_texture(const struct scene *s, FILE *out, int *current, int texture);

/* models.c: the text of the built-in OBJ model `name` ("torus.obj"), made
 * afresh into *text (the caller frees it). False for no such model (*text
 * NULL) or when out of memory (*len != 0 is never promised then). */
bool builtin_model(const char *name, char **text, size_t *len);

#endif
