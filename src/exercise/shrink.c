/* shrink.c - the smallest counterexample: fewest triangles, then the
 * smallest, roundest coordinates, while the check still fails. */
#define _POSIX_C_SOURCE 200809L   /* alarm */

#include "checker.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


struct shrinker {
    struct checker *C;
    int budget;
};

static bool still_fails(struct shrinker *S, const struct scene *s)
{
    if (S->budget <= 0)
        return false;
    S->budget--;
    if (check_guard)
        alarm(SCENE_SECONDS);   /* a candidate may loop where the original did not */
    struct verdict v;
    bool failed = !evaluate(S->C, s, &v);
    if (check_guard)
        alarm(0);
    return failed;
}

/* Keep candidate c in place of s when it still fails. */
static bool try_candidate(struct shrinker *S, struct scene *s, struct scene *c)
{
    if (still_fails(S, c)) {
        scene_free(s);
        *s = *c;
        return true;
    }
    scene_free(c);
    return false;
}

/* Fewest triangles: drop one at a time while the check still fails. */
static void drop_triangles(struct shrinker *S, struct scene *s)
{
    bool progress = true;
    while (progress && s->ntris > 1) {
        progress = false;
        for (int i = s->ntris - 1; i >= 0 && s->ntris > 1; i--) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            memmove(&c.tris[i], &c.tris[i + 1], sizeof c.tris[0] * (size_t)(c.ntris - i - 1));
            c.ntris--;
            progress |= try_candidate(S, s, &c);
        }
    }
}

double *scene_coord(struct scene *s, int k)
{
    struct vertex *v = &s->tris[k / 6].v[(k / 2) % 3];
    return k % 2 ? &v->y : &v->x;
}

/* Smallest coordinates: halve the scene while it fails (not under an image
 * texture), move it to the origin by whole pixels, make the target no
 * larger than it needs, then round each coordinate to the coarsest grid
 * (whole pixels, centres, halves, ...) that still fails. */
static void round_coordinates(struct shrinker *S, struct scene *s)
{
    /* under an image texture the size is what the scene is about (texels
     * magnified or minified): never halved, and moved by whole quads (2 x 2
     * pixels), so that every pixel keeps its place in its quad */
    bool textured = scene_texture_count(s) > 0;
    for (int pass = 0; pass < 3; pass++) {
        bool progress = false;
        /* half the size about the origin, on the 1/256 grid, while it fails */
        for (int k = 0; k < 8 && !textured; k++) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            for (int j = 0; j < 6 * c.ntris; j++)
                *scene_coord(&c, j) = round(*scene_coord(&c, j) * SUBPIXEL_HALF) / SUBPIXEL_ONE;
            if (!try_candidate(S, s, &c))
                break;
            progress = true;
        }
        /* to the origin, by whole pixels: every tie stays a tie */
        double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *scene_coord(s, k);
            if (k % 2)
                miny = fmin(miny, v), maxy = fmax(maxy, v);
            else
                minx = fmin(minx, v), maxx = fmax(maxx, v);
        }
        double dx = floor(minx) > 0 ? floor(minx) : 0, dy = floor(miny) > 0 ? floor(miny) : 0;
        if (textured)
            dx = 2 * floor(dx / 2), dy = 2 * floor(dy / 2);
        for (int axis = 0; axis < 2; axis++) {
            double d = axis ? dy : dx;
            if (d <= 0)
                continue;
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            for (int k = axis; k < 6 * c.ntris; k += 2)
                *scene_coord(&c, k) -= d;
            progress |= try_candidate(S, s, &c);
        }
        /* the target no larger than the triangles */
        int w = (int)fmin(s->w, fmax(1, ceil(maxx - dx) + 1)), h = (int)fmin(s->h, fmax(1, ceil(maxy - dy) + 1));
        if (w < s->w || h < s->h) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            c.w = w, c.h = h;
            progress |= try_candidate(S, s, &c);
        }
        /* each coordinate to a coarser grid */
        static const double steps[] = { 1, 0.5, 0.25, 0.125, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128 };
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *scene_coord(s, k);
            for (size_t g = 0; g < sizeof steps / sizeof steps[0]; g++) {
                double candidates[2] = { round(v / steps[g]) * steps[g],
                                         g == 0 ? floor(v) + 0.5 : NAN };
                bool done = false;
                for (int m = 0; m < 2 && !done; m++) {
                    double u = candidates[m];
                    if (isnan(u) || u == v || fabs(u) > fabs(v) + 1)
                        continue;
                    struct scene c;
                    if (!scene_copy(&c, s))
                        return;
                    *scene_coord(&c, k) = u;
                    done = try_candidate(S, s, &c);
                }
                if (done) {
                    progress = true;
                    break;
                }
            }
        }
        if (!progress)
            break;
    }
}

