/* clip.c - lesson 06's exercise: the front end of src/front/ around the
 * student's clipper (exercise_clip, one plane at a time), or around a whole
 * front end of an exhibit's making (exercise.h).
 *
 *   world --view_vertex--> view --YOUR CLIP, near--> --YOUR CLIP, far-->
 *         --project--> screen --guard band (the lesson's)--> --fan, cull--> 2-D triangles
 *
 * Whatever the clipper returns is looked at before it goes on: a vertex on
 * the wrong side of the plane, a coordinate that is not finite, or more
 * vertices than one plane can make of a convex polygon is a fault the check
 * reports (exercise_clip_fault). The picture is still drawn as far as it can
 * be, never with undefined behaviour: a depth below near is held to
 * max(|d|, near), which draws what projecting before clipping draws; a
 * polygon that cannot be used is dropped; colours are held to [0, 1]. */
#include "exercise.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"

static clip_fn current_clip;
static front_fn current_front;
static struct clip_fault fault;
static const struct world_tri *world_base;     /* the scene's world triangles */
static bool both_ways;

void exercise_clip_both_ways(bool on)
{
    both_ways = on;
}

void exercise_use_clip(clip_fn clip)
{
    current_clip = clip;
}

void exercise_use_front(front_fn front)
{
    current_front = front;
}

const struct clip_fault *exercise_clip_fault(void)
{
    return &fault;
}

void exercise_clip_fault_set(const struct clip_fault *f)
{
    fault = *f;
}

static bool on_kept_side(const struct plane *pl, double d)
{
    return pl->keep > 0 ? d >= pl->at : d <= pl->at;
}

static void first_fault(struct clip_fault f)
{
    if (fault.what == CLIP_OK)
        fault = f;
}

/* Is every vertex of a among those of b, to the last bit? */
static const struct pvert *missing_from(const struct poly *a, const struct poly *b)
{
    for (int i = 0; i < a->n; i++) {
        bool found = false;
        for (int k = 0; k < b->n && !found; k++)
            found = memcmp(a->v[i].pos, b->v[k].pos, sizeof a->v[i].pos) == 0
                    && memcmp(a->v[i].rgb, b->v[k].rgb, sizeof a->v[i].rgb) == 0;
        if (!found)
            return &a->v[i];
    }
    return NULL;
}

/* The polygon clipped walking it the other way gives the same vertices as
 * r, clipped this way (a usable polygon): else f says which is missing. */
static bool same_both_ways(const struct poly *r, const struct poly *in, const struct plane *pl,
                           struct clip_fault *f)
{
    struct poly rev = { .n = in->n }, back;
    for (int k = 0; k < in->n; k++)
        rev.v[k] = in->v[(in->n - k) % in->n];
    memset(&back, 0, sizeof back);
    current_clip(&back, &rev, pl);
    if (back.n < 0 || back.n > POLY_MAX)
        back.n = 0;
    const struct pvert *m = missing_from(r, &back);
    f->reversed = m == NULL;
    if (!m)
        m = missing_from(&back, r);
    if (!m)
        return true;
    memcpy(f->made, m->pos, sizeof f->made);
    return false;
}

/* Per world triangle: did the student's clipper give the lesson's polygons,
 * vertex for vertex, though perhaps starting at another (a cyclic
 * sequence: Sutherland-Hodgman written for the edge arriving at each
 * vertex gives them rotated one place)? Its fan then differs from the
 * lesson's, and the pictures by the snapping of the fan's slivers alone. */
static bool *as_lesson;
static int as_lesson_n;

bool exercise_clip_as_lesson(int tri)
{
    return tri >= 0 && tri < as_lesson_n && as_lesson[tri];
}

void exercise_clip_as_lesson_set(const unsigned char *flags, int n)
{
    bool *a = realloc(as_lesson, sizeof *a * (size_t)(n > 0 ? n : 1));
    as_lesson_n = a ? n : 0;
    as_lesson = a ? a : as_lesson;
    for (int i = 0; i < as_lesson_n; i++)
        as_lesson[i] = flags[i] != 0;
}

static bool same_vertex(const struct pvert *a, const struct pvert *b)
{
    for (int c = 0; c < 3; c++)
        if (fabs(a->pos[c] - b->pos[c]) > 1e-9 * fmax(1, fabs(b->pos[c])) || fabs(a->rgb[c] - b->rgb[c]) > 1e-9)
            return false;
    for (int c = 0; c < 2; c++)
        if (fabs(a->st[c] - b->st[c]) > 1e-9 * fmax(1, fabs(b->st[c])))
            return false;
    return true;
}

