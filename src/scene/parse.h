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
 * colour rgb, to w. Errors name the OBJ file (`name`) and its line. */
bool obj_read(struct world *w, FILE *f, const char *name, const double rgb[3], char *err,
              size_t errlen);

/* models.c: the text of the built-in OBJ model `name` ("torus.obj"), made
 * afresh into *text (the caller frees it). False for no such model (*text
 * NULL) or when out of memory (*len != 0 is never promised then). */
bool builtin_model(const char *name, char **text, size_t *len);

#endif
