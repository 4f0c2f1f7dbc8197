/* obj.c - the small part of Wavefront OBJ a 3-D scene reads (lessons/CONVENTIONS.md):
 *
 *     v 1.0 2.0 -0.5          a vertex (more numbers, w or a colour, are ignored)
 *     vt 0.25 0.75            texture coordinates u v (w ignored; v is 0 if absent):
 *                               s = u, t = 1 - v (OBJ's v points up, tristep's t down)
 *     f 1 2 3                 a face of vertices defined above it: 1-based,
 *     f -3 -2 -1              or negative (counting back from the last one),
 *     f 1/1 2/2 3/3 4/4       each as i, i/t, i//n or i/t/n (t: a vt above it,
 *     f 1//1 2//2 3//3          counted the same way); a polygon of n vertices
 *                               becomes the fan (1 2 3) (1 3 4) ...
 *
 * A corner without t has s = t = 0. Everything else (vn, o, g, s, usemtl,
 * mtllib, l, ...) and comments are ignored. Any error names the OBJ file and
 * its line. */
#define _POSIX_C_SOURCE 200809L   /* getline */

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "parse.h"

struct obj {
    struct parser p;
    double (*v)[3];
    int nv, cap;
    double (*vt)[2];        /* (s, t) of every vt line */
    int nvt, vt_cap;
    int (*face)[2];         /* the face being read: vertex and vt numbers from 0 (-1: none) */
    int nface, face_cap;
    bool used_vt;           /* some face corner named a vt */
};

#define SPACE " \t\r\n\v\f"

/* The next capacity of an array that is full at `cap` items, 0 when too large. */
static int next_cap(int cap)
{
    return cap > INT_MAX / 4 ? 0 : cap ? cap * 2 : 256;
}

/* The numbers left on the line: the first `max` of them into out, all of
 * them checked; *n says how many there were. */
static bool read_numbers(struct obj *o, double *out, int max, int *n)
{
    *n = 0;
    for (char *t; (t = strtok(NULL, SPACE)); ++*n) {
        double d;
        if (!scene_number(&o->p, t, &d))
            return false;
        if (*n < max)
            out[*n] = d;
    }
    return true;
}

/* v x y z [more numbers] */
static bool read_vertex(struct obj *o)
{
    double xyz[3];
    int n;
    if (!read_numbers(o, xyz, 3, &n))
        return false;
    if (n < 3)
        return scene_fail(&o->p, "'v' needs 3 numbers (x y z), got %d", n);
    for (int c = 0; c < 3; c++)
        if (!(fabs(xyz[c]) <= WORLD_LIMIT))
            return scene_fail(&o->p, "vertex %d: %c = %g is beyond the world's limit of 10^6",
                        o->nv + 1, "xyz"[c], xyz[c]);
    if (o->nv == o->cap) {
        int cap = next_cap(o->cap);
        double (*nv)[3] = cap ? realloc(o->v, (size_t)cap * sizeof *nv) : NULL;
        if (!nv)
            return scene_fail(&o->p, "out of memory after %d vertices", o->nv);
        o->v = nv;
        o->cap = cap;
    }
    memcpy(o->v[o->nv++], xyz, sizeof xyz);
    return true;
}

/* vt u [v [w]]: s = u, t = 1 - v */
static bool read_texcoord(struct obj *o)
{
    double uv[2] = { 0, 0 };
    int n;
    if (!read_numbers(o, uv, 2, &n))
        return false;
    if (n < 1)
        return scene_fail(&o->p, "'vt' needs 1 to 3 numbers (u [v [w]]), got none");
    const double st[2] = { uv[0], 1 - uv[1] };
    for (int c = 0; c < 2; c++)
        if (!(fabs(st[c]) <= SCENE_ST_MAX))
            return scene_fail(&o->p, "texture coordinate %d: %c = %g is outside [-%g, %g]",
                              o->nvt + 1, "st"[c], st[c], SCENE_ST_MAX, SCENE_ST_MAX);
    if (o->nvt == o->vt_cap) {
        int cap = next_cap(o->vt_cap);
        double (*nvt)[2] = cap ? realloc(o->vt, (size_t)cap * sizeof *nvt) : NULL;
        if (!nvt)
            return scene_fail(&o->p, "out of memory after %d texture coordinates", o->nvt);
        o->vt = nvt;
        o->vt_cap = cap;
    }
    memcpy(o->vt[o->nvt++], st, sizeof st);
    return true;
}

