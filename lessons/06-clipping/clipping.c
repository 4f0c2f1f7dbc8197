/* Lesson 06: from a 3-D scene to the screen - projection, near and far
 * clipping, the guard band.
 *
 * What it shows: the stage every real pipeline runs before the rasterizers of
 * lessons 01-05. A 3-D scene gives world-space triangles and a camera
 * (CONVENTIONS.md, "3-D scenes"); the screen triangles the rasterizer needs
 * are made in six steps, each a function of src/front/front.c:
 *
 *     world --look-at--> view --clip d >= near--> --clip d <= far-->
 *           --project--> screen --guard band--> --fan, cull--> lesson 05
 *
 *                  far  ___________________
 *                       \                 /        top-down: the frustum,
 *                        \     view      /         d up the page, x_v across
 *                         \   volume    /
 *                  near    \___________/
 *                            \       /
 *                             \     /   a vertex behind the eye (d < 0)
 *                              \   /    would divide by a negative depth:
 *                               eye     it must be clipped BEFORE projecting
 *
 * Clipping happens in view space, where everything is still linear along an
 * edge: a new vertex on the edge P0 -> P1 is P0 + t (P1 - P0), with
 * t = (plane - d0) / (d1 - d0), colour alike, its d set to the plane
 * exactly. Two triangles sharing an edge must make the same new vertex, so
 * the edge's ends are taken in one canonical order (lexicographic), never in
 * the order each triangle happens to walk them.
 *
 * x and y are not clipped to the screen: the edge arithmetic of lesson 03 is
 * exact for any vertex in [-16384, 16384), so a projected triangle inside
 * that guard band goes to the rasterizer as it is and the rasterizer's box
 * clamp does the rest. Only a triangle reaching beyond it is clipped, in 2-D.
 *
 * The rasterizer is lesson 05's (blocks, lesson 04's planes of 1/z): the
 * vertex's z is its view depth d, so 1/d is interpolated perspective-correct.
 *
 * What the depth buffer stores is a choice of its own: d (the lessons so
 * far), OpenGL's NDC z = (f+n)/(f-n) - 2fn/((f-n) d) in 24 bits, 1/d, or a
 * reversed float depth n (f - d) / ((f - n) d). The variants store each and
 * the exhibit shows what 24 bits of NDC z do to two walls 400 units away.
 *
 * The exhibits reproduce the classic slips: projecting before clipping,
 * clipping each triangle's shared edges in its own order, clipping x and y
 * to the viewport instead of using the guard band, and no guard band at all
 * with 32-bit edge values.
 */
#include <math.h>
#include <string.h>

#include "front/front.h"    /* the stages: view_vertex, clip_polygon, project, ... */
#include "lesson.h"
#include "shade/quad.h"     /* what lesson 05's pixels cost: QUAD_DEPTH_COST, ... */
#include "shade/shade.h"    /* shade_pixel */

/* The rasterizer is lesson 05's, by name (its fast build in the fast build). */
#if NARRATING
#define LESSON_05 lesson_05
#else
#define LESSON_05 lesson_05_fast
#endif
extern const struct lesson LESSON_05;

static const char *const pseudocode[] = {
    "for each world triangle (A, B, C):",                                  /* 0 */
    "  world -> view: q = p - eye; x_v = s.q, y_v = u.q, d = f.q",         /* 1 */
    "  clip against d >= near: keep, drop, or new vertex P0 + t (P1 - P0)", /* 2 */
    "  clip against d <= far, the same way",                               /* 3 */
    "  project: x_s = W/2 (1 + g x_v / (a d)), y_s = H/2 (1 - g y_v / d)", /* 4 */
    "  beyond the guard band [-16384, 16384)? clip x, y against it",       /* 5 */
    "  fan from the first vertex; cull by facing",                         /* 6 */
    "  rasterize each triangle: lesson 05, 1/d perspective-correct",       /* 7 */
    NULL,
};

