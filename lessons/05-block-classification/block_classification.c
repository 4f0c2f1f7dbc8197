/* Lesson 05: q x q block classification.
 *
 * What it shows: the block notes, "block-based" half-space rasterization (after
 * Mileff, Nehez and Dudra, "Accelerated Half-Space Triangle Rasterization",
 * 2015). Instead of testing every pixel of the bounding box, cut the box into
 * blocks of q x q pixels and test only the four corners of each block against
 * each edge. An edge function is linear, so over a rectangle it takes its
 * smallest and largest values at the corners: the corners decide the whole
 * block.
 *
 *     every corner outside one edge   -> the block is EMPTY:   skip it
 *     every corner inside every edge  -> the block is FULL:    RenderBlock,
 *                                        no per-pixel test at all
 *     otherwise                       -> the block is PARTIAL: test its
 *                                        pixels, stepping F from the corner
 *
 * New since lesson 04: the block loop and its three cases; a RenderBlock that
 * fills four pixels per SSE register; partial blocks tested four pixels at a
 * time with integer SSE compares. What stays: lesson 03's exact integer edge
 * values decide coverage (the corners use the very same values and the same
 * top-left bias as the pixel test, so "full" is really full), and lesson 04's
 * planes 1/z and a/z give perspective-correct depth and colour (formula 23),
 * four pixels at a time, from src/shade/quad.h: shared machinery, not this
 * lesson's idea. This file reads: the edges, the corners of a block, its
 * class, the three cases, the blocks.
 *
 * Two twins of the partial-block loop sit side by side: one pixel at a time
 * with exact 64-bit edge values, narrating every pixel (what the explorer
 * steps through), and four pixels per register (what the benchmark times).
 * Both shade a pixel with the same function, so they write the same bytes.
 */
#include <stdlib.h>

#include "lesson.h"
#include "shade/quad.h"      /* four pixels shaded and written per SSE register */

static const char *const pseudocode[] = {
    "setup: F0k = I0k x + J0k y + K0k + bias_k, k = 1, 2, 3",         /* 0 */
    "box = [minX, maxX] x [minY, maxY], clipped to the screen",         /* 1 */
    "loop y, x over the q x q blocks of the box:",                      /* 2 */
    "  checkw, checku, checkv = corner signs of F01, F02, F03",         /* 3 */
    "  if checkw == 0 || checku == 0 || checkv == 0: skip   (empty)",   /* 4 */
    "  if checkw == checku == checkv == 0xF: RenderBlock    (full)",    /* 5 */
    "  else loop by, bx over the block's pixels:            (partial)", /* 6 */
    "    F0k stepped from the corner: += I0k, += J0k",                  /* 7 */
    "    if F01 >= 0 && F02 >= 0 && F03 >= 0: RenderPixel(x, y)",       /* 8 */
    NULL,
};

enum { L_SETUP, L_BOX, L_LOOP, L_MASKS, L_EMPTY, L_FULL, L_PARTIAL, L_STEP, L_PIXEL };

/* trace_event.aux[] of this lesson: the block size of a block event, and its
 * level (0: a block of the grid or a coarse block, 1: a sub-block of a coarse
 * block in the hierarchical variant). */
static const char *const aux_names[] = { "q", "level", NULL };

#define Q_DEFAULT 8         /* the default block size (exercise 1 compares 4, 8, 16) */
enum { P_BLOCK };           /* the lesson's parameter rows: p->knob[P_BLOCK] is --block-size */
#define Q_COARSE 64         /* the hierarchical variant's coarse level */

/* --- the edges, as the block loop uses them ------------------------------- */

