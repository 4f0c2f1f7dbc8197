/* raster.c - snapping, triangle setup, the render target, the reference. */
#include "raster.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Round to the nearest integer, ties to even, for |v| < 2^51: adding
 * 1.5 * 2^52 pushes the fraction bits out of the double, which rounds in the
 * default rounding mode exactly as lrint() does; subtracting it again is
 * exact. Written out because lrint() is a library call, and every triangle
 * snaps six coordinates. Needs arithmetic in plain double precision
 * (FLT_EVAL_METHOD 0, as on x86-64); elsewhere lrint() itself. */
static double round_even(double v)
{
#if FLT_EVAL_METHOD == 0
    const double shift = 0x1.8p52;
    return (v + shift) - shift;
#else
    return (double)lrint(v);
#endif
}

int32_t snap_coord(double v, int bits)
{
    if (!(v > -COORD_LIMIT))            /* also catches NaN */
        v = -COORD_LIMIT;
    if (v > COORD_LIMIT)
        v = COORD_LIMIT;
    if (bits < 0)
        bits = 0;
    if (bits > SUBPIXEL_BITS)
        bits = SUBPIXEL_BITS;
    /* v * 2^bits is exact (|v| <= 2^14), so only the rounding rounds */
    double coarse = round_even(v * (double)(1 << bits));
    return (int32_t)coarse * (1 << (SUBPIXEL_BITS - bits));
}

static int64_t min3(int64_t a, int64_t b, int64_t c)
{
    int64_t m = a < b ? a : b;
    return m < c ? m : c;
}

static int64_t max3(int64_t a, int64_t b, int64_t c)
{
    int64_t m = a > b ? a : b;
    return m > c ? m : c;
}

bool tri_setup_bits(struct tri_setup *t, const struct vertex v[3], int w, int h, int bits)
{
    /* every field is set below (no memset: this runs once per triangle) */
    t->target_w = w;
    t->target_h = h;
    int32_t x[3], y[3];
    for (int i = 0; i < 3; i++) {
        x[i] = snap_coord(v[i].x, bits);
        y[i] = snap_coord(v[i].y, bits);
    }

    /* Orientation: twice the signed area is |AB x AC|. Negative means the
     * vertices run the other way round; taking B and C in the other order
     * makes every edge value positive inside, so one test serves both
     * windings. (An order to copy in, not a branch that swaps: the windings
     * of a scene's triangles come in any order.) */
    int64_t area2 = (int64_t)(x[1] - x[0]) * (y[2] - y[0])
                  - (int64_t)(y[1] - y[0]) * (x[2] - x[0]);
    t->swapped = area2 < 0;
    t->area2 = t->swapped ? -area2 : area2;
    int order[3] = { 0, t->swapped ? 2 : 1, t->swapped ? 1 : 2 };
    for (int i = 0; i < 3; i++) {
        t->v[i] = v[order[i]];
        t->x[i] = x[order[i]];
        t->y[i] = y[order[i]];
    }

    for (int k = 0; k < 3; k++) {
        int a = k, b = k == 2 ? 0 : k + 1;
        t->I[k] = (int64_t)t->y[a] - t->y[b];
        t->J[k] = (int64_t)t->x[b] - t->x[a];
        t->K[k] = (int64_t)t->x[a] * t->y[b] - (int64_t)t->y[a] * t->x[b];
        t->bias[k] = is_top_left(t->I[k], t->J[k]) ? 0 : -1;
    }

    /* Pixel px is a candidate when its centre px*256 + 128 lies in [xmin, xmax]. */
    int64_t minx = ceil_div(min3(t->x[0], t->x[1], t->x[2]) - SUBPIXEL_HALF, SUBPIXEL_ONE);
    int64_t maxx = floor_div(max3(t->x[0], t->x[1], t->x[2]) - SUBPIXEL_HALF, SUBPIXEL_ONE);
    int64_t miny = ceil_div(min3(t->y[0], t->y[1], t->y[2]) - SUBPIXEL_HALF, SUBPIXEL_ONE);
    int64_t maxy = floor_div(max3(t->y[0], t->y[1], t->y[2]) - SUBPIXEL_HALF, SUBPIXEL_ONE);
    t->minx = (int)(minx < 0 ? 0 : minx);
    t->miny = (int)(miny < 0 ? 0 : miny);
    t->maxx = (int)(maxx > w - 1 ? w - 1 : maxx);
    t->maxy = (int)(maxy > h - 1 ? h - 1 : maxy);

    t->empty = t->area2 == 0 || t->minx > t->maxx || t->miny > t->maxy;
    return !t->empty;
}