enum { L_EACH, L_VIEW, L_NEAR, L_FAR, L_PROJECT, L_GUARD, L_FAN, L_RASTER };

/* trace_event.aux[] of this lesson: lesson 05's block events keep their q
 * and level; the depth variants' pixel tests add the exact view depth and
 * what the stored value says it is, and where the stored value lies
 * between what near (0) and far (1) would store. */
static const char *const aux_names[] = { "q", "level", "d", "stored as d", "stored 0..1", NULL };

/* --- the pipeline, narrated ------------------------------------------------
 *
 * What front_triangle() in src/front/front.c does for every other program,
 * step by step and told: the explorer steps through it before the
 * rasterizer's own steps. */

#if NARRATING   /* the telling exists in the narrated build only */

struct narrator {
    struct trace *tr;
    int line;
};

static void narrate_clip(void *ctx, const struct clip_step *s)
{
    struct narrator *n = ctx;
    static const uint8_t what[] = { [CLIP_KEEP] = FRONT_KEEP, [CLIP_DROP] = FRONT_DROP,
                                    [CLIP_NEW] = FRONT_NEW };
    const double *c = s->v->pos;
    NARRATE(n->tr, .kind = TRACE_FRONT, .klass = what[s->what], .line = (uint8_t)n->line,
            .x = (int32_t)s->plane->id, .aux = { (float)c[0], (float)c[1], (float)c[2], (float)s->t });
}

static void narrate_plane(struct trace *tr, int line, const struct plane *pl, int n)
{
    NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_PLANE, .line = (uint8_t)line,
            .x = (int32_t)pl->id, .y = n, .aux = { (float)pl->at });
}

static void clip_told(struct poly *out, const struct poly *in, const struct plane *pl, int line,
                      struct trace *tr)
{
    struct narrator n = { tr, line };
    struct clip_watch w = { narrate_clip, &n };
    narrate_plane(tr, line, pl, in->n);
    clip_polygon(out, in, pl, &w);
}

/* Pixel of a screen position, for the explorer to outline (clamped: the
 * position may be far off the screen). */
static int32_t pixel_of(double v)
{
    return (int32_t)fmax(-2e9, fmin(2e9, floor(v)));
}

static void tell_front_end(const struct scene *s, int w, struct trace *tr)
{
    struct frustum fr;
    frustum_init(&fr, &s->world.cam, s->w, s->h);
    const struct world_tri *t = &s->world.tris[w];

    /* 1. world -> view */
    struct poly p = { .n = 3 }, q;
    for (int k = 0; k < 3; k++) {
        p.v[k] = view_vertex(&fr, t->p[k], t->rgb[k]);
        const double *c = p.v[k].pos;
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_VIEW, .line = L_VIEW, .x = k,
                .aux = { (float)c[0], (float)c[1], (float)c[2] });
    }
    /* 2, 3. near, then far, in view space */
    struct plane near = depth_plane(&fr, PLANE_NEAR), far = depth_plane(&fr, PLANE_FAR);
    clip_told(&q, &p, &near, L_NEAR, tr);
    clip_told(&p, &q, &far, L_FAR, tr);
    /* 4. projection and viewport */
    project(&fr, &p);
    for (int k = 0; k < p.n; k++) {
        const double *c = p.v[k].pos;
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_PROJECT, .line = L_PROJECT,
                .x = pixel_of(c[0]), .y = pixel_of(c[1]),
                .aux = { (float)c[0], (float)c[1], (float)c[2], (float)k });
    }
    /* 5. the guard band: used as it is when inside */
    bool inside = in_guard_band(&p);
    NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_GUARD, .line = L_GUARD, .y = p.n,
            .flags = inside ? TRACE_INSIDE : 0);
    for (int k = 0; k < 4 && !inside && p.n > 0; k++) {
        clip_told(&q, &p, &guard_planes[k], L_GUARD, tr);
        p = q;
    }
    /* 6. the fan, each triangle facing the viewer or not */
    for (int i = 1; i + 1 < p.n; i++) {
        struct vertex v[3];
        const struct pvert *c[3] = { &p.v[0], &p.v[i], &p.v[i + 1] };
        for (int k = 0; k < 3; k++)
            v[k] = (struct vertex){ .x = c[k]->pos[0], .y = c[k]->pos[1], .z = c[k]->pos[2] };
        NARRATE(tr, .kind = TRACE_FRONT, .klass = FRONT_TRIANGLE, .line = L_FAN, .x = i - 1,
                .flags = culled(s->world.cull, v) ? 0 : TRACE_INSIDE,
                .aux = { (float)facing_area(v) / 65536.0f });
    }
}