/* An optionally signed whole number at *s, advancing *s; false if none. */
static bool whole(const char **s, long *out)
{
    const char *q = *s;
    if (*q == '-' || *q == '+')
        q++;
    size_t digits = strspn(q, "0123456789");
    if (digits == 0 || digits > 9)
        return false;
    *out = strtol(*s, NULL, 10);
    *s = q + digits;
    return true;
}

/* One face corner: i, i/t, i//n or i/t/n. i and t are used. */
static bool read_corner(struct obj *o, const char *tok, int index[2])
{
    const char *s = tok;
    long i, t, n;
    bool has_t = false;
    bool ok = whole(&s, &i);
    if (ok && *s == '/') {
        s++;
        if (*s == '/')
            ok = (s++, whole(&s, &n));
        else if ((ok = has_t = whole(&s, &t)) && *s == '/')
            ok = (s++, whole(&s, &n));
    }
    if (!ok || *s != '\0')
        return scene_fail(&o->p, "'%.40s' is not a face corner (i, i/t, i//n or i/t/n)", tok);
    if (i == 0)
        return scene_fail(&o->p, "vertex index 0 (OBJ counts from 1, or from -1 backwards)");
    long k = i > 0 ? i - 1 : o->nv + i;
    if (k < 0 || k >= o->nv)
        return scene_fail(&o->p, "vertex %ld is not defined above this face (%d vertices so far)",
                    i, o->nv);
    index[0] = (int)k;
    index[1] = -1;
    if (has_t && t == 0)
        return scene_fail(&o->p, "texture coordinate index 0 (OBJ counts from 1, or from -1 backwards)");
    if (has_t) {
        long kt = t > 0 ? t - 1 : o->nvt + t;
        if (kt < 0 || kt >= o->nvt)
            return scene_fail(&o->p, "texture coordinate %ld is not defined above this face "
                                     "(%d vt lines so far)", t, o->nvt);
        index[1] = (int)kt;
        o->used_vt = true;
    }
    return true;
}

/* f c1 c2 c3 ..., fanned from c1 */
static bool read_face(struct obj *o, struct world *w, const double rgb[3])
{
    o->nface = 0;
    for (char *t; (t = strtok(NULL, SPACE));) {
        if (o->nface == o->face_cap) {
            int cap = next_cap(o->face_cap);
            int (*nf)[2] = cap ? realloc(o->face, (size_t)cap * sizeof *nf) : NULL;
            if (!nf)
                return scene_fail(&o->p, "out of memory");
            o->face = nf;
            o->face_cap = cap;
        }
        if (!read_corner(o, t, o->face[o->nface]))
            return false;
        o->nface++;
    }
    if (o->nface < 3)
        return scene_fail(&o->p, "'f' needs at least 3 vertices, got %d", o->nface);
    for (int k = 1; k + 1 < o->nface; k++) {
        struct world_tri t = { .texture = 0 };
        const int *corner[3] = { o->face[0], o->face[k], o->face[k + 1] };
        for (int j = 0; j < 3; j++) {
            memcpy(t.p[j], o->v[corner[j][0]], sizeof t.p[j]);
            memcpy(t.rgb[j], rgb, sizeof t.rgb[j]);
            if (corner[j][1] >= 0)
                memcpy(t.st[j], o->vt[corner[j][1]], sizeof t.st[j]);
        }
        if (!world_add(w, &t))
            return scene_fail(&o->p, "out of memory after %d triangles", w->ntris);
    }
    return true;
}

bool obj_read(struct scene *s, FILE *f, const char *name, const double rgb[3], char *err,
              size_t errlen)
{
    struct world *w = &s->world;
    struct obj o = { .p = { .name = name, .line = 0, .err = err, .errlen = errlen } };
    char *line = NULL;
    size_t cap = 0;
    bool ok = true;
    for (ssize_t len; ok && (len = getline(&line, &cap, f)) >= 0;) {
        o.p.line++;
        if (memchr(line, '\0', (size_t)len)) {
            ok = scene_fail(&o.p, "NUL byte in the line (is this a text file?)");
            break;
        }
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *kw = strtok(line, SPACE);
        if (!kw)
            continue;
        if (strcmp(kw, "v") == 0)
            ok = read_vertex(&o);
        else if (strcmp(kw, "vt") == 0)
            ok = read_texcoord(&o);
        else if (strcmp(kw, "f") == 0)
            ok = read_face(&o, w, rgb);
    }
    if (ok && ferror(f))
        ok = scene_fail(&o.p, "cannot read the file");
    if (ok && o.used_vt)
        s->has_st = true;
    free(line);
    free(o.v);
    free(o.vt);
    free(o.face);
    return ok;
}
