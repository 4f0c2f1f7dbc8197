/* Exercise 06: write lesson 06's clipper, Sutherland-Hodgman against one
 * plane in view space.
 *
 * The rest of the front end is given and runs your clipper twice for every
 * world triangle (src/exercise/clip.c, the lesson's front_triangle with
 * yours in place of clip_polygon):
 *
 *     world -> view -> exercise_clip(d >= near) -> exercise_clip(d <= far)
 *           -> project -> guard band -> fan, cull -> lesson 05's rasterizer
 *
 * Yours: the point where an edge crosses the plane, computed from the
 * edge's ends in the canonical order (README "Clipping against near and
 * far"), and the walk round the polygon that keeps, drops and adds
 * vertices. As given, exercise_clip clips nothing: the polygon goes on as
 * it came, and a vertex behind the eye is projected as projecting before
 * clipping does (the exhibit project-first).
 *
 *     make exercise LESSON=06        the explorer on this file (builtin:room)
 *     make check LESSON=06           the checks: the rasterizer's first
 *                                    (given, they pass), then yours on 3-D
 *                                    scenes, from a triangle that needs no
 *                                    clipping to random cameras
 */
#include <math.h>

#include "lesson.h"
#include "front/front.h"    /* struct poly, struct pvert, struct plane */

/* --- given: what a plane keeps, the canonical order, the point on an edge ------ */

/* Is v on the side of the plane that is kept? In view space the plane is
 * d = pl->at (pos[2] is d): d >= near is kept (keep = +1), d <= far too
 * (keep = -1). A vertex lying exactly on the plane is inside. */
static bool inside(const struct plane *pl, const struct pvert *v)
{
    return pl->keep > 0 ? v->pos[2] >= pl->at : v->pos[2] <= pl->at;
}

/* The canonical order of an edge's ends: is a before b, lexicographically
 * on (x_v, y_v, d)? */
static bool before(const struct pvert *a, const struct pvert *b)
{
    for (int i = 0; i < 3; i++)
        if (a->pos[i] != b->pos[i])
            return a->pos[i] < b->pos[i];
    return false;
}

/* v kept between a and b: rounding must not step past an edge's ends. */
static double between(double v, double a, double b)
{
    return fmin(fmax(v, fmin(a, b)), fmax(a, b));
}

/* P0 + t (P1 - P0), formula (3), for everything a vertex carries alike:
 * position, colour and texture coordinates (s, t). */
static double mix(double a, double b, double t)
{
    return between(a + t * (b - a), a, b);
}

static struct pvert lerp(const struct pvert *p0, const struct pvert *p1, double t)
{
    struct pvert n;
    for (int i = 0; i < 3; i++) {
        n.pos[i] = mix(p0->pos[i], p1->pos[i], t);
        n.rgb[i] = mix(p0->rgb[i], p1->rgb[i], t);
    }
    for (int i = 0; i < 2; i++)
        n.st[i] = mix(p0->st[i], p1->st[i], t);
    return n;
}

/* TODO 1, README "Clipping against near and far": the point where the
 * edge a - b crosses the plane. Take the edge's ends in the canonical
 * order, P0 the one before() the other, whichever of a and b the walk met
 * first: the triangle on the other side of the edge walks it the other way
 * and must make the very same vertex. Then
 *
 *     t = (pl->at - d0) / (d1 - d0),   P = lerp(P0, P1, t)
 *
 * and P's d set to the plane exactly (pos[2] = pl->at). */
static struct pvert crossing(const struct plane *pl, const struct pvert *a, const struct pvert *b)
{
    (void)pl, (void)b, (void)before, (void)lerp;
    return *a;
}

/* TODO 2, README "Clipping against near and far": Sutherland-Hodgman
 * against one plane. Walk the edges in->v[0] -> v[1], ..., v[n-1] -> v[0]
 * in order, from the first vertex, and for the edge a -> b:
 *
 *     a inside                       keep a (out->v[out->n++] = *a)
 *     one end inside, one outside    a new vertex, crossing(pl, a, b),
 *                                    unless the end inside lies exactly on
 *                                    the plane (it is the crossing itself)
 *
 * out->n starts at 0; a triangle comes out with 0, 3 or 4 vertices. */
void exercise_clip(struct poly *out, const struct poly *in, const struct plane *pl)
{
    (void)crossing, (void)inside, (void)pl;
    *out = *in;         /* clips nothing */
}

/* --- given: the rasterizer, lesson 05's, its steps on the pseudo-code's last line ---- */

extern const struct lesson lesson_05;

enum { L_RASTER = 7 };      /* "rasterize each triangle: lesson 05" */

struct relay {
    void (*sink)(void *ctx, const struct trace_event *ev);
    void *ctx;
};

static void on_raster_line(void *ctx, const struct trace_event *ev)
{
    const struct relay *r = ctx;
    struct trace_event e = *ev;
    e.line = L_RASTER;
    r->sink(r->ctx, &e);
}

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    if (!tr || !tr->sink) {
        lesson_05.variants[0].rasterize(t, p, fb, tr);
        return;
    }
    struct relay r = { tr->sink, tr->ctx };
    tr->sink = on_raster_line;
    tr->ctx = &r;
    lesson_05.variants[0].rasterize(t, p, fb, tr);
    tr->sink = r.sink;
    tr->ctx = r.ctx;
}
