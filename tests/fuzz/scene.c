/* scene.c - fuzz harness: scene text -> scene_parse (fuzz.h), and what
 * lesson 00 draws of an accepted one (its lines and triangle edges). */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "fuzz.h"
#include "raster/line.h"
#include "scene/scene.h"

static bool unit(double v)
{
    return v >= 0 && v <= 1;
}

/* What every accepted scene holds (lessons/CONVENTIONS.md, "Scene files"). */
static void check_ranges(const struct scene *s)
{
    if (s->w < 1 || s->w > TARGET_MAX || s->h < 1 || s->h > TARGET_MAX)
        fuzz_fail("accepted size %d x %d", s->w, s->h);
    for (int i = 0; i < 3; i++)
        if (!unit(s->background[i]))
            fuzz_fail("accepted background %g", s->background[i]);
    if (s->ntris < 0 || s->ntris > s->cap || (s->ntris && !s->tris))
        fuzz_fail("inconsistent triangle list");
    for (int i = 0; i < s->ntris; i++)
        for (int k = 0; k < 3; k++) {
            const struct vertex *v = &s->tris[i].v[k];
            if (!(v->x >= -COORD_LIMIT && v->x < COORD_LIMIT && v->y >= -COORD_LIMIT
                  && v->y < COORD_LIMIT))
                fuzz_fail("triangle %d: accepted vertex (%g, %g)", i, v->x, v->y);
            if (!(v->z >= SCENE_Z_MIN && v->z <= SCENE_Z_MAX))
                fuzz_fail("triangle %d: accepted z = %g", i, v->z);
            if (!unit(v->r) || !unit(v->g) || !unit(v->b))
                fuzz_fail("triangle %d: accepted colour %g %g %g", i, v->r, v->g, v->b);
            if (!(fabs(v->s) <= SCENE_ST_MAX && fabs(v->t) <= SCENE_ST_MAX))
                fuzz_fail("triangle %d: accepted texture coordinates %g %g", i, v->s, v->t);
        }
    if (s->nlines < 0 || s->nlines > s->lines_cap || (s->nlines && !s->lines))
        fuzz_fail("inconsistent line list");
    for (int i = 0; i < s->nlines; i++) {
        const struct scene_line *l = &s->lines[i];
        if (l->after < 0 || (i && l->after < l[-1].after))
            fuzz_fail("line %d: after %d triangles", i, l->after);
        for (int k = 0; k < 2; k++) {
            const struct vertex *v = &l->v[k];
            if (!(v->x >= -COORD_LIMIT && v->x < COORD_LIMIT && v->y >= -COORD_LIMIT && v->y < COORD_LIMIT)
                || !(v->z >= SCENE_Z_MIN && v->z <= SCENE_Z_MAX) || !unit(v->r) || !unit(v->g) || !unit(v->b))
                fuzz_fail("line %d: accepted end %d (%g, %g, %g)", i, k, v->x, v->y, v->z);
        }
    }
    for (int i = 0; i < s->ntris; i++)
        if (s->tris[i].texture < 0 || s->tris[i].texture > scene_texture_count(s))
            fuzz_fail("triangle %d: texture %d of %d", i, s->tris[i].texture, scene_texture_count(s));
    for (int k = 1; k <= scene_texture_count(s); k++) {
        const struct texture *t = scene_texture(s, k);
        if (!texture_size_ok(t->level[0].w) || !texture_size_ok(t->level[0].h)
            || t->level[t->nlevels - 1].w != 1 || t->level[t->nlevels - 1].h != 1)
            fuzz_fail("texture %d: accepted %d x %d with %d levels", k, t->level[0].w,
                      t->level[0].h, t->nlevels);
    }
}

/* Are a triangle's s and t read by anything? Not where no texture applies:
 * no image texture and no checker (scene_write may leave them out there). */
static bool st_ignored(const struct scene *s, int texture)
{
    return !s->has_st || (texture == 0 && !s->checker && scene_texture_count(s) > 0);
}

static bool same_vertex(struct vertex a, struct vertex b, bool st)
{
    if (!st)
        a.s = a.t = b.s = b.t = 0;
    return a.x == b.x && a.y == b.y && a.z == b.z && a.r == b.r && a.g == b.g && a.b == b.b
        && a.s == b.s && a.t == b.t;
}

static bool same_world_tri(const struct scene *s, const struct world_tri *a, const struct world_tri *b)
{
    bool st = !st_ignored(s, a->texture);
    return memcmp(a->p, b->p, sizeof a->p) == 0 && memcmp(a->rgb, b->rgb, sizeof a->rgb) == 0
        && (!st || memcmp(a->st, b->st, sizeof a->st) == 0) && a->texture == b->texture;
}

/* Screen triangles i of s and of back: the same vertices and texture. */
static bool same_screen_tri(const struct scene *s, const struct scene *back, int i)
{
    const struct scene_tri *a = &s->tris[i], *b = &back->tris[i];
    for (int k = 0; k < 3; k++)
        if (!same_vertex(a->v[k], b->v[k], !st_ignored(s, a->texture)))
            return false;
    return a->texture == b->texture;
}

/* scene_write then scene_parse gives back the very same values (a 3-D scene
 * as its camera, culling and world triangles, which the front end makes the
 * same screen triangles of; the same image textures, in the same order). */
