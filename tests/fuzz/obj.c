/* obj.c - fuzz harness: Wavefront OBJ text -> obj_read (fuzz.h), as an `obj`
 * line of a 3-D scene reads a model file (with texture coordinates). */
#define _POSIX_C_SOURCE 200809L   /* fmemopen */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "scene/parse.h"   /* obj_read: the scene folder's OBJ reader */

int fuzz_obj(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;   /* fmemopen wants at least one byte; an empty file is read elsewhere */
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f)
        return 0;
    struct scene s = { 0 };
    struct world *w = &s.world;
    const double rgb[3] = { 0.25, 0.5, 1 };
    char err[512];
    /* a world that already holds a triangle: the model's are appended */
    struct world_tri first = { .p = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 } } };
    if (!world_add(w, &first))
        abort();
    if (!obj_read(&s, f, "fuzz.obj", rgb, err, sizeof err)) {
        fuzz_check_message(err, "fuzz.obj");
    } else {
        const struct world_tri *t0 = &w->tris[0];
        if (w->ntris < 1 || memcmp(t0->p, first.p, sizeof first.p) != 0
            || memcmp(t0->rgb, first.rgb, sizeof first.rgb) != 0
            || memcmp(t0->st, first.st, sizeof first.st) != 0 || t0->texture != first.texture)
            fuzz_fail("the triangles already there were changed");
        for (int i = 1; i < w->ntris; i++)
            for (int k = 0; k < 3; k++)
                for (int j = 0; j < 3; j++) {
                    if (!(fabs(w->tris[i].p[k][j]) <= WORLD_LIMIT))
                        fuzz_fail("triangle %d: accepted coordinate %g", i, w->tris[i].p[k][j]);
                    if (w->tris[i].rgb[k][j] != rgb[j])
                        fuzz_fail("triangle %d: colour not the obj line's", i);
                    if (j < 2 && !(fabs(w->tris[i].st[k][j]) <= SCENE_ST_MAX))
                        fuzz_fail("triangle %d: accepted texture coordinate %g", i, w->tris[i].st[k][j]);
                    if (w->tris[i].texture != 0)
                        fuzz_fail("triangle %d: a texture from nowhere", i);
                }
    }
    fclose(f);
    scene_free(&s);
    return 0;
}
