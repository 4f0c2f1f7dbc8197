/* line.c - the diamond-exit rule for lines, exact (line.h). */
#include "line.h"

static int64_t min2(int64_t a, int64_t b)
{
    return a < b ? a : b;
}

static int64_t max2(int64_t a, int64_t b)
{
    return a > b ? a : b;
}

static int64_t abs64(int64_t a)
{
    return a < 0 ? -a : a;
}

static int clamp_int(int64_t v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : (int)v;
}

bool line_setup(struct line_setup *l, const struct vertex v[2], int w, int h)
{
    l->v[0] = v[0];
    l->v[1] = v[1];
    for (int i = 0; i < 2; i++) {
        l->x[i] = snap_coord(v[i].x, SUBPIXEL_BITS);
        l->y[i] = snap_coord(v[i].y, SUBPIXEL_BITS);
    }
    l->dx = (int64_t)l->x[1] - l->x[0];
    l->dy = (int64_t)l->y[1] - l->y[0];
    l->x_major = abs64(l->dx) >= abs64(l->dy);
    int64_t len2 = l->dx * l->dx + l->dy * l->dy;
    l->inv_len2 = len2 ? 1.0 / (double)len2 : 0;
    l->target_w = w;
    l->target_h = h;
    /* The moved segment's x runs over [min x + e, max x + e]: a diamond of
     * column px lies in x in (256 px, 256 px + 256), so the columns it may
     * meet are floor(min x / 256) .. floor(max x / 256); the same for rows. */
    int64_t x0 = floor_div(min2(l->x[0], l->x[1]), SUBPIXEL_ONE);
    int64_t x1 = floor_div(max2(l->x[0], l->x[1]), SUBPIXEL_ONE);
    int64_t y0 = floor_div(min2(l->y[0], l->y[1]), SUBPIXEL_ONE);
    int64_t y1 = floor_div(max2(l->y[0], l->y[1]), SUBPIXEL_ONE);
    l->minx = clamp_int(x0, 0, w - 1);
    l->maxx = clamp_int(x1, 0, w - 1);
    l->miny = clamp_int(y0, 0, h - 1);
    l->maxy = clamp_int(y1, 0, h - 1);
    l->empty = (l->dx == 0 && l->dy == 0) || x1 < 0 || x0 > w - 1 || y1 < 0 || y0 > h - 1;
    return !l->empty;
}

/* Half the diamond's width, 1/2 pixel. */
#define H SUBPIXEL_HALF

bool line_point_in_diamond(int64_t x, int64_t y, int px, int py)
{
    /* |X + e| + |Y + e^2| - 1/2 < 0, with X, Y the offsets from the centre:
     * |X + e| = |X| + sign(X) e, where X = 0 counts as positive (0 + e > 0),
     * and |Y + e^2| = |Y| + sign(Y) e^2 the same way. */
    int64_t X = x - pixel_centre(px), Y = y - pixel_centre(py);
    int64_t sx = X < 0 ? -1 : 1, sy = Y < 0 ? -1 : 1;
    return perturbed_sign(abs64(X) + abs64(Y) - H, sx, sy) < 0;
}

