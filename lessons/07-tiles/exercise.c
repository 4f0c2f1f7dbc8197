/* Exercise 07: write lesson 07's trivial-reject and trivial-accept corners,
 * and the class of a tile or block they give.
 *
 * One triangle goes through the tiles as threads.c's rasterize_one_tri takes
 * it, and all of that is here: every 64 x 64 tile of the box classified
 * (the screen's right and bottom edges cut the last ones), a FULL tile
 * shaded without a single test, a PARTIAL one cut into 8 x 8 blocks, each
 * classified in turn, a FULL block shaded without a test, a PARTIAL one
 * tested pixel by pixel; the edge values with the fill rule folded in, and
 * perspective-correct shading. Yours: the corner of a rectangle where an
 * edge is largest (trivial reject) and where it is smallest (trivial
 * accept), and the class the three edges give the rectangle. As given,
 * every corner is 0, every tile is called empty, and nothing is drawn.
 *
 *     make exercise LESSON=07        the explorer on this file: the blocks
 *                                    view shows your classes, rings and
 *                                    discs the corners the lesson picks
 *     make check LESSON=07           the checks; "tiles and blocks" draws
 *                                    scenes over many tiles, and the last
 *                                    is the lesson's own, "corner classes":
 *                                    every tile and block gets exactly the
 *                                    class its corners give it, EMPTY,
 *                                    FULL or PARTIAL
 *
 * One triangle at a time, not the bins and threads of the whole scene: the
 * check compares your picture with the exact rule after every triangle,
 * and the decisions of this lesson are all made per triangle and
 * rectangle (README "Write it yourself" says more).
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 07's pseudo-code, which the explorer lights. */
enum { L_SETUP, L_BIN, L_REJECT, L_ACCEPT, L_PARTIAL_TILE, L_TAKE, L_BIN_LOOP, L_FULL_TILE,
       L_SMALL, L_BLOCK_REJECT, L_BLOCK_ACCEPT, L_BLOCK_PARTIAL, L_STORE };

#define TILE 64     /* tile side, as tiles.c */
#define BLOCK 8     /* block side */

/* The edges with the fill rule folded in: F_k + bias_k at the centre of
 * pixel (x, y) is f0[k] + dx[k] * x + dy[k] * y, exactly; the pixel is
 * covered when that is >= 0 for k = 0, 1, 2. dx[k] = 256 I_k, dy[k] =
 * 256 J_k: the edge's value grows by dx[k] a pixel to the right and by
 * dy[k] a row down. */
struct edges {
    int64_t f0[3], dx[3], dy[3];
};

static int64_t edge_at(const struct edges *e, int k, int x, int y)
{
    return e->f0[k] + e->dx[k] * x + e->dy[k] * y;
}

/* The pixels x0..x1, y0..y1 of a tile or a block: its corners are the
 * centres of its corner PIXELS, x1 and y1 included (the tiles and blocks
 * the screen's right and bottom edges cut end there, not 64 or 8 pixels on). */
struct rect {
    int x0, y0, x1, y1;
};

/* TODO 1, README "2. Binning: one corner per edge": the trivial-reject
 * corner. Edge k is linear, so over the pixel centres of r it is largest at
 * one corner and smallest at the opposite one, and the signs of dx[k] and
 * dy[k] say which:
 *
 *     (x0, y0) o---------o (x1, y0)     dx > 0: F grows to the right, its
 *              |    r    |             largest value is in column x1;
 *     (x0, y1) o---------o (x1, y1)     dy > 0: F grows downwards, row y1
 *
 * Return edge_at() at that corner, the edge's largest value on r: when it
 * is < 0, every pixel of r is outside edge k. */
static int64_t reject_corner(const struct edges *e, int k, struct rect r)
{
    (void)e, (void)k, (void)r;
    return 0;
}

/* TODO 2, the same section: the trivial-accept corner, the opposite one,
 * where edge k is smallest on r: when it is >= 0, every pixel of r is
 * inside edge k. */
static int64_t accept_corner(const struct edges *e, int k, struct rect r)
{
    (void)e, (void)k, (void)r;
    return 0;
}

/* TODO 3, README "2. Binning: one corner per edge" and "4. Hierarchical
 * descent": the class of r, BLOCK_EMPTY, BLOCK_FULL or BLOCK_PARTIAL, from
 * two corners per edge. Empty when ONE edge's reject corner is < 0 (reject
 * with the accept corner, and the rectangles an edge crosses are thrown
 * away whole: the exhibit `wrong-corner`); full when EVERY edge's accept
 * corner is >= 0; partial otherwise. */
static enum block_class classify(const struct edges *e, struct rect r)
{
    (void)e, (void)r;
    (void)reject_corner, (void)accept_corner;
    return BLOCK_EMPTY;
}

/* --- the descent, the narration and the shading, as the lesson has them ------------ */

/* For the narration: which of the four corner pixel centres of r lie inside
 * edge k (bit 3 top-left, 2 top-right, 1 bottom-left, 0 bottom-right, as
 * lesson 05 shows them); the explorer's watch panel prints them. */
static uint16_t corner_bits(const struct edges *e, int k, struct rect r)
{
    return (uint16_t)((edge_at(e, k, r.x0, r.y0) >= 0) << 3 | (edge_at(e, k, r.x1, r.y0) >= 0) << 2
                      | (edge_at(e, k, r.x0, r.y1) >= 0) << 1 | (edge_at(e, k, r.x1, r.y1) >= 0));
}