/* The edge-function notes' edge functions with the fill rule folded in (struct
 * biased_edges, src/raster/raster.h): a pixel is covered when F0k + bias_k
 * >= 0 for k = 1, 2, 3 (bias 0 on a top or left edge, -1 otherwise). With
 * the bias in the constant, every test below, corner or pixel, is a plain
 * sign test, and the corners and the pixels agree by construction.
 *
 * Index k = 0, 1, 2 is the source's F01 (edge AB, checkw), F02 (edge BC,
 * checku) and F03 (edge CA, checkv); biased_edge_at(e, k, x, y) is
 * F0k + bias_k at the centre of pixel (x, y), exact. */

/* --- shading -------------------------------------------------------------
 *
 * Covered pixels are shaded four at a time by src/shade/quad.h: lesson 04's
 * planes of 1/z and a/z (struct planes), evaluated for a quad of four pixels
 * of a row (struct quad), their depth, colour and write (write_quad). That is
 * shared machinery, not this lesson's idea: read it there. */

/* Everything one triangle's blocks share. */
struct run {
    const struct tri_setup *t;
    struct target *fb;
    struct trace *tr;
    struct biased_edges e;
    struct planes pl;
    bool narrate;       /* a live trace in the narrated build: pixel by pixel */
    bool pixelwise;     /* partial blocks pixel by pixel even without a trace */
    bool fits_int32;    /* partial blocks' edge values fit the SSE int32 lanes */
    int size, level;    /* of the blocks being classified, for the narration */
};

/* --- classifying a block by its corners ---------------------------------- */

/* The source's checkw, checku, checkv: one bit per corner, set when that
 * corner is inside the edge. The corners are the CENTRES of the block's
 * corner pixels (the samples the pixel test uses), not the block's outline:
 *
 *      (x0, y0) bit 3  o---------o  bit 2 (x1, y0)
 *                      |  block  |
 *                      |  pixels |
 *      (x0, y1) bit 1  o---------o  bit 0 (x1, y1)
 *
 * A linear F is >= 0 on all four corners exactly when it is >= 0 on every
 * pixel centre between them; it is < 0 on all four exactly when it is < 0 on
 * every one of them. */
#define CORNERS_COST { .mul = 4, .add = 6 }     /* one edge: tl, then tr, bl, br from it */

static void corner_masks(struct run *r, int x0, int y0, int x1, int y1, unsigned mask[3])
{
    const struct biased_edges *e = &r->e;
    for (int k = 0; k < 3; k++) {
        int64_t tl = biased_edge_at(e, k, x0, y0);
        int64_t tr = tl + e->dx[k] * (x1 - x0);
        int64_t bl = tl + e->dy[k] * (y1 - y0);
        int64_t br = tr + (bl - tl);
        mask[k] = (unsigned)(tl >= 0) << 3 | (unsigned)(tr >= 0) << 2
                | (unsigned)(bl >= 0) << 1 | (unsigned)(br >= 0);
    }
    COUNT(r->tr, 3, CORNERS_COST);
}

/* How the masks are read. Only the first is right. */
enum block_rule {
    RULE_PER_EDGE,          /* empty: all corners outside ONE edge; full: inside ALL edges */
    RULE_CORNERS_OUTSIDE,   /* exhibit: empty when no corner is inside the triangle */
    RULE_OR_INSIDE,         /* exhibit: the pseudo-code's || in the fully-inside test */
};

static enum block_class classify(const unsigned m[3], enum block_rule rule)
{
    switch (rule) {
    case RULE_CORNERS_OUTSIDE:
        /* "every corner of the block is outside the triangle", read literally:
         * a corner is inside the triangle when it is inside all three edges */
        if ((m[0] & m[1] & m[2]) == 0)
            return BLOCK_EMPTY;
        break;
    case RULE_OR_INSIDE:
        if (m[0] == 0 || m[1] == 0 || m[2] == 0)
            return BLOCK_EMPTY;
        return m[0] == 0xF || m[1] == 0xF || m[2] == 0xF ? BLOCK_FULL : BLOCK_PARTIAL;
    case RULE_PER_EDGE:
        if (m[0] == 0 || m[1] == 0 || m[2] == 0)
            return BLOCK_EMPTY;
        break;
    }
    return m[0] == 0xF && m[1] == 0xF && m[2] == 0xF ? BLOCK_FULL : BLOCK_PARTIAL;
}

