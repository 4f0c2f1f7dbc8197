/* Lesson 06, what the explorer adds (compiled only in the narrated build;
 * the algorithm is clipping.c).
 *
 * Two views draw the front end of the focus triangle's world triangle over
 * the canvas (the cells stay, faded):
 *
 *   frustum  seen from above: the eye at the bottom, depth d up the canvas,
 *            x_v across, at one scale for both; the frustum's sides, the
 *            near and far planes, the guard band's sides (dashed, nearly
 *            flat: it is 256 screens wide), the triangle in view space, the
 *            polygon left after near and far, its new vertices with their t;
 *   screen   the screen zoomed out: the framebuffer, the guard band when it
 *            is in reach, the projected polygon before the guard band and
 *            the polygon drawn, with the scale written in the corner.
 *
 * A third, depth-error, colours each pixel of the current triangle by how
 * far the depth the buffer holds is from the exact one (reading the stored
 * value back as a depth): switch the variants to compare the storages.
 *
 * The watch panel tells each step of the front end in words. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "front/front.h"
#include "lesson_explorer.h"

extern const struct lesson lesson_06;

/* --- the world triangle told, through the stages -------------------------------- */

struct staged {
    struct frustum fr;
    struct poly view;           /* the world triangle in view space */
    struct poly clipped;        /* after near and far (view space) */
    struct poly projected;      /* that, projected (screen space) */
    struct poly drawn;          /* after the guard band */
    struct pvert made[POLY_MAX];/* new vertices of near and far, view space */
    double t[POLY_MAX];
    int nmade;
    struct poly after[PLANE_BOTTOM + 1];    /* what each plane kept and made */
    int plane, last_guard;      /* the plane being clipped against; the last guard plane */
    bool guard_inside;
};

static void add(struct poly *p, const float *pos)
{
    if (p->n < POLY_MAX)
        p->v[p->n++] = (struct pvert){ .pos = { pos[0], pos[1], pos[2] } };
}

/* The stages, as the pipeline tells them. */
static void collect(void *ctx, const struct trace_event *ev)
{
    struct staged *st = ctx;
    if (ev->kind != TRACE_FRONT)
        return;
    switch ((enum front_step)ev->klass) {
    case FRONT_VIEW:
        add(&st->view, ev->aux);
        break;
    case FRONT_PLANE:
        st->plane = ev->x >= 0 && ev->x <= PLANE_BOTTOM ? ev->x : PLANE_NEAR;
        st->after[st->plane].n = 0;
        if (st->plane > PLANE_FAR)
            st->last_guard = st->plane;
        break;
    case FRONT_NEW:
        if (st->plane <= PLANE_FAR && st->nmade < POLY_MAX) {
            st->made[st->nmade] = (struct pvert){ .pos = { ev->aux[0], ev->aux[1], ev->aux[2] } };
            st->t[st->nmade++] = ev->aux[3];
        }
        add(&st->after[st->plane], ev->aux);
        break;
    case FRONT_KEEP:
        add(&st->after[st->plane], ev->aux);
        break;
    case FRONT_PROJECT:
        add(&st->projected, ev->aux);
        break;
    case FRONT_GUARD:
        st->guard_inside = (ev->flags & TRACE_INSIDE) != 0;
        break;
    case FRONT_DROP:
    case FRONT_TRIANGLE:
    case FRONT_WORLD:
    case FRONT_STEP_COUNT:
        break;
    }
}

/* The stages of world triangle w: the lesson's pipeline run on it, told to
 * collect(). */
static bool stage(const struct raster_params *p, int w, struct staged *st)
{
    const struct scene *s = p->scene;
    if (!s || !s->world.camera_line || w < 0 || w >= s->world.ntris)
        return false;
    memset(st, 0, sizeof *st);
    st->last_guard = -1;
    frustum_init(&st->fr, &s->world.cam, s->w, s->h);
    struct trace tr = { .sink = collect, .ctx = st };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    tr.part = w;
    struct vertex out[POLY_MAX - 2][3];
    front_pipeline(&st->fr, s->world.cull, &s->world.tris[w], NULL, &tr, out);
    st->clipped = st->after[PLANE_FAR];
    st->drawn = st->guard_inside ? st->projected
                : st->last_guard >= 0 ? st->after[st->last_guard] : (struct poly){ 0 };
    return true;
}

