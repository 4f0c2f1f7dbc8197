/* Lesson 07: tiles, bins and threads - the production architecture.
 *
 * What it shows: how the rasterizers that ship (Mesa's llvmpipe, Abrash's
 * Larrabee rasterizer, the software occlusion culling that Giesen's
 * "Optimizing the basic rasterizer" takes apart) organise lesson 05's blocks
 * around a whole scene instead of one triangle:
 *
 *   1. set-up once per triangle: the three edges and the planes of 1/z, r/z,
 *      g/z, b/z, kept in a compact record;
 *   2. binning: the screen is cut into 64 x 64 tiles, and each triangle goes
 *      into the bin of every tile it may touch. One corner per edge decides
 *      that a tile is outside (the trivial-reject corner), one more that it
 *      is inside (the trivial-accept corner): Greene's and Abrash's test,
 *      instead of lesson 05's four corners per edge;
 *   3. tiles in cache: a worker takes a tile, loads its colour and depth into
 *      a 64 x 64 buffer (32 KB: it stays in the level-1 cache), draws every
 *      triangle of the bin in scene order, and stores the tile once. All the
 *      overdraw happens in cache;
 *   4. hierarchical descent: tile -> 8 x 8 blocks, each block rejected or
 *      accepted by its corners, partial blocks tested 8 pixels a register
 *      (AVX2 when the CPU has it, chosen at run time; SSE2 and plain C twins
 *      beside it, tested equal); a triangle whose box fits in one block skips
 *      the block tests altogether (the small-triangle path);
 *   5. threads: one worker per core takes tiles. Tiles do not overlap and a
 *      tile's bin keeps scene order, so the picture is the same bytes for any
 *      number of threads.
 *
 * Exact like every lesson: coverage is decided on lesson 03's integer edge
 * values with the top-left rule. One trick makes them fit 32-bit lanes: every
 * pixel centre of a tile lies a whole number of pixels away from the tile's
 * first one, so F(i, j) = F(0, 0) + 256 (I i + J j), and
 *
 *     F(i, j) >= 0   <=>   I i + J j + floor(F(0, 0) / 256) >= 0     (E)
 *
 * I i + J j stays below 2^30 inside a tile whatever the triangle (|I|, |J|
 * <= 2^23, 0 <= i, j < 64), so (E) is exact in int32: 8 pixels per AVX2
 * register.
 *
 * Colour and depth as lesson 05: perspective-correct from the planes of 1/z
 * and a/z (seed 001, formula 23), z = 1 / (1/z) by a true division, the same
 * float operations in every twin so that they write the same bytes.
 */
#define _POSIX_C_SOURCE 200809L     /* pthreads, sysconf */
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lesson.h"
#include "shade/quad.h"         /* the planes of 1/z and a/z (lesson 04), CHECKER_DARK */
#include "simd.h"               /* SSE2: four lanes a register, on any CPU */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TRISTEP_SIMDE)
#include <immintrin.h>          /* AVX2: eight lanes a register, where the CPU has it */
#define TILES_AVX2 1
#else
#define TILES_AVX2 0
#endif
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF    /* no fused multiply-add: every twin rounds alike */
#endif

static const char *const pseudocode[] = {
    "setup, once per triangle: edges E_k, planes 1/z, r/z, g/z, b/z",        /* 0 */
    "bin: for each 64 x 64 tile of the box:",                                /* 1 */
    "  reject corner of an edge < 0 -> not in the bin",                      /* 2 */
    "  accept corners of all edges >= 0 -> in the bin, FULL",                /* 3 */
    "  else -> in the bin, PARTIAL",                                         /* 4 */
    "worker: take the next tile, load it into cache;",                       /* 5 */
    "  for each triangle of its bin, in scene order:",                       /* 6 */
    "    FULL: shade every pixel, 8 a register, no test",                    /* 7 */
    "    box fits a block: test its rows, 8 pixels a register",              /* 8 */
    "    else for each 8 x 8 block of the box: reject corner < 0 -> skip",   /* 9 */
    "      accept corners >= 0 -> shade 8 pixels a register, no test",       /* 10 */
    "      else test 8 pixels a register, shade the covered ones",           /* 11 */
    "  store the tile once",                                                 /* 12 */
    NULL,
};

enum { L_SETUP, L_BIN, L_REJECT, L_ACCEPT, L_PARTIAL_TILE, L_TAKE, L_BIN_LOOP, L_FULL_TILE,
       L_SMALL, L_BLOCK_REJECT, L_BLOCK_ACCEPT, L_BLOCK_PARTIAL, L_STORE };

/* trace_event.aux[] of this lesson: for a tile or block event its size and
 * level (0 tile, 1 block), the tile's bin size, the triangle's place in the
 * bin, and the worker thread that drew the tile in the real run. */
static const char *const aux_names[] = { "q", "level", "bin", "entry", "thread", NULL };
enum { P_THREADS };         /* the lesson's parameter rows: p->knob[P_THREADS] is --threads */

#define TILE 64             /* tile side: 64 x 64 colour + depth = 32 KB, level-1 cache */
#define BLOCK 8             /* block side, and pixels a register (AVX2) */
#define LANES 8
#define MAX_THREADS 64
#define E_LIMIT (1 << 30)   /* |I i + J j| < 2^30 inside a tile: see (E) */

/* --- 1. set-up, once per triangle ----------------------------------------- */

/* Planes of the perspective-correct attributes (seed 001, formula 23): 1/z,
 * and 255 a / z for a = r, g, b, each linear in screen space:
 *
 *     P(x, y) = (P0 + Py (y - miny)) + Px (x - minx)
 *
 * evaluated in that order, in float, at every pixel by every twin. */
enum { ST_S, ST_T, ST_COUNT };      /* texture planes, N s / z and N t / z, apart */

/* One triangle after set-up: 136 bytes, what the tiles read. The bins hold
 * copies of it, so that a worker reads its tile's triangles one after
 * another instead of all over memory. */
struct tri {
    int64_t c[3];               /* F_k + bias_k at the centre of pixel (0, 0) */
    int32_t di[3], dj[3];       /* I_k, J_k: F_k grows by 256 I_k per pixel right, 256 J_k per row */
    int16_t minx, miny, maxx, maxy; /* pixels whose centre may be covered, on the target */
    uint8_t bias_neg;           /* bit k: bias_k = -1 (edge k neither top nor left) */
    bool textured;              /* st holds the planes of N s / z and N t / z */
    bool full;                  /* in a bin: the tile lies wholly inside */
    float p0[QUAD_PLANES], px[QUAD_PLANES], py[QUAD_PLANES];
    float st[3 * ST_COUNT];     /* P0, Px, Py of s, then of t */
};

/* The record of a triangle that tri_setup() has snapped and normalised
 * (tristep's shared set-up, so coverage is decided on the same numbers as
 * every other lesson); the texture planes only for a textured scene. */
