/* Lesson 04, what the explorer adds (compiled only in the narrated build;
 * the algorithm is simd_perspective.c): four views of its own, and in the
 * lanes view the register of the pixel tested drawn beside it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lesson_explorer.h"

extern const struct lesson lesson_04;

/* What the lesson narrates in trace_event.aux[] (its aux_names): the four
 * lanes of the register, then the pixel's texture coordinates. */
enum { AUX_INV_Z, AUX_W, AUX_U, AUX_V, AUX_S, AUX_T };

/* A rectangle, x, y its top-left corner, in scene pixels. */
static void rect(const struct lesson_canvas *c, double x, double y, double w, double h,
                 struct pen pen)
{
    c->polygon(c, (const double[][2]){ { x, y }, { x + w, y }, { x + w, y + h }, { x, y + h } }, 4,
               pen);
}

/* "st": the texture coordinates (s, t) of each shown pixel as red and green.
 * On the floor the green rows crowd towards the horizon when perspective-
 * correct and spread evenly when affine. */
static bool st_cell(const struct tri_setup *t, const struct trace_event *test,
                    const struct trace_event *write, double rgb[3])
{
    (void)t;
    (void)write;
    if (!test || !(test->flags & TRACE_INSIDE))
        return false;
    rgb[0] = test->aux[AUX_S] < 0 ? 0 : test->aux[AUX_S] > 1 ? 1 : test->aux[AUX_S];
    rgb[1] = test->aux[AUX_T] < 0 ? 0 : test->aux[AUX_T] > 1 ? 1 : test->aux[AUX_T];
    rgb[2] = 0.3;
    return true;
}

/* "inv-z": lane 0 as brightness, 1 - exp(-2 / z): near is bright, and the
 * steps between rows are equal in 1/z, not in z. */
static bool inv_z_cell(const struct tri_setup *t, const struct trace_event *test,
                       const struct trace_event *write, double rgb[3])
{
    (void)t;
    (void)write;
    if (!test)
        return false;
    double g = test->aux[AUX_INV_Z] > 0 ? 1 - exp(-2.0 * test->aux[AUX_INV_Z]) : 0;
    bool in = test->flags & TRACE_INSIDE;
    rgb[0] = rgb[1] = rgb[2] = in ? g : 0.4 * g;
    return true;
}

/* "affine-error": how far affine texturing lands from the correct (s, t) at
 * each covered pixel, from the lanes (w, u, v are the screen-space weights):
 *
 *     affine  s = u sA + v sB + w sC
 *     correct s = (u sA/ZA + v sB/ZB + w sC/ZC) / (u/ZA + v/ZB + w/ZC)    (23)
 *
 * black where they agree, through red to yellow at AFFINE_ERROR_FULL or more
 * (texture units: the whole texture is 1 wide). */
#define AFFINE_ERROR_FULL 0.25

static bool affine_error_cell(const struct tri_setup *t, const struct trace_event *test,
                              const struct trace_event *write, double rgb[3])
{
    (void)write;
    if (!test || !(test->flags & TRACE_INSIDE))
        return false;
    const struct vertex *A = &t->v[0], *B = &t->v[1], *C = &t->v[2];
    double w = test->aux[AUX_W], u = test->aux[AUX_U], v = test->aux[AUX_V];
    double qa = u / A->z, qb = v / B->z, qc = w / C->z, inv_z = qa + qb + qc;
    double ds = (u * A->s + v * B->s + w * C->s) - (qa * A->s + qb * B->s + qc * C->s) / inv_z;
    double dt = (u * A->t + v * B->t + w * C->t) - (qa * A->t + qb * B->t + qc * C->t) / inv_z;
    double e = sqrt(ds * ds + dt * dt) / AFFINE_ERROR_FULL;
    e = e > 1 ? 1 : e;
    rgb[0] = e < 0.5 ? 2 * e : 1;
    rgb[1] = e < 0.5 ? 0 : 2 * e - 1;
    rgb[2] = 0.1;
    return true;
}