/* A polygon of canvas points drawn inside the canvas [0, w] x [0, h] only:
 * cut there by the very clipper of the lesson. */
static void clipped_polygon(const struct lesson_canvas *c, const double (*xy)[2], int n, double w,
                            double h, struct pen pen)
{
    if (n < 3 || n > POLY_MAX - 4)
        return;
    struct poly p = { .n = n }, q;
    for (int k = 0; k < n; k++)
        p.v[k] = (struct pvert){ .pos = { xy[k][0], xy[k][1], 1 } };
    const struct plane edges[4] = { { PLANE_LEFT, "x >= 0", 0, 0, +1, true },
                                    { PLANE_RIGHT, "x <= w", 0, w, -1, true },
                                    { PLANE_TOP, "y >= 0", 1, 0, +1, true },
                                    { PLANE_BOTTOM, "y <= h", 1, h, -1, true } };
    for (int k = 0; k < 4 && p.n > 0; k++) {
        clip_polygon(&q, &p, &edges[k], NULL);
        p = q;
    }
    double out[POLY_MAX][2];
    for (int k = 0; k < p.n; k++)
        out[k][0] = p.v[k].pos[0], out[k][1] = p.v[k].pos[1];
    if (p.n >= 3)
        c->polygon(c, (const double(*)[2])out, p.n, pen);
}

/* --- frustum: the view from above ------------------------------------------------ */

struct top {
    double ox, oy, scale;       /* canvas point of the eye; canvas units per unit of view space */
    double w, h;                /* the canvas: lines stay inside it */
};

/* Liang-Barsky: the part of a -> b inside [0, w] x [0, h], false if none. */
static bool inside_canvas(double a[2], double b[2], double w, double h)
{
    double t0 = 0, t1 = 1, d[2] = { b[0] - a[0], b[1] - a[1] };
    const double lo[2] = { 0, 0 }, hi[2] = { w, h };
    for (int k = 0; k < 2; k++) {
        double p[2] = { -d[k], d[k] }, q[2] = { a[k] - lo[k], hi[k] - a[k] };
        for (int j = 0; j < 2; j++) {
            if (p[j] == 0) {
                if (q[j] < 0)
                    return false;
                continue;
            }
            double r = q[j] / p[j];
            if (p[j] < 0)
                t0 = fmax(t0, r);
            else
                t1 = fmin(t1, r);
        }
    }
    if (t0 > t1)
        return false;
    double a0[2] = { a[0], a[1] };
    for (int k = 0; k < 2; k++) {
        a[k] = a0[k] + t0 * d[k];
        b[k] = a0[k] + t1 * d[k];
    }
    return true;
}

static void top_point(const struct top *m, double xv, double d, double out[2])
{
    out[0] = m->ox + xv * m->scale;
    out[1] = m->oy - d * m->scale;
}

static void top_line(const struct lesson_canvas *c, const struct top *m, double x0, double d0,
                     double x1, double d1, struct pen pen)
{
    double a[2], b[2];
    top_point(m, x0, d0, a);
    top_point(m, x1, d1, b);
    if (inside_canvas(a, b, m->w, m->h))
        c->line(c, a[0], a[1], b[0], b[1], pen);
}

