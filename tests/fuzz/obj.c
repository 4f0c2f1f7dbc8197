/* obj.c - fuzz harness: Wavefront OBJ text -> obj_read (fuzz.h), as an `obj`
 * line of a 3-D scene reads a model file. */
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
    struct world w = { 0 };
    const double rgb[3] = { 0.25, 0.5, 1 };
    char err[512];
    /* a world that already holds a triangle: the model's are appended */
    struct world_tri first = { .p = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 } } };
    if (!world_add(&w, &first))
        abort();
    if (!obj_read(&w, f, "fuzz.obj", rgb, err, sizeof err)) {
        fuzz_check_message(err, "fuzz.obj");
    } else {
        if (w.ntris < 1 || memcmp(&w.tris[0], &first, sizeof first) != 0)
            fuzz_fail("the triangles already there were changed");
        for (int i = 1; i < w.ntris; i++)
            for (int k = 0; k < 3; k++)
                for (int j = 0; j < 3; j++) {
                    if (!(fabs(w.tris[i].p[k][j]) <= WORLD_LIMIT))
                        fuzz_fail("triangle %d: accepted coordinate %g", i, w.tris[i].p[k][j]);
                    if (w.tris[i].rgb[k][j] != rgb[j])
                        fuzz_fail("triangle %d: colour not the obj line's", i);
                }
    }
    fclose(f);
    free(w.tris);
    free(w.from);
    return 0;
}
