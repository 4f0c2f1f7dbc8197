/* Lesson 03: incremental edge functions.
 *
 * What it shows: lesson 02's loop without its multiplications. An edge
 * function is linear in x and y (the edge-function notes, sections 2 and 3):
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
 * Edge numbering is the notes': 01 = AB, 02 = BC, 03 = CA. The coefficients
 * come from the shared setup (src/raster/raster.h: t->I, t->J, t->K, t->bias,
 * the edge functions lesson 02 explains), here called by the notes' names.
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_scaled: the colour every lesson gives a pixel */

static const char *const pseudocode[] = {
    "snap A, B, C; I0k, J0k, K0k of edges 01, 02, 03 (6)-(8)",  /* 0 */
    "K0k += bias0k   (top-left rule: 0 or -1)",                 /* 1 */
    "F0k = I0k X + J0k Y + K0k   (X, Y: the first centre)",     /* 2 */
    "Cy0k = F0k",                                               /* 3 */
    "loop y = minY to maxY:",                                   /* 4 */
    "  Cx0k = Cy0k;  u, v, w = Cx02, Cx03, Cx01 / area2  (13)-(15)", /* 5 */
    "  loop x = minX..maxX, Cx0k, colour, z += d/dx  (9):",     /* 6 */
    "    if Cx01 >= 0 and Cx02 >= 0 and Cx03 >= 0:",            /* 7 */
    "      Render(x, y) with colour, z",                        /* 8 */
    "  Cy0k += 256 J0k   (10)",                                 /* 9 */
    NULL,
};

enum { L_SETUP, L_BIAS, L_FIRST, L_CY, L_LOOP_Y, L_ROW, L_LOOP_X, L_TEST, L_RENDER,
       L_STEP_Y };

/* The watch panel's values: what is being stepped besides the edge values
 * (colours scaled to 0..255 and s, t by the checker's N: see attrs_of). */
static const char *const aux_names[] = { "z", "255r", "255g", "255b", "Ns", "Nt", NULL };

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
 * than stepping u, v, w and mixing them (three multiplications). The colour
 * channels are stepped already multiplied by 255, and s, t by the checker's
 * N (attrs_of), so the pixel writes them as they are: the loop over a row
 * adds and never multiplies, shading included.
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

/* A vertex's values, scaled once per triangle for shade_scaled(). */
#define ATTRS_OF_COST { .mul = 5, .add = 0 }

static inline struct attrs attrs_of(const struct vertex *v, const struct raster_params *p)
{
    double n = shade_scale_st(p);
    return (struct attrs){ v->z, SHADE_SCALE_RGB * v->r, SHADE_SCALE_RGB * v->g,
                           SHADE_SCALE_RGB * v->b, n * v->s, n * v->t };
}

/* What a triangle's attributes need once: the vertices' values, 1 / area2
 * and the change per pixel to the right. */
struct attributes {
    struct attrs A, B, C;
    double inv_area2;
    struct attrs dPdx;
};

static void attributes_setup(struct attributes *a, const struct tri_setup *t,
                             const struct raster_params *p, struct trace *tr)
{
    a->A = attrs_of(&t->v[0], p);
    a->B = attrs_of(&t->v[1], p);
    a->C = attrs_of(&t->v[2], p);
    COUNT(tr, 3, ATTRS_OF_COST);
    a->inv_area2 = 1.0 / (double)t->area2;
    COUNT(tr, 1, RECIPROCAL_COST);
    /* change of u, v, w per pixel to the right: (13)-(15) with F += 256 I */
    double du = (double)(t->I[EDGE_BC] * SUBPIXEL_ONE) * a->inv_area2;
    double dv = (double)(t->I[EDGE_CA] * SUBPIXEL_ONE) * a->inv_area2;
    double dw = (double)(t->I[EDGE_AB] * SUBPIXEL_ONE) * a->inv_area2;
    a->dPdx = attrs_mix(du, a->A, dv, a->B, dw, a->C);
    COUNT(tr, 3, EDGE_INCREMENTS_COST);     /* 256 I times 1 / area2: 2 products each */
    COUNT(tr, NATTR, INTERPOLATE_COST);
}

/* The values at the first pixel of a row, from its exact edge values. */
static inline struct attrs attributes_restart(const struct attributes *a, int64_t F01,
                                              int64_t F02, int64_t F03, struct trace *tr)
{
    double u = (double)F02 * a->inv_area2;     /* (13) */
    double v = (double)F03 * a->inv_area2;     /* (14) */
    double w = (double)F01 * a->inv_area2;     /* (15) */
    COUNT(tr, 1, BARYCENTRIC_COST);
    COUNT(tr, NATTR, INTERPOLATE_COST);
    return attrs_mix(u, a->A, v, a->B, w, a->C);
}