static void draw_frustum(const struct lesson_canvas *c, const struct staged *st, int w, int h,
                         const struct trace_event *last)
{
    const struct frustum *fr = &st->fr;
    /* depth shown: the triangle's, at least a few near planes, at most far */
    double dmax = 4 * fr->near;
    for (int k = 0; k < 3; k++)
        dmax = fmax(dmax, st->view.v[k].pos[2] * 1.15);
    dmax = fmin(dmax, fr->far * 1.08);
    struct top m = { w / 2.0, h * 0.95, h * 0.9 / dmax, w, h };
    double side = fr->aspect / fr->g;               /* x_v / d on the frustum's sides */
    double band = (GUARD_BAND / fr->half_w) * side; /* ... on the guard band's, about */
    c->polygon(c, (const double[][2]){ { 0, 0 }, { w, 0 }, { w, h }, { 0, h } }, 4,
               (struct pen){ .fill = INK_BACKING, .alpha = 0.8 });
    for (int s = -1; s <= 1; s += 2) {
        top_line(c, &m, 0, 0, s * side * dmax, dmax, (struct pen){ .stroke = INK_TEXT, .width = 1.5 });
        top_line(c, &m, 0, 0, s * band * dmax, dmax,
                 (struct pen){ .stroke = INK_PROBE, .width = 1, .dashed = true });
    }
    top_line(c, &m, -side * fr->near, fr->near, side * fr->near, fr->near,
             (struct pen){ .stroke = INK_MARK, .width = 2 });
    if (fr->far <= dmax)
        top_line(c, &m, -side * fr->far, fr->far, side * fr->far, fr->far,
                 (struct pen){ .stroke = INK_MARK, .width = 2 });
    double xy[POLY_MAX][2];
    for (int k = 0; k < st->clipped.n; k++)
        top_point(&m, st->clipped.v[k].pos[0], st->clipped.v[k].pos[2], xy[k]);
    if (st->clipped.n >= 3)
        clipped_polygon(c, (const double(*)[2])xy, st->clipped.n, w, h,
                        (struct pen){ .fill = INK_UPPER, .alpha = 0.45, .stroke = INK_UPPER, .width = 2 });
    for (int k = 0; k < 3; k++)
        top_point(&m, st->view.v[k].pos[0], st->view.v[k].pos[2], xy[k]);
    clipped_polygon(c, (const double(*)[2])xy, 3, w, h, (struct pen){ .stroke = INK_EDGE_AB, .width = 1.5 });
    static const enum ink vertex_ink[3] = { INK_VERTEX_A, INK_VERTEX_B, INK_VERTEX_C };
    static const char *const names[3] = { "A", "B", "C" };
    double u = c->unit;
    for (int k = 0; k < 3; k++) {
        c->disc(c, xy[k][0], xy[k][1], 4, (struct pen){ .fill = vertex_ink[k] });
        c->label(c, xy[k][0] + 6 * u, xy[k][1] - 8 * u, names[k], 12, INK_TEXT);
    }
    for (int k = 0; k < st->nmade; k++) {
        double q[2];
        top_point(&m, st->made[k].pos[0], st->made[k].pos[2], q);
        c->disc(c, q[0], q[1], 5, (struct pen){ .fill = INK_PROBE, .stroke = INK_OUTLINE });
        char text[32];
        snprintf(text, sizeof text, "t = %.3f", st->t[k]);
        c->label(c, q[0] + 7 * u, q[1] + 2 * u, text, 11, INK_PROBE);
    }
    if (last && last->kind == TRACE_FRONT && (last->klass == FRONT_NEW || last->klass == FRONT_VIEW
                                              || last->klass == FRONT_KEEP || last->klass == FRONT_DROP)) {
        double q[2];
        top_point(&m, last->aux[0], last->aux[2], q);
        c->disc(c, q[0], q[1], 9, (struct pen){ .stroke = INK_MARK, .width = 2.5 });
    }
    c->label(c, 6 * u, 6 * u, "from above: d up, x_v across; near and far solid, "
              "guard band dashed", 11, INK_TEXT);
    double e[2];
    top_point(&m, 0, 0, e);
    c->label(c, e[0] + 6 * u, e[1] - 16 * u, "eye", 11, INK_TEXT);
}

/* --- screen: zoomed out ------------------------------------------------------------ */

