/* front.c - the 3-D front end, stage by stage (see front.h). */
#include "front.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* --- world to view: gluLookAt ------------------------------------------------ */

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(double out[3], const double a[3], const double b[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize(double v[3])
{
    double len = sqrt(dot(v, v));
    for (int i = 0; i < 3; i++)
        v[i] = v[i] / len;
}

void frustum_init(struct frustum *v, const struct camera *c, int w, int h)
{
    /*            u (up)
     *            |   f (forward, to the target)
     *            |  /
     *     eye    | /
     *            +------ s (side, to the right)
     *
     * f = normalize(target - eye), s = normalize(f x up), u = s x f. */
    memcpy(v->eye, c->eye, sizeof v->eye);
    for (int i = 0; i < 3; i++)
        v->f[i] = c->target[i] - c->eye[i];
    normalize(v->f);
    cross(v->s, v->f, c->up);
    normalize(v->s);
    cross(v->u, v->s, v->f);
    const double pi = 3.14159265358979323846;
    v->g = 1.0 / tan(c->fovy * pi / 360.0);
    v->aspect = (double)w / (double)h;
    v->half_w = w / 2.0;
    v->half_h = h / 2.0;
    v->near = c->near;
    v->far = c->far;
}

struct pvert view_vertex(const struct frustum *v, const double p[3], const double rgb[3])
{
    double q[3] = { p[0] - v->eye[0], p[1] - v->eye[1], p[2] - v->eye[2] };
    struct pvert out = { .pos = { dot(v->s, q), dot(v->u, q), dot(v->f, q) } };
    memcpy(out.rgb, rgb, sizeof out.rgb);
    return out;
}

/* --- clipping: Sutherland-Hodgman, one plane at a time -------------------------- */

struct plane depth_plane(const struct frustum *v, enum plane_id id)
{
    if (id == PLANE_FAR)
        return (struct plane){ PLANE_FAR, "d <= far", 2, v->far, -1, false };
    return (struct plane){ PLANE_NEAR, "d >= near", 2, v->near, +1, false };
}

const struct plane guard_planes[4] = {
    { PLANE_LEFT, "x >= -16384", 0, -GUARD_BAND, +1, true },
    { PLANE_RIGHT, "x <= 16383", 0, GUARD_BAND - 1, -1, true },
    { PLANE_TOP, "y >= -16384", 1, -GUARD_BAND, +1, true },
    { PLANE_BOTTOM, "y <= 16383", 1, GUARD_BAND - 1, -1, true },
};

static bool inside(const struct plane *pl, const struct pvert *v)
{
    double c = v->pos[pl->axis];
    return pl->keep > 0 ? c >= pl->at : c <= pl->at;
}

bool pvert_before(const struct pvert *a, const struct pvert *b)
{
    for (int i = 0; i < 3; i++)
        if (a->pos[i] != b->pos[i])
            return a->pos[i] < b->pos[i];
    return false;
}

/* v kept between a and b: a point on an edge lies between its ends, and
 * rounding must not step past them (a depth below near, a colour above 1). */
static double between(double v, double a, double b)
{
    return fmin(fmax(v, fmin(a, b)), fmax(a, b));
}

/* The point where the edge p0 -> p1 meets the plane: p0 + t (p1 - p0). In
 * view space everything is linear along the edge. In screen space x and y
 * are, but d is not: 1/d and colour/d are, so those are interpolated and
 * divided back (what keeps the colours perspective-correct). */
static struct pvert edge_point(const struct plane *pl, const struct pvert *p0,
                               const struct pvert *p1, double *t_out)
{
    int a = pl->axis;
    double t = (pl->at - p0->pos[a]) / (p1->pos[a] - p0->pos[a]);
    struct pvert n;
    if (!pl->screen) {
        for (int i = 0; i < 3; i++) {
            n.pos[i] = p0->pos[i] + t * (p1->pos[i] - p0->pos[i]);
            n.rgb[i] = p0->rgb[i] + t * (p1->rgb[i] - p0->rgb[i]);
        }
        for (int i = 0; i < 2; i++)
            n.st[i] = p0->st[i] + t * (p1->st[i] - p0->st[i]);
    } else {
        for (int i = 0; i < 2; i++)
            n.pos[i] = p0->pos[i] + t * (p1->pos[i] - p0->pos[i]);
        double w0 = 1.0 / p0->pos[2], w1 = 1.0 / p1->pos[2];
        double w = w0 + t * (w1 - w0);
        n.pos[2] = 1.0 / w;
        for (int i = 0; i < 3; i++)
            n.rgb[i] = (p0->rgb[i] * w0 + t * (p1->rgb[i] * w1 - p0->rgb[i] * w0)) / w;
        for (int i = 0; i < 2; i++)
            n.st[i] = (p0->st[i] * w0 + t * (p1->st[i] * w1 - p0->st[i] * w0)) / w;
    }
    for (int i = 0; i < 3; i++) {
        n.pos[i] = between(n.pos[i], p0->pos[i], p1->pos[i]);
        n.rgb[i] = between(n.rgb[i], p0->rgb[i], p1->rgb[i]);
    }
    for (int i = 0; i < 2; i++)
        n.st[i] = between(n.st[i], p0->st[i], p1->st[i]);
    n.pos[a] = pl->at;          /* on the plane exactly */
    *t_out = t;
    return n;
}

/* A value as the narration carries it: a float (a position projected from
 * just beyond near may lie beyond the float's range: held at its end). */
static float aux(double v)
{
    return (float)fmax(-FLT_MAX, fmin(FLT_MAX, v));
}

#define AUX_POS(v) aux((v)->pos[0]), aux((v)->pos[1]), aux((v)->pos[2])

void clip_polygon(struct poly *out, const struct poly *in, const struct plane *pl,
                  struct trace *tr)
{
    uint8_t line = pl->id == PLANE_NEAR ? FRONT_LINE_NEAR
                   : pl->id == PLANE_FAR ? FRONT_LINE_FAR : FRONT_LINE_GUARD;
    NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_PLANE, .line = line, .x = (int32_t)pl->id,
            .y = in->n, .aux = { (float)pl->at });
    out->n = 0;
    for (int i = 0; i < in->n; i++) {
        const struct pvert *a = &in->v[i], *b = &in->v[(i + 1) % in->n];
        bool ina = inside(pl, a), inb = inside(pl, b);
        if (ina)
            out->v[out->n++] = *a;
        NARRATE(tr, .kind = TRACE_FRONT, .klass = ina ? FRONT_KEEP : FRONT_DROP, .line = line,
                .x = (int32_t)pl->id, .aux = { AUX_POS(a) });
        /* a new vertex only where the edge really crosses: an end lying on
         * the plane is itself the crossing, and is kept as it is */
        const struct pvert *in_end = ina ? a : b;
        if (ina != inb && in_end->pos[pl->axis] != pl->at) {
            const struct pvert *p0 = pvert_before(b, a) ? b : a, *p1 = p0 == a ? b : a;
            double t;
            struct pvert *n = &out->v[out->n++];
            *n = edge_point(pl, p0, p1, &t);
            NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_NEW, .line = line,
                    .x = (int32_t)pl->id, .aux = { AUX_POS(n), (float)t });
        }
    }
}