static inline uint32_t attrs_colour(struct attrs P, const struct raster_params *p,
                                    struct trace *tr)
{
    return shade_scaled(p, tr, P.r, P.g, P.b, P.s, P.t);
}

/* --- the algorithm ---------------------------------------------------------------- */

/* How the loop holds its running edge values after each addition: exactly,
 * as 64-bit integers (the algorithm), or in a single-precision float (the
 * exhibit at the end of the file). Everything else in the loop is the same.
 * The values and their steps are whole numbers, so a float addition gives
 * the exact sum rounded to the nearest float: what (float) does to it. */
enum hold { EXACT, IN_FLOAT };

static inline int64_t held(int64_t F, enum hold h)
{
    return h == EXACT ? F : (int64_t)(float)F;
}

/* The edge-function notes' loop with the fill rule. The bounding box comes from setup,
 * already clamped to the target:
 *
 *       minX                 maxX
 *   minY +--o--o--o--o--o--o--+      o = a pixel centre; F is evaluated
 *        |  o  o  o /\ o  o   |      (multiplied out) at the first one
 *        |  o  o  o/  \o  o   |      only. Every other centre is reached
 *        |  o  o  /o  o\  o   |      by "+ 256 I" to the right or
 *        |  o  o /o  o  o\o   |      "+ 256 J" down from the row above.
 *   maxY +--o--o/--------- \--+
 *
 * Compiled once per way of holding the values (always_inline, h a constant):
 * the exact loop carries no trace of the float one. */
static inline __attribute__((always_inline)) void
step_edges(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
           struct trace *tr, enum hold h)
{
    NARRATE_SETUP(tr, t, L_SETUP);
    if (t->empty)
        return;

    /* The edge coefficients (6)-(8) in the notes' names, with the fill rule
     * folded into the constant: F + bias >= 0 is the whole inside test. */
    const int64_t I01 = t->I[EDGE_AB], J01 = t->J[EDGE_AB], b01 = t->bias[EDGE_AB];
    const int64_t I02 = t->I[EDGE_BC], J02 = t->J[EDGE_BC], b02 = t->bias[EDGE_BC];
    const int64_t I03 = t->I[EDGE_CA], J03 = t->J[EDGE_CA], b03 = t->bias[EDGE_CA];
    const int64_t K01 = t->K[EDGE_AB] + b01;
    const int64_t K02 = t->K[EDGE_BC] + b02;
    const int64_t K03 = t->K[EDGE_CA] + b03;
    COUNT(tr, 3, FILL_RULE_COST);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_BIAS);

    /* Steps of one pixel, in 1/256 units: (9) and (10) times 256. */
    const int64_t dx01 = I01 * SUBPIXEL_ONE, dy01 = J01 * SUBPIXEL_ONE;
    const int64_t dx02 = I02 * SUBPIXEL_ONE, dy02 = J02 * SUBPIXEL_ONE;
    const int64_t dx03 = I03 * SUBPIXEL_ONE, dy03 = J03 * SUBPIXEL_ONE;
    COUNT(tr, 3, EDGE_INCREMENTS_COST);

    /* The only evaluation of the edge functions: the first pixel centre. */
    const int64_t X = pixel_centre(t->minx), Y = pixel_centre(t->miny);
    int64_t Cy01 = held(I01 * X + J01 * Y + K01, h);
    int64_t Cy02 = held(I02 * X + J02 * Y + K02, h);
    int64_t Cy03 = held(I03 * X + J03 * Y + K03, h);
    COUNT(tr, 3, EDGE_VALUE_COST);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_CY, .span = L_CY - L_FIRST, .x = t->minx, .y = t->miny,
            .e = { Cy01 - b01, Cy02 - b02, Cy03 - b03 });

    struct attributes at;
    attributes_setup(&at, t, p, tr);

    for (int y = t->miny; y <= t->maxy; y++) {
        int64_t Cx01 = Cy01, Cx02 = Cy02, Cx03 = Cy03;
        /* The attributes restart from the exact edge values of the row's
         * first centre: the running ones with the bias taken off again, or,
         * where those may have drifted (float), evaluated anew. */
        int64_t F01, F02, F03;
        if (h == EXACT) {
            F01 = Cx01 - b01, F02 = Cx02 - b02, F03 = Cx03 - b03;
            COUNT(tr, 3, FILL_RULE_COST);
        } else {
            F01 = edge_value(t, EDGE_AB, t->minx, y);
            F02 = edge_value(t, EDGE_BC, t->minx, y);
            F03 = edge_value(t, EDGE_CA, t->minx, y);
            COUNT(tr, 3, EDGE_VALUE_COST);
        }
        struct attrs P = attributes_restart(&at, F01, F02, F03, tr);
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .span = L_ROW - L_LOOP_Y, .x = t->minx, .y = y,
                .x1 = t->maxx, .y1 = y, .e = { Cx01 - b01, Cx02 - b02, Cx03 - b03 });

        for (int x = t->minx; x <= t->maxx; x++) {
            bool inside = Cx01 >= 0 && Cx02 >= 0 && Cx03 >= 0;
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .span = L_TEST - L_LOOP_X, .x = x,
                    .y = y, .e = { Cx01 - b01, Cx02 - b02, Cx03 - b03 },
                    .flags = inside ? TRACE_INSIDE : 0,
                    .aux = { (float)P.z, (float)P.r, (float)P.g, (float)P.b, (float)P.s, (float)P.t });
            if (inside)
                PLOT(fb, tr, L_RENDER, x, y, (float)P.z, attrs_colour(P, p, tr));

            Cx01 = held(Cx01 + dx01, h);
            Cx02 = held(Cx02 + dx02, h);
            Cx03 = held(Cx03 + dx03, h);
            P = attrs_step(P, at.dPdx);
            COUNT(tr, 3, EDGE_STEP_COST);
            COUNT(tr, NATTR, PLANE_STEP_COST);
        }
        Cy01 = held(Cy01 + dy01, h);
        Cy02 = held(Cy02 + dy02, h);
        Cy03 = held(Cy03 + dy03, h);
        COUNT(tr, 3, EDGE_STEP_COST);
        NARRATE(tr, .kind = TRACE_STEP, .line = L_STEP_Y, .x = t->minx, .y = y + 1,
                .e = { Cy01 - b01, Cy02 - b02, Cy03 - b03 });
    }
}

