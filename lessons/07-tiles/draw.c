/* Lesson 07, stage 3: one triangle inside one tile (llvmpipe's
 * lp_rast_tri.c): the tile buffer it is drawn in, and the descent tile ->
 * 8 x 8 blocks -> strips of 8 pixels, which one of the twins of strips.c
 * draws. */
#include <string.h>

#include "tiles.h"
#if TILES_AVX2
#define AVX2 __attribute__((target("avx2")))
#endif

/* --- where the pixels go: the tile buffer, or the target itself ---------- */

/* Load the part `part` of tile r (the rectangle its bin's triangles may
 * touch: what is outside it is never read) into the tile buffer; the
 * pixels of r are then written through the result. */
struct dst tile_load(struct tile_buf *b, const struct target *fb, struct rect r, struct rect part)
{
    size_t at = (size_t)(part.y0 - r.y0) * TILE + (size_t)(part.x0 - r.x0);
    for (int j = 0; j < part.h; j++) {
        size_t row = (size_t)(part.y0 + j) * (size_t)fb->w + (size_t)part.x0, o = at + (size_t)j * TILE;
        memcpy(b->color + o, fb->color + row, (size_t)part.w * sizeof *b->color);
        memcpy(b->depth + o, fb->depth + row, (size_t)part.w * sizeof *b->depth);
    }
    size_t first = (size_t)r.y0 * (size_t)fb->w + (size_t)r.x0;
    return (struct dst){ b->color, b->depth, fb->count ? fb->count + first : NULL, TILE, r.w, r.h,
                         TILE + LANES, fb->w };
}

/* Store that part back: once per tile. */
void tile_store(const struct tile_buf *b, struct target *fb, struct rect r, struct rect part)
{
    size_t at = (size_t)(part.y0 - r.y0) * TILE + (size_t)(part.x0 - r.x0);
    for (int j = 0; j < part.h; j++) {
        size_t row = (size_t)(part.y0 + j) * (size_t)fb->w + (size_t)part.x0, o = at + (size_t)j * TILE;
        memcpy(fb->color + row, b->color + o, (size_t)part.w * sizeof *b->color);
        memcpy(fb->depth + row, b->depth + o, (size_t)part.w * sizeof *b->depth);
    }
}

/* The same rectangle written in place, on the target. */
struct dst target_dst(struct target *fb, struct rect r)
{
    size_t o = (size_t)r.y0 * (size_t)fb->w + (size_t)r.x0;
    return (struct dst){ fb->color + o, fb->depth + o, fb->count ? fb->count + o : NULL,
                         fb->w, r.w, r.h, r.w, fb->w };
}


struct tri_in_tile tri_in_tile_make(const struct tri *t, struct rect r)
{
    struct tri_in_tile c = { t, t->textured ? t->st : NULL, r.x0, r.y0, { 0, 0, 0 } };
    for (int k = 0; k < 3; k++) {
        int64_t e = floor_div(edge_at(t, k, r.x0, r.y0), SUBPIXEL_ONE);    /* no branch on the sign */
        c.e0[k] = (int32_t)(e > E_LIMIT ? E_LIMIT : e < -E_LIMIT - 1 ? -E_LIMIT - 1 : e);
    }
    return c;
}

/* --- the descent: tile -> blocks -> 8 pixels a register ------------------ */

/* The lanes of columns i .. i + 7 that lie in [x0, x1] (x0 - 7 <= i <= x1). */
static inline unsigned lane_mask(int i, int x0, int x1)
{
    int lo = x0 - i < 0 ? 0 : x0 - i, hi = x1 - i > LANES - 1 ? LANES - 1 : x1 - i;
    return (2u << hi) - (1u << lo);
}

/* Narrated pixel by pixel, writing the target as it goes (what the
 * explorer steps through): the test (E), then the scalar twin's shading. */
