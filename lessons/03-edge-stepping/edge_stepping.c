/* Lesson 03: incremental edge functions.
 *
 * What it shows: lesson 02's loop without its multiplications. An edge
 * function is linear in x and y (seed 001, sections 2 and 3):
 *
 *     F01(Px, Py) = I01 * Px + J01 * Py + K01                          (6)
 *     F02(Px, Py) = I02 * Px + J02 * Py + K02                          (7)
 *     F03(Px, Py) = I03 * Px + J03 * Py + K03                          (8)
 *
 * so one step to the right adds I and one step down adds J:
 *
 *     F01(Px+1, Py) - F01(Px, Py) = I01                                (9)
 *     F01(Px, Py+1) - F01(Px, Py) = J01                                (10)
 *
 * Evaluate the three edge functions once, at the centre of the first pixel
 * of the bounding box; from there on every pixel costs three additions. The
 * colour and depth are linear too, so they are stepped the same way.
 *
 * New since lesson 02: nothing about WHICH pixels are covered (the coverage
 * is identical, pixel for pixel, on every triangle), only HOW the edge
 * values are obtained: by additions instead of products. Two details make it
 * exact rather than approximately right:
 *
 *   - the edge values are integers (1/65536 px^2) and the increments are
 *     integers, so a thousand additions land exactly where one evaluation
 *     would; the exhibit "float" does the same loop in single precision and
 *     loses pixels on a large triangle;
 *   - the top-left rule's bias is added to the constant term K once, so the
 *     test in the loop is a bare ">= 0" on all three edges.
 *
 * Units. Vertices and pixel centres are in 1/256 pixel, so "one pixel to the
 * right" is Px + 256 and the step of formula (9) is 256 * I01 in our units:
 *
 *       pixel x        pixel x+1
 *     +---------+    +---------+
 *     |    o----|----|--->o    |     F(x+1) = F(x) + 256 * I01
 *     +---------+    +---------+     (a centre is 256 units further on)
 *
 * Edge numbering is the seed's: 01 = AB, 02 = BC, 03 = CA. The coefficients
 * come from the shared setup (src/raster/raster.h: t->I, t->J, t->K, t->bias,
 * the edge functions lesson 02 explains), here called by the seed's names.
 */
#include "lesson.h"

#include <stdio.h>
#include <string.h>

static const char *const pseudocode[] = {
    "snap A, B, C; I0k, J0k, K0k of edges 01, 02, 03 (6)-(8)",  /* 0 */
    "K0k += bias0k   (top-left rule: 0 or -1)",                 /* 1 */
    "F0k = I0k * minX + J0k * minY + K0k   (first centre)",     /* 2 */
    "Cy0k = F0k",                                               /* 3 */
    "loop y = minY to maxY:",                                   /* 4 */
    "  Cx0k = Cy0k;  u, v, w = Cx02, Cx03, Cx01 / area2  (13)-(15)", /* 5 */
    "  loop x = minX to maxX:",                                 /* 6 */
    "    if Cx01 >= 0 and Cx02 >= 0 and Cx03 >= 0:",            /* 7 */
    "      Render(x, y) with colour, z",                        /* 8 */
    "    Cx0k += 256 I0k;  colour, z += d/dx   (9)",            /* 9 */
    "  Cy0k += 256 J0k   (10)",                                 /* 10 */
    NULL,
};

enum { L_SETUP, L_BIAS, L_FIRST, L_CY, L_LOOP_Y, L_ROW, L_LOOP_X, L_TEST, L_RENDER,
       L_STEP_X, L_STEP_Y };

/* The watch panel's values: what is being stepped besides the edge values. */
static const char *const aux_names[] = { "z", "r", "g", "b", "s", "t", NULL };

/* --- the attributes: z, r, g, b, s, t, stepped like the edge values ------------ */

/* Any attribute P at a point is u P_A + v P_B + w P_C (11) with
 *
 *     u = F02 / area2,  v = F03 / area2,  w = F01 / area2        (13)-(15)
 *
 * (area2 = F01 + F02 + F03, the same at every point). u, v and w are linear,
 * so P is: one pixel to the right it changes by
 *
 *     dP/dx = (256 I02 P_A + 256 I03 P_B + 256 I01 P_C) / area2
 *
 * a constant of the triangle. Stepping P itself (one addition) is cheaper
 * than stepping u, v, w and mixing them (three multiplications).
 *
 * The sums are in double precision and drift by a rounding error per step;
 * every row restarts them exactly from the integer edge values of its first
 * pixel, so the drift never crosses a row (at most 16384 steps: about 1e-12,
 * see the README).
 *
 * The six values travel as one small struct, passed and returned by value:
 * the compiler keeps a local one in registers for the whole row. */