bool line_meets_diamond(const struct line_setup *l, int px, int py)
{
    const int64_t cx = pixel_centre(px), cy = pixel_centre(py);
    const int64_t ax = l->x[0], ay = l->y[0], bx = l->x[1], by = l->y[1];

    /* Axis (1, 1): x + y of a moved point is x + y + e + e^2. The diamond's
     * projection is the open interval (cx + cy - 1/2, cx + cy + 1/2), the
     * segment's the closed one between its ends'. They do not overlap iff
     * the segment's largest is at most the diamond's lower bound, or its
     * smallest at least the upper one. */
    int64_t s = cx + cy, smin = min2(ax + ay, bx + by), smax = max2(ax + ay, bx + by);
    if (perturbed_sign(smax - (s - H), 1, 1) <= 0 || perturbed_sign(smin - (s + H), 1, 1) >= 0)
        return false;

    /* Axis (1, -1): x - y moves by e - e^2. */
    int64_t d = cx - cy, dmin = min2(ax - ay, bx - by), dmax = max2(ax - ay, bx - by);
    if (perturbed_sign(dmax - (d - H), 1, -1) <= 0 || perturbed_sign(dmin - (d + H), 1, -1) >= 0)
        return false;

    /* The segment's normal n = (-dy, dx): the whole segment projects to the
     * one value n.(A + delta - c) = n.(A - c) - dy e + dx e^2, the diamond
     * to the open interval n.c +- (1/2) max(|dx|, |dy|) (its support is at
     * a corner). Disjoint iff that value lies at or beyond either bound. */
    int64_t v0 = -l->dy * (ax - cx) + l->dx * (ay - cy);
    int64_t m = H * max2(abs64(l->dx), abs64(l->dy));
    if (perturbed_sign(v0 - m, -l->dy, l->dx) >= 0 || perturbed_sign(v0 + m, -l->dy, l->dx) <= 0)
        return false;
    return true;
}

bool line_draws(const struct line_setup *l, int px, int py)
{
    return !l->empty && line_meets_diamond(l, px, py) &&
           !line_point_in_diamond(l->x[1], l->y[1], px, py);
}

void line_reference(const struct line_setup *l, void (*cover)(void *ctx, int x, int y), void *ctx)
{
    if (l->empty)
        return;
    for (int y = l->miny; y <= l->maxy; y++)
        for (int x = l->minx; x <= l->maxx; x++)
            if (line_draws(l, x, y))
                cover(ctx, x, y);
}

/* --- the walk: one pixel per column (or row) in the middle, the rule at the ends ---
 *
 * x-major (|dx| >= |dy|): a line of slope |m| <= 1 meets the diamond of
 * pixel (px, py) iff it crosses the column's centre line x = cx inside the
 * diamond's open vertical extent, cy - 1/2 < y < cy + 1/2, since
 * |t| + |Y + m t| >= |Y| for |m| <= 1 (the diamond is nearest the line at
 * its centre column). So the infinite line meets exactly one diamond per
 * column, the one where it crosses x = cx, and in every column strictly
 * between A's and B's that crossing is on the segment: those columns draw
 * it, no test needed. The first and last columns are where the segment may
 * stop short of the crossing, or end inside the diamond: there the pixel
 * the line crosses is decided by the rule itself (line_draws).
 *
 * The crossing row, exactly: the moved line at x = cx has
 *
 *     y = (ay dx + (cx - ax) dy) / dx  -  (dy / dx) e  +  e^2
 *
 * Multiplied by sign(dx) the numerator is n, over the positive |dx|. When n
 * is a multiple of 256 |dx| the line crosses exactly at a row boundary, and
 * the e term decides: it moves the crossing up (the row above) iff dy / dx
 * > 0, else down (dy = 0: e^2 moves it down). Hence bias = 1 iff dx dy > 0,
 * and row = floor((n - bias) / (256 |dx|)). Bresenham's error term is the
 * remainder, err = n - bias - row 256 |dx| in [0, 256 |dx|) (err / |dx| is
 * how far, in 1/256 pixel, the crossing lies below the row's top: the
 * error term in sub-pixels, kept whole by the factor |dx|). One column on
 * (256 units of x in the walk's direction) adds 256 dy to n, and the row
 * moves by at most one, as the error leaves [0, 256 |dx|).
 *
 * y-major is the same with x and y exchanged; the moved line at y = cy has
 * x = (...) / dy + e - (dx / dy) e^2, whose e term is always +1: a crossing
 * on a column boundary goes right, and the bias is 0. */
typedef void (*plot_fn)(void *ctx, int x, int y);

/* Compiled into each caller with its plot (always_inline, plot a
 * constant): line_draw's shading inlined in the loop, no call per pixel. */