/* --- the three cases ------------------------------------------------------ */

/* FULL: RenderBlock. Every pixel of the block is covered, so there is no
 * test at all: shade four pixels at a time and write them. Only the first
 * and the last quad of a row may stick out of the block. */
static void render_block(struct run *r, int x0, int y0, int x1, int y1)
{
    int xq0 = x0 & ~3, xq1 = x1 & ~3;
    __m128i first = lanes_within(xq0, x0, x1), last = lanes_within(xq1, x0, x1);
    __m128i all = _mm_set1_epi32(-1);
    struct target *fb = r->fb;
    bool checker = r->pl.checker, whole = quads_fit(fb, xq1);
    struct quad step = quad_step(&r->pl);
    uint64_t pixels = (uint64_t)(x1 - x0 + 1) * (uint64_t)(y1 - y0 + 1);
    COUNT(r->tr, pixels, QUAD_DEPTH_COST);
    COUNT(r->tr, pixels, QUAD_COLOUR_COST);
    COUNT(r->tr, pixels * QUAD_PLANES, PLANE_STEP_COST);
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, xq0, y);
        size_t row = (size_t)y * (size_t)fb->w;
        for (int xq = xq0; xq <= x1; xq += 4) {
            __m128i mask = xq == xq0 ? first : xq == xq1 ? last : all;
            if (whole)
                write_quad(fb->depth + row + xq, fb->color + row + xq, mask, &qd, checker);
            else
                write_quad_pixels(fb, xq, y, mask, &qd, checker);
            quad_next(&qd, &step, checker);
        }
    }
}

/* PARTIAL, one pixel at a time: the source's inner loop. The edge values
 * start at the block's corner and step by I0k to the right and J0k down
 * (formulas 9 and 10 of the edge-function notes), exact in 64 bits. Every test and every
 * write is a step of the narration. */
static void partial_block_pixels(struct run *r, int x0, int y0, int x1, int y1)
{
    const struct biased_edges *e = &r->e;
    struct quad step = quad_step(&r->pl);
    int64_t cy[3] = { biased_edge_at(e, 0, x0, y0), biased_edge_at(e, 1, x0, y0),
                      biased_edge_at(e, 2, x0, y0) };
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, x0 & ~3, y);
        int64_t cx[3] = { cy[0], cy[1], cy[2] };
        for (int x = x0; x <= x1; x++) {
            if (x > x0 && (x & 3) == 0) {   /* the next quad of four pixels */
                quad_next(&qd, &step, r->pl.checker);
                COUNT(r->tr, 4 * QUAD_PLANES, PLANE_STEP_COST);
            }
            bool in = cx[0] >= 0 && cx[1] >= 0 && cx[2] >= 0;
            NARRATE(r->tr, .kind = TRACE_PIXEL_TEST, .line = L_PIXEL, .span = L_PIXEL - L_STEP, .x = x, .y = y,
                    .e = { cx[0] - e->bias[0], cx[1] - e->bias[1], cx[2] - e->bias[2] },
                    .flags = in ? TRACE_INSIDE : 0);
            if (in) {
                __m128 z4;
                __m128i c4;
                float z[4];
                uint32_t rgba[4];
                shade_quad(&r->pl, &qd, &z4, &c4);
                _mm_storeu_ps(z, z4);
                _mm_storeu_si128((__m128i *)rgba, c4);
                COUNT(r->tr, 1, QUAD_DEPTH_COST);
                COUNT(r->tr, 1, QUAD_COLOUR_COST);
                PLOT(r->fb, r->tr, L_PIXEL, x, y, z[x & 3], rgba[x & 3]);
            }
            for (int k = 0; k < 3; k++)
                cx[k] += e->dx[k];
            COUNT(r->tr, 3, EDGE_STEP_COST);
        }
        for (int k = 0; k < 3; k++)
            cy[k] += e->dy[k];
    }
}

