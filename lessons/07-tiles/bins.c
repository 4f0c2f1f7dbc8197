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

#define _POSIX_C_SOURCE 200809L     /* pthreads */
#include <pthread.h>
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

/* Blocks are kept from one run to the next, as llvmpipe keeps its scenes:
 * fresh memory from the system costs a page fault per 4 KB, about as much
 * as drawing the small triangles it holds. The pool is shared by every run
 * and every worker, under a lock taken once per block. */
#define POOL_MAX 16384          /* blocks kept: 64 MB */
static pthread_mutex_t pool_lock = PTHREAD_MUTEX_INITIALIZER;
static struct bin_block *pool;
static int pool_size;

static struct bin_block *block_get(void)
{
    pthread_mutex_lock(&pool_lock);
    struct bin_block *b = pool;
    if (b) {
        pool = b->next;
        pool_size--;
    }
    pthread_mutex_unlock(&pool_lock);
    if (!b && !(b = malloc(sizeof *b)))
        return NULL;
    b->next = NULL;
    b->n = 0;
    return b;
}

/* Give a bin's blocks back to the pool (beyond POOL_MAX, to the system). */
void bin_free(struct bin *bin)
{
    struct bin_block *b = bin->first;
    if (!b)
        return;
    pthread_mutex_lock(&pool_lock);
    while (b) {
        struct bin_block *next = b->next;
        if (pool_size < POOL_MAX) {
            b->next = pool;
            pool = b;
            pool_size++;
        } else {
            free(b);
        }
        b = next;
    }
    pthread_mutex_unlock(&pool_lock);
    bin->first = bin->last = NULL;
}

/* Ask the cache for the lines of [p, p + n), to be written soon. */
static void prefetch_for_write(const void *p, size_t n)
{
    const char *c = p;
    for (size_t o = 0; o < n; o += CACHE_LINE)
        __builtin_prefetch(c + o, 1);
    __builtin_prefetch(c + n - 1, 1);
}

static bool bin_push(struct bin *bin, const struct tri *t, bool full)
{
    struct bin_block *b = bin->last;
    if (!b || b->n == BIN_BLOCK) {
        struct bin_block *fresh = block_get();
        if (!fresh)
            return false;
        if (b)
            b->next = fresh;
        else
            bin->first = fresh;
        bin->last = b = fresh;
    }
    b->rec[b->n] = *t;
    b->rec[b->n++].full = full;
    /* This bin's next triangle comes hundreds of triangles later, after
     * the other bins': its slot, asked for now, is in the cache by then.
     * Otherwise every record written waits for its lines from memory
     * (hundreds of bins filled at once are more streams than the hardware
     * prefetcher follows). */
    if (b->n < BIN_BLOCK)
        prefetch_for_write(&b->rec[b->n], sizeof *t);
    return true;
}

/* Put a triangle into the bins of the tiles it may touch. A box within one
 * tile needs no test: the tile's blocks will sort it out. */
bool bin_triangle(const struct tri *t, const struct grid *g, struct bin *bins, enum corners rule)
{
    int tx0 = t->minx / TILE, tx1 = t->maxx / TILE, ty0 = t->miny / TILE, ty1 = t->maxy / TILE;
    if (tx0 == tx1 && ty0 == ty1)
        return bin_push(&bins[ty0 * g->nx + tx0], t, false);
    for (int ty = ty0; ty <= ty1; ty++)
        for (int tx = tx0; tx <= tx1; tx++) {
            int tile = ty * g->nx + tx;
            enum block_class k = classify_rect(t, tile_rect(g, tile), rule);
            if (k != BLOCK_EMPTY && !bin_push(&bins[tile], t, k == BLOCK_FULL))
                return false;
        }
    return true;
}