static void tri_record(struct tri *r, const struct tri_setup *t, int checker)
{
    r->textured = checker > 0;
    r->full = false;
    for (int k = 0; k < 3; k++) {
        r->c[k] = edge_value(t, k, 0, 0) + t->bias[k];
        r->di[k] = (int32_t)t->I[k];
        r->dj[k] = (int32_t)t->J[k];
    }
    r->bias_neg = (uint8_t)((t->bias[0] ? 1 : 0) | (t->bias[1] ? 2 : 0) | (t->bias[2] ? 4 : 0));
    r->minx = (int16_t)t->minx, r->miny = (int16_t)t->miny;
    r->maxx = (int16_t)t->maxx, r->maxy = (int16_t)t->maxy;

    /* lesson 04's planes, in double at (minx, miny) (src/shade/quad.c), kept in float */
    struct planes pl;
    planes_solve(&pl, t, &(struct raster_params){ .checker = checker });
    for (int q = 0; q < QUAD_PLANES; q++)
        r->p0[q] = (float)pl.p0[q], r->px[q] = (float)pl.px[q], r->py[q] = (float)pl.py[q];
    for (int q = 0; r->textured && q < ST_COUNT; q++) {
        float *o = r->st + 3 * q;
        o[0] = (float)pl.p0[PL_S + q], o[1] = (float)pl.px[PL_S + q], o[2] = (float)pl.py[PL_S + q];
    }
}

/* --- 2. binning -------------------------------------------------------------
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

struct rect {
    int x0, y0, w, h;           /* pixels x0 .. x0 + w - 1, y0 .. y0 + h - 1 */
};

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

/* F_k + bias_k at the centre of pixel (x, y): exact, 64 bits. */
static int64_t edge_at(const struct tri *t, int k, int x, int y)
{
    return t->c[k] + SUBPIXEL_ONE * ((int64_t)t->di[k] * x + (int64_t)t->dj[k] * y);
}

/* For the narration only: which of the four corner pixel centres of x0..x1,
 * y0..y1 are inside edge k (bit 3 top-left, 2 top-right, 1 bottom-left, 0
 * bottom-right, as lesson 05 shows them). The test itself reads two. */
__attribute__((unused))     /* the fast build compiles the narration out */
static inline uint16_t corner_bits(const struct tri *t, int k, int x0, int y0, int x1, int y1)
{
    return (uint16_t)((edge_at(t, k, x0, y0) >= 0) << 3 | (edge_at(t, k, x1, y0) >= 0) << 2
                      | (edge_at(t, k, x0, y1) >= 0) << 1 | (edge_at(t, k, x1, y1) >= 0));
}

/* Which corners decide: one per edge and test (the lesson), all four of
 * each edge as lesson 05 tests them (to measure the difference), or the
 * exhibit's wrong corner (the accept corner used to reject). */
enum corners { CORNERS_ONE, CORNERS_FOUR, CORNERS_WRONG };

/* Is rectangle r outside the triangle (BLOCK_EMPTY), inside it (BLOCK_FULL)
 * or neither (BLOCK_PARTIAL)? */
static enum block_class classify_rect(const struct tri *t, struct rect r, enum corners rule)
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

/* The tile grid over a w x h target. */
struct grid {
    int w, h, nx, ny, n;
};

static struct grid grid_of(int w, int h)
{
    struct grid g = { w, h, (w + TILE - 1) / TILE, (h + TILE - 1) / TILE, 0 };
    g.n = g.nx * g.ny;
    return g;
}

static struct rect tile_rect(const struct grid *g, int tile)
{
    struct rect r = { (tile % g->nx) * TILE, (tile / g->nx) * TILE, TILE, TILE };
    if (r.x0 + r.w > g->w)
        r.w = g->w - r.x0;
    if (r.y0 + r.h > g->h)
        r.h = g->h - r.y0;
    return r;
}

/* A bin: copies of the records of the triangles that may touch a tile, in
 * scene order, each marked `full` when it covers the whole tile, in a chain
 * of blocks of BIN_BLOCK records (4 KB): read one after another, written
 * without ever moving. */
#define BIN_BLOCK 30
#define CACHE_LINE 64

struct bin_block {
    struct bin_block *next;
    uint32_t n;
    struct tri rec[BIN_BLOCK];
};

struct bin {
    struct bin_block *first, *last;
};

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
static void bin_free(struct bin *bin)
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
static bool bin_triangle(const struct tri *t, const struct grid *g, struct bin *bins,
                         enum corners rule)
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

/* --- 3. where the pixels go: the tile buffer, or the target itself -------- */

/* Colour, depth and coverage counts of a w x h rectangle of pixels, rows
 * `stride` apart. Eight lanes may be read and written at once from column i
 * when i + 8 <= wide (the tile buffer has room past its last column; the
 * target, where another thread may own the next tile, has none). */
struct dst {
    uint32_t *color;
    float *depth;
    uint8_t *count;             /* NULL: nobody counts coverage */
    int stride, w, h, wide;
};

struct tile_buf {
    _Alignas(32) uint32_t color[TILE * TILE + LANES];
    _Alignas(32) float depth[TILE * TILE + LANES];
    uint8_t count[TILE * TILE + LANES];
};

static struct dst tile_load(struct tile_buf *b, const struct target *fb, struct rect r)
{
    for (int j = 0; j < r.h; j++) {
        size_t row = (size_t)(r.y0 + j) * (size_t)fb->w + (size_t)r.x0;
        memcpy(b->color + j * TILE, fb->color + row, (size_t)r.w * sizeof *b->color);
        memcpy(b->depth + j * TILE, fb->depth + row, (size_t)r.w * sizeof *b->depth);
        if (fb->count)
            memcpy(b->count + j * TILE, fb->count + row, (size_t)r.w);
    }
    return (struct dst){ b->color, b->depth, fb->count ? b->count : NULL, TILE, r.w, r.h,
                         TILE + LANES };
}

static void tile_store(const struct tile_buf *b, struct target *fb, struct rect r)
{
    for (int j = 0; j < r.h; j++) {
        size_t row = (size_t)(r.y0 + j) * (size_t)fb->w + (size_t)r.x0;
        memcpy(fb->color + row, b->color + j * TILE, (size_t)r.w * sizeof *b->color);
        memcpy(fb->depth + row, b->depth + j * TILE, (size_t)r.w * sizeof *b->depth);
        if (fb->count)
            memcpy(fb->count + row, b->count + j * TILE, (size_t)r.w);
    }
}

/* The same rectangle written in place, on the target. */
static struct dst target_dst(struct target *fb, struct rect r)
{
    size_t o = (size_t)r.y0 * (size_t)fb->w + (size_t)r.x0;
    return (struct dst){ fb->color + o, fb->depth + o, fb->count ? fb->count + o : NULL,
                         fb->w, r.w, r.h, r.w };
}

/* --- 4. one triangle inside one tile -------------------------------------- */

/* What every pixel test and every shaded pixel of a triangle in a tile
 * needs. e0 is (E) at the tile's first pixel: covered <=> e0_k + I_k i +
 * J_k j >= 0 for k = 0, 1, 2, clamped so that a far edge stays a far edge. */
struct tt {
    const struct tri *t;
    const float *st;            /* texture planes (s then t: P0, Px, Py), or NULL */
    int tx, ty;                 /* the tile's first pixel on the target */
    int32_t e0[3];
};