static inline __attribute__((always_inline)) void
walk(const struct line_setup *l, plot_fn plot, void *ctx)
{
    if (l->empty)
        return;
    const bool xm = l->x_major;
    const int64_t au = xm ? l->x[0] : l->y[0], av = xm ? l->y[0] : l->x[0];
    const int64_t bu = xm ? l->x[1] : l->y[1];
    const int64_t du = xm ? l->dx : l->dy, dv = xm ? l->dy : l->dx;
    const int su = du > 0 ? 1 : -1;
    const int64_t step = SUBPIXEL_ONE * abs64(du);   /* 256 |du| */
    const int64_t bias = xm && du * dv > 0;
    const int nu = xm ? l->target_w : l->target_h, nv = xm ? l->target_h : l->target_w;

    /* The columns from A's to B's (rows, y-major), those on the target. */
    const int64_t first = floor_div(au, SUBPIXEL_ONE), last = floor_div(bu, SUBPIXEL_ONE);
    const int64_t lo = max2(min2(first, last), 0), hi = min2(max2(first, last), nu - 1);
    if (lo > hi)
        return;
    const int64_t start = su > 0 ? lo : hi, end = su > 0 ? hi : lo;

    /* The crossing at the first column walked, from scratch; then stepped. */
    int64_t n = (av * du + (pixel_centre((int)start) - au) * dv) * su - bias;
    int64_t v = floor_div(n, step), err = n - v * step;
    for (int64_t u = start;; u += su) {
        if (v >= 0 && v < nv) {
            int px = (int)(xm ? u : v), py = (int)(xm ? v : u);
            if ((u != first && u != last) || line_draws(l, px, py))
                plot(ctx, px, py);
        }
        if (u == end)
            break;
        err += SUBPIXEL_ONE * dv;
        if (err >= step)
            err -= step, v++;
        else if (err < 0)
            err += step, v--;
    }
}

void line_walk(const struct line_setup *l, void (*plot)(void *ctx, int x, int y), void *ctx)
{
    walk(l, plot, ctx);
}

/* --- drawing into a target ------------------------------------------------------ */

struct line_plot {
    const struct line_setup *l;
    struct target *fb;
    ptrdiff_t ahead;    /* PREFETCH_STEPS steps on along the line, in pixels of the target */
};

/* A long line visits a new row (a new cache line of colour and depth) at
 * every step of a y-major walk: asking for the pixel a few steps on while
 * this one is shaded hides most of the wait for memory. */
#define PREFETCH_STEPS 8

static void plot_shaded(void *ctx, int x, int y)
{
    const struct line_plot *p = ctx;
    size_t n = (size_t)p->fb->w * (size_t)p->fb->h;
    size_t next = (size_t)y * (size_t)p->fb->w + (size_t)x + (size_t)p->ahead;   /* wraps: unsigned */
    if (next < n) {
        __builtin_prefetch(p->fb->depth + next, 1);
        __builtin_prefetch(p->fb->color + next, 1);
    }
    double z, rgb[3];
    line_shade(p->l, x, y, &z, rgb);
    target_write(p->fb, x, y, (float)z, pack_rgb(rgb[0], rgb[1], rgb[2]));
}

void line_draw(const struct line_setup *l, struct target *fb)
{
    /* PREFETCH_STEPS steps on: along the major axis, and the minor's share */
    int64_t du = l->x_major ? l->dx : l->dy, dv = l->x_major ? l->dy : l->dx;
    int64_t su = du > 0 ? 1 : -1, dminor = du ? PREFETCH_STEPS * dv / (du * su) : 0;
    ptrdiff_t ahead = l->x_major ? (ptrdiff_t)(PREFETCH_STEPS * su + dminor * fb->w)
                                 : (ptrdiff_t)(PREFETCH_STEPS * su * fb->w + dminor);
    walk(l, plot_shaded, &(struct line_plot){ l, fb, ahead });
}