struct attrs {
    double z, r, g, b, s, t;
};

#define NATTR 6     /* members of struct attrs */

/* u A + v B + w C, member by member: (11) */
static inline struct attrs attrs_mix(double u, struct attrs A, double v, struct attrs B,
                                     double w, struct attrs C)
{
    return (struct attrs){
        u * A.z + v * B.z + w * C.z, u * A.r + v * B.r + w * C.r,
        u * A.g + v * B.g + w * C.g, u * A.b + v * B.b + w * C.b,
        u * A.s + v * B.s + w * C.s, u * A.t + v * B.t + w * C.t,
    };
}

/* One pixel to the right: additions only. */
static inline struct attrs attrs_step(struct attrs P, struct attrs d)
{
    return (struct attrs){ P.z + d.z, P.r + d.r, P.g + d.g, P.b + d.b, P.s + d.s, P.t + d.t };
}

static inline struct attrs attrs_of(const struct vertex *v)
{
    return (struct attrs){ v->z, v->r, v->g, v->b, v->s, v->t };
}

/* What a triangle's attributes need once: the vertices' values, 1 / area2
 * and the change per pixel to the right. */
struct attributes {
    struct attrs A, B, C;
    double inv_area2;
    struct attrs dPdx;
};

static void attributes_setup(struct attributes *a, const struct tri_setup *t, struct trace *tr)
{
    a->A = attrs_of(&t->v[0]);
    a->B = attrs_of(&t->v[1]);
    a->C = attrs_of(&t->v[2]);
    a->inv_area2 = 1.0 / (double)t->area2;
    /* change of u, v, w per pixel to the right: (13)-(15) with F += 256 I */
    double du = (double)(t->I[EDGE_BC] * SUBPIXEL_ONE) * a->inv_area2;
    double dv = (double)(t->I[EDGE_CA] * SUBPIXEL_ONE) * a->inv_area2;
    double dw = (double)(t->I[EDGE_AB] * SUBPIXEL_ONE) * a->inv_area2;
    a->dPdx = attrs_mix(du, a->A, dv, a->B, dw, a->C);
    COUNT_OPS(tr, 1 + 3 * 2 + 3 * NATTR, 2 * NATTR);
}

/* The values at the first pixel of a row, from its exact edge values. */
static inline struct attrs attributes_restart(const struct attributes *a, int64_t F01,
                                              int64_t F02, int64_t F03, struct trace *tr)
{
    double u = (double)F02 * a->inv_area2;     /* (13) */
    double v = (double)F03 * a->inv_area2;     /* (14) */
    double w = (double)F01 * a->inv_area2;     /* (15) */
    COUNT_OPS(tr, 3 + 3 * NATTR, 2 * NATTR);
    return attrs_mix(u, a->A, v, a->B, w, a->C);
}

static inline uint32_t attrs_colour(struct attrs P, const struct raster_params *p)
{
    return shade_pixel(p, P.r, P.g, P.b, P.s, P.t);
}

/* --- the algorithm ---------------------------------------------------------------- */

/* Seed 001's loop with the fill rule. The bounding box comes from setup,
 * already clamped to the target:
 *
 *       minX                 maxX
 *   minY +--o--o--o--o--o--o--+      o = a pixel centre; F is evaluated
 *        |  o  o  o /\ o  o   |      (multiplied out) at the first one
 *        |  o  o  o/  \o  o   |      only. Every other centre is reached
 *        |  o  o  /o  o\  o   |      by "+ 256 I" to the right or
 *        |  o  o /o  o  o\o   |      "+ 256 J" down from the row above.
 *   maxY +--o--o/--------- \--+
 */