static struct tt tt_make(const struct tri *t, struct rect r)
{
    struct tt c = { t, t->textured ? t->st : NULL, r.x0, r.y0, { 0, 0, 0 } };
    for (int k = 0; k < 3; k++) {
        int64_t e = floor_div(edge_at(t, k, r.x0, r.y0), SUBPIXEL_ONE);    /* no branch on the sign */
        c.e0[k] = (int32_t)(e > E_LIMIT ? E_LIMIT : e < -E_LIMIT - 1 ? -E_LIMIT - 1 : e);
    }
    return c;
}

/* Row terms P0 + Py (y - miny) of every plane, for row j of the tile. */
static inline void plane_rows(const struct tt *c, int j, float row[QUAD_PLANES], float st_row[ST_COUNT])
{
    const struct tri *t = c->t;
    float dyf = (float)(c->ty + j - t->miny);
    for (int q = 0; q < QUAD_PLANES; q++)
        row[q] = t->p0[q] + t->py[q] * dyf;
    if (c->st)
        for (int q = 0; q < ST_COUNT; q++)
            st_row[q] = c->st[3 * q] + c->st[3 * q + 2] * dyf;
}

/* Saturating coverage counts of the lanes in `mask` (bit l = column i + l). */
static void count_lanes(const struct dst *d, int i, int j, unsigned mask)
{
    if (!d->count)
        return;
    uint8_t *c = d->count + (size_t)j * (size_t)d->stride + (size_t)i;
    for (int l = 0; l < LANES; l++)
        if (mask >> l & 1 && c[l] < 255)
            c[l]++;
}

/* The conversions of the SIMD instructions, written out for the scalar twin:
 * cvtps2dq rounds to nearest even, cvttps2dq truncates, and both give
 * INT32_MIN for anything out of range (NaN included). */
static int32_t cvt_round(float f)
{
    float r = f + 0.0f;
    if (!(r >= -2147483648.0f && r < 2147483648.0f))
        return INT32_MIN;
    /* round half to even, as the default rounding mode does */
    float fl = (float)(int64_t)r;
    if (fl > r)
        fl -= 1.0f;
    float frac = r - fl;
    int64_t i = (int64_t)fl;
    if (frac > 0.5f || (frac == 0.5f && (i & 1)))
        i++;
    return (int32_t)i;
}

static int32_t cvt_trunc(float f)
{
    if (!(f >= -2147483648.0f && f < 2147483648.0f))
        return INT32_MIN;
    return (int32_t)f;
}

/* floor(), as int32, the way the SSE twin computes it. */
static int32_t floor_i32(float f)
{
    int32_t i = cvt_trunc(f);
    if ((float)i > f)
        i = (int32_t)((uint32_t)i - 1u);
    return i;
}

static uint32_t byte_of(int32_t v)
{
    return (uint32_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

/* Named costs (trace/trace.h) per pixel, for the explorer's counters:
 *   LANE_EDGE_COST   (E) of one edge in one lane: the row's value + I_k l
 *   PLANE_AT_COST    one plane at a pixel: the row's term + Px (x - minx)
 *   COLOUR_TIMES_Z_COST  r, g, b = (255 a / z) z
 * z = 1 / (1/z) is RECIPROCAL_COST (shade/shade.h); rounding and packing are
 * conversions, not arithmetic. */
#define LANE_EDGE_COST { .mul = 1, .add = 1 }
#define PLANE_AT_COST { .mul = 1, .add = 1 }
#define COLOUR_TIMES_Z_COST { .mul = 3, .add = 0 }

/* --- the three twins of the pixel work: plain C, SSE2, AVX2 ---------------
 *
 * A twin draws a strip: the columns i .. i + 7 of rows y0 .. y1 of the tile
 * (a block, a small triangle's box, a column of a FULL tile), the lanes of
 * `mask` only. Down the strip, what depends on the column alone is computed
 * once: the column terms Px (x - minx) of every plane, and (E) of each edge
 * at the strip's first row, which then steps by J_k a row (exact: integers).
 * At each row, each pixel:
 *
 *   cover: (E) >= 0 for all three edges (when the strip is tested);
 *   shade: 1/z = row term + column term, z = 1 / (1/z), nearer than the
 *          buffer -> colour = (255 a / z) z, the same for r, g, b.
 *
 * Same float operations in the same order in all three: same bytes. */

/* The lanes of `mask` whose pixel (i + l, j) passes (E) for all three edges. */
static unsigned cover8_c(const struct tt *c, int i, int j, unsigned mask)
{
    unsigned in = 0;
    for (int l = 0; l < LANES; l++) {
        bool inside = mask >> l & 1;
        for (int k = 0; k < 3; k++)
            inside = inside && c->e0[k] + c->t->di[k] * (i + l) + c->t->dj[k] * j >= 0;
        in |= (unsigned)inside << l;
    }
    return in;
}

/* One pixel, column i + l: the scalar twin, also used by the narration. */
static bool shade1_c(const struct tt *c, const struct dst *d, const float row[QUAD_PLANES],
                     const float st_row[ST_COUNT], int i, int j, float *z_out, uint32_t *rgba_out)
{
    const struct tri *t = c->t;
    float dxf = (float)(c->tx + i - t->minx);
    float z = 1.0f / (row[PL_INV_Z] + t->px[PL_INV_Z] * dxf);
    float *dp = d->depth + (size_t)j * (size_t)d->stride + (size_t)i;
    float r = (row[PL_R] + t->px[PL_R] * dxf) * z;
    float g = (row[PL_G] + t->px[PL_G] * dxf) * z;
    float b = (row[PL_B] + t->px[PL_B] * dxf) * z;
    if (c->st) {
        int32_t square = (int32_t)((uint32_t)floor_i32((st_row[ST_S] + c->st[1] * dxf) * z)
                                   + (uint32_t)floor_i32((st_row[ST_T] + c->st[4] * dxf) * z));
        if (square & 1) {
            r *= (float)CHECKER_DARK;
            g *= (float)CHECKER_DARK;
            b *= (float)CHECKER_DARK;
        }
    }
    uint32_t rgba = 0xff000000u | byte_of(cvt_round(r)) << 16 | byte_of(cvt_round(g)) << 8
                  | byte_of(cvt_round(b));
    *z_out = z;
    *rgba_out = rgba;
    return z < *dp;
}

/* Row terms of the planes for row j, computed once a row by the caller. */
struct rows {
    float p[QUAD_PLANES], st[ST_COUNT];
};

static void shade8_c(const struct tt *c, const struct dst *d, const struct rows *rw, int i, int j,
                     unsigned mask)
{
    count_lanes(d, i, j, mask);
    const float *row = rw->p, *st_row = rw->st;
    for (int l = 0; l < LANES; l++) {
        float z;
        uint32_t rgba;
        if (mask >> l & 1 && shade1_c(c, d, row, st_row, i + l, j, &z, &rgba)) {
            size_t o = (size_t)j * (size_t)d->stride + (size_t)(i + l);
            d->depth[o] = z;
            d->color[o] = rgba;
        }
    }
}

/* Plain C: row by row, pixel by pixel, straight from the formulas. */
static void strip_c(const struct tt *c, const struct dst *d, int i, int y0, int y1, unsigned mask,
                    bool test)
{
    for (int j = y0; j <= y1; j++) {
        struct rows rw;
        plane_rows(c, j, rw.p, rw.st);
        unsigned m = test ? cover8_c(c, i, j, mask) : mask;
        if (m)
            shade8_c(c, d, &rw, i, j, m);
    }
}

/* SSE2: two registers of four lanes. */
static __m128i clamp_byte_sse2(__m128i v)
{
    v = _mm_and_si128(v, _mm_cmpgt_epi32(v, _mm_setzero_si128()));     /* max(v, 0) */
    __m128i big = _mm_cmpgt_epi32(v, _mm_set1_epi32(255));
    return _mm_or_si128(_mm_andnot_si128(big, v), _mm_and_si128(big, _mm_set1_epi32(255)));
}

/* The four pixels at o (rows of the planes `row`, columns `col`, `dxf`) whose
 * lanes `in` has: depth test, shade, write. */
static void shade4_sse2(const struct tt *c, const struct dst *d, const struct rows *rw,
                        const __m128 col[QUAD_PLANES], __m128 dxf, __m128 in, size_t o)
{
    const float *row = rw->p, *st_row = rw->st;
    __m128 z = _mm_div_ps(_mm_set1_ps(1.0f), _mm_add_ps(_mm_set1_ps(row[PL_INV_Z]), col[PL_INV_Z]));
    __m128 old_z = _mm_loadu_ps(d->depth + o);
    __m128 pass = _mm_and_ps(_mm_cmplt_ps(z, old_z), in);
    if (!_mm_movemask_ps(pass))
        return;
    __m128 r = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_R]), col[PL_R]), z);
    __m128 g = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_G]), col[PL_G]), z);
    __m128 b = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(row[PL_B]), col[PL_B]), z);
    if (c->st) {
        __m128 s = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(st_row[ST_S]), _mm_mul_ps(_mm_set1_ps(c->st[1]), dxf)), z);
        __m128 tt = _mm_mul_ps(_mm_add_ps(_mm_set1_ps(st_row[ST_T]), _mm_mul_ps(_mm_set1_ps(c->st[4]), dxf)), z);
        __m128 scale = checker_scale(s, tt);
        r = _mm_mul_ps(r, scale);
        g = _mm_mul_ps(g, scale);
        b = _mm_mul_ps(b, scale);
    }
    __m128i rgba = _mm_or_si128(_mm_set1_epi32((int)0xff000000u),
                   _mm_or_si128(_mm_slli_epi32(clamp_byte_sse2(_mm_cvtps_epi32(r)), 16),
                   _mm_or_si128(_mm_slli_epi32(clamp_byte_sse2(_mm_cvtps_epi32(g)), 8),
                                clamp_byte_sse2(_mm_cvtps_epi32(b)))));
    __m128i pass_i = _mm_castps_si128(pass);
    __m128i old_c = _mm_loadu_si128((const __m128i *)(d->color + o));
    _mm_storeu_ps(d->depth + o, _mm_or_ps(_mm_and_ps(pass, z), _mm_andnot_ps(pass, old_z)));
    _mm_storeu_si128((__m128i *)(d->color + o),
                     _mm_or_si128(_mm_and_si128(pass_i, rgba), _mm_andnot_si128(pass_i, old_c)));
}