#else
static void tell_front_end(const struct scene *s, int w, struct trace *tr)
{
    (void)s, (void)w, (void)tr;
}
#endif

/* The rasterizer's events point at line 7 of this lesson's pseudo-code. */
struct relay {
    void (*sink)(void *ctx, const struct trace_event *ev);
    void *ctx;
};

static void at_raster_line(void *ctx, const struct trace_event *ev)
{
    const struct relay *r = ctx;
    struct trace_event e = *ev;
    e.line = L_RASTER;
    r->sink(r->ctx, &e);
}

/* Is screen triangle i of the scene the first its world triangle made? */
static bool first_of_its_world_triangle(const struct scene *s, uint32_t i, int *w)
{
    if (!s || !s->world.camera_line || !s->world.from || i >= (uint32_t)s->ntris)
        return false;
    *w = s->world.from[i];
    return i == 0 || s->world.from[i - 1] != *w;
}

/* Lesson 05 on one screen triangle, its steps on the last line. */
static void rasterize_05(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    if (NARRATING && tr && tr->sink) {
        struct relay r = { tr->sink, tr->ctx };
        tr->sink = at_raster_line;
        tr->ctx = &r;
        LESSON_05.variants[0].rasterize(t, p, fb, tr);
        tr->sink = r.sink;
        tr->ctx = r.ctx;
    } else {
        LESSON_05.variants[0].rasterize(t, p, fb, tr);
    }
}

/* The lesson: tell the front end of a world triangle with its first screen
 * triangle, then rasterize the screen triangle with lesson 05. (The
 * exhibits that make their triangles another way are not told: their
 * triangles are not what the told pipeline makes.) */
static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    int w;
    if (NARRATING && tr && first_of_its_world_triangle(p->scene, tr->tri, &w))
        tell_front_end(p->scene, w, tr);
    rasterize_05(t, p, fb, tr);
}

/* --- what the depth buffer stores --------------------------------------------
 *
 * The target keeps the nearest surface with "smaller wins". Each choice is
 * stored so that this holds (a value where larger is nearer is stored
 * negated, which is exact in floating point):
 *
 *     d          view depth, float                      the lessons so far
 *     ndc24      OpenGL: z_ndc = (f+n)/(f-n) - 2fn/((f-n) d) in [-1, 1],
 *                window depth (z_ndc + 1) / 2 in 24-bit fixed point
 *     inverse    1/d, float (linear in screen space, what lesson 04 steps)
 *     reversed   n (f - d) / ((f - n) d), float: 1 at near, 0 at far, so
 *                that the float's dense values near 0 go to the far range
 *
 * With a small near plane NDC z crowds almost all its values next to the
 * near plane: 400 units away with n = 0.01 and f = 1000, one step of 24 bits
 * is 0.32 units of depth. The reversed float spends its exponent where NDC z
 * wastes its bits. */
enum depth_store { STORE_D, STORE_NDC24, STORE_INVERSE, STORE_REVERSED };

#define NDC24_STEPS 16777215.0      /* 2^24 - 1 */