/* Classify r with your classify(), and narrate it: a tile (level 0) or a
 * block (level 1), on the pseudo-code line of its class. */
static enum block_class classified(const struct edges *e, struct rect r, int level, struct trace *tr)
{
    enum block_class klass = classify(e, r);
    static const int lines[2][3] = {
        { L_REJECT, L_FULL_TILE, L_PARTIAL_TILE },
        { L_BLOCK_REJECT, L_BLOCK_ACCEPT, L_BLOCK_PARTIAL },
    };
    NARRATE(tr, .kind = TRACE_BLOCK, .line = lines[level][klass], .x = r.x0, .y = r.y0, .x1 = r.x1,
            .y1 = r.y1, .klass = (uint8_t)klass, .aux = { level ? BLOCK : TILE, (float)level },
            .mask = { corner_bits(e, 0, r), corner_bits(e, 1, r), corner_bits(e, 2, r) });
    (void)lines;    /* the fast build compiles the narration out */
    return klass;
}

/* The pixels of r: each tested when `test` (a PARTIAL block), else shaded
 * without a test (a FULL tile or block); colour and depth perspective-
 * correct at the pixel centre, in double precision (src/raster's
 * reference_shade: lesson 04's formula 23), and written. */
static void pixels(const struct tri_setup *t, const struct raster_params *p, const struct edges *e,
                   struct target *fb, struct trace *tr, struct rect r, bool test, int line)
{
    for (int y = r.y0; y <= r.y1; y++)
        for (int x = r.x0; x <= r.x1; x++) {
            if (test) {
                int64_t F[3] = { edge_at(e, 0, x, y), edge_at(e, 1, x, y), edge_at(e, 2, x, y) };
                bool in = F[0] >= 0 && F[1] >= 0 && F[2] >= 0;
                NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = line, .x = x, .y = y,
                        .e = { F[0] - t->bias[0], F[1] - t->bias[1], F[2] - t->bias[2] },
                        .flags = in ? TRACE_INSIDE : 0);
                if (!in)
                    continue;
            }
            double z, rgb[3], st[2];
            reference_shade(t, x, y, true, &z, rgb, st);
            PLOT(fb, tr, line, x, y, (float)z, shade_pixel(p, tr, rgb[0], rgb[1], rgb[2], st[0], st[1]));
        }
}

/* One triangle through the tiles, as threads.c's rasterize_one_tri takes it:
 * every 64 x 64 tile of the box (cut by the screen's edges) classified; a
 * FULL tile shaded without a test; a PARTIAL one cut into the 8 x 8 blocks
 * of the tile's grid, each cut to the box (a small triangle's box is then
 * one block, where tiles.c takes a path of its own) and classified in turn. */
void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    struct edges e;
    for (int k = 0; k < 3; k++) {
        e.dx[k] = t->I[k] * SUBPIXEL_ONE;
        e.dy[k] = t->J[k] * SUBPIXEL_ONE;
        e.f0[k] = t->I[k] * SUBPIXEL_HALF + t->J[k] * SUBPIXEL_HALF + t->K[k] + t->bias[k];
    }
    for (int ty = t->miny / TILE; ty <= t->maxy / TILE; ty++)
        for (int tx = t->minx / TILE; tx <= t->maxx / TILE; tx++) {
            struct rect tile = { tx * TILE, ty * TILE, tx * TILE + TILE - 1, ty * TILE + TILE - 1 };
            tile.x1 = tile.x1 < fb->w - 1 ? tile.x1 : fb->w - 1;
            tile.y1 = tile.y1 < fb->h - 1 ? tile.y1 : fb->h - 1;
            enum block_class klass = classified(&e, tile, 0, tr);
            if (klass == BLOCK_EMPTY)
                continue;
            if (klass == BLOCK_FULL) {
                pixels(t, p, &e, fb, tr, tile, false, L_FULL_TILE);
                continue;
            }
            /* the box inside this tile, and the blocks of the tile's grid over it */
            struct rect box = { t->minx > tile.x0 ? t->minx : tile.x0, t->miny > tile.y0 ? t->miny : tile.y0,
                                t->maxx < tile.x1 ? t->maxx : tile.x1, t->maxy < tile.y1 ? t->maxy : tile.y1 };
            for (int by = box.y0 - box.y0 % BLOCK; by <= box.y1; by += BLOCK)
                for (int bx = box.x0 - box.x0 % BLOCK; bx <= box.x1; bx += BLOCK) {
                    struct rect b = { bx > box.x0 ? bx : box.x0, by > box.y0 ? by : box.y0,
                                      bx + BLOCK - 1 < box.x1 ? bx + BLOCK - 1 : box.x1,
                                      by + BLOCK - 1 < box.y1 ? by + BLOCK - 1 : box.y1 };
                    klass = classified(&e, b, 1, tr);
                    if (klass != BLOCK_EMPTY)
                        pixels(t, p, &e, fb, tr, b, klass == BLOCK_PARTIAL,
                               klass == BLOCK_FULL ? L_BLOCK_ACCEPT : L_BLOCK_PARTIAL);
                }
        }
}
