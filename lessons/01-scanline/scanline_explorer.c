/* Lesson 01, what the explorer adds (compiled only in the narrated build;
 * the algorithm is scanline.c).
 *
 * The watch panel: for a row or span, where the row's centre line crosses
 * the triangle's left and right sides and the prestep from the left crossing
 * to the first centre; in its TRIANGLE section the per-row x increments of
 * the three edges (formulas (2)-(4) with c = x), the per-pixel colour and
 * depth increments across a span (formula (1)), and the case. The canvas: in
 * the spans view the upper and lower halves of the triangle in two tints and
 * the gradients of luminance and z as arrows from the centroid; in every view
 * but the colour view the current scanline with its two edge crossings.
 *
 * Everything here is worked out from the triangle's snapped vertices, the
 * way the tutorial's formulas read, not by running the walk again. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lesson_explorer.h"

extern const struct lesson lesson_01;

/* Vertices 1, 2, 3 as the walk names them: 1 on top, the order kept. */
static void walk_order(const struct tri_setup *t, int v[3])
{
    int top = 0;
    if (t->y[1] < t->y[top])
        top = 1;
    if (t->y[2] < t->y[top])
        top = 2;
    for (int i = 0; i < 3; i++)
        v[i] = (top + i) % 3;
}

/* The attributes the panel names, of vertex i. */
enum { ATTR_Z, ATTR_R, ATTR_G, ATTR_B, ATTR_COUNT };

static double attr(const struct tri_setup *t, int i, int a)
{
    const struct vertex *v = &t->v[i];
    return a == ATTR_Z ? v->z : a == ATTR_R ? v->r : a == ATTR_G ? v->g : v->b;
}

/* The change of attribute a per pixel in x (formula (1)) and in y (its
 * companion), from the plane through the three vertices. */
static void gradient(const struct tri_setup *t, const int v[3], int a, double *dx, double *dy)
{
    double x21 = (double)(t->x[v[1]] - t->x[v[0]]), x31 = (double)(t->x[v[2]] - t->x[v[0]]);
    double y21 = (double)(t->y[v[1]] - t->y[v[0]]), y31 = (double)(t->y[v[2]] - t->y[v[0]]);
    double c21 = attr(t, v[1], a) - attr(t, v[0], a), c31 = attr(t, v[2], a) - attr(t, v[0], a);
    *dx = (c21 * y31 - c31 * y21) * SUBPIXEL_ONE / (double)t->area2;
    *dy = (c31 * x21 - c21 * x31) * SUBPIXEL_ONE / (double)t->area2;
}

/* x per row along p -> q, in pixels; false for a horizontal edge. */
static size_t put(char *buf, size_t n, size_t at, const char *name, const struct tri_setup *t,
                  int p, int q)
{
    if (at >= n)
        return at;
    int k = t->y[p] == t->y[q]
                ? snprintf(buf + at, n - at, "%s = flat", name)
                : snprintf(buf + at, n - at, "%s = %.4g", name,
                           (double)(t->x[q] - t->x[p]) / (double)(t->y[q] - t->y[p]));
    return k < 0 ? at : at + (size_t)k;
}

static void constants(const struct tri_setup *t, const struct raster_params *p, char *buf,
                      size_t n)
{
    (void)p;
    int v[3];
    walk_order(t, v);
    double dc[ATTR_COUNT], unused;
    for (int a = 0; a < ATTR_COUNT; a++)
        gradient(t, v, a, &dc[a], &unused);
    size_t at = 0;
    buf[0] = '\0';
    at = put(buf, n, at, "Dc12", t, v[0], v[1]);
    at = put(buf, n, at, ", Dc13", t, v[0], v[2]);
    at = put(buf, n, at, ", Dc23", t, v[1], v[2]);
    if (at < n)
        snprintf(buf + at, n - at,
                 " px/row\n"
                 "Dc r = %.4g, g = %.4g, b = %.4g, z = %.4g /px\n"
                 "case = %s\n"
                 "walk: 1 = %c (top), 2 = %c, 3 = %c\n",
                 dc[ATTR_R], dc[ATTR_G], dc[ATTR_B], dc[ATTR_Z],
                 t->y[v[1]] > t->y[v[2]] ? "[A] (3 is the middle vertex, on the left)"
                                         : "[B] (2 is the middle vertex, on the right)",
                 'A' + v[0], 'A' + v[1], 'A' + v[2]);
}

/* Where the centre line of row y crosses the triangle's left and right
 * sides, in pixels; false when it misses the triangle. */
