/* cracks.h - the family of scenes the walk-order search looks through
 * (tests/search/cracks.c), and how cracks are counted on them; shared with
 * tests/test_lesson06.c, which recounts the scene the search found.
 *
 * A scene: a flat floor (y = 0), a k x k grid of quads cut in two, turned by
 * a random angle, seen from a random height with the far plane cutting it
 * at a random distance. A flat floor never covers a pixel twice, so the
 * exact front end covers every pixel 0 or 1 times. Cracks of a front end:
 *
 *   doubled   pixels it covers twice or more;
 *   missed    pixels it leaves uncovered that the exact front end covers,
 *             and whose eight neighbours the exact front end covers too
 *             (inside the mesh: not where the cut itself, rounded in
 *             float, runs a little elsewhere).
 */
#ifndef TRISTEP_SEARCH_CRACKS_H
#define TRISTEP_SEARCH_CRACKS_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "lesson.h"

static uint64_t crack_rng(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static double crack_unit(uint64_t *s)
{
    return (double)(crack_rng(s) >> 11) * 0x1p-53;
}

static double crack_range(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * crack_unit(s);
}

/* Floor number `seed` of the family, 320 x 240; false when out of memory. */
static bool crack_floor(struct scene *s, uint64_t seed)
{
    uint64_t r = seed;
    memset(s, 0, sizeof *s);
    s->w = 320, s->h = 240;
    int k = 8 + (int)(crack_unit(&r) * 33);
    double extent = crack_range(&r, 20, 400), turn = crack_range(&r, 0, 1.5707963267948966);
    double height = crack_range(&r, 0.2, 5), yaw = crack_range(&r, 0, 6.283185307179586);
    struct world *w = &s->world;
    w->camera_line = 1;
    w->cam = (struct camera){ { 0, height, 0 },
                              { 10 * sin(yaw), height - crack_range(&r, 0.2, 3), 10 * cos(yaw) },
                              { 0, 1, 0 }, crack_range(&r, 40, 90), crack_range(&r, 0.05, 1),
                              crack_range(&r, 0.15, 0.9) * extent };
    double c = cos(turn), sn = sin(turn);
    for (int a = 0; a < k; a++)
        for (int b = 0; b < k; b++) {
            double q[4][3];
            static const int corner[4][2] = { { 0, 0 }, { 0, 1 }, { 1, 1 }, { 1, 0 } };
            for (int i = 0; i < 4; i++) {
                double u = extent * (2.0 * (a + corner[i][0]) / k - 1), v = extent * (2.0 * (b + corner[i][1]) / k - 1);
                q[i][0] = c * u - sn * v, q[i][1] = 0, q[i][2] = sn * u + c * v;
            }
            struct world_tri t[2] = { { .texture = 0 }, { .texture = 0 } };
            static const int tris[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 3; i++) {
                    memcpy(t[j].p[i], q[tris[j][i]], sizeof q[0]);
                    for (int ch = 0; ch < 3; ch++)
                        t[j].rgb[i][ch] = crack_unit(&r);
                }
            if (!world_add(w, &t[0]) || !world_add(w, &t[1]))
                return false;
        }
    return true;
}

static void crack_count(void *ctx, int x, int y)
{
    int *c = ((int **)ctx)[0];
    int wd = *((int **)ctx)[1];
    c[(size_t)y * (size_t)wd + (size_t)x]++;
}

/* How many screen triangles cover each pixel when `front` projects s
 * (a copy); NULL when out of memory. */
static int *crack_coverage(const struct scene *s, front_fn front)
{
    struct scene c;
    int *count = calloc((size_t)s->w * (size_t)s->h, sizeof *count);
    if (!count || !scene_copy(&c, s)) {
        free(count);
        return NULL;
    }
    int wd = s->w;
    void *ctx[2] = { count, &wd };
    if (front(&c))
        for (int i = 0; i < c.ntris; i++) {
            struct tri_setup t;
            tri_setup(&t, c.tris[i].v, c.w, c.h);
            reference_coverage(&t, crack_count, ctx);
        }
    scene_free(&c);
    return count;
}

struct cracks {
    int missed, doubled;
};

/* The cracks of `got` against the exact coverage `want` (see above). */
static struct cracks crack_compare(const int *want, const int *got, int w, int h)
{
    struct cracks k = { 0, 0 };
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            k.doubled += got[i] >= 2;
            if (got[i] != 0 || want[i] != 1)
                continue;
            bool inside = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int nx = x + dx, ny = y + dy;
                    inside = inside && nx >= 0 && ny >= 0 && nx < w && ny < h
                             && want[(size_t)ny * (size_t)w + (size_t)nx] >= 1;
                }
            k.missed += inside;
        }
    return k;
}

#endif