void clip_polygon_rect(struct poly *p, double x0, double y0, double x1, double y1)
{
    const struct plane edges[4] = { { PLANE_LEFT, "x >= x0", 0, x0, +1, true },
                                    { PLANE_RIGHT, "x <= x1", 0, x1, -1, true },
                                    { PLANE_TOP, "y >= y0", 1, y0, +1, true },
                                    { PLANE_BOTTOM, "y <= y1", 1, y1, -1, true } };
    struct poly q;
    for (int k = 0; k < 4 && p->n > 0; k++) {
        clip_polygon(&q, p, &edges[k], NULL);
        *p = q;
    }
}

/* --- projection and the guard band ------------------------------------------------ */

void project(const struct frustum *v, struct poly *p)
{
    for (int i = 0; i < p->n; i++) {
        double *c = p->v[i].pos;
        double x = v->half_w * (1 + v->g * c[0] / (v->aspect * c[2]));
        double y = v->half_h * (1 - v->g * c[1] / c[2]);
        c[0] = x;
        c[1] = y;
    }
}

bool in_guard_band(const struct poly *p)
{
    for (int i = 0; i < p->n; i++)
        for (int a = 0; a < 2; a++)
            if (!(p->v[i].pos[a] >= -GUARD_BAND && p->v[i].pos[a] < GUARD_BAND))
                return false;
    return true;
}