static double store_depth(enum depth_store how, double d, double n, double f)
{
    switch (how) {
    case STORE_NDC24: {
        double ndc = (f + n) / (f - n) - 2 * f * n / ((f - n) * d);
        return floor((ndc + 1) / 2 * NDC24_STEPS + 0.5);      /* an integer: exact in a float */
    }
    case STORE_INVERSE:
        return -(double)(float)(1 / d);
    case STORE_REVERSED:
        return -(double)(float)(n * (f - d) / ((f - n) * d));
    case STORE_D:
        break;
    }
    return (double)(float)d;
}

/* What a stored value says the depth is. */
static double stored_as_d(enum depth_store how, double v, double n, double f)
{
    switch (how) {
    case STORE_NDC24: {
        double ndc = v / NDC24_STEPS * 2 - 1;
        return 2 * f * n / ((f - n) * ((f + n) / (f - n) - ndc));
    }
    case STORE_INVERSE:
        return -1 / v;
    case STORE_REVERSED:
        return n * f / (n - v * (f - n));       /* v is -z: z (f - n) d = n (f - d) */
    case STORE_D:
        break;
    }
    return v;
}

/* Where a stored value lies between the values of near (0) and far (1). */
static double stored_fraction(enum depth_store how, double d, double n, double f)
{
    double at_n = store_depth(how, n, n, f), at_f = store_depth(how, f, n, f);
    return (store_depth(how, d, n, f) - at_n) / (at_f - at_n);
}

/* The pixel loop of lesson 02 with exact edge values, shaded in double
 * precision (perspective-correct), storing the chosen depth: what matters
 * here is the stored value, not the speed. */
static void rasterize_storing(const struct tri_setup *t, const struct raster_params *p,
                              struct target *fb, struct trace *tr, enum depth_store how)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_RASTER, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    double n = 1, f = 2;        /* a 2-D scene has no camera: any n < f will do */
    if (p->scene && p->scene->world.camera_line)
        n = p->scene->world.cam.near, f = p->scene->world.cam.far;
    for (int y = t->miny; y <= t->maxy; y++)
        for (int x = t->minx; x <= t->maxx; x++) {
            int64_t e[3];
            bool in = true;
            for (int k = 0; k < 3; k++) {
                e[k] = edge_value(t, k, x, y);
                in = in && edge_inside(t, k, e[k]);
            }
            if (!in)
                continue;
            double d, rgb[3], st[2];
            reference_shade(t, x, y, true, &d, rgb, st);
            double stored = store_depth(how, d, n, f);
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_RASTER, .x = x, .y = y,
                    .e = { e[0], e[1], e[2] }, .flags = TRACE_INSIDE,
                    .aux = { 0, 0, (float)d, (float)stored_as_d(how, stored, n, f),
                             (float)stored_fraction(how, d, n, f) });
            uint32_t rgba = shade_pixel(p, tr, rgb[0], rgb[1], rgb[2], st[0], st[1]);
            PLOT(fb, tr, L_RASTER, x, y, (float)stored, rgba);
        }
}

static void rasterize_ndc24(const struct tri_setup *t, const struct raster_params *p,
                            struct target *fb, struct trace *tr)
{
    rasterize_storing(t, p, fb, tr, STORE_NDC24);
}

static void rasterize_inverse(const struct tri_setup *t, const struct raster_params *p,
                              struct target *fb, struct trace *tr)
{
    rasterize_storing(t, p, fb, tr, STORE_INVERSE);
}

static void rasterize_reversed(const struct tri_setup *t, const struct raster_params *p,
                               struct target *fb, struct trace *tr)
{
    rasterize_storing(t, p, fb, tr, STORE_REVERSED);
}

/* The storages other than d are exhibits too: not slips, but the explorer
 * shows them against the lesson (by colour: their buffers hold other
 * numbers) and the exercise checks, which read the depth buffer as d,
 * rightly refuse them. */

/* --- the classic slips, as front ends of their own ---------------------------- */

/* Step 1 alone: the world triangle in view space. */
static void view_triangle(const struct frustum *v, const struct world_tri *t, struct poly *p)
{
    p->n = 3;
    for (int k = 0; k < 3; k++)
        p->v[k] = view_vertex(v, t->p[k], t->rgb[k]);
}