bool tri_setup(struct tri_setup *t, const struct vertex v[3], int w, int h)
{
    return tri_setup_bits(t, v, w, h, SUBPIXEL_BITS);
}

/* --- render target ------------------------------------------------------------ */

/* A buffer of the target on whole cache lines (64 bytes): the rows of a
 * target whose width is a multiple of 16 pixels then start on a line, so
 * that threads drawing neighbouring tiles (lesson 07) never share a line. */
static void *on_lines(size_t bytes)
{
    return aligned_alloc(64, (bytes + 63) / 64 * 64);
}

bool target_init(struct target *fb, int w, int h, uint32_t background)
{
    memset(fb, 0, sizeof *fb);
    if (w < 1 || h < 1 || w > TARGET_MAX || h > TARGET_MAX)
        return false;
    size_t n = (size_t)w * (size_t)h;
    fb->w = w;
    fb->h = h;
    fb->background = background;
    fb->color = on_lines(n * sizeof *fb->color);
    fb->depth = on_lines(n * sizeof *fb->depth);
    fb->count = on_lines(n);
    if (!fb->color || !fb->depth || !fb->count) {
        target_free(fb);
        return false;
    }
    target_clear(fb);
    return true;
}

void target_clear(struct target *fb)
{
    size_t n = (size_t)fb->w * (size_t)fb->h;
    for (size_t i = 0; i < n; i++) {
        fb->color[i] = fb->background;
        fb->depth[i] = INFINITY;
    }
    memset(fb->count, 0, n);
    if (fb->samples)
        for (size_t i = 0; i < n * (size_t)fb->samples->n; i++) {
            fb->samples->color[i] = fb->background;
            fb->samples->depth[i] = INFINITY;
        }
}

static void samples_free(struct target_samples *ms)
{
    if (ms) {
        free(ms->color);
        free(ms->depth);
        free(ms);
    }
}

void target_free(struct target *fb)
{
    free(fb->color);
    free(fb->depth);
    free(fb->count);
    samples_free(fb->samples);
    memset(fb, 0, sizeof *fb);
}

/* Storage for n samples of every pixel of fb, not yet cleared. */
static struct target_samples *samples_alloc(const struct target *fb, int n)
{
    size_t m = (size_t)fb->w * (size_t)fb->h * (size_t)n;
    struct target_samples *ms = calloc(1, sizeof *ms);
    if (!ms)
        return NULL;
    ms->n = n;
    ms->color = malloc(m * sizeof *ms->color);
    ms->depth = malloc(m * sizeof *ms->depth);
    if (!ms->color || !ms->depth) {
        samples_free(ms);
        return NULL;
    }
    return ms;
}

bool target_multisample(struct target *fb, int n)
{
    if (n <= 1) {
        samples_free(fb->samples);
        fb->samples = NULL;
        return true;
    }
    if (n > SAMPLES_MAX || !fb->color)
        return false;
    struct target_samples *ms = samples_alloc(fb, n);
    if (!ms)
        return false;
    samples_free(fb->samples);
    fb->samples = ms;
    size_t m = (size_t)fb->w * (size_t)fb->h * (size_t)n;
    for (size_t i = 0; i < m; i++) {
        ms->color[i] = fb->background;
        ms->depth[i] = INFINITY;
    }
    return true;
}

const struct sample_pattern *sample_pattern(int n)
{
    static const struct sample_pattern one = { 1, { 128 }, { 128 } };
    static const struct sample_pattern four = { 4, { 96, 224, 32, 160 }, { 32, 96, 160, 224 } };
    static const struct sample_pattern eight = {
        8, { 144, 112, 208, 80, 48, 16, 176, 240 }, { 80, 176, 144, 48, 208, 112, 240, 16 } };
    return n == 1 ? &one : n == 4 ? &four : n == 8 ? &eight : NULL;
}