/* PARTIAL, four pixels at a time: the same loop with a quad of pixels per
 * register. Only the edges that cross the block are tested; an edge whose
 * four corners are all inside is inside for every pixel of the block.
 *
 *        xq0       x0          x1
 *         |  .  .  [#  #  #  #  #  #  #  #] .  .  |   quads of 4 pixels,
 *         +-----------+-----------+-----------+     aligned on the screen;
 *                                                   lanes outside [x0, x1] off
 *
 * An edge that crosses the block changes sign inside it, so its values there
 * are smaller than its change across the block, (|I0k| + |J0k|) * 256 * q,
 * and the caller checked that this fits an int32 lane. */
static void partial_block_quads(struct run *r, int x0, int y0, int x1, int y1, const unsigned mask[3])
{
    const struct biased_edges *e = &r->e;
    int xq0 = x0 & ~3;
    __m128i row_f[3], step_x[3], step_y[3];
    for (int k = 0; k < 3; k++) {
        if (mask[k] == 0xF) {   /* inside this edge everywhere: nothing to test */
            row_f[k] = step_x[k] = step_y[k] = _mm_setzero_si128();
            continue;
        }
        int64_t f = biased_edge_at(e, k, xq0, y0);
        row_f[k] = _mm_setr_epi32((int32_t)f, (int32_t)(f + e->dx[k]),
                                  (int32_t)(f + 2 * e->dx[k]), (int32_t)(f + 3 * e->dx[k]));
        step_x[k] = _mm_set1_epi32((int32_t)(4 * e->dx[k]));
        step_y[k] = _mm_set1_epi32((int32_t)e->dy[k]);
    }
    struct target *fb = r->fb;
    bool checker = r->pl.checker, whole = quads_fit(fb, x1 & ~3);
    struct quad step = quad_step(&r->pl);
    for (int y = y0; y <= y1; y++) {
        struct quad qd = quad_at(&r->pl, xq0, y);
        size_t row = (size_t)y * (size_t)fb->w;
        __m128i f[3] = { row_f[0], row_f[1], row_f[2] };
        for (int xq = xq0; xq <= x1; xq += 4) {
            /* covered: all three values >= 0, i.e. the sign bit of none is set */
            __m128i any_negative = _mm_srai_epi32(_mm_or_si128(_mm_or_si128(f[0], f[1]), f[2]), 31);
            __m128i covered = _mm_andnot_si128(any_negative, lanes_within(xq, x0, x1));
            bool any = _mm_movemask_ps(_mm_castsi128_ps(covered)) != 0;
            if (any && whole)
                write_quad(fb->depth + row + xq, fb->color + row + xq, covered, &qd, checker);
            else if (any)
                write_quad_pixels(fb, xq, y, covered, &qd, checker);
            quad_next(&qd, &step, checker);
            for (int k = 0; k < 3; k++)
                f[k] = _mm_add_epi32(f[k], step_x[k]);
        }
        for (int k = 0; k < 3; k++)
            row_f[k] = _mm_add_epi32(row_f[k], step_y[k]);
    }
}

/* --- blocks ----------------------------------------------------------------- */