/* Steps 1 to 4 as the lesson takes them, for the slips that come after:
 * view space, near, far, projection. */
static void clipped_and_projected(const struct frustum *v, const struct world_tri *t,
                                  struct poly *p)
{
    struct poly q;
    view_triangle(v, t, p);
    struct plane near = depth_plane(v, PLANE_NEAR), far = depth_plane(v, PLANE_FAR);
    clip_polygon(&q, p, &near, NULL);
    clip_polygon(p, &q, &far, NULL);
    project(v, p);
}

/* Exhibit project-first: divide by d before clipping. A vertex behind the
 * eye (d < 0) lands mirrored through the centre of the screen, so a
 * triangle crossing d = 0 is drawn inside out, across the screen; triangles
 * wholly behind the eye appear too. (Its depth is taken as |d|.) */
static int pipeline_project_first(const struct frustum *v, enum cull cull,
                                   const struct world_tri *t, struct vertex out[][3])
{
    struct poly p;
    view_triangle(v, t, &p);
    project(v, &p);                                 /* the slip: before clipping */
    for (int k = 0; k < 3; k++)
        p.v[k].pos[2] = fmax(fabs(p.v[k].pos[2]), v->near);
    if (!in_guard_band(&p))
        clip_guard_band(&p, NULL);
    return fan(&p, cull, out);
}

/* Exhibit walk-order: near and far clipped as many pipelines clip, in single
 * precision (as GPUs do), and each triangle taking its edges in its own
 * walking order. The two triangles sharing an edge walk it in opposite
 * directions, compute P0 + t (P1 - P0) from opposite ends, round
 * differently, and the two new vertices differ: where an edge crosses the
 * plane at a shallow angle, t carries the float's error of d0 and d1 times
 * the edge's length, the twins snap to different 1/256 positions, and
 * pixels along the shared edge are missed or covered twice. The exhibit
 * float-canonical is the same float clipper taking the ends in the
 * canonical order: its new vertices are off by as much, but the same in
 * both triangles, and the mesh stays closed. */
static bool float_before(const struct pvert *a, const struct pvert *b)
{
    for (int i = 0; i < 3; i++)
        if (a->pos[i] != b->pos[i])
            return a->pos[i] < b->pos[i];
    return false;
}

static void clip_float(struct poly *out, const struct poly *in, const struct plane *pl, bool canonical)
{
    out->n = 0;
    for (int i = 0; i < in->n; i++) {
        const struct pvert *a = &in->v[i], *b = &in->v[(i + 1) % in->n];
        bool ina = pl->keep > 0 ? a->pos[2] >= pl->at : a->pos[2] <= pl->at;
        bool inb = pl->keep > 0 ? b->pos[2] >= pl->at : b->pos[2] <= pl->at;
        if (ina)
            out->v[out->n++] = *a;
        if (ina != inb) {
            const struct pvert *p0 = a, *p1 = b;
            if (canonical && float_before(b, a))
                p0 = b, p1 = a;
            float t = (float)((float)pl->at - (float)p0->pos[2]) / ((float)p1->pos[2] - (float)p0->pos[2]);
            struct pvert *nv = &out->v[out->n++];
            for (int c = 0; c < 3; c++) {
                nv->pos[c] = (float)p0->pos[c] + t * ((float)p1->pos[c] - (float)p0->pos[c]);
                nv->rgb[c] = (float)p0->rgb[c] + t * ((float)p1->rgb[c] - (float)p0->rgb[c]);
                nv->rgb[c] = fmin(fmax(nv->rgb[c], 0), 1);
            }
            nv->pos[2] = pl->at;
        }
    }
}