static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    step_edges(t, p, fb, tr, EXACT);
}

/* --- exhibit: the same loop in single-precision float ------------------------------- */

/* Only how the running values are held changes. The increments 256 I and
 * 256 J are exact in float (I has at most 24 bits; times 256 is a shift of
 * the exponent), and so is nothing else: a float has 24 significant bits,
 * and an edge value of a triangle a few hundred pixels wide needs 30 or
 * more. Every addition rounds to the nearest float, the errors pile up
 * along the row and down the rows, and a centre close to an edge lands on
 * the wrong side of it. Colour and depth are stepped as in the exact loop. */
static void rasterize_float(const struct tri_setup *t, const struct raster_params *p,
                            struct target *fb, struct trace *tr)
{
    step_edges(t, p, fb, tr, IN_FLOAT);
}

static const struct lesson_variant variants[] = {
    { .name = "stepping", .kind = VARIANT_ALGORITHM, .rasterize = rasterize,
      .what = "integer edge values stepped by additions: exact (the edge-function notes)" },
    { .name = "float", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_float,
      .what = "exhibit: the same loop in single-precision float drifts on large triangles" },
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
    /* the precision every lesson snaps to; its exhibit is fewer bits */
    .params = (const struct lesson_param[]){
        { .option = "subpixel-bits", .arg = "N", .name = "sub-pixel bits",
          .help = "snap vertices to N fractional bits, 0..8 (default 8)",
          .key = ']', .key_down = '[', .min = 0, .max = SUBPIXEL_BITS, .def = SUBPIXEL_BITS,
          .slot = PARAM_SUBPIXEL_BITS },
        { 0 } },
    .compare = compare,
    .cost_tested = (const struct cost_term[]){
        COST_TERM(3, EDGE_STEP_COST), COST_TERM(NATTR, PLANE_STEP_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){ COST_TERM(1, PACK_SCALED_COST), { 0 } },
    .exercise = { .write_line = L_RENDER, .no_pixel_mul = true,
                  /* graded: the stepping of section 2 the other way, which this file does not print */
                  .variants = (const struct exercise_variant[]){
                      { .name = "from-bottom-right", .rule = FILL_TOP_LEFT, .from_bottom_right = true,
                        .what = "the box walked from its bottom-right pixel: rows from the bottom up, "
                                "each from right to left, the same pixels covered" },
                      { 0 } } },
};
