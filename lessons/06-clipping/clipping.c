/* Lesson 06: from a 3-D scene to the screen - projection, near and far
 * clipping, the guard band.
 *
 * What it shows: the stage every real pipeline runs before the rasterizers of
 * lessons 01-05. A 3-D scene gives world-space triangles and a camera
 * (lessons/CONVENTIONS.md, "3-D scenes"); the screen triangles the rasterizer needs
 * are made in six steps, front_pipeline() of src/front/front.c, which every
 * program runs on every 3-D scene and this lesson runs again, narrated:
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

/* The front end tells its steps at lines 0-6 (enum front_line); the
 * rasterizer's at line 7. */
static const char *const pseudocode[] = {
    [FRONT_LINE_EACH] = "for each world triangle (A, B, C):",
    [FRONT_LINE_VIEW] = "  world -> view: q = p - eye; x_v = s.q, y_v = u.q, d = f.q",
    [FRONT_LINE_NEAR] = "  clip against d >= near: keep, drop, or new vertex P0 + t (P1 - P0)",
    [FRONT_LINE_FAR] = "  clip against d <= far, the same way",
    [FRONT_LINE_PROJECT] = "  project: x_s = W/2 (1 + g x_v / (a d)), y_s = H/2 (1 - g y_v / d)",
    [FRONT_LINE_GUARD] = "  beyond the guard band [-16384, 16384)? clip x, y against it",
    [FRONT_LINE_FAN] = "  fan from the first vertex; cull by facing",
    [FRONT_LINES] = "  rasterize each triangle: lesson 05, 1/d perspective-correct",
    NULL,
};

enum { L_RASTER = FRONT_LINES };

/* trace_event.aux[] of this lesson: lesson 05's block events keep their q
 * and level; the depth variants' pixel tests add the exact view depth and
 * what the stored value says it is, and where the stored value lies
 * between what near (0) and far (1) would store. */
static const char *const aux_names[] = { "q", "level", "d", "stored as d", "stored 0..1", NULL };

/* --- the pipeline, narrated ------------------------------------------------
 *
 * Every program has run front_pipeline() on the scene already, silently, for
 * its screen triangles (front_scene). The lesson runs it again for each
 * world triangle, told, just before the first screen triangle the world
 * triangle made: a world triangle that made none (wholly clipped, or
 * culled) is told before the next screen triangle, or after the last. */

/* Tell world triangles first .. last - 1 of the scene. */
static void tell_front_end(const struct scene *s, int first, int last, struct trace *tr)
{
    struct frustum fr;
    frustum_init(&fr, &s->world.cam, s->w, s->h);
    for (int w = first; w < last; w++) {
        struct vertex out[POLY_MAX - 2][3];
        tr->part = w;
        front_pipeline(&fr, s->world.cull, &s->world.tris[w], NULL, tr, out);
    }
}

/* Lesson 05 on one screen triangle, every step of it told at the last line. */
static void rasterize_05(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    if (tr) {
        tr->one_line = true;
        tr->line = L_RASTER;
    }
    LESSON_05.variants[0].rasterize(t, p, fb, tr);
    if (tr)
        tr->one_line = false;
}

/* The lesson: the front end of the world triangles up to this screen
 * triangle's, then lesson 05 on the screen triangle. (The exhibits that
 * make their triangles another way are not told: their triangles are not
 * what the lesson's pipeline makes.) */
static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    const struct scene *s = drawn_scene(p);
    bool told = NARRATING && tr && s && s->world.camera_line && s->world.from
                && tr->tri < (uint32_t)s->ntris;
    int i = told ? (int)tr->tri : 0, w = told ? s->world.from[i] : 0;
    if (told && (i == 0 || s->world.from[i - 1] != w))
        tell_front_end(s, i == 0 ? 0 : s->world.from[i - 1] + 1, w + 1, tr);
    if (told)
        tr->part = w;
    rasterize_05(t, p, fb, tr);
    if (told && i == s->ntris - 1)
        tell_front_end(s, w + 1, s->world.ntris, tr);
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
 * near plane: the window depth grows by fn / ((f - n) d^2) per unit of d,
 * so 400 units away with n = 0.01 and f = 1000 one step of 24 bits,
 * 1 / (2^24 - 1), is 0.954 units of depth. The reversed float spends its
 * exponent where NDC z wastes its bits. */
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
    const struct scene *s = drawn_scene(p);
    if (s && s->world.camera_line)
        n = s->world.cam.near, f = s->world.cam.far;
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

/* Exhibit project-first: divide by d before clipping (no near or far
 * clipping at all). A vertex behind the eye (d < 0) lands mirrored through
 * the centre of the screen, so a triangle crossing d = 0 is drawn inside
 * out, across the screen; triangles wholly behind the eye appear too. (Its
 * depth is taken as |d|.) */
static void clip_nothing(struct poly *out, const struct poly *in, const struct plane *pl,
                         struct trace *tr)
{
    (void)pl, (void)tr;
    *out = *in;
}