/* The lanes of `mask` (bit l: lane l) as a register of all-ones lanes. */
static __m128 lanes_sse2(unsigned mask)
{
    __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
    return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)mask), bits), bits));
}

static void strip_sse2(const struct tt *c, const struct dst *d, int i, int y0, int y1,
                       unsigned mask, bool test)
{
    if (i + LANES > d->wide) {      /* no room for whole registers: lane by lane */
        strip_c(c, d, i, y0, y1, mask, test);
        return;
    }
    /* down the strip: the column terms of each plane and (E) at row y0,
     * each edge stepping by J_k a row; lanes 0-3, then 4-7 */
    const struct tri *t = c->t;
    __m128 dx[2], cols[2][QUAD_PLANES], want[2];
    __m128i edge[2][3], step[3];
    for (int h = 0; h < 2; h++) {
        dx[h] = _mm_cvtepi32_ps(_mm_add_epi32(_mm_set1_epi32(c->tx + i + 4 * h - t->minx),
                                              _mm_setr_epi32(0, 1, 2, 3)));
        for (int q = 0; q < QUAD_PLANES; q++)
            cols[h][q] = _mm_mul_ps(_mm_set1_ps(t->px[q]), dx[h]);
        want[h] = lanes_sse2(mask >> 4 * h & 0xF);
    }
    for (int k = 0; k < 3; k++) {
        int32_t base = c->e0[k] + t->di[k] * i + t->dj[k] * y0, di = t->di[k];
        edge[0][k] = _mm_add_epi32(_mm_set1_epi32(base), _mm_setr_epi32(0, di, 2 * di, 3 * di));
        edge[1][k] = _mm_add_epi32(edge[0][k], _mm_set1_epi32(4 * di));
        step[k] = _mm_set1_epi32(t->dj[k]);
    }
    size_t o = (size_t)y0 * (size_t)d->stride + (size_t)i;
    for (int j = y0; j <= y1; j++, o += (size_t)d->stride) {
        __m128 in[2] = { want[0], want[1] };
        for (int h = 0; test && h < 2; h++) {
            /* a lane is outside when some edge's (E) is negative: its sign
             * bit, spread over the lane */
            __m128i out = _mm_or_si128(_mm_or_si128(edge[h][0], edge[h][1]), edge[h][2]);
            in[h] = _mm_andnot_ps(_mm_castsi128_ps(_mm_srai_epi32(out, 31)), want[h]);
            for (int k = 0; k < 3; k++)
                edge[h][k] = _mm_add_epi32(edge[h][k], step[k]);
        }
        unsigned m = (unsigned)_mm_movemask_ps(in[0]) | (unsigned)_mm_movemask_ps(in[1]) << 4;
        if (!m)
            continue;
        count_lanes(d, i, j, m);
        struct rows rw;
        plane_rows(c, j, rw.p, rw.st);
        for (int h = 0; h < 2; h++)
            if (m >> 4 * h & 0xF)
                shade4_sse2(c, d, &rw, cols[h], dx[h], in[h], o + (size_t)(4 * h));
    }
}

#if TILES_AVX2
#define AVX2 __attribute__((target("avx2")))

AVX2 static __m256i floor_avx2(__m256 v)
{
    __m256i i = _mm256_cvttps_epi32(v);
    __m256 too_big = _mm256_cmp_ps(_mm256_cvtepi32_ps(i), v, _CMP_GT_OQ);
    return _mm256_add_epi32(i, _mm256_castps_si256(too_big));
}

AVX2 static __m256i byte_avx2(__m256 v)
{
    return _mm256_min_epi32(_mm256_max_epi32(_mm256_cvtps_epi32(v), _mm256_setzero_si256()),
                            _mm256_set1_epi32(255));
}