static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;

    /* The edge coefficients (6)-(8) in the seed's names, with the fill rule
     * folded into the constant: F + bias >= 0 is the whole inside test. */
    const int64_t I01 = t->I[EDGE_AB], J01 = t->J[EDGE_AB], b01 = t->bias[EDGE_AB];
    const int64_t I02 = t->I[EDGE_BC], J02 = t->J[EDGE_BC], b02 = t->bias[EDGE_BC];
    const int64_t I03 = t->I[EDGE_CA], J03 = t->J[EDGE_CA], b03 = t->bias[EDGE_CA];
    const int64_t K01 = t->K[EDGE_AB] + b01;
    const int64_t K02 = t->K[EDGE_BC] + b02;
    const int64_t K03 = t->K[EDGE_CA] + b03;
    COUNT_OPS(tr, 0, 3);

    /* Steps of one pixel, in 1/256 units: (9) and (10) times 256. */
    const int64_t dx01 = I01 * SUBPIXEL_ONE, dy01 = J01 * SUBPIXEL_ONE;
    const int64_t dx02 = I02 * SUBPIXEL_ONE, dy02 = J02 * SUBPIXEL_ONE;
    const int64_t dx03 = I03 * SUBPIXEL_ONE, dy03 = J03 * SUBPIXEL_ONE;
    COUNT_OPS(tr, 6, 0);

    /* The only evaluation of the edge functions: the first pixel centre. */
    const int64_t X = pixel_centre(t->minx), Y = pixel_centre(t->miny);
    int64_t Cy01 = I01 * X + J01 * Y + K01;
    int64_t Cy02 = I02 * X + J02 * Y + K02;
    int64_t Cy03 = I03 * X + J03 * Y + K03;
    COUNT_OPS(tr, 6, 6);

    struct attributes at;
    attributes_setup(&at, t, tr);

    for (int y = t->miny; y <= t->maxy; y++) {
        int64_t Cx01 = Cy01, Cx02 = Cy02, Cx03 = Cy03;
        struct attrs P = attributes_restart(&at, Cx01 - b01, Cx02 - b02, Cx03 - b03, tr);
        COUNT_OPS(tr, 0, 3);
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y,
                .e = { Cx01 - b01, Cx02 - b02, Cx03 - b03 });

        for (int x = t->minx; x <= t->maxx; x++) {
            bool inside = Cx01 >= 0 && Cx02 >= 0 && Cx03 >= 0;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .x = x, .y = y,
                    .e = { Cx01 - b01, Cx02 - b02, Cx03 - b03 },
                    .bary = { (float)((double)(Cx02 - b02) * at.inv_area2),
                              (float)((double)(Cx03 - b03) * at.inv_area2),
                              (float)((double)(Cx01 - b01) * at.inv_area2) },
                    .aux = { (float)P.z, (float)P.r, (float)P.g,
                             (float)P.b, (float)P.s, (float)P.t },
                    .flags = inside ? TRACE_INSIDE : 0);
            if (inside)
                PLOT(fb, tr, L_RENDER, x, y, (float)P.z, attrs_colour(P, p));

            Cx01 += dx01;
            Cx02 += dx02;
            Cx03 += dx03;
            P = attrs_step(P, at.dPdx);
            COUNT_OPS(tr, 0, 3 + NATTR);
        }
        Cy01 += dy01;
        Cy02 += dy02;
        Cy03 += dy03;
        COUNT_OPS(tr, 0, 3);
    }
}

/* --- exhibit: the same loop in single-precision float ------------------------------- */

/* Only the type of the running values changes. The increments 256 I and
 * 256 J are exact in float (I has at most 24 bits; times 256 is a shift of
 * the exponent), and so is nothing else: a float has 24 significant bits,
 * and an edge value of a triangle a few hundred pixels wide needs 30 or
 * more. Every addition rounds to the nearest float, the errors pile up
 * along the row and down the rows, and a centre close to an edge lands on
 * the wrong side of it. Colour and depth are stepped as in the exact loop. */