static void depth_as_abs_then_guard_band(const struct frustum *v, struct poly *p)
{
    for (int k = 0; k < p->n; k++)
        p->v[k].pos[2] = fmax(fabs(p->v[k].pos[2]), v->near);
    if (!in_guard_band(p))
        clip_guard_band(p, NULL);
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
            if (canonical && pvert_before(b, a))
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

static void clip_float_walk(struct poly *out, const struct poly *in, const struct plane *pl,
                            struct trace *tr)
{
    (void)tr;
    clip_float(out, in, pl, false);
}

static void clip_float_canonical(struct poly *out, const struct poly *in, const struct plane *pl,
                                 struct trace *tr)
{
    (void)tr;
    clip_float(out, in, pl, true);
}

/* Exhibit viewport: x and y clipped to the framebuffer, [0, W] x [0, H],
 * for every triangle that crosses its border, instead of only beyond the
 * guard band. The picture is the same; the vertices and triangles are not:
 * every triangle over an edge of the screen is cut and fanned. */
static void clip_to_viewport(const struct frustum *v, struct poly *p)
{
    const struct plane screen[4] = {
        { PLANE_LEFT, "x >= 0", 0, 0, +1, true }, { PLANE_RIGHT, "x <= W", 0, 2 * v->half_w, -1, true },
        { PLANE_TOP, "y >= 0", 1, 0, +1, true }, { PLANE_BOTTOM, "y <= H", 1, 2 * v->half_h, -1, true },
    };
    for (int k = 0; k < 4 && p->n > 0; k++) {
        struct poly q;
        clip_polygon(&q, p, &screen[k], NULL);
        *p = q;
    }
}

/* Exhibit no-guard-32: no x/y clipping at all, and edge values in 32-bit
 * integers, as a rasterizer without a guard band would have them. Lesson
 * 03's budget: with 8 sub-pixel bits, |F| <= 8 R^2 must stay below 2^31, so
 * vertices may lie only 64 pixels from the origin. The projected vertices
 * of a triangle near the eye lie thousands of pixels away: the products
 * wrap around and coverage turns to noise. (The front end keeps the
 * vertices where a snapped coordinate still fits 32 bits.) */
#define NO_GUARD_LIMIT 1048576.0    /* 2^20 px: 2^28 in 1/256 units, inside int32 */

static void no_guard_band(const struct frustum *v, struct poly *p)
{
    (void)v;
    for (int k = 0; k < p->n; k++)
        for (int a = 0; a < 2; a++)
            p->v[k].pos[a] = fmax(-NO_GUARD_LIMIT, fmin(NO_GUARD_LIMIT, p->v[k].pos[a]));
}

/* --- the APIs' way: clipping in homogeneous clip space -------------------------
 *
 * OpenGL, Vulkan and Direct3D clip after the projection matrix and before
 * the divide, a vertex being (x_c, y_c, z_c, w) with
 *
 *     x_c = (g / a) x_v,   y_c = g y_v,   z_c = A d + B,   w = d
 *
 *     OpenGL:      A = (f+n)/(f-n), B = -2fn/(f-n),  kept where -w <= z_c <= w
 *     Vulkan, D3D: A = f/(f-n),     B = -fn/(f-n),   kept where  0 <= z_c <= w
 *
 * z_c = -w (GL) and z_c = 0 (Vulkan) hold where d = n, z_c = w where d = f:
 * the same planes. A boundary value b = k . (x_c, y_c, z_c, w) is linear in
 * the four coordinates, so along an edge it is linear in t: the crossing is
 * at t = b0 / (b0 - b1), (n - d0) / (d1 - d0) again but rounded another
 * way, and every coordinate is interpolated with it; the divide by w comes
 * after. */
struct hvert { double c[4], rgb[3]; };
struct hpoly { int n; struct hvert v[POLY_MAX]; };

static bool h_before(const struct hvert *a, const struct hvert *b)
{
    for (int i = 0; i < 4; i++)
        if (a->c[i] != b->c[i])
            return a->c[i] < b->c[i];
    return false;
}

/* Sutherland-Hodgman against the boundary kz z_c + kw w >= 0, the edge's
 * ends in canonical order. */
static void clip_homogeneous(struct hpoly *out, const struct hpoly *in, double kz, double kw)
{
    out->n = 0;
    for (int i = 0; i < in->n; i++) {
        const struct hvert *a = &in->v[i], *b = &in->v[(i + 1) % in->n];
        double ba = kz * a->c[2] + kw * a->c[3], bb = kz * b->c[2] + kw * b->c[3];
        if (ba >= 0)
            out->v[out->n++] = *a;
        if ((ba >= 0) != (bb >= 0) && (ba >= 0 ? ba : bb) != 0) {
            const struct hvert *p0 = h_before(b, a) ? b : a, *p1 = p0 == a ? b : a;
            double b0 = p0 == a ? ba : bb, b1 = p0 == a ? bb : ba, t = b0 / (b0 - b1);
            struct hvert *n = &out->v[out->n++];
            for (int k = 0; k < 4; k++)
                n->c[k] = p0->c[k] + t * (p1->c[k] - p0->c[k]);
            for (int k = 0; k < 3; k++)
                n->rgb[k] = fmin(fmax(p0->rgb[k] + t * (p1->rgb[k] - p0->rgb[k]),
                                      fmin(p0->rgb[k], p1->rgb[k])), fmax(p0->rgb[k], p1->rgb[k]));
        }
    }
}

/* View space -> clip space, near and far, the divide and the viewport. */
static void clip_space(const struct frustum *v, struct poly *p, bool gl)
{
    double n = v->near, f = v->far;
    double A = gl ? (f + n) / (f - n) : f / (f - n), B = gl ? -2 * f * n / (f - n) : -f * n / (f - n);
    struct hpoly h = { .n = p->n }, q;
    for (int k = 0; k < p->n; k++) {
        const double *c = p->v[k].pos;
        h.v[k] = (struct hvert){ .c = { v->g / v->aspect * c[0], v->g * c[1], A * c[2] + B, c[2] } };
        memcpy(h.v[k].rgb, p->v[k].rgb, sizeof h.v[k].rgb);
    }
    clip_homogeneous(&q, &h, 1, gl ? 1 : 0);        /* z_c >= -w, or z_c >= 0 */
    clip_homogeneous(&h, &q, -1, 1);                /* z_c <= w */
    p->n = h.n;
    for (int k = 0; k < h.n; k++) {
        const double *c = h.v[k].c;
        p->v[k] = (struct pvert){ .pos = { v->half_w * (1 + c[0] / c[3]), v->half_h * (1 - c[1] / c[3]),
                                           c[3] } };
        memcpy(p->v[k].rgb, h.v[k].rgb, sizeof p->v[k].rgb);
    }
}

static void clip_space_gl(const struct frustum *v, struct poly *p) { clip_space(v, p, true); }
static void clip_space_vk(const struct frustum *v, struct poly *p) { clip_space(v, p, false); }

/* The slips and the alternatives, each a front end of its own. */
static bool front_project_first(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .clip = clip_nothing,
                                                   .screen = depth_as_abs_then_guard_band });
}

