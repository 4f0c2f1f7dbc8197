/* Lesson 07, stage 2: binning (llvmpipe's lp_scene.c).
 *
 * An edge function is linear, so over a rectangle of pixel centres it is
 * smallest at one corner and largest at the opposite one, and WHICH corner
 * depends only on the signs of I and J (Greene 1996; Abrash 2009):
 *
 *        I > 0, J > 0: F grows right and down    reject corner: bottom-right
 *        +-------------+                          accept corner: top-left
 *        |accept       |
 *        |       ----> |   If F < 0 at the reject corner (the largest value),
 *        |      |      |   the tile is outside this edge: not in the bin.
 *        |      v reject   If F >= 0 at every edge's accept corner (each
 *        +-------------+   edge's smallest value), the tile is inside: FULL.
 *
 * One corner per edge per test, where lesson 05 evaluated four. */

#define _POSIX_C_SOURCE 200809L     /* aligned_alloc */
#include <stdint.h>
#include <stdlib.h>

#include "tiles.h"

/* Corner offsets: (w - 1, h - 1) picked per edge by the signs of I and J. */
static int64_t reject_corner(const struct tri *t, int k, int64_t f, int w, int h)
{
    return f + SUBPIXEL_ONE * ((t->di[k] > 0 ? (int64_t)t->di[k] * (w - 1) : 0)
                               + (t->dj[k] > 0 ? (int64_t)t->dj[k] * (h - 1) : 0));
}

static int64_t accept_corner(const struct tri *t, int k, int64_t f, int w, int h)
{
    return f + SUBPIXEL_ONE * ((t->di[k] < 0 ? (int64_t)t->di[k] * (w - 1) : 0)
                               + (t->dj[k] < 0 ? (int64_t)t->dj[k] * (h - 1) : 0));
}

/* Is rectangle r outside the triangle (BLOCK_EMPTY), inside it (BLOCK_FULL)
 * or neither (BLOCK_PARTIAL)? */
enum block_class classify_rect(const struct tri *t, struct rect r, enum corners rule)
{
    bool full = true;
    for (int k = 0; k < 3; k++) {
        int64_t f = edge_at(t, k, r.x0, r.y0);
        int64_t lo, hi;     /* the edge's smallest and largest value on r */
        if (rule == CORNERS_FOUR) {
            int64_t right = SUBPIXEL_ONE * (int64_t)t->di[k] * (r.w - 1);
            int64_t down = SUBPIXEL_ONE * (int64_t)t->dj[k] * (r.h - 1);
            int64_t c[4] = { f, f + right, f + down, f + right + down };
            lo = hi = c[0];
            for (int i = 1; i < 4; i++) {
                lo = c[i] < lo ? c[i] : lo;
                hi = c[i] > hi ? c[i] : hi;
            }
        } else {
            lo = accept_corner(t, k, f, r.w, r.h);
            hi = rule == CORNERS_WRONG ? lo : reject_corner(t, k, f, r.w, r.h);
        }
        if (hi < 0)
            return BLOCK_EMPTY;
        full = full && lo >= 0;
    }
    return full ? BLOCK_FULL : BLOCK_PARTIAL;
}

/* --- where the bins live: each worker's own memory ------------------------
 *
 * A worker bins its shares of the scene into blocks of its own arena: no
 * lock, no line written by two cores. The arena's chunks are kept from one
 * run to the next, as llvmpipe keeps its scenes: fresh memory from the
 * system costs a page fault per 4 KB, about as much as drawing the small
 * triangles it holds. */
#define CHUNK_BYTES ((size_t)1 << 20)

struct chunk {
    struct chunk *next;
    size_t used, size;
    _Alignas(CACHE_LINE) unsigned char data[];
};

void *arena_alloc(struct arena *a, size_t n)
{
    n = (n + CACHE_LINE - 1) & ~(size_t)(CACHE_LINE - 1);
    while (a->cur && a->cur->used + n > a->cur->size)
        a->cur = a->cur->next;          /* kept from an earlier run, or NULL */
    if (!a->cur) {
        size_t size = n > CHUNK_BYTES ? n : CHUNK_BYTES;
        struct chunk *c = size <= SIZE_MAX - sizeof *c ? aligned_alloc(CACHE_LINE, sizeof *c + size)
                                                       : NULL;
        if (!c)
            return NULL;
        c->next = NULL;
        c->used = 0;
        c->size = size;
        if (a->last)
            a->last->next = c;
        else
            a->first = c;
        a->last = a->cur = c;
    }
    void *p = a->cur->data + a->cur->used;
    a->cur->used += n;
    return p;
}