/* Is a the polygon b, starting at any of its vertices? */
static bool same_cycle(const struct poly *a, const struct poly *b)
{
    if (a->n != b->n)
        return false;
    for (int k = 0; k < b->n || (k == 0 && b->n == 0); k++) {
        bool same = true;
        for (int i = 0; i < a->n && same; i++)
            same = same_vertex(&a->v[i], &b->v[(i + k) % b->n]);
        if (same)
            return true;
    }
    return false;
}

/* The student's clipper against one plane, looked at: false when its
 * polygon cannot be used (dropped). */
static bool student_clip(struct poly *out, const struct poly *in, const struct plane *pl, int tri)
{
    struct poly r;
    memset(&r, 0, sizeof r);
    current_clip(&r, in, pl);
    struct clip_fault f = { .tri = tri, .plane = (int)pl->id, .at = pl->at, .n_in = in->n, .n = r.n };
    if (r.n < 0 || r.n > in->n + 1) {   /* a convex polygon gains one vertex at most */
        f.what = CLIP_TOO_MANY;
        first_fault(f);
        return false;
    }
    for (int k = 0; k < r.n; k++) {
        struct pvert *v = &r.v[k];
        for (int c = 0; c < 3; c++)
            if (!isfinite(v->pos[c]) || !isfinite(v->rgb[c])) {
                f.what = CLIP_NOT_FINITE, f.vertex = k;
                first_fault(f);
                return false;
            }
        if (!on_kept_side(pl, v->pos[2])) {
            f.what = CLIP_OUTSIDE, f.vertex = k, f.d = v->pos[2];
            first_fault(f);
        }
        for (int c = 0; c < 3; c++)
            v->rgb[c] = fmin(fmax(v->rgb[c], 0), 1);
        for (int c = 0; c < 2; c++)     /* s and t, held finite and in range */
            v->st[c] = isfinite(v->st[c]) ? fmin(fmax(v->st[c], -SCENE_ST_MAX), SCENE_ST_MAX) : 0;
    }
    if (both_ways && fault.what == CLIP_OK && !same_both_ways(&r, in, pl, &f)) {
        f.what = CLIP_ORDER;
        first_fault(f);
    }
    struct poly lesson;
    clip_polygon(&lesson, in, pl, NULL);
    if (tri >= 0 && tri < as_lesson_n && !same_cycle(&r, &lesson))
        as_lesson[tri] = false;
    *out = r;
    return true;
}

/* The world triangle being drawn, and its frustum's near plane, for the
 * clip stage below. */
static int current_tri;
static double current_near;

/* The clip stage of lesson 06's pipeline done by the student's clipper:
 * what it leaves behind near is drawn, not divided by d <= 0. */
static void student_stage(struct poly *out, const struct poly *in, const struct plane *pl,
                          struct trace *tr)
{
    (void)tr;
    if (!student_clip(out, in, pl, current_tri)) {
        out->n = 0;
        return;
    }
    for (int k = 0; k < out->n; k++)
        out->v[k].pos[2] = fmax(fabs(out->v[k].pos[2]), current_near);
}

/* Lesson 06's pipeline, front_pipeline() in src/front/front.c, with the
 * student's clipper for near and far. */
static int clip_pipeline(const struct frustum *v, enum cull cull, const struct world_tri *t,
                         struct vertex out[][3])
{
    static const struct front_way way = { .clip = student_stage };
    current_tri = (int)(t - world_base);
    current_near = v->near;
    return front_pipeline(v, cull, t, &way, NULL, out);
}

bool exercise_front(struct scene *s)
{
    fault = (struct clip_fault){ .what = CLIP_OK };
    as_lesson_n = 0;
    if (current_front)
        return current_front(s);
    if (!current_clip)
        return front_scene(s);
    world_base = s->world.tris;
    bool *a = realloc(as_lesson, sizeof *a * (size_t)(s->world.ntris > 0 ? s->world.ntris : 1));
    as_lesson_n = a ? s->world.ntris : 0;
    as_lesson = a ? a : as_lesson;
    for (int i = 0; i < as_lesson_n; i++)
        as_lesson[i] = true;
    return front_scene_with(s, clip_pipeline);
}