static bool front_walk_order(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .clip = clip_float_walk });
}

static bool front_float_canonical(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .clip = clip_float_canonical });
}

static bool front_viewport(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .screen = clip_to_viewport });
}

static bool front_no_guard(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .screen = no_guard_band });
}

static bool front_clip_space_gl(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .clip_project = clip_space_gl });
}

static bool front_clip_space_vk(struct scene *s)
{
    return front_scene_way(s, &(struct front_way){ .clip_project = clip_space_vk });
}

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
    { .name = "clip", .kind = VARIANT_ALGORITHM, .rasterize = rasterize,
      .what = "clip near and far, guard band, lesson 05's rasterizer storing d" },
    { .name = "inverse", .kind = VARIANT_CONTRAST, .rasterize = rasterize_inverse,
      .other_depth = true,
      .what = "storage: the depth buffer holds 1/d as a float (the same picture)" },
    { .name = "reversed", .kind = VARIANT_CONTRAST, .rasterize = rasterize_reversed,
      .other_depth = true,
      .what = "storage: reversed float depth n (f - d) / ((f - n) d) (the same picture)" },
    { .name = "ndc24", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_ndc24,
      .other_depth = true,
      .what = "exhibit: OpenGL's NDC z in 24 bits: far surfaces close together fight" },
    { .name = "project-first", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_05,
      .front = front_project_first,
      .what = "exhibit: projecting before clipping: a triangle behind the eye, inside out" },
    { .name = "walk-order", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_05,
      .front = front_walk_order,
      .what = "exhibit: float clipping in each triangle's own edge order: cracks" },
    { .name = "float-canonical", .kind = VARIANT_CONTRAST, .rasterize = rasterize_05,
      .front = front_float_canonical,
      .what = "float clipping in the canonical order: the cut moves, no crack" },
    { .name = "viewport", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_05,
      .front = front_viewport,
      .what = "exhibit: x, y clipped to the screen, not the guard band: more clipping" },
    { .name = "no-guard-32", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_edges32,
      .front = front_no_guard,
      .what = "exhibit: no guard band and 32-bit edge values: lesson 03's overflow" },
    { .name = "clip-space-gl", .kind = VARIANT_ALTERNATIVE, .rasterize = rasterize_05,
      .front = front_clip_space_gl,
      .what = "near and far clipped in clip space, -w <= z <= w (OpenGL): the same picture" },
    { .name = "clip-space-vk", .kind = VARIANT_ALTERNATIVE, .rasterize = rasterize_05,
      .front = front_clip_space_vk,
      .what = "near and far clipped in clip space, 0 <= z <= w (Vulkan, D3D): the same picture" },
};

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
    /* the exercise: the student's clipper in the front end, lesson 05's
     * rasterizer given (lessons/06-clipping/exercise.c) */
    .exercise = { .write_line = L_RASTER, .clip = true },
    /* a pixel costs what it costs in lesson 05: the front end's work is per
     * triangle, not per pixel */
    .cost_tested = (const struct cost_term[]){ COST_TERM(3, EDGE_STEP_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, QUAD_DEPTH_COST), COST_TERM(1, QUAD_COLOUR_COST), { 0 } },
};