/* Classify one block (pixels x0..x1, y0..y1), narrate it, and act. */
static enum block_class block(struct run *r, enum block_rule rule, int x0, int y0, int x1, int y1,
                              bool act_on_partial)
{
    unsigned m[3];
    corner_masks(r, x0, y0, x1, y1, m);
    enum block_class klass = classify(m, rule);
    int line = klass == BLOCK_EMPTY ? L_EMPTY : klass == BLOCK_FULL ? L_FULL : L_PARTIAL;
    NARRATE(r->tr, .kind = TRACE_BLOCK, .line = (uint8_t)line, .span = (uint8_t)(line - L_LOOP),
            .x = x0, .y = y0,
            .x1 = x1, .y1 = y1, .klass = (uint8_t)klass,
            .mask = { (uint16_t)m[0], (uint16_t)m[1], (uint16_t)m[2] },
            .e = { biased_edge_at(&r->e, 0, x0, y0) - r->e.bias[0],
                   biased_edge_at(&r->e, 1, x0, y0) - r->e.bias[1],
                   biased_edge_at(&r->e, 2, x0, y0) - r->e.bias[2] },
            .aux = { (float)r->size, (float)r->level });
    if (klass == BLOCK_FULL && !trace_frozen(r->tr))
        render_block(r, x0, y0, x1, y1);
    if (klass != BLOCK_PARTIAL || !act_on_partial)
        return klass;
    if (r->narrate || r->pixelwise || !r->fits_int32)
        partial_block_pixels(r, x0, y0, x1, y1);
    else
        partial_block_quads(r, x0, y0, x1, y1, m);
    return klass;
}

/* The q x q grid over the part x0..x1, y0..y1 of the box. The grid is aligned
 * on the screen (block edges at multiples of q), so neighbouring triangles
 * share blocks and a block's rows line up with the SSE quads; blocks are
 * clipped to the box. A box that fits in one block is that block. */
static void blocks(struct run *r, enum block_rule rule, int x0, int y0, int x1, int y1, int q, int level)
{
    r->size = q;
    r->level = level;
    if (x1 - x0 < q && y1 - y0 < q) {
        block(r, rule, x0, y0, x1, y1, true);
        return;
    }
    for (int by = y0 - y0 % q; by <= y1; by += q) {
        int ya = by < y0 ? y0 : by, yb = by + q - 1 > y1 ? y1 : by + q - 1;
        for (int bx = x0 - x0 % q; bx <= x1; bx += q) {
            int xa = bx < x0 ? x0 : bx, xb = bx + q - 1 > x1 ? x1 : bx + q - 1;
            block(r, rule, xa, ya, xb, yb, true);
        }
    }
}

/* --- the rasterizer ----------------------------------------------------------- */

struct block_options {
    int q;                  /* block size; 0 = --block-size, else Q_DEFAULT */
    int coarse;             /* > 0: hierarchical, coarse blocks of this size first */
    enum block_rule rule;
    bool pixelwise;         /* partial blocks one pixel at a time, always */
};

static void rasterize_blocks(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr, struct block_options o)
{
    NARRATE_SETUP(tr, t, TRACE_LINES(L_SETUP, L_BOX));  /* the edges and their box */
    if (t->empty)
        return;
    int q = o.q > 0 ? o.q : p->knob[P_BLOCK] > 0 ? p->knob[P_BLOCK] : Q_DEFAULT;
    if (q > Q_COARSE)
        q = Q_COARSE;

    struct run r;       /* set field by field: an initializer would clear all of it, per triangle */
    r.t = t;
    r.fb = fb;
    r.tr = tr;
    r.narrate = NARRATING && tr;
    r.pixelwise = o.pixelwise;
    r.size = q;
    r.level = 0;
    biased_edges_setup(&r.e, t, true);
    planes_setup(&r.pl, t, p);
    /* the SSE partial loop keeps edge values in int32 lanes: see there */
    int64_t widest = 0;
    for (int k = 0; k < 3; k++) {
        int64_t span = llabs(r.e.dx[k]) + llabs(r.e.dy[k]);
        widest = span > widest ? span : widest;
    }
    r.fits_int32 = widest * (q + 4) < INT32_MAX;

    if (o.coarse <= 0 || (t->maxx - t->minx < q && t->maxy - t->miny < q)) {
        blocks(&r, o.rule, t->minx, t->miny, t->maxx, t->maxy, q, 0);
        return;
    }
    /* Hierarchical: a coarse block that is empty or full settles all of its
     * sub-blocks at once; only a partial one is looked at q x q block by
     * q x q block. */
    int c = o.coarse;
    for (int cy = t->miny - t->miny % c; cy <= t->maxy; cy += c) {
        int ya = cy < t->miny ? t->miny : cy, yb = cy + c - 1 > t->maxy ? t->maxy : cy + c - 1;
        for (int cx = t->minx - t->minx % c; cx <= t->maxx; cx += c) {
            int xa = cx < t->minx ? t->minx : cx, xb = cx + c - 1 > t->maxx ? t->maxx : cx + c - 1;
            r.size = c;
            r.level = 0;
            if (block(&r, o.rule, xa, ya, xb, yb, false) == BLOCK_PARTIAL)
                blocks(&r, o.rule, xa, ya, xb, yb, q, 1);
        }
    }
}