static void rasterize_float(const struct tri_setup *t, const struct raster_params *p,
                            struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;

    const float dx01 = (float)(t->I[EDGE_AB] * SUBPIXEL_ONE);
    const float dx02 = (float)(t->I[EDGE_BC] * SUBPIXEL_ONE);
    const float dx03 = (float)(t->I[EDGE_CA] * SUBPIXEL_ONE);
    const float dy01 = (float)(t->J[EDGE_AB] * SUBPIXEL_ONE);
    const float dy02 = (float)(t->J[EDGE_BC] * SUBPIXEL_ONE);
    const float dy03 = (float)(t->J[EDGE_CA] * SUBPIXEL_ONE);
    COUNT_OPS(tr, 6, 0);

    /* the first centre exactly, bias included, then rounded once to float */
    float Cy01 = (float)(edge_value(t, EDGE_AB, t->minx, t->miny) + t->bias[EDGE_AB]);
    float Cy02 = (float)(edge_value(t, EDGE_BC, t->minx, t->miny) + t->bias[EDGE_BC]);
    float Cy03 = (float)(edge_value(t, EDGE_CA, t->minx, t->miny) + t->bias[EDGE_CA]);
    COUNT_OPS(tr, 6, 9);

    struct attributes at;
    attributes_setup(&at, t, tr);

    for (int y = t->miny; y <= t->maxy; y++) {
        float Cx01 = Cy01, Cx02 = Cy02, Cx03 = Cy03;
        /* the attributes restart from the exact values, as in the exact loop,
         * so that only coverage differs */
        struct attrs P = attributes_restart(&at, edge_value(t, EDGE_AB, t->minx, y),
                                            edge_value(t, EDGE_BC, t->minx, y),
                                            edge_value(t, EDGE_CA, t->minx, y), tr);
        COUNT_OPS(tr, 6, 6);
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y,
                .e = { (int64_t)Cx01 - t->bias[EDGE_AB], (int64_t)Cx02 - t->bias[EDGE_BC],
                       (int64_t)Cx03 - t->bias[EDGE_CA] });

        for (int x = t->minx; x <= t->maxx; x++) {
            bool inside = Cx01 >= 0 && Cx02 >= 0 && Cx03 >= 0;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .x = x, .y = y,
                    .e = { (int64_t)Cx01 - t->bias[EDGE_AB], (int64_t)Cx02 - t->bias[EDGE_BC],
                           (int64_t)Cx03 - t->bias[EDGE_CA] },
                    .aux = { (float)P.z, (float)P.r, (float)P.g,
                             (float)P.b, (float)P.s, (float)P.t },
                    .flags = inside ? TRACE_INSIDE : 0);
            if (inside)
                PLOT(fb, tr, L_RENDER, x, y, (float)P.z, attrs_colour(P, p));

            Cx01 += dx01;
            Cx02 += dx02;
            Cx03 += dx03;
            P = attrs_step(P, at.dPdx);
            COUNT_OPS(tr, 0, 3 + NATTR);
        }
        Cy01 += dy01;
        Cy02 += dy02;
        Cy03 += dy03;
        COUNT_OPS(tr, 0, 3);
    }
}

/* --- what the explorer draws ----------------------------------------------------
 *
 * The watch panel's TRIANGLE section: I0k and J0k of each edge, raw (1/256
 * px) and in pixels, and the two steps the loop adds, 256 I0k to the right
 * and 256 J0k down. The canvas, in every view but the colour view: at the
 * current pixel, the two steps as arrows to the next centre right ("+I") and
 * below ("+J"); in the edges view also each edge's normal (I, J), the
 * direction in which its F grows, at the edge's middle in the edge's colour. */
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
    cairo_set_line_width(c->cr, 2.5 * c->unit);
    if (strcmp(c->view, "edges") == 0) {
        for (int k = 0; k < 3; k++) {
            int b = (k + 1) % 3;
            double mx = (t->x[k] + t->x[b]) / 2.0 / SUBPIXEL_ONE;
            double my = (t->y[k] + t->y[b]) / 2.0 / SUBPIXEL_ONE;
            double nx = (double)t->I[k], ny = (double)t->J[k], d = hypot(nx, ny);
            double len = 45 * c->unit;
            c->arrow(c, mx, my, mx + nx / d * len, my + ny / d * len, c->edge_rgb[k]);
            char buf[40];
            snprintf(buf, sizeof buf, "(I0%d, J0%d)", k + 1, k + 1);
            c->label(c, mx + nx / d * len + 4 * c->unit, my + ny / d * len, buf, 10, c->edge_rgb[k]);
        }
    }
    if (!last || (last->kind != TRACE_PIXEL_TEST && last->kind != TRACE_PIXEL_WRITE
                  && last->kind != TRACE_ROW))
        return;
    double x = last->x + 0.5, y = last->y + 0.5;
    c->arrow(c, x, y, x + 1, y, 0xffffff);
    c->arrow(c, x, y, x, y + 1, 0xffffff);
    c->label(c, x + 1 + 3 * c->unit, y - 8 * c->unit, "+I", 11, 0xffffff);
    c->label(c, x + 3 * c->unit, y + 1 + 1 * c->unit, "+J", 11, 0xffffff);
}

static const struct lesson_variant variants[] = {
    { "stepping", "integer edge values stepped by additions: exact (seed 001)", rasterize, false },
    { "float", "exhibit: the same loop in single-precision float drifts on large triangles",
      rasterize_float, true },
};

static const char *const compare[] = { "02-barycentric", NULL };

const struct lesson lesson_03 = {
    .id = "03-edge-stepping",
    .title = "Incremental edge functions",
    .pseudocode = pseudocode,
    .builtin_scene = "edge-steps",
    .exhibit_scene = "float-drift",
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .params = LESSON_PARAM_SUBPIXEL,
    .compare = compare,
    .overlay = overlay,
    .constants = constants,
    .exercise = { .write_line = L_RENDER, .no_pixel_mul = true },
};