static void draw_screen(const struct lesson_canvas *c, const struct staged *st, int w, int h)
{
    /* zoom out until the projected polygon and the framebuffer fit, at most
     * until the guard band does */
    double reach = fmax(w, h) / 2.0;
    for (int k = 0; k < st->projected.n; k++)
        for (int a = 0; a < 2; a++)
            reach = fmax(reach, fabs(st->projected.v[k].pos[a] - (a ? h : w) / 2.0) * 1.1);
    reach = fmin(reach, GUARD_BAND * 1.15);
    double zoom = fmin(w, h) / 2.0 / reach;         /* canvas units per screen pixel */
    double cx = w / 2.0, cy = h / 2.0;
#define MAP(px, py) { cx + ((px) - w / 2.0) * zoom, cy + ((py) - h / 2.0) * zoom }
    c->polygon(c, (const double[][2]){ { 0, 0 }, { w, 0 }, { w, h }, { 0, h } }, 4,
               (struct pen){ .fill = INK_BACKING, .alpha = 0.8 });
    double band[4][2] = { MAP(-GUARD_BAND, -GUARD_BAND), MAP(GUARD_BAND, -GUARD_BAND),
                          MAP(GUARD_BAND, GUARD_BAND), MAP(-GUARD_BAND, GUARD_BAND) };
    clipped_polygon(c, (const double(*)[2])band, 4, w, h,
                    (struct pen){ .stroke = INK_PROBE, .dashed = true, .width = 1.5 });
    double fb[4][2] = { MAP(0, 0), MAP(w, 0), MAP(w, h), MAP(0, h) };
    c->polygon(c, (const double(*)[2])fb, 4, (struct pen){ .stroke = INK_MARK, .width = 2 });
    double xy[POLY_MAX][2];
    for (int k = 0; k < st->projected.n; k++) {
        double q[2] = MAP(st->projected.v[k].pos[0], st->projected.v[k].pos[1]);
        xy[k][0] = q[0], xy[k][1] = q[1];
    }
    if (st->projected.n >= 3)
        clipped_polygon(c, (const double(*)[2])xy, st->projected.n, w, h,
                        (struct pen){ .stroke = INK_EDGE_AB, .width = 1.5 });
    for (int k = 0; k < st->drawn.n; k++) {
        double q[2] = MAP(st->drawn.v[k].pos[0], st->drawn.v[k].pos[1]);
        xy[k][0] = q[0], xy[k][1] = q[1];
    }
    if (st->drawn.n >= 3)
        clipped_polygon(c, (const double(*)[2])xy, st->drawn.n, w, h,
                        (struct pen){ .fill = INK_UPPER, .alpha = 0.4, .stroke = INK_UPPER, .width = 2 });
#undef MAP
    char text[128];
    snprintf(text, sizeof text, "the screen zoomed out 1:%.0f: framebuffer solid, guard band "
             "[-16384, 16384) dashed", 1 / zoom);
    c->label(c, 6 * c->unit, 6 * c->unit, text, 11, INK_TEXT);
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    bool top = strcmp(c->view, "frustum") == 0, screen = strcmp(c->view, "screen") == 0;
    if ((!top && !screen) || !last || !p->scene)
        return;
    /* the world triangle told (a front-end step), or the focus's */
    const struct world *wd = &p->scene->world;
    int w = last->kind == TRACE_FRONT ? last->part
            : wd->from && last->tri < (uint32_t)p->scene->ntris ? wd->from[last->tri] : -1;
    struct staged st;
    if (!stage(p, w, &st))
        return;
    (void)t;
    if (top)
        draw_frustum(c, &st, p->scene->w, p->scene->h, last);
    else
        draw_screen(c, &st, p->scene->w, p->scene->h);
}

/* --- views ---------------------------------------------------------------------- */

/* The views that only draw over the canvas leave every cell faded. */
static bool no_cell(const struct tri_setup *t, const struct trace_event *test,
                    const struct trace_event *write, double rgb[3])
{
    (void)t, (void)test, (void)write, (void)rgb;
    return false;
}

/* How far the stored depth is from the exact one: black when they agree
 * to 10^-9, then blue, green, yellow, red at 10^-2 relative and beyond. */
static bool depth_error_cell(const struct tri_setup *t, const struct trace_event *test,
                             const struct trace_event *write, double rgb[3])
{
    if (!write || !test)
        return false;
    double exact, col[3], st[2], held;
    if (test->aux[2] > 0) {                 /* a depth variant: it told both */
        exact = test->aux[2];
        held = test->aux[3];
    } else {                                /* lesson 05's: the buffer holds d */
        reference_shade(t, write->x, write->y, true, &exact, col, st);
        held = write->z;
    }
    double err = fabs(held - exact) / exact;
    double v = err <= 1e-9 ? 0 : fmin(1, (log10(err) + 9) / 7);
    rgb[0] = fmin(1, 2 * v);
    rgb[1] = v < 0.5 ? 2 * v : 2 - 2 * v;
    rgb[2] = v < 0.3 ? v / 0.3 : fmax(0, 1 - (v - 0.3) / 0.3);
    if (v == 0)
        rgb[0] = rgb[1] = rgb[2] = 0.05;
    return true;
}

/* The stored value between near (white) and far (black), linearly: what
 * the storage spends on each depth shows as it is (NDC z of a far wall is
 * all but black, reversed float depth all but white). */
static bool stored_cell(const struct tri_setup *t, const struct trace_event *test,
                        const struct trace_event *write, double rgb[3])
{
    (void)t;
    if (!write || !test || !(test->aux[2] > 0))
        return false;
    double v = 1 - fmin(1, fmax(0, test->aux[4]));
    rgb[0] = rgb[1] = rgb[2] = v;
    return true;
}