void clip_guard_band(struct poly *p, struct trace *tr)
{
    for (int k = 0; k < 4 && p->n > 0; k++) {
        struct poly out;
        clip_polygon(&out, p, &guard_planes[k], tr);
        *p = out;
    }
}

/* --- fan and cull --------------------------------------------------------------- */

int64_t facing_area(const struct vertex v[3])
{
    int64_t x[3], y[3];
    for (int i = 0; i < 3; i++) {
        x[i] = snap_coord(v[i].x, SUBPIXEL_BITS);
        y[i] = snap_coord(v[i].y, SUBPIXEL_BITS);
    }
    return (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
}

bool culled(enum cull cull, const struct vertex v[3])
{
    if (cull == CULL_NONE)
        return false;
    bool front = facing_area(v) < 0;    /* counter-clockwise as seen, in y-down space */
    return cull == CULL_BACK ? !front : front;
}

static struct vertex screen_vertex(const struct pvert *p)
{
    return (struct vertex){ .x = p->pos[0], .y = p->pos[1], .z = p->pos[2],
                            .r = p->rgb[0], .g = p->rgb[1], .b = p->rgb[2],
                            .s = p->st[0], .t = p->st[1] };
}

int fan(const struct poly *p, enum cull cull, struct vertex out[][3], struct trace *tr)
{
    int n = 0;
    for (int i = 1; i + 1 < p->n; i++) {
        struct vertex t[3] = { screen_vertex(&p->v[0]), screen_vertex(&p->v[i]),
                               screen_vertex(&p->v[i + 1]) };
        bool drawn = !culled(cull, t);
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_TRIANGLE, .line = FRONT_LINE_FAN, .x = i - 1,
                .flags = drawn ? TRACE_INSIDE : 0, .aux = { (float)facing_area(t) / 65536.0f });
        if (drawn)
            memcpy(out[n++], t, sizeof t);
    }
    return n;
}

/* --- the pipeline ------------------------------------------------------------------ */

/* Pixel of a screen position, for the explorer to outline (clamped: the
 * position may be far off the screen). */
static int32_t pixel_of(double v)
{
    return (int32_t)fmax(-2e9, fmin(2e9, floor(v)));
}

int front_pipeline(const struct frustum *v, enum cull cull, const struct world_tri *t,
                   const struct front_way *way, struct trace *tr, struct vertex out[][3])
{
    NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_WORLD, .line = FRONT_LINE_EACH);
    struct poly p = { .n = 3 }, q;
    for (int k = 0; k < 3; k++) {                               /* world -> view */
        p.v[k] = view_vertex(v, t->p[k], t->rgb[k]);
        memcpy(p.v[k].st, t->st[k], sizeof p.v[k].st);          /* (s, t) ride along */
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_VIEW, .line = FRONT_LINE_VIEW, .x = k,
                .aux = { AUX_POS(&p.v[k]) });
    }
    if (way && way->clip_project) {
        way->clip_project(v, &p);                               /* an alternative's */
        if (p.n == 0)
            return 0;
    } else {
        void (*clip)(struct poly *, const struct poly *, const struct plane *, struct trace *) =
            way && way->clip ? way->clip : clip_polygon;
        struct plane near = depth_plane(v, PLANE_NEAR), far = depth_plane(v, PLANE_FAR);
        clip(&q, &p, &near, tr);                                /* d >= near */
        if (q.n == 0)
            return 0;                                           /* wholly behind near */
        clip(&p, &q, &far, tr);                                 /* d <= far */
        if (p.n == 0)
            return 0;                                           /* wholly beyond far */
        project(v, &p);                                         /* view -> screen */
    }
    for (int k = 0; k < p.n; k++) {
        const double *c = p.v[k].pos;
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_PROJECT, .line = FRONT_LINE_PROJECT,
                .x = pixel_of(c[0]), .y = pixel_of(c[1]), .aux = { AUX_POS(&p.v[k]), (float)k });
    }
    if (way && way->screen) {
        way->screen(v, &p);                                     /* an exhibit's x, y */
    } else {
        bool inside = in_guard_band(&p);
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_GUARD, .line = FRONT_LINE_GUARD, .y = p.n,
                .flags = inside ? TRACE_INSIDE : 0);
        if (!inside)
            clip_guard_band(&p, tr);                            /* only beyond the band */
    }
    return fan(&p, cull, out, tr);                              /* triangles, culled */
}