static int pipeline_float(const struct frustum *v, enum cull cull, const struct world_tri *t,
                          struct vertex out[][3], bool canonical)
{
    struct poly p, q;
    view_triangle(v, t, &p);
    struct plane near = depth_plane(v, PLANE_NEAR), far = depth_plane(v, PLANE_FAR);
    clip_float(&q, &p, &near, canonical);
    clip_float(&p, &q, &far, canonical);
    project(v, &p);
    if (!in_guard_band(&p))
        clip_guard_band(&p, NULL);
    return fan(&p, cull, out);
}

static int pipeline_walk_order(const struct frustum *v, enum cull cull, const struct world_tri *t,
                               struct vertex out[][3])
{
    return pipeline_float(v, cull, t, out, false);
}

static int pipeline_float_canonical(const struct frustum *v, enum cull cull, const struct world_tri *t,
                                    struct vertex out[][3])
{
    return pipeline_float(v, cull, t, out, true);
}

/* Exhibit viewport: x and y clipped to the framebuffer, [0, W] x [0, H],
 * for every triangle that crosses its border, instead of only beyond the
 * guard band. The picture is the same; the vertices and triangles are not:
 * every triangle over an edge of the screen is cut and fanned. */
static int pipeline_viewport(const struct frustum *v, enum cull cull, const struct world_tri *t,
                             struct vertex out[][3])
{
    struct poly p, q;
    clipped_and_projected(v, t, &p);
    const struct plane screen[4] = {
        { PLANE_LEFT, "x >= 0", 0, 0, +1, true }, { PLANE_RIGHT, "x <= W", 0, 2 * v->half_w, -1, true },
        { PLANE_TOP, "y >= 0", 1, 0, +1, true }, { PLANE_BOTTOM, "y <= H", 1, 2 * v->half_h, -1, true },
    };
    for (int k = 0; k < 4 && p.n > 0; k++) {
        clip_polygon(&q, &p, &screen[k], NULL);
        p = q;
    }
    return fan(&p, cull, out);
}

/* Exhibit no-guard-32: no x/y clipping at all, and edge values in 32-bit
 * integers, as a rasterizer without a guard band would have them. Lesson
 * 03's budget: with 8 sub-pixel bits, |F| <= 8 R^2 must stay below 2^31, so
 * vertices may lie only 64 pixels from the origin. The projected vertices
 * of a triangle near the eye lie thousands of pixels away: the products
 * wrap around and coverage turns to noise. (The front end keeps the
 * vertices where a snapped coordinate still fits 32 bits.) */
#define NO_GUARD_LIMIT 1048576.0    /* 2^20 px: 2^28 in 1/256 units, inside int32 */

static int pipeline_no_guard(const struct frustum *v, enum cull cull, const struct world_tri *t,
                             struct vertex out[][3])
{
    struct poly p;
    clipped_and_projected(v, t, &p);
    for (int k = 0; k < p.n; k++)
        for (int a = 0; a < 2; a++)
            p.v[k].pos[a] = fmax(-NO_GUARD_LIMIT, fmin(NO_GUARD_LIMIT, p.v[k].pos[a]));
    return fan(&p, cull, out);
}

static bool front_project_first(struct scene *s) { return front_scene_with(s, pipeline_project_first); }
static bool front_walk_order(struct scene *s) { return front_scene_with(s, pipeline_walk_order); }
static bool front_float_canonical(struct scene *s) { return front_scene_with(s, pipeline_float_canonical); }
static bool front_viewport(struct scene *s) { return front_scene_with(s, pipeline_viewport); }
static bool front_no_guard(struct scene *s) { return front_scene_with(s, pipeline_no_guard); }

/* Edge values wrapped to 32 bits, as int32_t arithmetic would leave them
 * (computed in uint32_t, where wrapping is defined, then read back). */
static int32_t wrap32(int64_t I, int64_t J, int64_t K, int64_t px, int64_t py)
{
    uint32_t f = (uint32_t)I * (uint32_t)px + (uint32_t)J * (uint32_t)py + (uint32_t)K;
    return f <= INT32_MAX ? (int32_t)f : -(int32_t)(UINT32_MAX - f) - 1;
}