/* --- the variants ------------------------------------------------------------- */

static void rasterize_q8(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0 });
}

static void rasterize_q4(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 4 });
}

static void rasterize_q16(const struct tri_setup *t, const struct raster_params *p,
                          struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 16 });
}

static void rasterize_hier(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0, .coarse = Q_COARSE });
}

static void rasterize_pixelwise(const struct tri_setup *t, const struct raster_params *p,
                                struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .q = 0, .pixelwise = true });
}

static void rasterize_corners_outside(const struct tri_setup *t, const struct raster_params *p,
                                      struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .rule = RULE_CORNERS_OUTSIDE });
}

static void rasterize_or_inside(const struct tri_setup *t, const struct raster_params *p,
                                struct target *fb, struct trace *tr)
{
    rasterize_blocks(t, p, fb, tr, (struct block_options){ .rule = RULE_OR_INSIDE });
}

static const struct lesson_variant variants[] = {
    { .name = "q8", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_q8,
      .what = "8 x 8 blocks (or --block-size Q), partial blocks four pixels at a time" },
    { .name = "q4", .kind = VARIANT_TWIN, .rasterize = rasterize_q4,
      .what = "4 x 4 blocks" },
    { .name = "q16", .kind = VARIANT_TWIN, .rasterize = rasterize_q16,
      .what = "16 x 16 blocks" },
    { .name = "hier", .kind = VARIANT_TWIN, .rasterize = rasterize_hier,
      .what = "64 x 64 coarse blocks, the partial ones cut into 8 x 8 blocks" },
    { .name = "q8-pixel", .kind = VARIANT_TWIN, .rasterize = rasterize_pixelwise,
      .what = "8 x 8 blocks, partial blocks one pixel at a time (64-bit edge values)" },
    { .name = "corners-outside", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_corners_outside,
      .what = "exhibit: skip a block when every corner is outside the triangle" },
    { .name = "or-inside", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_or_inside,
      .what = "exhibit: the pseudo-code's || makes a block full when inside ONE edge" },
};

static const char *const compare[] = { "02-barycentric", "03-edge-stepping", NULL };

const struct lesson lesson_05 = {
    .id = "05-block-classification",
    .title = "q x q block classification",
    .pseudocode = pseudocode,
    .builtin_scene = "blocks",
    .exhibit_scene = "blocks-exhibits",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .params = (const struct lesson_param[]){
        [P_BLOCK] = { .option = "block-size", .arg = "Q", .name = "block", .key = 'b', .min = 4,
                      .max = 16, .values = (const int[]){ 4, 8, 16, -1 }, .def = Q_DEFAULT,
                      .help = "block size for block lessons (4, 8 or 16)" },
        { 0 } },
    .cost_tested = (const struct cost_term[]){ COST_TERM(3, EDGE_STEP_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, QUAD_DEPTH_COST), COST_TERM(1, QUAD_COLOUR_COST), { 0 } },
    .compare = compare,
    .exercise = { .write_line = L_PIXEL, .full_blocks = true },
};