static bool row_crossings(const struct tri_setup *t, int y, double *xl, double *xr)
{
    double yc = (double)pixel_centre(y);
    int n = 0;
    double x[3];
    for (int k = 0; k < 3; k++) {
        int b = (k + 1) % 3;
        double y0 = t->y[k], y1 = t->y[b], x0 = t->x[k], x1 = t->x[b];
        if (y0 == y1 || yc < fmin(y0, y1) || yc > fmax(y0, y1))
            continue;
        x[n++] = (x0 + (x1 - x0) * (yc - y0) / (y1 - y0)) / SUBPIXEL_ONE;
    }
    if (n < 2)
        return false;
    *xl = fmin(fmin(x[0], x[1]), x[n - 1]);
    *xr = fmax(fmax(x[0], x[1]), x[n - 1]);
    return true;
}

/* A row or span: its two crossings, and the span's prestep from the left
 * crossing to its first centre. */
static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    (void)p;
    buf[0] = '\0';
    double xl, xr;
    if ((ev->kind != TRACE_ROW && ev->kind != TRACE_SPAN) || !row_crossings(t, ev->y, &xl, &xr))
        return;
    if (ev->kind == TRACE_SPAN)
        snprintf(buf, n, "x_left %.6g, x_right %.6g, prestep %.6g\n", xl, xr, ev->x + 0.5 - xl);
    else
        snprintf(buf, n, "x_left %.6g, x_right %.6g\n", xl, xr);
}

/* Where the overlay's names go: the first of a few places beside a point
 * that covers nothing already drawn (the current scanline and its crossings,
 * the vertices' handles and names, the names placed before). Rectangles in
 * scene pixels. */
struct spot {
    double x0, y0, x1, y1;
};

struct spots {
    struct spot taken[16];
    int n;
};

static bool spot_free(const struct spots *sp, struct spot r)
{
    for (int i = 0; i < sp->n; i++) {
        const struct spot *o = &sp->taken[i];
        if (r.x0 < o->x1 && o->x0 < r.x1 && r.y0 < o->y1 && o->y0 < r.y1)
            return false;
    }
    return true;
}

static void spot_take(struct spots *sp, struct spot r)
{
    if (sp->n < (int)(sizeof sp->taken / sizeof sp->taken[0]))
        sp->taken[sp->n++] = r;
}

/* A name (10 px text) near scene point (x, y): on the preferred side of it
 * (left or right, above or below), else on another, whichever is free first. */