const struct sample_pattern *sample_grid(int n)
{
    static const struct sample_pattern four = { 4, { 64, 192, 64, 192 }, { 64, 64, 192, 192 } };
    static const struct sample_pattern eight = {
        8, { 32, 96, 160, 224, 32, 96, 160, 224 }, { 64, 64, 64, 64, 192, 192, 192, 192 } };
    return n == 4 ? &four : n == 8 ? &eight : sample_pattern(n);
}

bool target_copy(struct target *dst, const struct target *src)
{
    if (dst->w != src->w || dst->h != src->h || !dst->color) {
        target_free(dst);
        if (!target_init(dst, src->w, src->h, src->background))
            return false;
    }
    size_t n = (size_t)src->w * (size_t)src->h;
    memcpy(dst->color, src->color, n * sizeof *dst->color);
    memcpy(dst->depth, src->depth, n * sizeof *dst->depth);
    memcpy(dst->count, src->count, n);
    dst->background = src->background;
    if (!src->samples)
        return target_multisample(dst, 1);
    if (!dst->samples || dst->samples->n != src->samples->n) {
        struct target_samples *ms = samples_alloc(dst, src->samples->n);
        if (!ms)
            return false;
        samples_free(dst->samples);
        dst->samples = ms;
    }
    size_t m = n * (size_t)src->samples->n;
    memcpy(dst->samples->color, src->samples->color, m * sizeof *dst->samples->color);
    memcpy(dst->samples->depth, src->samples->depth, m * sizeof *dst->samples->depth);
    return true;
}

/* --- reference ------------------------------------------------------------------ */

/* |P0P1 x P0P| (the edge-function notes, formula 2), P given in 1/256 units. */
static int64_t cross_at(int32_t x0, int32_t y0, int32_t x1, int32_t y1, int64_t px, int64_t py)
{
    return ((int64_t)x1 - x0) * (py - y0) - (px - x0) * ((int64_t)y1 - y0);
}

/* The bottom-right rule is the top-left rule of the edge walked the other
 * way: (I, J) becomes (-I, -J), so a right edge (I < 0) reads as left and
 * a bottom edge (I == 0, J < 0) as top. It is the top-left rule turned
 * half way round the screen, and keeps meshes watertight for the same
 * reason: a shared edge is walked one way by each of its two triangles, so
 * exactly one of them owns it under either rule. */
bool reference_edge_owns(enum fill_convention rule, int64_t I, int64_t J)
{
    return rule == FILL_BOTTOM_RIGHT ? is_top_left(-I, -J) : is_top_left(I, J);
}

bool reference_point_covered(const struct tri_setup *t, int64_t sx, int64_t sy)
{
    return reference_point_covered_rule(t, FILL_TOP_LEFT, sx, sy);
}

bool reference_point_covered_rule(const struct tri_setup *t, enum fill_convention rule,
                                  int64_t sx, int64_t sy)
{
    const int32_t *X = t->x, *Y = t->y;
    if (cross_at(X[0], Y[0], X[1], Y[1], X[2], Y[2]) <= 0)
        return false;   /* degenerate (setup normalised the orientation) */
    for (int k = 0; k < 3; k++) {
        int a = k, b = (k + 1) % 3;
        int64_t f = cross_at(X[a], Y[a], X[b], Y[b], sx, sy);
        bool on_edge_ok = f == 0 && reference_edge_owns(rule, (int64_t)Y[a] - Y[b], (int64_t)X[b] - X[a]);
        if (!(f > 0 || on_edge_ok))
            return false;
    }
    return true;
}

/* Sutherland-Hodgman: keep the part of polygon p (n points) where
 * sign * (coordinate axis) <= sign * bound; returns the new count. */
static int clip_polygon(double (*p)[2], int n, int axis, double bound, double sign)
{
    double out[10][2];
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = p[i], *b = p[(i + 1) % n];
        double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
        if (da <= 0)
            out[m][0] = a[0], out[m][1] = a[1], m++;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            double s = da / (da - db);
            out[m][0] = a[0] + s * (b[0] - a[0]);
            out[m][1] = a[1] + s * (b[1] - a[1]);
            m++;
        }
    }
    for (int i = 0; i < m; i++)
        p[i][0] = out[i][0], p[i][1] = out[i][1];
    return m;
}