int front_triangle(const struct frustum *v, enum cull cull, const struct world_tri *t,
                   struct vertex out[][3])
{
    return front_pipeline(v, cull, t, NULL, NULL, out);
}

/* Every world triangle through pipeline, or (pipeline NULL) through
 * front_pipeline() the way `way` says. */
static bool scene_through(struct scene *s, pipeline_fn pipeline, const struct front_way *way)
{
    struct world *w = &s->world;
    if (!w->camera_line)
        return true;
    struct frustum v;
    frustum_init(&v, &w->cam, s->w, s->h);
    s->ntris = 0;
    int from_cap = 0;
    for (int i = 0; i < w->ntris; i++) {
        struct vertex tris[POLY_MAX - 2][3];
        int n = pipeline ? pipeline(&v, w->cull, &w->tris[i], tris)
                         : front_pipeline(&v, w->cull, &w->tris[i], way, NULL, tris);
        for (int k = 0; k < n; k++) {
            if (!scene_add_textured(s, tris[k], w->tris[i].texture))
                return false;
            if (s->ntris > from_cap) {
                int cap = s->cap;
                int *nf = realloc(w->from, (size_t)cap * sizeof *nf);
                if (!nf)
                    return false;
                w->from = nf;
                from_cap = cap;
            }
            w->from[s->ntris - 1] = i;
        }
    }
    return true;
}

bool front_scene(struct scene *s)
{
    return scene_through(s, NULL, NULL);
}

bool front_scene_with(struct scene *s, pipeline_fn pipeline)
{
    return scene_through(s, pipeline, NULL);
}

bool front_scene_way(struct scene *s, const struct front_way *way)
{
    return scene_through(s, NULL, way);
}

bool front_move_vertex(struct scene *s, int i, double ox, double oy, double x, double y)
{
    struct world *w = &s->world;
    if (!w->camera_line || !w->from || i < 0 || i >= s->ntris || w->from[i] < 0
        || w->from[i] >= w->ntris)
        return false;
    struct frustum v;
    frustum_init(&v, &w->cam, s->w, s->h);
    const struct world_tri *t = &w->tris[w->from[i]];
    for (int k = 0; k < 3; k++) {
        struct poly p = { .n = 1, .v = { view_vertex(&v, t->p[k], t->rgb[k]) } };
        double d = p.v[0].pos[2];
        if (!(d >= v.near && d <= v.far))
            continue;           /* clipped away: not a vertex on the screen */
        project(&v, &p);
        if (fabs(p.v[0].pos[0] - ox) > 1e-9 * fmax(1, fabs(ox))
            || fabs(p.v[0].pos[1] - oy) > 1e-9 * fmax(1, fabs(oy)))
            continue;
        /* project() backwards at depth d, then view space back to the world */
        double xv = (x / v.half_w - 1) * v.aspect * d / v.g;
        double yv = (1 - y / v.half_h) * d / v.g;
        double old[3] = { t->p[k][0], t->p[k][1], t->p[k][2] }, now[3];
        for (int a = 0; a < 3; a++) {
            now[a] = v.eye[a] + xv * v.s[a] + yv * v.u[a] + d * v.f[a];
            now[a] = fmin(fmax(now[a], -WORLD_LIMIT), WORLD_LIMIT);
        }
        for (int j = 0; j < w->ntris; j++)
            for (int m = 0; m < 3; m++) {
                double *q = w->tris[j].p[m];
                if (q[0] == old[0] && q[1] == old[1] && q[2] == old[2])
                    memcpy(q, now, sizeof now);
            }
        return true;
    }
    return false;
}