static void narrate_pixels(const struct tri_in_tile *c, const struct dst *d, const struct rows *rw,
                           struct trace *tr, int i0, int j, unsigned mask)
{
    const struct tri *t = c->t;
    for (int l = 0; l < LANES; l++) {
        if (!(mask >> l & 1))
            continue;
        int i = i0 + l;
        bool in = true;
        for (int k = 0; k < 3; k++)
            in = in && c->e0[k] + t->di[k] * i + t->dj[k] * j >= 0;
        COUNT(tr, 3, LANE_EDGE_COST);
        /* the narration shows F_k itself: the bias taken out again */
        NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_BLOCK_PARTIAL, .x = c->tx + i, .y = c->ty + j,
                .e = { edge_at(t, 0, c->tx + i, c->ty + j) + (t->bias_neg & 1),
                       edge_at(t, 1, c->tx + i, c->ty + j) + (t->bias_neg >> 1 & 1),
                       edge_at(t, 2, c->tx + i, c->ty + j) + (t->bias_neg >> 2 & 1) },
                .flags = in ? TRACE_INSIDE : 0);
        if (!in)
            continue;
        float z;
        uint32_t rgba;
        bool pass = shade1_c(c, d, rw, i, j, &z, &rgba);
        COUNT(tr, QUAD_PLANES, PLANE_AT_COST);
        COUNT(tr, 1, RECIPROCAL_COST);
        COUNT(tr, 1, COLOUR_TIMES_Z_COST);
        NARRATE(tr, .kind = TRACE_PIXEL_WRITE, .line = L_BLOCK_PARTIAL, .x = c->tx + i, .y = c->ty + j, .z = z,
                .rgba = rgba, .flags = pass ? TRACE_DEPTH_PASS : 0);
        if (tr && tr->frozen)
            return;
        size_t o = (size_t)j * (size_t)d->stride + (size_t)i;
        size_t oc = (size_t)j * (size_t)d->count_stride + (size_t)i;
        if (d->count && d->count[oc] < 255)
            d->count[oc]++;
        if (pass) {
            d->depth[o] = z;
            d->color[o] = rgba;
        }
    }
}

/* Rows y0 .. y1 (tile coordinates) of the columns x0 .. x1: test them when
 * `test`, else shade every pixel (a FULL block or tile); strip after strip
 * of 8 columns, by the twin, or pixel by pixel when narrated. */
static inline __attribute__((always_inline)) void
draw_rows(const struct tri_in_tile *c, const struct dst *d, struct trace *tr, int x0, int y0, int x1,
          int y1, bool test, strip_fn strip)
{
    if (NARRATING && tr && test) {
        for (int j = y0; j <= y1; j++) {
            struct rows rw;
            plane_rows(c, j, &rw);
            for (int i = x0; i <= x1; i += LANES)
                narrate_pixels(c, d, &rw, tr, i, j, lane_mask(i, x0, x1));
        }
        return;
    }
    for (int i = x0; i <= x1; i += LANES) {
        unsigned m = lane_mask(i, x0, x1);
        if (frozen(tr))
            return;
        if (!test) {    /* a FULL block or tile: shaded without a test */
            int n = __builtin_popcount(m) * (y1 - y0 + 1);
            COUNT(tr, (unsigned)n * QUAD_PLANES, PLANE_AT_COST);
            COUNT(tr, n, RECIPROCAL_COST);
            COUNT(tr, n, COLOUR_TIMES_Z_COST);
        }
        strip(c, d, i, y0, y1, m, test);
    }
}

/* Draw triangle t into the tile r (pixels written through d). `full`: the
 * binning found the tile wholly inside. */