static void check_round_trip(const struct scene *s)
{
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    if (!out)
        return;   /* out of memory: nothing to check */
    bool wrote = scene_write(s, out);
    fclose(out);
    struct scene back;
    char err[512];
    if (!wrote)
        fuzz_fail("scene_write failed");
    if (!scene_parse(&back, "written", text, len, err, sizeof err))
        fuzz_fail("the written scene does not read back: %s", err);
    if (back.w != s->w || back.h != s->h || back.checker != s->checker
        || (!s->world.camera_line && back.ntris != s->ntris)
        || memcmp(back.background, s->background, sizeof s->background) != 0)
        fuzz_fail("the written scene reads back different");
    if (scene_texture_count(&back) != scene_texture_count(s))
        fuzz_fail("the written scene reads back %d textures, not %d", scene_texture_count(&back),
                  scene_texture_count(s));
    for (int k = 1; k <= scene_texture_count(s); k++) {
        const struct texture *a = scene_texture(s, k), *b = scene_texture(&back, k);
        if (strcmp(a->name, b->name) != 0 || a->wrap != b->wrap)
            fuzz_fail("texture %d reads back as %s, not %s", k, b->name, a->name);
    }
    const struct world *w = &s->world, *bw = &back.world;
    if (w->camera_line
        && (!bw->camera_line || bw->cull != w->cull || bw->ntris != w->ntris
            || memcmp(&bw->cam, &w->cam, sizeof w->cam) != 0))
        fuzz_fail("the written 3-D scene reads back a different world");
    for (int i = 0; w->camera_line && i < w->ntris; i++)
        if (!same_world_tri(s, &w->tris[i], &bw->tris[i]))
            fuzz_fail("world triangle %d reads back different", i);
    if (w->camera_line && front_scene(&back)) {
        if (back.ntris != s->ntris)
            fuzz_fail("the written 3-D scene projects to %d screen triangles, not %d", back.ntris, s->ntris);
        for (int i = 0; i < s->ntris; i++)
            if (!same_screen_tri(s, &back, i))
                fuzz_fail("the written 3-D scene projects to another screen triangle %d", i);
    }
    for (int i = 0; i < s->ntris && !w->camera_line; i++)
        if (!same_screen_tri(s, &back, i))
            fuzz_fail("triangle %d reads back different", i);
    if (back.nlines != s->nlines)
        fuzz_fail("the written scene reads back %d lines, not %d", back.nlines, s->nlines);
    for (int i = 0; i < s->nlines; i++)
        if (back.lines[i].after != s->lines[i].after || !same_vertex(back.lines[i].v[0], s->lines[i].v[0], false)
            || !same_vertex(back.lines[i].v[1], s->lines[i].v[1], false))
            fuzz_fail("line %d reads back different", i);
    scene_free(&back);
    free(text);
}

/* A 3-D scene's world: camera as lessons/CONVENTIONS.md requires, world points
 * within 10^6, colours in [0, 1]; what the front end makes of it, screen
 * triangles inside the guard band at depths in [near, far]. */
static void check_world(struct scene *s)
{
    const struct world *w = &s->world;
    const struct camera *c = &w->cam;
    if (!(c->fovy > 0 && c->fovy < 180 && c->near >= SCENE_Z_MIN && c->far > c->near
          && c->far <= SCENE_Z_MAX))
        fuzz_fail("accepted camera fovy %g near %g far %g", c->fovy, c->near, c->far);
    for (int i = 0; i < w->ntris; i++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++)
                if (!(fabs(w->tris[i].p[k][j]) <= WORLD_LIMIT) || !unit(w->tris[i].rgb[k][j]))
                    fuzz_fail("world triangle %d: accepted %g / colour %g", i,
                              w->tris[i].p[k][j], w->tris[i].rgb[k][j]);
    if (!front_scene(s))
        return;   /* out of memory */
    for (int i = 0; i < s->ntris; i++) {
        if (w->from[i] < 0 || w->from[i] >= w->ntris || (i && w->from[i] < w->from[i - 1]))
            fuzz_fail("screen triangle %d comes from world triangle %d", i, w->from[i]);
        for (int k = 0; k < 3; k++) {
            const struct vertex *v = &s->tris[i].v[k];
            if (!(v->z >= c->near && v->z <= c->far))
                fuzz_fail("screen triangle %d: depth %.17g outside [%g, %g]", i, v->z, c->near,
                          c->far);
        }
    }
}

static void count_pixel(void *ctx, int x, int y)
{
    (void)x, (void)y;
    ++*(long *)ctx;
}

/* What lesson 00 draws of it, on a target of at most 64 x 64: the walk
 * and the reference draw the same number of pixels of every segment (the
 * sanitizers watching the arithmetic). */
static void check_lines(const struct scene *s)
{
    int n;
    struct vertex *v = scene_wireframe(s, &n);
    if (!v)
        return;     /* out of memory */
    int w = s->w < 64 ? s->w : 64, h = s->h < 64 ? s->h : 64;
    for (int i = 0; i < n && i < 64; i++) {
        struct line_setup l;
        line_setup(&l, v + 2 * i, w, h);
        long walked = 0, decided = 0;
        line_walk(&l, count_pixel, &walked);
        line_reference(&l, count_pixel, &decided);
        if (walked != decided)
            fuzz_fail("segment %d: the walk draws %ld pixels, the rule %ld", i, walked, decided);
    }
    free(v);
}

int fuzz_scene(const uint8_t *data, size_t size)
{
    struct scene s;
    char err[512];
    if (!scene_parse(&s, "fuzz.scene", (const char *)data, size, err, sizeof err)) {
        fuzz_check_message(err, "fuzz.scene");
        if (s.ntris != 0 || s.tris || s.nlines != 0 || s.lines)
            fuzz_fail("a rejected scene keeps triangles or lines");
        return 0;
    }
    if (s.world.camera_line)
        check_world(&s);
    check_ranges(&s);
    check_round_trip(&s);
    check_lines(&s);
    scene_free(&s);
    return 0;
}