double reference_pixel_area(const struct tri_setup *t, int px, int py)
{
    if (t->area2 <= 0)
        return 0;
    /* a triangle clipped by four half-planes has at most 7 corners */
    double p[10][2];
    for (int i = 0; i < 3; i++)
        p[i][0] = t->x[i] / (double)SUBPIXEL_ONE, p[i][1] = t->y[i] / (double)SUBPIXEL_ONE;
    int n = 3;
    n = clip_polygon(p, n, 0, px, -1);
    n = clip_polygon(p, n, 0, px + 1, 1);
    n = clip_polygon(p, n, 1, py, -1);
    n = clip_polygon(p, n, 1, py + 1, 1);
    double a = 0;
    for (int i = 0; i < n; i++)
        a += p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1];
    a = a < 0 ? -a / 2 : a / 2;
    return a > 1 ? 1 : a;
}

void reference_coverage(const struct tri_setup *t,
                        void (*cover)(void *ctx, int x, int y), void *ctx)
{
    reference_coverage_rule(t, FILL_TOP_LEFT, cover, ctx);
}

void reference_coverage_rule(const struct tri_setup *t, enum fill_convention rule,
                             void (*cover)(void *ctx, int x, int y), void *ctx)
{
    const int32_t *X = t->x, *Y = t->y;
    int64_t area2 = cross_at(X[0], Y[0], X[1], Y[1], X[2], Y[2]);
    if (area2 <= 0)   /* setup normalised the orientation: <= 0 means degenerate */
        return;

    /* A generous box: every pixel touched by the vertices' extent, one more
     * on each side, clamped to the target. Cheap to get right. */
    int64_t x0 = floor_div(min3(X[0], X[1], X[2]), SUBPIXEL_ONE) - 1;
    int64_t x1 = floor_div(max3(X[0], X[1], X[2]), SUBPIXEL_ONE) + 1;
    int64_t y0 = floor_div(min3(Y[0], Y[1], Y[2]), SUBPIXEL_ONE) - 1;
    int64_t y1 = floor_div(max3(Y[0], Y[1], Y[2]), SUBPIXEL_ONE) + 1;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > t->target_w - 1) x1 = t->target_w - 1;
    if (y1 > t->target_h - 1) y1 = t->target_h - 1;

    for (int64_t py = y0; py <= y1; py++) {
        for (int64_t px = x0; px <= x1; px++) {
            int64_t cx = px * SUBPIXEL_ONE + SUBPIXEL_HALF;
            int64_t cy = py * SUBPIXEL_ONE + SUBPIXEL_HALF;
            if (reference_point_covered_rule(t, rule, cx, cy))
                cover(ctx, (int)px, (int)py);
        }
    }
}

void reference_shade(const struct tri_setup *t, int px, int py, bool perspective,
                     double *z, double rgb[3], double st[2])
{
    int64_t f[3];
    for (int k = 0; k < 3; k++)
        f[k] = edge_value(t, k, px, py);
    double b[3];
    barycentric(t, f, b);
    const struct vertex *v = t->v;

    if (!perspective) {
        *z = b[0] * v[0].z + b[1] * v[1].z + b[2] * v[2].z;
        rgb[0] = b[0] * v[0].r + b[1] * v[1].r + b[2] * v[2].r;
        rgb[1] = b[0] * v[0].g + b[1] * v[1].g + b[2] * v[2].g;
        rgb[2] = b[0] * v[0].b + b[1] * v[1].b + b[2] * v[2].b;
        st[0] = b[0] * v[0].s + b[1] * v[1].s + b[2] * v[2].s;
        st[1] = b[0] * v[0].t + b[1] * v[1].t + b[2] * v[2].t;
        return;
    }
    /* 1/z is linear in screen space; so is a/z for any attribute a. */
    double q[3] = { b[0] / v[0].z, b[1] / v[1].z, b[2] / v[2].z };
    double inv_z = q[0] + q[1] + q[2];
    *z = 1.0 / inv_z;
    rgb[0] = (q[0] * v[0].r + q[1] * v[1].r + q[2] * v[2].r) * *z;
    rgb[1] = (q[0] * v[0].g + q[1] * v[1].g + q[2] * v[2].g) * *z;
    rgb[2] = (q[0] * v[0].b + q[1] * v[1].b + q[2] * v[2].b) * *z;
    st[0] = (q[0] * v[0].s + q[1] * v[1].s + q[2] * v[2].s) * *z;
    st[1] = (q[0] * v[0].t + q[1] * v[1].t + q[2] * v[2].t) * *z;
}