static void rasterize_edges32(const struct tri_setup *t, const struct raster_params *p,
                              struct target *fb, struct trace *tr)
{
    if (t->empty)
        return;
    for (int y = t->miny; y <= t->maxy; y++)    /* the box is still right: it needs no product */
        for (int x = t->minx; x <= t->maxx; x++) {
            int64_t cx = pixel_centre(x), cy = pixel_centre(y);
            int32_t e[3];
            bool in = true;
            for (int k = 0; k < 3; k++) {
                e[k] = wrap32(t->I[k], t->J[k], t->K[k], cx, cy);
                in = in && (int64_t)e[k] + t->bias[k] >= 0;
            }
            if (!in)
                continue;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_RASTER, .x = x, .y = y,
                    .e = { e[0], e[1], e[2] }, .flags = TRACE_INSIDE);
            double w = 1.0 / 3;         /* the weights are noise too: a flat average */
            const struct vertex *v = t->v;
            double z = 1 / (w / v[0].z + w / v[1].z + w / v[2].z);
            uint32_t rgba = shade_pixel(p, tr, w * (v[0].r + v[1].r + v[2].r),
                                        w * (v[0].g + v[1].g + v[2].g),
                                        w * (v[0].b + v[1].b + v[2].b), 0, 0);
            PLOT(fb, tr, L_RASTER, x, y, (float)z, rgba);
        }
}

static const struct lesson_variant variants[] = {
    { "clip", "clip near and far, guard band, lesson 05's rasterizer storing d", rasterize, false },
    { "inverse", "storage: the depth buffer holds 1/d as a float (the same picture)",
      rasterize_inverse, true },
    { "reversed", "storage: reversed float depth n (f - d) / ((f - n) d) (the same picture)",
      rasterize_reversed, true },
    { "ndc24", "exhibit: OpenGL's NDC z in 24 bits: far surfaces close together fight",
      rasterize_ndc24, true },
    { "project-first", "exhibit: projecting before clipping: a triangle behind the eye, inside out",
      rasterize_05, true },
    { "walk-order", "exhibit: float clipping in each triangle's own edge order: cracks",
      rasterize_05, true },
    { "float-canonical", "float clipping in the canonical order: the cut moves, no crack",
      rasterize_05, true },
    { "viewport", "exhibit: x, y clipped to the screen, not the guard band: more clipping",
      rasterize_05, true },
    { "no-guard-32", "exhibit: no guard band and 32-bit edge values: lesson 03's overflow",
      rasterize_edges32, true },
};

/* How each variant makes the screen triangles (NULL: the shared front end). */
static const front_fn fronts[] = {
    NULL, NULL, NULL, NULL, front_project_first, front_walk_order, front_float_canonical, front_viewport,
    front_no_guard,
};

_Static_assert(sizeof fronts / sizeof fronts[0] == sizeof variants / sizeof variants[0],
               "one front end per variant");

/* The variants whose depth buffer holds another quantity than d. */
static const bool other_depth[] = { false, true, true, true, false, false, false, false, false };
_Static_assert(sizeof other_depth / sizeof other_depth[0] == sizeof variants / sizeof variants[0],
               "one entry per variant");

const struct lesson lesson_06 = {
    .id = "06-clipping",
    .title = "From a 3-D scene to the screen: near and far clipping, the guard band",
    .pseudocode = pseudocode,
    .builtin_scene = "room",
    .exhibit_scene = "room",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .fronts = fronts,
    .other_depth = other_depth,
    /* the exercise: the student's clipper in the front end, lesson 05's
     * rasterizer given (lessons/06-clipping/exercise.c) */
    .exercise = { .write_line = L_RASTER, .clip = true },
    /* a pixel costs what it costs in lesson 05: the front end's work is per
     * triangle, not per pixel */
    .cost_tested = (const struct cost_term[]){ COST_TERM(3, EDGE_STEP_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, QUAD_DEPTH_COST), COST_TERM(1, QUAD_COLOUR_COST), { 0 } },
};