/* Every chunk empty again, kept for the next run. */
void arena_reset(struct arena *a)
{
    for (struct chunk *c = a->first; c; c = c->next)
        c->used = 0;
    a->cur = a->first;
}

/* Ask the cache for the line of p, to be written soon. */
static void prefetch_for_write(const void *p)
{
    __builtin_prefetch(p, 1);
}

static bool bin_push(struct bin *bin, struct arena *a, uint32_t entry)
{
    struct bin_block *b = bin->last;
    if (!b || b->n == BIN_BLOCK) {
        struct bin_block *fresh = arena_alloc(a, sizeof *fresh);
        if (!fresh)
            return false;
        fresh->next = NULL;
        fresh->n = 0;
        if (b)
            b->next = fresh;
        else
            bin->first = fresh;
        bin->last = b = fresh;
    }
    b->entry[b->n++] = entry;
    /* This bin's next triangle comes hundreds of triangles later, after
     * the other bins': its slot, asked for now, is in the cache by then
     * (hundreds of bins filled at once are more streams than the hardware
     * prefetcher follows). */
    if (b->n < BIN_BLOCK)
        prefetch_for_write(&b->entry[b->n]);
    return true;
}

/* Put triangle number `index` (record t) into the bins of the tiles it may
 * touch, memory from arena a. A box within one tile needs no test: the
 * tile's blocks will sort it out. */
bool bin_triangle(const struct tri *t, uint32_t index, const struct grid *g, struct bin *bins,
                  struct arena *a, enum corners rule, struct trace *tr)
{
    int tx0 = t->minx / TILE, tx1 = t->maxx / TILE, ty0 = t->miny / TILE, ty1 = t->maxy / TILE;
    NARRATE(tr, .kind = TRACE_BLOCK, .line = L_BIN, .x = tx0 * TILE, .y = ty0 * TILE,
            .x1 = tx1 * TILE + TILE - 1 < g->w ? tx1 * TILE + TILE - 1 : g->w - 1,
            .y1 = ty1 * TILE + TILE - 1 < g->h ? ty1 * TILE + TILE - 1 : g->h - 1,
            .klass = BLOCK_CLASS_COUNT, .aux = { TILE, 0 });
    if (tx0 == tx1 && ty0 == ty1)
        return bin_push(&bins[ty0 * g->nx + tx0], a, bin_entry_of(index, false));
    for (int ty = ty0; ty <= ty1; ty++)
        for (int tx = tx0; tx <= tx1; tx++) {
            int tile = ty * g->nx + tx;
            struct rect r = tile_rect(g, tile);
            enum block_class k = classify_rect(t, r, rule);
            NARRATE(tr, .kind = TRACE_BLOCK,
                    .line = k == BLOCK_EMPTY ? L_REJECT : k == BLOCK_FULL ? L_ACCEPT : L_PARTIAL_TILE,
                    .x = r.x0, .y = r.y0, .x1 = r.x0 + r.w - 1, .y1 = r.y0 + r.h - 1,
                    /* FULL is said by the tile's own step, when it is filled */
            .klass = k == BLOCK_FULL ? BLOCK_CLASS_COUNT : (uint8_t)k, .aux = { TILE, 0 },
                    .mask = { corner_bits(t, 0, r.x0, r.y0, r.x0 + r.w - 1, r.y0 + r.h - 1),
                              corner_bits(t, 1, r.x0, r.y0, r.x0 + r.w - 1, r.y0 + r.h - 1),
                              corner_bits(t, 2, r.x0, r.y0, r.x0 + r.w - 1, r.y0 + r.h - 1) });
            if (k != BLOCK_EMPTY && !bin_push(&bins[tile], a, bin_entry_of(index, k == BLOCK_FULL)))
                return false;
        }
    return true;
}