/* (E) of edge k at the pixels (i .. i + 7, j) of the tile. */
AVX2 static inline __m256i edge8_avx2(const struct tt *c, int k, int i, int j)
{
    const struct tri *t = c->t;
    return _mm256_add_epi32(_mm256_set1_epi32(c->e0[k] + t->di[k] * i + t->dj[k] * j),
                            _mm256_mullo_epi32(_mm256_set1_epi32(t->di[k]),
                                               _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
}

/* AVX2: one register of eight lanes, the same steps as the SSE2 twin. */
AVX2 static void strip_avx2(const struct tt *c, const struct dst *d, int i, int y0, int y1,
                            unsigned mask, bool test)
{
    if (i + LANES > d->wide) {
        strip_c(c, d, i, y0, y1, mask, test);
        return;
    }
    const struct tri *t = c->t;
    /* down the strip: the column terms of each plane and (E) at row y0,
     * each edge stepping by J_k a row */
    __m256 dx = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(c->tx + i - t->minx),
                                                    _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
    __m256 col_inv_z = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_INV_Z]), dx);
    __m256 col_r = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_R]), dx);
    __m256 col_g = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_G]), dx);
    __m256 col_b = _mm256_mul_ps(_mm256_set1_ps(t->px[PL_B]), dx);
    __m256i e0 = edge8_avx2(c, 0, i, y0), e1 = edge8_avx2(c, 1, i, y0), e2 = edge8_avx2(c, 2, i, y0);
    __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    __m256 want = _mm256_castsi256_ps(_mm256_cmpeq_epi32(
        _mm256_and_si256(_mm256_set1_epi32((int)mask), bits), bits));
    float *depth = d->depth + (size_t)y0 * (size_t)d->stride + (size_t)i;
    uint32_t *color = d->color + (size_t)y0 * (size_t)d->stride + (size_t)i;
    for (int j = y0; j <= y1; j++, depth += d->stride, color += d->stride) {
        __m256 in = want;
        if (test) {
            /* a lane is outside when some edge's (E) is negative: its sign
             * bit, spread over the lane */
            __m256i out = _mm256_or_si256(_mm256_or_si256(e0, e1), e2);
            in = _mm256_andnot_ps(_mm256_castsi256_ps(_mm256_srai_epi32(out, 31)), want);
            e0 = _mm256_add_epi32(e0, _mm256_set1_epi32(t->dj[0]));
            e1 = _mm256_add_epi32(e1, _mm256_set1_epi32(t->dj[1]));
            e2 = _mm256_add_epi32(e2, _mm256_set1_epi32(t->dj[2]));
        }
        unsigned m = (unsigned)_mm256_movemask_ps(in);
        if (!m)
            continue;
        count_lanes(d, i, j, m);
        struct rows rw;
        plane_rows(c, j, rw.p, rw.st);
        const float *row = rw.p, *st_row = rw.st;
        __m256 z = _mm256_div_ps(_mm256_set1_ps(1.0f),
                                 _mm256_add_ps(_mm256_set1_ps(row[PL_INV_Z]), col_inv_z));
        __m256 old_z = _mm256_loadu_ps(depth);
        __m256 pass = _mm256_and_ps(_mm256_cmp_ps(z, old_z, _CMP_LT_OQ), in);
        if (!_mm256_movemask_ps(pass))
            continue;
        __m256 r = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_R]), col_r), z);
        __m256 g = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_G]), col_g), z);
        __m256 b = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(row[PL_B]), col_b), z);
        if (c->st) {
            __m256 s = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(st_row[ST_S]),
                                                   _mm256_mul_ps(_mm256_set1_ps(c->st[1]), dx)), z);
            __m256 tq = _mm256_mul_ps(_mm256_add_ps(_mm256_set1_ps(st_row[ST_T]),
                                                    _mm256_mul_ps(_mm256_set1_ps(c->st[4]), dx)), z);
            __m256i square = _mm256_add_epi32(floor_avx2(s), floor_avx2(tq));
            __m256 dark = _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                _mm256_and_si256(square, _mm256_set1_epi32(1)), _mm256_set1_epi32(1)));
            __m256 scale = _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_set1_ps((float)CHECKER_DARK), dark);
            r = _mm256_mul_ps(r, scale);
            g = _mm256_mul_ps(g, scale);
            b = _mm256_mul_ps(b, scale);
        }
        __m256i rgba = _mm256_or_si256(_mm256_set1_epi32((int)0xff000000u),
                       _mm256_or_si256(_mm256_slli_epi32(byte_avx2(r), 16),
                       _mm256_or_si256(_mm256_slli_epi32(byte_avx2(g), 8), byte_avx2(b))));
        __m256i old_c = _mm256_loadu_si256((const __m256i *)color);
        _mm256_storeu_ps(depth, _mm256_blendv_ps(old_z, z, pass));
        _mm256_storeu_si256((__m256i *)color,
                            _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(old_c),
                                                                 _mm256_castsi256_ps(rgba), pass)));
    }
}
#endif

/* --- the descent: tile -> blocks -> 8 pixels a register ------------------ */

typedef void (*strip_fn)(const struct tt *c, const struct dst *d, int i, int y0, int y1,
                         unsigned mask, bool test);

/* Which twin draws: chosen once per run. */
enum twin { TWIN_BEST, TWIN_AVX2, TWIN_SSE2, TWIN_C };

/* The lanes of columns i .. i + 7 that lie in [x0, x1] (x0 - 7 <= i <= x1). */
static inline unsigned lane_mask(int i, int x0, int x1)
{
    int lo = x0 - i < 0 ? 0 : x0 - i, hi = x1 - i > LANES - 1 ? LANES - 1 : x1 - i;
    return (2u << hi) - (1u << lo);
}

/* Narrated pixel by pixel, writing the target as it goes (what the
 * explorer steps through): the test (E), then the scalar twin's shading. */
static void narrate_pixels(const struct tt *c, const struct dst *d, const struct rows *rw,
                           struct trace *tr, int i0, int j, unsigned mask)
{
    const struct tri *t = c->t;
    const float *row = rw->p, *st_row = rw->st;
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
        bool pass = shade1_c(c, d, row, st_row, i, j, &z, &rgba);
        COUNT(tr, QUAD_PLANES, PLANE_AT_COST);
        COUNT(tr, 1, RECIPROCAL_COST);
        COUNT(tr, 1, COLOUR_TIMES_Z_COST);
        NARRATE(tr, .kind = TRACE_PIXEL_WRITE, .line = L_BLOCK_PARTIAL, .x = c->tx + i, .y = c->ty + j, .z = z,
                .rgba = rgba, .flags = pass ? TRACE_DEPTH_PASS : 0);
        if (tr && tr->frozen)
            return;
        size_t o = (size_t)j * (size_t)d->stride + (size_t)i;
        if (d->count && d->count[o] < 255)
            d->count[o]++;
        if (pass) {
            d->depth[o] = z;
            d->color[o] = rgba;
        }
    }
}