/* Plain colours and depths for a coverage or property counterexample. */
static void plain_attributes(struct shrinker *S, struct scene *s)
{
    static const double rgb[3][3] = { { 1, 0.2, 0.2 }, { 0.2, 1, 0.2 }, { 0.3, 0.5, 1 } };
    struct scene c;
    if (!scene_copy(&c, s))
        return;
    for (int i = 0; i < c.ntris; i++)
        for (int k = 0; k < 3; k++) {
            struct vertex *v = &c.tris[i].v[k];
            v->z = 1 + i;
            v->r = rgb[i % 3][0], v->g = rgb[i % 3][1], v->b = rgb[i % 3][2];
            v->s = v->t = 0;
        }
    c.background[0] = c.background[1] = c.background[2] = 0;
    try_candidate(S, s, &c);
}

/* --- a 3-D scene: fewer world triangles, rounder world coordinates ---------- */

static void drop_world_triangles(struct shrinker *S, struct scene *s)
{
    bool progress = true;
    while (progress && s->world.ntris > 1) {
        progress = false;
        for (int i = s->world.ntris - 1; i >= 0 && s->world.ntris > 1; i--) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            struct world *w = &c.world;
            memmove(&w->tris[i], &w->tris[i + 1], sizeof w->tris[0] * (size_t)(w->ntris - i - 1));
            w->ntris--;
            progress |= try_candidate(S, s, &c);
        }
    }
}

/* Each world coordinate to the coarsest grid (whole units, halves, ...,
 * 1/64) that still fails; then plain colours, one per triangle. */
static void round_world(struct shrinker *S, struct scene *s, bool plain)
{
    static const double steps[] = { 1, 0.5, 0.25, 0.125, 1.0 / 16, 1.0 / 64 };
    for (int i = 0; i < s->world.ntris; i++)
        for (int k = 0; k < 9; k++) {
            double v = s->world.tris[i].p[k / 3][k % 3];
            for (size_t g = 0; g < sizeof steps / sizeof steps[0]; g++) {
                double u = round(v / steps[g]) * steps[g] + 0.0;     /* -0 as 0 */
                if (u == v)
                    break;
                struct scene c;
                if (!scene_copy(&c, s))
                    return;
                c.world.tris[i].p[k / 3][k % 3] = u;
                if (try_candidate(S, s, &c))
                    break;
            }
        }
    if (!plain)
        return;
    static const double rgb[3][3] = { { 1, 0.2, 0.2 }, { 0.2, 1, 0.2 }, { 0.3, 0.5, 1 } };
    struct scene c;
    if (!scene_copy(&c, s))
        return;
    for (int i = 0; i < c.world.ntris; i++)
        for (int k = 0; k < 3; k++)
            memcpy(c.world.tris[i].rgb[k], rgb[i % 3], sizeof rgb[0]);
    try_candidate(S, s, &c);
}

void shrink(struct checker *C, struct scene *s)
{
    struct shrinker S = { C, SHRINK_BUDGET };
    if (s->world.camera_line) {
        drop_world_triangles(&S, s);
        round_world(&S, s, C->kind != CK_COLOUR);
        return;
    }
    drop_triangles(&S, s);
    round_coordinates(&S, s);
    if (C->kind == CK_COVERAGE || C->kind == CK_PROPERTY || C->kind == CK_ORDER)
        plain_attributes(&S, s);
}