static inline __attribute__((always_inline)) void
draw_in_tile(const struct tri *t, struct rect r, bool full, const struct dst *d, struct trace *tr,
             bool four, strip_fn strip)
{
    struct tri_in_tile c = tri_in_tile_make(t, r);
    if (full) {     /* narrated by the tile's own (FULL) step: the caller's */
        draw_rows(&c, d, tr, 0, 0, r.w - 1, r.h - 1, false, strip);
        return;
    }
    /* the box, in tile coordinates */
    int x0 = t->minx - r.x0, y0 = t->miny - r.y0, x1 = t->maxx - r.x0, y1 = t->maxy - r.y0;
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > r.w - 1 ? r.w - 1 : x1, y1 = y1 > r.h - 1 ? r.h - 1 : y1;

    if (x1 - x0 < BLOCK && y1 - y0 < BLOCK) {    /* the small-triangle path */
        NARRATE(tr, .kind = TRACE_BLOCK, .line = L_SMALL, .x = r.x0 + x0, .y = r.y0 + y0,
                .x1 = r.x0 + x1, .y1 = r.y0 + y1, .klass = BLOCK_PARTIAL, .aux = { BLOCK, 1 });
        draw_rows(&c, d, tr, x0, y0, x1, y1, true, strip);
        return;
    }
    /* 8 x 8 blocks, aligned in the tile: one reject and one accept corner
     * per edge, in (E)'s int32 units */
    int32_t rej[3], acc[3];
    for (int k = 0; k < 3; k++) {
        int32_t a = t->di[k], b = t->dj[k];
        rej[k] = (a > 0 ? a : 0) * (BLOCK - 1) + (b > 0 ? b : 0) * (BLOCK - 1);
        acc[k] = (a < 0 ? a : 0) * (BLOCK - 1) + (b < 0 ? b : 0) * (BLOCK - 1);
    }
    for (int by = y0 & ~(BLOCK - 1); by <= y1; by += BLOCK) {
        for (int bx = x0 & ~(BLOCK - 1); bx <= x1; bx += BLOCK) {
            /* a block cut by the screen's right or bottom edge has its
             * corners on its last pixels there, not on the next tile's */
            int bx1 = bx + BLOCK - 1 < r.w ? bx + BLOCK - 1 : r.w - 1;
            int by1 = by + BLOCK - 1 < r.h ? by + BLOCK - 1 : r.h - 1;
            bool cut = bx1 - bx < BLOCK - 1 || by1 - by < BLOCK - 1;
            enum block_class klass = BLOCK_FULL;
            for (int k = 0; k < 3; k++) {
                int32_t a = t->di[k], b = t->dj[k];
                int32_t e = c.e0[k] + a * bx + b * by, lo = e + acc[k], hi = e + rej[k];
                if (cut) {
                    lo = e + (a < 0 ? a : 0) * (bx1 - bx) + (b < 0 ? b : 0) * (by1 - by);
                    hi = e + (a > 0 ? a : 0) * (bx1 - bx) + (b > 0 ? b : 0) * (by1 - by);
                }
                if (four) {     /* lesson 05's way, for the measurement: every corner */
                    int32_t right = a * (bx1 - bx), down = b * (by1 - by);
                    int32_t q[4] = { e, e + right, e + down, e + right + down };
                    lo = hi = q[0];
                    for (int i = 1; i < 4; i++) {
                        lo = q[i] < lo ? q[i] : lo;
                        hi = q[i] > hi ? q[i] : hi;
                    }
                }
                if (hi < 0) {
                    klass = BLOCK_EMPTY;
                    break;
                }
                if (lo < 0)
                    klass = BLOCK_PARTIAL;
            }
            NARRATE(tr, .kind = TRACE_BLOCK,
                    .line = klass == BLOCK_EMPTY ? L_BLOCK_REJECT
                          : klass == BLOCK_FULL ? L_BLOCK_ACCEPT : L_BLOCK_PARTIAL,
                    .x = r.x0 + bx, .y = r.y0 + by, .x1 = r.x0 + bx1, .y1 = r.y0 + by1,
                    .klass = (uint8_t)klass, .aux = { BLOCK, 1 },
                    .mask = { corner_bits(t, 0, r.x0 + bx, r.y0 + by, r.x0 + bx1, r.y0 + by1),
                              corner_bits(t, 1, r.x0 + bx, r.y0 + by, r.x0 + bx1, r.y0 + by1),
                              corner_bits(t, 2, r.x0 + bx, r.y0 + by, r.x0 + bx1, r.y0 + by1) });
            if (klass != BLOCK_EMPTY)
                draw_rows(&c, d, tr, bx, by, bx1, by1, klass == BLOCK_PARTIAL, strip);
        }
    }
}

static void draw_c(const struct tri *t, struct rect r, bool full, const struct dst *d,
                   struct trace *tr, bool four)
{
    draw_in_tile(t, r, full, d, tr, four, strip_c);
}

static void draw_sse2(const struct tri *t, struct rect r, bool full, const struct dst *d,
                   struct trace *tr, bool four)
{
    draw_in_tile(t, r, full, d, tr, four, strip_sse2);
}

#if TILES_AVX2
AVX2 static void draw_avx2(const struct tri *t, struct rect r, bool full, const struct dst *d,
                           struct trace *tr, bool four)
{
    draw_in_tile(t, r, full, d, tr, four, strip_avx2);
}
#endif

/* The twin to run: AVX2 only where the CPU says it has it. */
draw_fn pick_twin(enum twin w)
{
#if TILES_AVX2
    if ((w == TWIN_BEST || w == TWIN_AVX2) && __builtin_cpu_supports("avx2"))
        return draw_avx2;
#endif
    return w == TWIN_C ? draw_c : draw_sse2;
}