static bool frozen(const struct trace *tr)
{
    return NARRATING && tr && tr->frozen;
}

/* Rows y0 .. y1 (tile coordinates) of the columns x0 .. x1: test them when
 * `test`, else shade every pixel (a FULL block or tile); strip after strip
 * of 8 columns, by the twin, or pixel by pixel when narrated. */
static inline __attribute__((always_inline)) void
draw_rows(const struct tt *c, const struct dst *d, struct trace *tr, int x0, int y0, int x1,
          int y1, bool test, strip_fn strip)
{
    if (NARRATING && tr && test) {
        for (int j = y0; j <= y1; j++) {
            struct rows rw;
            plane_rows(c, j, rw.p, rw.st);
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
    struct tt c = tt_make(t, r);
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

typedef void (*draw_fn)(const struct tri *t, struct rect r, bool full, const struct dst *d,
                        struct trace *tr, bool four);

/* The twin to run: AVX2 only where the CPU says it has it. */
static draw_fn pick_twin(enum twin w)
{
#if TILES_AVX2
    if ((w == TWIN_BEST || w == TWIN_AVX2) && __builtin_cpu_supports("avx2"))
        return draw_avx2;
#endif
    return w == TWIN_C ? draw_c : draw_sse2;
}

/* --- 5. the whole scene: binning, then workers taking tiles --------------- */

struct tiles_options {
    enum twin twin;
    int threads;                /* 0: --threads, else one per core */
    bool tile_buffers;          /* false: draw into the target in place */
    enum corners corners;       /* CORNERS_ONE, or the measurement, or the exhibit */
    bool no_bins;               /* triangle after triangle through all its tiles, in place */
    bool unordered;             /* exhibit: each worker draws its own chunk's bins first */
};

/* A run over one scene: the set-up records, one bin per chunk of triangles
 * per tile, and the next tile nobody has taken. */
struct run {
    const struct scene *s;
    const struct raster_params *p;
    struct target *fb;
    struct tiles_options o;
    draw_fn draw;
    struct grid g;
    int threads, nchunks;       /* workers; shares of the scene (SHARES_PER_THREAD each) */
    struct bin *bins;           /* nchunks x g.n, chunk-major */
    atomic_int next_chunk;
    atomic_int next_tile;
    atomic_bool failed;
    uint8_t *thread_of;         /* per tile: the worker that drew it, or NULL */
    /* every share binned: chunks_done == nchunks, announced under the lock */
    pthread_mutex_t lock;
    pthread_cond_t binned;
    int chunks_done;
};

/* The scene is cut into a few shares per worker (more shares than workers:
 * the last ones go to whoever is free). */
#define SHARES_PER_THREAD 4

static int shares(int threads)
{
    return threads > 1 ? SHARES_PER_THREAD * threads : 1;
}

/* Set-up and binning of chunk `c`: a contiguous share of the scene, so that
 * chunk 0's bins then chunk 1's hold every tile's triangles in scene order. */
static void bin_chunk(struct run *r, int c)
{
    int n = r->s->ntris;
    int lo = (int)((int64_t)n * c / r->nchunks), hi = (int)((int64_t)n * (c + 1) / r->nchunks);
    struct bin *bins = r->bins + (size_t)c * (size_t)r->g.n;
    for (int i = lo; i < hi; i++) {
        struct tri_setup t;
        struct tri rec;
        if (!tri_setup_bits(&t, r->s->tris[i].v, r->s->w, r->s->h, r->p->subpixel_bits))
            continue;
        tri_record(&rec, &t, r->p->checker);
        if (!bin_triangle(&rec, &r->g, bins, r->o.corners)) {
            atomic_store(&r->failed, true);
            return;
        }
    }
}

/* Draw one tile: load it, every chunk's bin in order, store it. */
static void draw_tile(struct run *r, int tile, int worker, struct tile_buf *buf)
{
    bool empty = true;
    for (int c = 0; c < r->nchunks && empty; c++)
        empty = !r->bins[(size_t)c * (size_t)r->g.n + (size_t)tile].first;
    if (empty)
        return;
    if (r->thread_of)
        r->thread_of[tile] = (uint8_t)worker;
    struct rect rc = tile_rect(&r->g, tile);
    struct dst d = r->o.tile_buffers ? tile_load(buf, r->fb, rc) : target_dst(r->fb, rc);
    for (int k = 0; k < r->nchunks; k++) {
        /* the exhibit starts with the worker's own shares: order depends on who took the tile */
        int c = r->o.unordered ? (k + worker * SHARES_PER_THREAD) % r->nchunks : k;
        struct bin *b = &r->bins[(size_t)c * (size_t)r->g.n + (size_t)tile];
        for (const struct bin_block *blk = b->first; blk; blk = blk->next)
            for (uint32_t e = 0; e < blk->n; e++)
                r->draw(&blk->rec[e], rc, blk->rec[e].full, &d, NULL, r->o.corners == CORNERS_FOUR);
        bin_free(b);    /* here, on every worker, while its blocks are in cache */
    }
    if (r->o.tile_buffers)
        tile_store(buf, r->fb, rc);
}

struct worker {
    struct run *r;
    int id;
};

static void *work(void *arg)
{
    struct worker *w = arg;
    struct run *r = w->r;
    /* set-up and binning: shares taken one at a time, so that a worker the
     * system puts to sleep for a while holds up no more than one share */
    for (int c; (c = atomic_fetch_add(&r->next_chunk, 1)) < r->nchunks;) {
        bin_chunk(r, c);
        pthread_mutex_lock(&r->lock);
        if (++r->chunks_done == r->nchunks)
            pthread_cond_broadcast(&r->binned);
        pthread_mutex_unlock(&r->lock);
    }
    /* no tile before every share is binned: its bins are not complete */
    pthread_mutex_lock(&r->lock);
    while (r->chunks_done < r->nchunks)
        pthread_cond_wait(&r->binned, &r->lock);
    pthread_mutex_unlock(&r->lock);
    if (atomic_load(&r->failed))
        return NULL;
    struct tile_buf *buf = r->o.tile_buffers ? aligned_alloc(32, sizeof *buf) : NULL;
    if (r->o.tile_buffers && !buf) {
        atomic_store(&r->failed, true);
        return NULL;
    }
    for (;;) {
        int tile = atomic_fetch_add(&r->next_tile, 1);
        if (tile >= r->g.n)
            break;
        draw_tile(r, tile, w->id, buf);
    }
    free(buf);
    return NULL;
}

static int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

/* Draw the whole scene; `thread_of` (one byte per tile, or NULL) receives
 * the worker that drew each tile. Returns false when out of memory (the
 * target may then hold part of the scene). */
static void rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                              struct target *fb, struct trace *tr, struct tiles_options o);

static bool draw_scene(const struct scene *s, const struct raster_params *p, struct target *fb,
                       struct tiles_options o, uint8_t *thread_of)
{
    if (o.no_bins) {    /* for the measurement: what binning saves */
        for (int i = 0; i < s->ntris; i++) {
            struct tri_setup t;
            tri_setup_bits(&t, s->tris[i].v, s->w, s->h, p->subpixel_bits);
            rasterize_one_tri(&t, p, fb, NULL, o);
        }
        return true;
    }
    struct run *r = calloc(1, sizeof *r);
    if (!r)
        return false;
    int threads = o.threads > 0 ? o.threads
                  : p->knob[P_THREADS] > 0 ? p->knob[P_THREADS] : default_threads();
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    r->s = s, r->p = p, r->fb = fb, r->o = o;
    r->draw = pick_twin(o.twin);
    r->g = grid_of(fb->w, fb->h);
    r->threads = threads;
    r->nchunks = shares(threads);
    r->thread_of = thread_of;
    atomic_init(&r->next_tile, 0);
    atomic_init(&r->next_chunk, 0);
    atomic_init(&r->failed, false);
    r->bins = calloc((size_t)r->nchunks * (size_t)r->g.n, sizeof *r->bins);
    bool ok = r->bins;
    pthread_t tid[MAX_THREADS];
    struct worker w[MAX_THREADS];
    int started = 1;
    bool sync = ok && pthread_mutex_init(&r->lock, NULL) == 0;
    if (sync && pthread_cond_init(&r->binned, NULL) != 0) {
        pthread_mutex_destroy(&r->lock);
        sync = false;
    }
    ok = ok && sync;
    if (ok) {
        for (int i = 0; i < threads; i++)
            w[i] = (struct worker){ r, i };
        /* a worker that cannot be started is no harm: the others take its
         * shares and tiles */
        for (; started < threads; started++)
            if (pthread_create(&tid[started], NULL, work, &w[started]) != 0)
                break;
        work(&w[0]);
        for (int i = 1; i < started; i++)
            pthread_join(tid[i], NULL);
        pthread_cond_destroy(&r->binned);
        pthread_mutex_destroy(&r->lock);
        ok = !atomic_load(&r->failed);
    }
    /* the workers gave back the bins of the tiles they drew; what is left
     * (a run that ran out of memory) goes back here */
    for (size_t b = 0; r->bins && b < (size_t)r->nchunks * (size_t)r->g.n; b++)
        bin_free(&r->bins[b]);
    free(r->bins);
    free(r);
    return ok;
}

/* --- one triangle through the same pipeline (tests, the narrated replay) -- */

/* The triangle binned, then drawn tile by tile in place: the same decisions
 * as the scene run, narrated. p->tile > 0 restricts it to tile p->tile - 1
 * (the narrated replay's units, see lesson.h). */
static void rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                              struct target *fb, struct trace *tr, struct tiles_options o)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SETUP, .x = ts->minx, .y = ts->miny,
            .x1 = ts->maxx, .y1 = ts->maxy, .e = { ts->area2, 0, 0 });
    if (ts->empty)
        return;
    struct tri t;
    tri_record(&t, ts, p->checker);
    draw_fn draw = pick_twin(o.twin);
    struct grid g = grid_of(fb->w, fb->h);
    for (int ty = t.miny / TILE; ty <= t.maxy / TILE; ty++)
        for (int tx = t.minx / TILE; tx <= t.maxx / TILE; tx++) {
            int tile = ty * g.nx + tx;
            if (p->tile > 0 && tile != p->tile - 1)
                continue;
            struct rect rc = tile_rect(&g, tile);
            enum block_class k = classify_rect(&t, rc, o.corners);
            NARRATE(tr, .kind = TRACE_BLOCK,
                    .line = k == BLOCK_EMPTY ? L_REJECT : k == BLOCK_FULL ? L_FULL_TILE : L_PARTIAL_TILE,
                    .x = rc.x0, .y = rc.y0, .x1 = rc.x0 + rc.w - 1, .y1 = rc.y0 + rc.h - 1,
                    .klass = (uint8_t)k, .aux = { TILE, 0, (float)p->bin_size, (float)p->bin_entry,
                                                 (float)p->thread },
                    .mask = { corner_bits(&t, 0, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1),
                              corner_bits(&t, 1, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1),
                              corner_bits(&t, 2, rc.x0, rc.y0, rc.x0 + rc.w - 1, rc.y0 + rc.h - 1) });
            if (k == BLOCK_EMPTY || frozen(tr))
                continue;
            struct dst d = target_dst(fb, rc);
            draw(&t, rc, k == BLOCK_FULL, &d, tr, o.corners == CORNERS_FOUR);
        }
}

