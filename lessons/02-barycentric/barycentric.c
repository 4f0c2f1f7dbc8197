/* Lesson 02: bounding-box barycentrics with the top-left fill rule.
 *
 * What it shows: the simplest exact rasterizer. Visit every pixel of the
 * triangle's bounding box, evaluate the three edge functions at the pixel
 * centre, and keep the pixel when all three say "inside" (the lab text); decide
 * centres exactly on an edge with the top-left rule (the fill-rule notes). The edge
 * values divided by twice the area are the barycentric weights alpha, beta,
 * gamma that interpolate colour and depth.
 *
 * New since lesson 01: no edge walking, no sorted vertices; one test per
 * pixel, the same for every pixel, which is what makes the fill rule easy
 * to state and what the later lessons speed up.
 *
 * The edge functions, in the lab text's names (setup has made them positive
 * inside, see src/raster/raster.h):
 *
 *     F_ab(x, y) = (y_a - y_b) x + (x_b - x_a) y + x_a y_b - x_b y_a
 *     F_bc, F_ca likewise.
 *
 *             a                  F_ab > 0 on the side of c,
 *            / \                 F_bc > 0 on the side of a,
 *           /   \                F_ca > 0 on the side of b:
 *          /  p  \               p is inside when all three are > 0,
 *         c ----- b              or == 0 on a top or left edge.
 *
 *     alpha = F_bc(p) / F_bc(a),  beta = F_ca(p) / F_ca(b),  gamma = F_ab(p) / F_ab(c)
 *
 * and F_bc(a) = F_ca(b) = F_ab(c) = twice the triangle's area (area2).
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

static const char *const pseudocode[] = {
    "snap a, b, c to 1/256 px; if area < 0: swap b, c",  /* 0 */
    "box = findBoundingBox(a, b, c)",                     /* 1 */
    "foreach pixel (x, y) in box:",                       /* 2 */
    "  F_ab, F_bc, F_ca at (x + 0.5, y + 0.5)",            /* 3 */
    "  if inside(F_ab) and inside(F_bc) and inside(F_ca):",/* 4 */
    "    alpha, beta, gamma = F_bc, F_ca, F_ab / area2",  /* 5 */
    "    color = alpha c_a + beta c_b + gamma c_c",       /* 6 */
    "    drawPixel(x, y) with color, z",                  /* 7 */
    NULL,
};

enum { L_SETUP, L_BOX, L_LOOP, L_EDGES, L_TEST, L_BARY, L_COLOR, L_DRAW };

/* How a centre exactly on an edge (F == 0) is decided. Only the first is
 * right; the other two are the exhibits of this lesson. */
enum fill_rule {
    RULE_TOP_LEFT,      /* the fill-rule notes: on an edge counts only for top and left edges */
    RULE_INCLUSIVE,     /* F >= 0 on every edge: shared edges drawn twice */
    RULE_STRICT,        /* 0 < alpha, beta, gamma (the lab text): shared edges dropped */
};

static bool inside(const struct tri_setup *t, const int64_t F[3], enum fill_rule rule)
{
    switch (rule) {
    case RULE_INCLUSIVE:
        return F[0] >= 0 && F[1] >= 0 && F[2] >= 0;
    case RULE_STRICT:
        return F[0] > 0 && F[1] > 0 && F[2] > 0;
    case RULE_TOP_LEFT:
        break;
    }
    return edge_inside(t, EDGE_AB, F[0]) && edge_inside(t, EDGE_BC, F[1])
        && edge_inside(t, EDGE_CA, F[2]);
}

static void rasterize_rule(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr, enum fill_rule rule)
{
    const struct vertex *a = &t->v[0], *b = &t->v[1], *c = &t->v[2];
    NARRATE_SETUP(tr, t, TRACE_LINES(L_SETUP, L_BOX));     /* the box comes with the setup */
    if (t->empty)
        return;
    double inv_area2 = 1.0 / (double)t->area2;

    for (int y = t->miny; y <= t->maxy; y++) {
        NARRATE(tr, .kind = TRACE_ROW, .line = L_LOOP, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y);
        for (int x = t->minx; x <= t->maxx; x++) {
            /* the lab text's edge equations, evaluated directly at the centre */
            int64_t F[3] = {
                edge_value(t, EDGE_AB, x, y),   /* F_ab */
                edge_value(t, EDGE_BC, x, y),   /* F_bc */
                edge_value(t, EDGE_CA, x, y),   /* F_ca */
            };
            bool in = inside(t, F, rule);
            COUNT(tr, 3, EDGE_VALUE_COST);
            COUNT(tr, 3, FILL_RULE_COST);
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_TEST, .span = L_TEST - L_EDGES, .x = x, .y = y,
                    .e = { F[0], F[1], F[2] }, .flags = in ? TRACE_INSIDE : 0);
            if (!in)
                continue;

            double alpha = (double)F[1] * inv_area2;
            double beta = (double)F[2] * inv_area2;
            double gamma = (double)F[0] * inv_area2;
            COUNT(tr, 1, BARYCENTRIC_COST);
            double z = alpha * a->z + beta * b->z + gamma * c->z;
            uint32_t color = shade_pixel(p, tr,
                alpha * a->r + beta * b->r + gamma * c->r,
                alpha * a->g + beta * b->g + gamma * c->g,
                alpha * a->b + beta * b->b + gamma * c->b,
                alpha * a->s + beta * b->s + gamma * c->s,
                alpha * a->t + beta * b->t + gamma * c->t);
            COUNT(tr, 6, INTERPOLATE_COST);     /* z, r, g, b, s, t */
            PLOT(fb, tr, TRACE_LINES(L_BARY, L_DRAW), x, y, (float)z, color);
        }
    }
}

static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    rasterize_rule(t, p, fb, tr, RULE_TOP_LEFT);
}

static void rasterize_inclusive(const struct tri_setup *t, const struct raster_params *p,
                                struct target *fb, struct trace *tr)
{
    rasterize_rule(t, p, fb, tr, RULE_INCLUSIVE);
}

static void rasterize_strict(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr)
{
    rasterize_rule(t, p, fb, tr, RULE_STRICT);
}

static const struct lesson_variant variants[] = {
    { .name = "top-left", .kind = VARIANT_ALGORITHM, .rasterize = rasterize,
      .what = "the top-left rule decides centres on an edge (the fill-rule notes)" },
    { .name = "inclusive", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_inclusive,
      .what = "exhibit: F >= 0 on every edge draws shared edges twice" },
    { .name = "strict", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_strict,
      .what = "exhibit: 0 < alpha, beta, gamma (the lab text) leaves cracks" },
};

const struct lesson lesson_02 = {
    .id = "02-barycentric",
    .title = "Bounding-box barycentrics with the top-left fill rule",
    .pseudocode = pseudocode,
    .builtin_scene = "triangle",
    .exhibit_scene = "shared-edge",
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .cost_tested = (const struct cost_term[]){
        COST_TERM(3, EDGE_VALUE_COST), COST_TERM(3, FILL_RULE_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, BARYCENTRIC_COST), COST_TERM(6, INTERPOLATE_COST),
        COST_TERM(1, PACK_RGB_COST), { 0 } },
    .exercise = { .write_line = L_DRAW,
                  /* graded: the idea of section 4 under the other rule, which this file does not print */
                  .variants = (const struct exercise_variant[]){
                      { .name = "bottom-right", .rule = FILL_BOTTOM_RIGHT,
                        .what = "the bottom-right fill rule: a centre on an edge is covered when the edge "
                                "is a bottom or a right edge" },
                      { 0 } } },
};