/* "lanes": the register of the pixel being tested, drawn lane by lane beside
 * it, each lane a labelled bar with the scalar it stands for:
 *
 *     +--------+--------+--------+--------+
 *     |  1/z   |   w    |   u    |   v    |    one __m128: Cx
 *     +--------+--------+--------+--------+
 *      depth     weight   weight   weight
 *      z = 1/lane0  of C   of A     of B
 *
 * w, u, v run from 0 to 1 inside the triangle; the 1/z bar is drawn against
 * the largest 1/z of the three vertices (the nearest one). The cells show
 * w, u, v as blue, red, green, like the vertices they weigh. */
static bool lanes_cell(const struct tri_setup *t, const struct trace_event *test,
                       const struct trace_event *write, double rgb[3])
{
    (void)t;
    (void)write;
    if (!test)
        return false;
    double k = test->flags & TRACE_INSIDE ? 0.8 : 0.25;
    rgb[0] = k * fmin(fmax(test->aux[AUX_U], 0), 1);
    rgb[1] = k * fmin(fmax(test->aux[AUX_V], 0), 1);
    rgb[2] = k * fmin(fmax(test->aux[AUX_W], 0), 1);
    return true;
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    (void)p;
    if (strcmp(c->view, "lanes") != 0 || !last || last->kind != TRACE_PIXEL_TEST
        || t->area2 <= 0)
        return;
    static const char *const name[4] = { "1/z", "w", "u", "v" };
    static const enum ink ink[4] = { INK_TEXT, INK_VERTEX_C, INK_VERTEX_A, INK_VERTEX_B };
    double max_inv_z = fmax(fmax(1 / t->v[0].z, 1 / t->v[1].z), 1 / t->v[2].z);
    double u = c->unit, bw = 46 * u, bh = 70 * u;
    double x0 = last->x + 1.5, base = last->y + 0.5 + bh / 2;
    rect(c, x0 - 6 * u, base - bh - 30 * u, 4 * bw + 12 * u, bh + 58 * u,
         (struct pen){ .fill = INK_BACKING, .alpha = 0.9 });
    for (int i = 0; i < 4; i++) {
        double v = last->aux[i], full = i == AUX_INV_Z ? max_inv_z : 1;
        double f = fmin(fmax(v / full, 0), 1);
        double x = x0 + i * bw;
        rect(c, x + 6 * u, base - f * bh, bw - 12 * u, f * bh, (struct pen){ .fill = ink[i] });
        rect(c, x + 6 * u, base - bh, bw - 12 * u, bh, (struct pen){ .stroke = ink[i] });
        char buf[32];
        snprintf(buf, sizeof buf, "%.2f", v);
        c->label(c, x + 4 * u, base - bh - 24 * u, buf, 10, ink[i]);
        c->label(c, x + 10 * u, base + 4 * u, name[i], 11, ink[i]);
    }
    char z[48];
    snprintf(z, sizeof z, "z = 1/lane 0 = %.4g", last->aux[AUX_INV_Z] > 0 ? 1 / last->aux[AUX_INV_Z] : 0);
    c->label(c, x0, base + 18 * u, z, 10, INK_TEXT);
}

static const struct lesson_view views[] = {
    { "lanes", "the register (1/z, w, u, v) of the pixel tested, as bars; cells: u, v, w as "
               "red, green, blue", lanes_cell },
    { "st", "texture coordinates s (red), t (green) of the pixels that show", st_cell },
    { "inv-z", "lane 0, 1/z, as brightness: brighter is nearer; dim outside", inv_z_cell },
    { "affine-error", "|affine - correct| of (s, t): black 0, red, yellow 0.25 or more",
      affine_error_cell },
};

const struct lesson_explorer lesson_04_explorer = {
    .lesson = &lesson_04,
    .views = views,
    .nviews = sizeof views / sizeof views[0],
    .overlay = overlay,
};
