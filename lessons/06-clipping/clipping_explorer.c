/* Lesson 06, what the explorer adds (compiled only in the narrated build;
 * the algorithm is clipping.c).
 *
 * Two views draw the front end of the world triangle told (or the focus
 * triangle's) in place of the canvas:
 *
 *   frustum  seen from above: the eye at the bottom, depth d up the canvas,
 *            x_v across, at one scale for both; the frustum's sides, the
 *            near and far planes, the guard band's sides (dashed, nearly
 *            flat: it is 256 screens wide), the triangle in view space, the
 *            polygon left after near and far, its new vertices with their t;
 *            when the near plane cuts close to the eye, a second panel
 *            shows that part magnified;
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
    const struct scene *s = drawn_scene(p);
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

/* --- drawing inside a rectangle of the canvas ------------------------------------- */

struct rect {
    double x0, y0, x1, y1;
};

/* Liang-Barsky: the part of a -> b inside r, false if none. */
static bool inside_rect(double a[2], double b[2], const struct rect *r)
{
    double t0 = 0, t1 = 1, d[2] = { b[0] - a[0], b[1] - a[1] };
    const double lo[2] = { r->x0, r->y0 }, hi[2] = { r->x1, r->y1 };
    for (int k = 0; k < 2; k++) {
        double p[2] = { -d[k], d[k] }, q[2] = { a[k] - lo[k], hi[k] - a[k] };
        for (int j = 0; j < 2; j++) {
            if (p[j] == 0) {
                if (q[j] < 0)
                    return false;
                continue;
            }
            double t = q[j] / p[j];
            if (p[j] < 0)
                t0 = fmax(t0, t);
            else
                t1 = fmin(t1, t);
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

static void rect_line(const struct lesson_canvas *c, const struct rect *r, const double a[2],
                      const double b[2], struct pen pen)
{
    double p[2] = { a[0], a[1] }, q[2] = { b[0], b[1] };
    if (inside_rect(p, q, r))
        c->line(c, p[0], p[1], q[0], q[1], pen);
}

/* A polygon of canvas points inside r only: filled where it lies inside
 * (cut by the very clipper of the lesson), its own edges outlined where
 * they run inside; no outline along r's border. */
static void rect_polygon(const struct lesson_canvas *c, const struct rect *r, const double (*xy)[2],
                         int n, struct pen pen)
{
    if (n < 3 || n > POLY_MAX - 4)
        return;
    struct poly p = { .n = n };
    for (int k = 0; k < n; k++)
        p.v[k] = (struct pvert){ .pos = { xy[k][0], xy[k][1], 1 } };
    clip_polygon_rect(&p, r->x0, r->y0, r->x1, r->y1);
    double out[POLY_MAX][2];
    for (int k = 0; k < p.n; k++)
        out[k][0] = p.v[k].pos[0], out[k][1] = p.v[k].pos[1];
    if (p.n >= 3 && pen.fill != INK_NONE)
        c->polygon(c, (const double(*)[2])out, p.n, (struct pen){ .fill = pen.fill, .alpha = pen.alpha });
    for (int k = 0; k < n && pen.stroke != INK_NONE; k++)
        rect_line(c, r, xy[k], xy[(k + 1) % n], (struct pen){ .stroke = pen.stroke, .width = pen.width,
                                                              .alpha = pen.alpha, .dashed = pen.dashed });
}

/* The views draw a picture of their own: an opaque backing hides the
 * canvas, the triangle's edges and its vertices' marks off the canvas. */
static void backing(const struct lesson_canvas *c, int w, int h)
{
    double m = 1e4 * c->unit;   /* past the explorer's whole canvas: it clips */
    c->polygon(c, (const double[][2]){ { -m, -m }, { w + m, -m }, { w + m, h + m }, { -m, h + m } }, 4,
               (struct pen){ .fill = INK_BACKING });
}

/* --- frustum: the view from above ------------------------------------------------ */

/* One panel of the view from above: view space (x_v across, d up) mapped
 * into the canvas rectangle r at one scale for both axes. */
struct top {
    struct rect r;
    double ox, oy, scale;       /* canvas point of the eye; canvas units per unit of view space */
};

/* Fit the box [x0, x1] x [d0, d1] of view space into r, with a margin. */
static struct top top_fit(struct rect r, double x0, double x1, double d0, double d1)
{
    double margin = 0.08 * fmin(r.x1 - r.x0, r.y1 - r.y0), top_room = 2 * margin;
    double sw = (r.x1 - r.x0 - 2 * margin) / fmax(x1 - x0, 1e-12);
    double sh = (r.y1 - r.y0 - margin - top_room) / fmax(d1 - d0, 1e-12);
    struct top m = { .r = r, .scale = fmin(sw, sh) };
    m.ox = (r.x0 + r.x1) / 2 - (x0 + x1) / 2 * m.scale;
    m.oy = (r.y0 + top_room + r.y1 - margin) / 2 + (d0 + d1) / 2 * m.scale;
    return m;
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
    rect_line(c, &m->r, a, b, pen);
}

static bool in_rect(const struct rect *r, const double p[2])
{
    return p[0] >= r->x0 && p[0] <= r->x1 && p[1] >= r->y0 && p[1] <= r->y1;
}

/* One panel: the frustum, near and far, the guard band's sides, the
 * triangle, the polygon left, the new vertices (with their t when `t_labels`)
 * and a ring on the vertex of the current step. */
static void top_panel(const struct lesson_canvas *c, const struct staged *st, const struct top *m,
                      const struct trace_event *last, bool t_labels, const char *title)
{
    const struct frustum *fr = &st->fr;
    double u = c->unit, reach = (m->r.y1 - m->r.y0 + m->r.x1 - m->r.x0) / m->scale;
    double side = fr->aspect / fr->g;               /* x_v / d on the frustum's sides */
    double band = (GUARD_BAND / fr->half_w) * side; /* ... on the guard band's, about */
    for (int s = -1; s <= 1; s += 2) {
        top_line(c, m, 0, 0, s * side * reach, reach, (struct pen){ .stroke = INK_TEXT, .width = 1.5 });
        top_line(c, m, 0, 0, s * band * reach, reach,
                 (struct pen){ .stroke = INK_PROBE, .width = 1, .dashed = true });
    }
    for (int k = 0; k < 2; k++) {                   /* near and far, as wide as the frustum */
        double d = k ? fr->far : fr->near;
        top_line(c, m, -side * d, d, side * d, d, (struct pen){ .stroke = INK_MARK, .width = 2 });
    }
    double xy[POLY_MAX][2];
    for (int k = 0; k < st->clipped.n; k++)
        top_point(m, st->clipped.v[k].pos[0], st->clipped.v[k].pos[2], xy[k]);
    rect_polygon(c, &m->r, (const double(*)[2])xy, st->clipped.n,
                 (struct pen){ .fill = INK_UPPER, .alpha = 0.45, .stroke = INK_UPPER, .width = 2 });
    for (int k = 0; k < 3; k++)
        top_point(m, st->view.v[k].pos[0], st->view.v[k].pos[2], xy[k]);
    rect_polygon(c, &m->r, (const double(*)[2])xy, 3, (struct pen){ .stroke = INK_EDGE_AB, .width = 1.5 });
    static const enum ink vertex_ink[3] = { INK_VERTEX_A, INK_VERTEX_B, INK_VERTEX_C };
    static const char *const names[3] = { "A", "B", "C" };
    for (int k = 0; k < 3; k++)
        if (in_rect(&m->r, xy[k])) {
            c->disc(c, xy[k][0], xy[k][1], 4, (struct pen){ .fill = vertex_ink[k] });
            c->label(c, xy[k][0] + 6 * u, xy[k][1] - 8 * u, names[k], 12, INK_TEXT);
        }
    for (int k = 0; k < st->nmade; k++) {
        double q[2];
        top_point(m, st->made[k].pos[0], st->made[k].pos[2], q);
        if (!in_rect(&m->r, q))
            continue;
        c->disc(c, q[0], q[1], 5, (struct pen){ .fill = INK_PROBE, .stroke = INK_OUTLINE });
        if (t_labels) {         /* outward: left of a vertex left of the axis, right of one right */
            char text[32];
            snprintf(text, sizeof text, "t = %.3f", st->t[k]);
            bool left = st->made[k].pos[0] < 0;
            c->label(c, q[0] + (left ? -70 : 9) * u, q[1] + 6 * u, text, 11, INK_PROBE);
        }
    }
    if (last && last->kind == TRACE_FRONT && last->x <= PLANE_FAR
        && (last->klass == FRONT_NEW || last->klass == FRONT_VIEW || last->klass == FRONT_KEEP
            || last->klass == FRONT_DROP)) {
        double q[2];
        top_point(m, last->aux[0], last->aux[2], q);
        if (in_rect(&m->r, q))
            c->disc(c, q[0], q[1], 9, (struct pen){ .stroke = INK_MARK, .width = 2.5 });
    }
    double e[2];
    top_point(m, 0, 0, e);
    if (in_rect(&m->r, e)) {    /* below the eye, away from the planes above it */
        c->disc(c, e[0], e[1], 3, (struct pen){ .fill = INK_TEXT });
        c->label(c, e[0] - 12 * u, e[1] + 6 * u, "eye", 11, INK_TEXT);
    }
    c->label(c, m->r.x0 + 6 * u, m->r.y0 + 6 * u, title, 11, INK_TEXT);
}

static void draw_frustum(const struct lesson_canvas *c, const struct staged *st, int w, int h,
                         const struct trace_event *last)
{
    const struct frustum *fr = &st->fr;
    /* the whole triangle: its box with the eye, at least a few near planes
     * deep, at most to far */
    double x0 = 0, x1 = 0, d0 = 0, d1 = 4 * fr->near;
    for (int k = 0; k < 3; k++) {
        const double *v = st->view.v[k].pos;
        x0 = fmin(x0, v[0]), x1 = fmax(x1, v[0]);
        d0 = fmin(d0, v[2]), d1 = fmax(d1, v[2]);
    }
    d1 = fmin(d1, fr->far * 1.04);
    /* near the eye: the new vertices on near, the vertices before it, the eye */
    double nx0 = -fr->aspect / fr->g * fr->near, nx1 = -nx0, nd0 = 0, nd1 = fr->near;
    int cut = 0;
    for (int k = 0; k < st->nmade; k++)
        if (fabs(st->made[k].pos[2] - fr->near) <= 1e-6 * fr->near) {     /* on near (told as floats) */
            nx0 = fmin(nx0, st->made[k].pos[0]), nx1 = fmax(nx1, st->made[k].pos[0]);
            cut++;
        }
    for (int k = 0; k < 3; k++) {
        const double *v = st->view.v[k].pos;
        if (v[2] < fr->near)
            nx0 = fmin(nx0, v[0]), nx1 = fmax(nx1, v[0]), nd0 = fmin(nd0, v[2]);
    }
    double pad = 0.2 * fmax(nx1 - nx0, nd1 - nd0);
    nx0 -= pad, nx1 += pad, nd0 -= pad, nd1 += pad;
    backing(c, w, h);
    struct rect all = { 0, 0, w, h };
    if (cut == 0 || (nd1 - nd0) * 4 > d1 - d0) {   /* nothing small to see near the eye */
        struct top one = top_fit(all, x0, x1, d0, d1);
        top_panel(c, st, &one, last, true,
                  "from above: d up, x_v across; near and far solid, guard band dashed");
        return;
    }
    /* two panels: the whole triangle, and near the eye magnified */
    struct rect left = { 0, 0, w * 0.42, h }, right = { w * 0.42, 0, w, h };
    struct top whole = top_fit(left, x0, x1, d0, d1), detail = top_fit(right, nx0, nx1, nd0, nd1);
    top_panel(c, st, &whole, last, false, "from above: d up, x_v across");
    top_panel(c, st, &detail, last, true, "near the eye, magnified");
    c->line(c, right.x0, 0, right.x0, h, (struct pen){ .stroke = INK_TEXT, .width = 1, .alpha = 0.5 });
    char text[64];
    snprintf(text, sizeof text, "x%.0f", detail.scale / whole.scale);
    c->label(c, right.x0 + 6 * c->unit, 22 * c->unit, text, 11, INK_TEXT);
    /* where the detail lies in the whole: its box */
    double b[4][2];
    top_point(&whole, nx0, nd0, b[0]), top_point(&whole, nx1, nd0, b[1]);
    top_point(&whole, nx1, nd1, b[2]), top_point(&whole, nx0, nd1, b[3]);
    rect_polygon(c, &left, (const double(*)[2])b, 4,
                 (struct pen){ .stroke = INK_MARK, .width = 1, .dashed = true });
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
    struct rect all = { 0, 0, w, h };
#define MAP(px, py) { cx + ((px) - w / 2.0) * zoom, cy + ((py) - h / 2.0) * zoom }
    backing(c, w, h);
    double band[4][2] = { MAP(-GUARD_BAND, -GUARD_BAND), MAP(GUARD_BAND, -GUARD_BAND),
                          MAP(GUARD_BAND, GUARD_BAND), MAP(-GUARD_BAND, GUARD_BAND) };
    bool band_seen = false;     /* a side of the band inside the canvas */
    for (int k = 0; k < 4; k++) {
        double a[2] = { band[k][0], band[k][1] }, b[2] = { band[(k + 1) % 4][0], band[(k + 1) % 4][1] };
        band_seen = band_seen || inside_rect(a, b, &all);
    }
    rect_polygon(c, &all, (const double(*)[2])band, 4,
                 (struct pen){ .stroke = INK_PROBE, .dashed = true, .width = 1.5 });
    double fb[4][2] = { MAP(0, 0), MAP(w, 0), MAP(w, h), MAP(0, h) };
    c->polygon(c, (const double(*)[2])fb, 4, (struct pen){ .stroke = INK_MARK, .width = 2 });
    double xy[POLY_MAX][2];
    for (int k = 0; k < st->projected.n; k++) {
        double q[2] = MAP(st->projected.v[k].pos[0], st->projected.v[k].pos[1]);
        xy[k][0] = q[0], xy[k][1] = q[1];
    }
    rect_polygon(c, &all, (const double(*)[2])xy, st->projected.n,
                 (struct pen){ .stroke = INK_EDGE_AB, .width = 1.5 });
    for (int k = 0; k < st->drawn.n; k++) {
        double q[2] = MAP(st->drawn.v[k].pos[0], st->drawn.v[k].pos[1]);
        xy[k][0] = q[0], xy[k][1] = q[1];
    }
    rect_polygon(c, &all, (const double(*)[2])xy, st->drawn.n,
                 (struct pen){ .fill = INK_UPPER, .alpha = 0.4, .stroke = INK_UPPER, .width = 2 });
#undef MAP
    char text[128];
    snprintf(text, sizeof text, "the screen zoomed out 1:%.0f: framebuffer solid, %s", 1 / zoom,
             band_seen ? "guard band [-16384, 16384) dashed" : "the guard band lies beyond the canvas");
    c->label(c, 6 * c->unit, 6 * c->unit, text, 11, INK_TEXT);
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    bool top = strcmp(c->view, "frustum") == 0, screen = strcmp(c->view, "screen") == 0;
    const struct scene *s = drawn_scene(p);
    if ((!top && !screen) || !last || !s)
        return;
    /* the world triangle told (a front-end step), or the focus's */
    const struct world *wd = &s->world;
    int w = last->kind == TRACE_FRONT ? last->part
            : wd->from && last->tri < (uint32_t)s->ntris ? wd->from[last->tri] : -1;
    struct staged st;
    if (!stage(p, w, &st))
        return;
    (void)t;
    if (top)
        draw_frustum(c, &st, s->w, s->h, last);
    else
        draw_screen(c, &st, s->w, s->h);
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

/* The stored value between what near (white) and far (black) store,
 * linearly: what the storage spends on each depth shows as it is. NDC z,
 * 1/d and reversed depth are each a + b/d, so all three show
 * (1/n - 1/d) / (1/n - 1/f) of the way to black: all but black a few near
 * planes from the eye. On builtin:room even the wall beside the eye, the
 * nearest surface, comes out dark. */
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
                "NDC z, 1/d and reversed depth alike crowd into the black end; a depth variant's "
                "pixels only", stored_cell },
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
        snprintf(buf, n, "world triangle %d of %d\n", ev->part + 1,
                 drawn_scene(p) ? drawn_scene(p)->world.ntris : 0);
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
    const struct scene *s = drawn_scene(p);
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