/* --- the narrated order ------------------------------------------------------ */

/* The exhibit `unordered` draws a tile's bin starting with the share of the
 * scene its worker binned (draw_tile): the same order for the units of a
 * tile drawn by `worker`, with the triangles cut into `shares` shares of a
 * scene of n as bin_chunk cuts them. */
static bool rotate_shares(struct lesson_unit *u, long m, size_t n, int shares, int worker)
{
    struct lesson_unit *tmp = malloc((size_t)(m ? m : 1) * sizeof *tmp);
    if (!tmp)
        return false;
    long k = 0;
    for (int step = 0; step < shares; step++) {
        int c = (step + worker * SHARES_PER_THREAD) % shares;
        size_t lo = n * (size_t)c / (size_t)shares, hi = n * (size_t)(c + 1) / (size_t)shares;
        for (long e = 0; e < m; e++)
            if (u[e].tri >= lo && u[e].tri < hi)
                tmp[k++] = u[e];
    }
    memcpy(u, tmp, (size_t)m * sizeof *u);
    free(tmp);
    return true;
}

/* The explorer steps through the run tile after tile, in row-major order,
 * and inside a tile through its bin in scene order: one unit per (tile,
 * triangle) pair that binning keeps. The tiles go to the workers as the
 * pool hands them out: each tile to the first worker free, in that order,
 * if a tile took as long as the pixels of its triangles' boxes in it (the
 * real run's assignment depends on the machine's timing; this one is the
 * same on every run, so that figures can be reproduced). */