static const struct lesson_view views[] = {
    { "frustum", "from above: the frustum, near and far, the guard band, the triangle and "
                 "the polygon left after clipping, new vertices with their t", no_cell },
    { "screen", "the screen zoomed out: the framebuffer, the guard band, the projected "
                "polygon and the polygon drawn", no_cell },
    { "stored", "the depth buffer's value between near (white) and far (black), linear: "
                "NDC z crowds into the black end; a depth variant's pixels only", stored_cell },
    { "depth-error", "stored depth against the exact d: black below 1e-9, blue 1e-7, "
                     "green 1e-5, red 1e-2 and more (relative)", depth_error_cell },
};

/* --- the watch panel ------------------------------------------------------------ */

static const char *plane_name(int id)
{
    static const char *const names[] = { "d >= near", "d <= far", "x >= -16384", "x <= 16383",
                                         "y >= -16384", "y <= 16383" };
    return id >= 0 && id < 6 ? names[id] : "?";
}

static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    (void)t;
    buf[0] = '\0';
    if (ev->kind != TRACE_FRONT)
        return;
    const float *a = ev->aux;
    switch ((enum front_step)ev->klass) {
    case FRONT_WORLD:
        snprintf(buf, n, "world triangle %d of %d\n", ev->part + 1, p->scene ? p->scene->world.ntris : 0);
        break;
    case FRONT_VIEW:
        snprintf(buf, n, "vertex %c in view space:\nx_v %.5g, y_v %.5g, d %.5g%s\n", 'A' + ev->x,
                 a[0], a[1], a[2], a[2] <= 0 ? "  (behind the eye)" : "");
        break;
    case FRONT_PLANE:
        snprintf(buf, n, "clip the %d-gon against %s (%.5g)\n", ev->y, plane_name(ev->x), a[0]);
        break;
    case FRONT_KEEP:
    case FRONT_DROP:
        snprintf(buf, n, "%s: vertex (%.5g, %.5g, %.5g) %s\n", plane_name(ev->x), a[0], a[1], a[2],
                 ev->klass == FRONT_KEEP ? "inside: kept" : "outside: dropped");
        break;
    case FRONT_NEW:
        snprintf(buf, n, "%s: the edge crosses it at t = %.6g\nnew vertex (%.6g, %.6g, %.6g)\n",
                 plane_name(ev->x), a[3], a[0], a[1], a[2]);
        break;
    case FRONT_PROJECT:
        snprintf(buf, n, "vertex %d projected: x_s %.6g, y_s %.6g, z = d %.5g\n", (int)a[3] + 1,
                 a[0], a[1], a[2]);
        break;
    case FRONT_GUARD:
        snprintf(buf, n, "%d vertices: %s\n", ev->y,
                 (ev->flags & TRACE_INSIDE) ? "inside the guard band, used as they are"
                                            : "beyond the guard band: clip x, y against it");
        break;
    case FRONT_TRIANGLE:
        snprintf(buf, n, "fan triangle %d: 2 x area %.6g px\u00b2 (%s): %s\n", ev->x + 1, a[0],
                 a[0] < 0 ? "front-facing" : a[0] > 0 ? "back-facing" : "zero",
                 (ev->flags & TRACE_INSIDE) ? "drawn" : "culled");
        break;
    case FRONT_STEP_COUNT:
        break;
    }
}

static void constants(const struct tri_setup *t, const struct raster_params *p, char *buf, size_t n)
{
    (void)t;
    const struct scene *s = p->scene;
    if (!s || !s->world.camera_line) {
        snprintf(buf, n, "a 2-D scene: no front end");
        return;
    }
    struct frustum fr;
    frustum_init(&fr, &s->world.cam, s->w, s->h);
    snprintf(buf, n, "near = %.5g, far = %.5g\ng = 1/tan(fovy/2) = %.5g, a = %.5g\n"
             "%d world triangles -> %d on screen", fr.near, fr.far, fr.g, fr.aspect,
             s->world.ntris, s->ntris);
}

const struct lesson_explorer lesson_06_explorer = {
    .lesson = &lesson_06,
    .views = views,
    .nviews = sizeof views / sizeof views[0],
    .overlay = overlay,
    .constants = constants,
    .watch = watch,
};
