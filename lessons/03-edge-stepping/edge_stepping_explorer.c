/* Lesson 03, what the explorer adds (compiled only in the narrated build;
 * the algorithm is edge_stepping.c).
 *
 * The watch panel's TRIANGLE section: I0k and J0k of each edge, raw (1/256
 * px) and in pixels, and the two steps the loop adds, 256 I0k to the right
 * and 256 J0k down. The canvas, in every view but the colour view: at the
 * current pixel, the two steps as arrows to the next centre right ("+I") and
 * below ("+J"); in the edges view also each edge's normal (I, J), the
 * direction in which its F grows, at the edge's middle in the edge's colour. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lesson_explorer.h"

static void constants(const struct tri_setup *t, const struct raster_params *p, char *buf,
                      size_t n)
{
    /* the overflow budget of the bits in use (README, "The overflow budget"):
     * |F| <= 8 R^2 keeps R below 2^14 units in 32 bits, 2^30 units in 64 */
    int bits = p->subpixel_bits;
    int w = snprintf(buf, n, "%d sub-pixel bits: |coordinates| < %ld px in 32-bit, "
                     "%ld px in 64-bit edges\n", bits, (1L << 14) >> bits, (1L << 30) >> bits);
    size_t at = w < 0 ? n : (size_t)w;
    for (int k = 0; k < 3 && at < n; k++) {
        int w = snprintf(buf + at, n - at, "I0%d = %lld (%.5g px), J0%d = %lld (%.5g px)\n", k + 1,
                         (long long)t->I[k], (double)t->I[k] / SUBPIXEL_ONE, k + 1,
                         (long long)t->J[k], (double)t->J[k] / SUBPIXEL_ONE);
        at = w < 0 ? n : at + (size_t)w;
    }
    if (at < n)
        snprintf(buf + at, n - at, "right: F0k += 256 I0k = %lld, %lld, %lld\n"
                 "down:  F0k += 256 J0k = %lld, %lld, %lld\n",
                 (long long)(t->I[0] * SUBPIXEL_ONE), (long long)(t->I[1] * SUBPIXEL_ONE),
                 (long long)(t->I[2] * SUBPIXEL_ONE), (long long)(t->J[0] * SUBPIXEL_ONE),
                 (long long)(t->J[1] * SUBPIXEL_ONE), (long long)(t->J[2] * SUBPIXEL_ONE));
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    (void)p;
    if (t->area2 <= 0 || strcmp(c->view, "color") == 0)
        return;
    if (strcmp(c->view, "edges") == 0) {
        static const enum ink edge_ink[3] = { INK_EDGE_AB, INK_EDGE_BC, INK_EDGE_CA };
        for (int k = 0; k < 3; k++) {
            int b = (k + 1) % 3;
            double mx = (t->x[k] + t->x[b]) / 2.0 / SUBPIXEL_ONE;
            double my = (t->y[k] + t->y[b]) / 2.0 / SUBPIXEL_ONE;
            double nx = (double)t->I[k], ny = (double)t->J[k], d = hypot(nx, ny);
            double len = 45 * c->unit;
            c->arrow(c, mx, my, mx + nx / d * len, my + ny / d * len, edge_ink[k]);
            char buf[40];
            snprintf(buf, sizeof buf, "(I0%d, J0%d)", k + 1, k + 1);
            c->label(c, mx + nx / d * len + 4 * c->unit, my + ny / d * len, buf, 10, edge_ink[k]);
        }
    }
    if (!last || (last->kind != TRACE_PIXEL_TEST && last->kind != TRACE_PIXEL_WRITE
                  && last->kind != TRACE_ROW))
        return;
    double x = last->x + 0.5, y = last->y + 0.5;
    /* from the current cell's border when cells are large enough to carry
     * numbers (the arrows would cover them), else from its centre */
    double from = c->unit < 1.0 / 20 ? 0.5 : 0;
    c->arrow(c, x + from, y, x + 1, y, INK_MARK);
    c->arrow(c, x, y + from, x, y + 1, INK_MARK);
    c->label(c, x + 1 + 3 * c->unit, y - 8 * c->unit, "+I", 11, INK_MARK);
    c->label(c, x + 3 * c->unit, y + 1 + 1 * c->unit, "+J", 11, INK_MARK);
}

extern const struct lesson lesson_03;

const struct lesson_explorer lesson_03_explorer = {
    .lesson = &lesson_03,
    .overlay = overlay,
    .constants = constants,
};