static void place_label(const struct lesson_canvas *c, struct spots *sp, double x, double y,
                        const char *name, enum ink ink, bool left, bool above)
{
    double u = c->unit, w = (6.5 * (double)strlen(name) + 6) * u, h = 15 * u;
    double xs[2] = { x + 6 * u, x - w - 6 * u }, ys[2] = { y + 4 * u, y - h - 4 * u };
    double at[6][2];
    int n = 0;
    for (int i = 0; i < 2; i++)             /* the preferred side first, in x then y */
        for (int j = 0; j < 2; j++)
            at[n][0] = xs[(i + left) % 2], at[n][1] = ys[(j + above) % 2], n++;
    at[n][0] = x - w / 2, at[n][1] = y + 10 * u, n++;
    at[n][0] = x - w / 2, at[n][1] = y - h - 10 * u, n++;
    int pick = 0;
    for (int i = 0; i < n; i++)
        if (spot_free(sp, (struct spot){ at[i][0], at[i][1], at[i][0] + w, at[i][1] + h })) {
            pick = i;
            break;
        }
    spot_take(sp, (struct spot){ at[pick][0], at[pick][1], at[pick][0] + w, at[pick][1] + h });
    c->label(c, at[pick][0], at[pick][1], name, 10, ink);
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    (void)p;
    if (t->area2 <= 0)
        return;
    int v[3];
    walk_order(t, v);
    bool case_a = t->y[v[1]] > t->y[v[2]];
    int mid = case_a ? v[2] : v[1], bottom = case_a ? v[1] : v[2];
    double s = 1.0 / SUBPIXEL_ONE, u = c->unit;
    double x1 = t->x[v[0]] * s, y1 = t->y[v[0]] * s, xm = t->x[mid] * s, ym = t->y[mid] * s;
    double xb = t->x[bottom] * s, yb = t->y[bottom] * s;
    /* point A of "Draw X": the long edge 1 -> bottom at the middle vertex's height */
    double xa = yb > y1 ? x1 + (xb - x1) * (ym - y1) / (yb - y1) : xm;

    /* what the names must not cover: the vertices with their handles and
     * names (drawn by the explorer about 16 screen pixels out), the current
     * scanline with its crossings and their values */
    struct spots sp = { .n = 0 };
    for (int k = 0; k < 3; k++) {
        double vx = t->x[k] * s, vy = t->y[k] * s;
        spot_take(&sp, (struct spot){ vx - 30 * u, vy - 30 * u, vx + 30 * u, vy + 30 * u });
    }
    double xl = 0, xr = 0, yc = 0;
    bool scan = last && strcmp(c->view, "color") != 0
                && (last->kind == TRACE_ROW || last->kind == TRACE_SPAN)
                && row_crossings(t, last->y, &xl, &xr);
    if (scan) {
        yc = last->y + 0.5;
        spot_take(&sp, (struct spot){ t->minx, yc - 7 * u, t->maxx + 1, yc + 22 * u });
        spot_take(&sp, (struct spot){ xl - 72 * u, yc - 7 * u, xr + 80 * u, yc + 22 * u });
    }

    if (strcmp(c->view, "spans") == 0) {
        c->polygon(c, (const double[][2]){ { x1, y1 }, { xm, ym }, { xa, ym } }, 3,
                   (struct pen){ .fill = INK_UPPER, .alpha = 0.30 });
        c->polygon(c, (const double[][2]){ { xm, ym }, { xa, ym }, { xb, yb } }, 3,
                   (struct pen){ .fill = INK_LOWER, .alpha = 0.28 });
        c->line(c, xm, ym, xa, ym,
                (struct pen){ .stroke = INK_MARK, .width = 1.5, .alpha = 0.8, .dashed = true });

        /* gradients: luminance (formula (1) and its y companion) and z */
        double gx = (x1 + xm + xb) / 3, gy = (y1 + ym + yb) / 3;
        double d[ATTR_COUNT][2];
        for (int a = 0; a < ATTR_COUNT; a++)
            gradient(t, v, a, &d[a][0], &d[a][1]);
        double lx = 0.299 * d[ATTR_R][0] + 0.587 * d[ATTR_G][0] + 0.114 * d[ATTR_B][0];
        double ly = 0.299 * d[ATTR_R][1] + 0.587 * d[ATTR_G][1] + 0.114 * d[ATTR_B][1];
        const struct { double x, y; const char *name; enum ink ink; } arrows[2] = {
            { lx, ly, "brighter", INK_BRIGHTER }, { d[ATTR_Z][0], d[ATTR_Z][1], "z grows", INK_DEEPER },
        };
        double len = 70 * u;
        double tip[2][2];
        bool shown[2] = { false, false };
        for (int k = 0; k < 2; k++) {
            double h = hypot(arrows[k].x, arrows[k].y);
            if (!(h > 0))
                continue;
            tip[k][0] = gx + arrows[k].x / h * len, tip[k][1] = gy + arrows[k].y / h * len;
            c->arrow(c, gx, gy, tip[k][0], tip[k][1], arrows[k].ink);
            shown[k] = true;
        }
        /* the names on top: the halves at the line between them, outside the
         * triangle, then the arrows' at their tips */
        double hx = case_a ? fmax(xm, xa) : fmin(xm, xa);   /* beside point A, outside */
        place_label(c, &sp, hx, ym, "upper", INK_UPPER, !case_a, true);
        place_label(c, &sp, hx, ym, "lower", INK_LOWER, !case_a, false);
        for (int k = 0; k < 2; k++)
            if (shown[k])
                place_label(c, &sp, tip[k][0], tip[k][1], arrows[k].name, arrows[k].ink,
                            arrows[k].x < 0, arrows[k].y < 0);
    }

    /* the current scanline and where its centre line crosses the two edges */
    if (!scan)
        return;
    c->line(c, t->minx, yc, t->maxx + 1, yc, (struct pen){ .stroke = INK_MARK, .width = 1.5, .alpha = 0.85 });
    const struct { double x; const char *name; } at[2] = { { xl, "xl" }, { xr, "xr" } };
    for (int k = 0; k < 2; k++) {
        c->disc(c, at[k].x, yc, 5, (struct pen){ .fill = INK_PROBE, .stroke = INK_OUTLINE, .width = 1.5 });
        char buf[32];
        snprintf(buf, sizeof buf, "%s %.3f", at[k].name, at[k].x);
        double lx = k ? at[k].x + 8 * u : at[k].x - 68 * u;
        c->label(c, lx, yc + 6 * u, buf, 10, INK_PROBE);
    }
}

const struct lesson_explorer lesson_01_explorer = {
    .lesson = &lesson_01,
    .overlay = overlay,
    .constants = constants,
    .watch = watch,
};