static long narration_units(const struct scene *s, const struct lesson_variant *v,
                            const struct raster_params *p, struct lesson_unit *out, long cap)
{
    bool unordered = strcmp(v->name, "unordered") == 0;
    struct grid g = grid_of(s->w, s->h);
    size_t n = (size_t)s->ntris;
    long *count = calloc((size_t)g.n + 1, sizeof *count);
    double *work = calloc((size_t)g.n, sizeof *work);
    long total = -1;
    if (!count || !work)
        goto done;
    /* bin sizes: the tiles that do not reject each triangle (set up twice
     * rather than kept: a scene may have millions of triangles) */
    for (int pass = 0; pass < 2; pass++) {
        long *next = count;     /* pass 1: where each tile's next unit goes */
        for (size_t i = 0; i < n; i++) {
            struct tri_setup ts;
            struct tri rec, *t = &rec;
            bool live = tri_setup_bits(&ts, s->tris[i].v, s->w, s->h, p->subpixel_bits);
            if (live)
                tri_record(t, &ts, p->checker);
            for (int ty = t->miny / TILE; live && ty <= t->maxy / TILE; ty++)
                for (int tx = t->minx / TILE; tx <= t->maxx / TILE; tx++) {
                    int tile = ty * g.nx + tx;
                    struct rect r = tile_rect(&g, tile);
                    if (classify_rect(t, r, CORNERS_ONE) == BLOCK_EMPTY)
                        continue;
                    if (pass == 0) {
                        count[tile + 1]++;
                        int w = (t->maxx < r.x0 + r.w - 1 ? t->maxx : r.x0 + r.w - 1)
                              - (t->minx > r.x0 ? t->minx : r.x0) + 1;
                        int h = (t->maxy < r.y0 + r.h - 1 ? t->maxy : r.y0 + r.h - 1)
                              - (t->miny > r.y0 ? t->miny : r.y0) + 1;
                        work[tile] += (double)w * h;
                    } else if (next[tile] < cap) {
                        out[next[tile]++] = (struct lesson_unit){ .tri = (uint32_t)i, .tile = tile };
                    } else {
                        next[tile]++;
                    }
                }
        }
        if (pass == 0) {
            for (int tile = 0; tile < g.n; tile++)
                count[tile + 1] += count[tile];     /* count[tile]: the tile's first unit */
            total = count[g.n];
            if (cap < total)
                goto done;
        }
    }
    /* count[tile] now points past the tile's last unit; the pool hands out
     * the tiles with triangles in order, each to the worker free first */
    int threads = p->knob[P_THREADS] > 0 ? p->knob[P_THREADS] : default_threads();
    threads = threads > MAX_THREADS ? MAX_THREADS : threads;
    double busy[MAX_THREADS] = { 0 };
    int worker = 0;
    for (long u = 0, first = 0; u < total; u++) {
        int tile = out[u].tile;
        if (u == 0 || tile != out[u - 1].tile) {
            first = u;
            worker = 0;
            for (int w = 1; w < threads; w++)
                worker = busy[w] < busy[worker] ? w : worker;
            busy[worker] += work[tile];
            if (unordered && !rotate_shares(out + first, count[tile] - first, n, shares(threads),
                                            worker)) {
                total = -1;
                goto done;
            }
        }
        out[u].bin_entry = (int32_t)(u - first);
        out[u].bin_size = (int32_t)(count[tile] - first);
        out[u].thread = worker;
    }
done:
    free(count);
    free(work);
    return total;
}

/* --- the variants ------------------------------------------------------------- */

#define VARIANT(name, ...)                                                                   \
    static void rasterize_##name(const struct tri_setup *t, const struct raster_params *p,  \
                                 struct target *fb, struct trace *tr)                       \
    {                                                                                        \
        rasterize_one_tri(t, p, fb, tr, (struct tiles_options){ __VA_ARGS__ });              \
    }                                                                                        \
    static bool scene_##name(const struct scene *s, const struct raster_params *p,          \
                             struct target *fb)                                              \
    {                                                                                        \
        return draw_scene(s, p, fb, (struct tiles_options){ __VA_ARGS__ }, NULL);            \
    }

VARIANT(tiles, .twin = TWIN_BEST, .tile_buffers = true)
VARIANT(one_thread, .twin = TWIN_BEST, .tile_buffers = true, .threads = 1)
VARIANT(in_place, .twin = TWIN_BEST, .threads = 1)
VARIANT(four_corners, .twin = TWIN_BEST, .tile_buffers = true, .threads = 1, .corners = CORNERS_FOUR)
VARIANT(sse2, .twin = TWIN_SSE2, .tile_buffers = true, .threads = 1)
VARIANT(scalar, .twin = TWIN_C, .tile_buffers = true, .threads = 1)
VARIANT(no_bins, .twin = TWIN_BEST, .threads = 1, .no_bins = true)
VARIANT(wrong_corner, .twin = TWIN_BEST, .tile_buffers = true, .corners = CORNERS_WRONG)
VARIANT(unordered, .twin = TWIN_BEST, .tile_buffers = true, .unordered = true)

static const struct lesson_variant variants[] = {
    { .name = "tiles", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_tiles,
      .what = "64 x 64 tiles in cache, 8 x 8 blocks, 8 pixels a register (AVX2 where the CPU "
      "has it), one worker per core (or --threads N)" },
    { .name = "1-thread", .kind = VARIANT_TWIN, .rasterize = rasterize_one_thread,
      .what = "the same on one thread" },
    { .name = "in-place", .kind = VARIANT_TWIN, .rasterize = rasterize_in_place,
      .what = "one thread, no tile buffers: each tile drawn straight into the framebuffer" },
    { .name = "four-corners", .kind = VARIANT_TWIN, .rasterize = rasterize_four_corners,
      .what = "one thread, every corner of every edge tested, as in lesson 05" },
    { .name = "sse2", .kind = VARIANT_TWIN, .rasterize = rasterize_sse2,
      .what = "one thread, the SSE2 twin: two registers of four pixels" },
    { .name = "scalar", .kind = VARIANT_TWIN, .rasterize = rasterize_scalar,
      .what = "one thread, the plain C twin: one pixel at a time" },
    { .name = "no-bins", .kind = VARIANT_TWIN, .rasterize = rasterize_no_bins,
      .what = "one thread, no bins: triangle after triangle through the tiles of its box" },
    { .name = "wrong-corner", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_wrong_corner,
      .what = "exhibit: tiles rejected with the accept corner of each edge" },
    { .name = "unordered", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_unordered,
      .what = "exhibit: each worker draws its own share of a bin first, so the order "
      "within a tile depends on which thread took it" },
};

static const rasterize_scene_fn scenes[] = {
    scene_tiles, scene_one_thread, scene_in_place, scene_four_corners, scene_sse2, scene_scalar,
    scene_no_bins, scene_wrong_corner, scene_unordered,
};

static const char *const compare[] = { "05-block-classification", NULL };

const struct lesson lesson_07 = {
    .id = "07-tiles",
    .title = "Tiles, bins and threads: the production architecture",
    .pseudocode = pseudocode,
    .builtin_scene = "tiles",
    .exhibit_scene = "tiles-exhibits",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .params = (const struct lesson_param[]){
        [P_THREADS] = { .option = "threads", .arg = "N", .name = "threads",
                        .help = "worker threads of a tiled lesson, 1..64 (default: one per core)",
                        .min = 1, .max = MAX_THREADS },
        { 0 } },
    .compare = compare,
    .rasterize_scene = scenes,
    .narration_units = narration_units,
    .cost_tested = (const struct cost_term[]){ COST_TERM(3, LANE_EDGE_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(QUAD_PLANES, PLANE_AT_COST), COST_TERM(1, RECIPROCAL_COST),
        COST_TERM(1, COLOUR_TIMES_Z_COST), { 0 } },
    /* exercise.c: one triangle through the tiles; every tile and block
     * called FULL covered in full and the other way round (the box of the
     * small-triangle path is tested, not classified) */
    .exercise = { .write_line = L_BLOCK_PARTIAL, .full_blocks = true, .tiles = true,
                  .class_lines = (const int[]){ L_REJECT, L_FULL_TILE, L_PARTIAL_TILE, L_BLOCK_REJECT,
                                                L_BLOCK_ACCEPT, L_BLOCK_PARTIAL, -1 } },
};
