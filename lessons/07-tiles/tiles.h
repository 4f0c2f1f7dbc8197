/* tiles.h - what the stages of lesson 07 share: the triangle record, the
 * tile grid, the bins, the tile buffer and the functions one stage calls in
 * another. The stages, in the order a frame runs them, as llvmpipe cuts its
 * own (src/gallium/drivers/llvmpipe/):
 *
 *   setup.c    the record of one triangle               (lp_setup_tri.c)
 *   bins.c     which tiles it may touch: the bins       (lp_scene.c)
 *   draw.c     one triangle inside one tile: the descent (lp_rast_tri.c)
 *   strips.c   ... its pixels, 8 a register: C, SSE2 and AVX2 twins
 *   threads.c  the workers that take the tiles          (lp_rast.c)
 *   tiles.c    the lesson: pseudo-code, variants, narrated order
 */
#ifndef TRISTEP_TILES_H
#define TRISTEP_TILES_H

#include <stdint.h>

#include "lesson.h"
#include "shade/quad.h"         /* the planes of 1/z and a/z (lesson 04), CHECKER_DARK */
#include "simd.h"               /* SSE2: four lanes a register, on any CPU */

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TRISTEP_SIMDE)
#define TILES_AVX2 1            /* AVX2 twin compiled, run where the CPU has it */
#else
#define TILES_AVX2 0
#endif
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF    /* no fused multiply-add: every twin rounds alike */
#endif

/* Both builds of the lesson (narrated and fast) link into one program, so
 * what one file of the lesson calls in another carries the build in its
 * name: the fast build's ends in _fast. */
#ifndef TRISTEP_NARRATE
#define tri_record tri_record_fast
#define tri_set_up tri_set_up_fast
#define classify_rect classify_rect_fast
#define arena_alloc arena_alloc_fast
#define arena_reset arena_reset_fast
#define bin_triangle bin_triangle_fast
#define tile_load tile_load_fast
#define tile_store tile_store_fast
#define target_dst target_dst_fast
#define tri_in_tile_make tri_in_tile_make_fast
#define shade1_c shade1_c_fast
#define strip_c strip_c_fast
#define strip_sse2 strip_sse2_fast
#define strip_avx2 strip_avx2_fast
#define pick_twin pick_twin_fast
#define draw_scene draw_scene_fast
#define rasterize_one_tri rasterize_one_tri_fast
#define default_threads default_threads_fast
#define tiles_drawn_units tiles_drawn_units_fast
#define tiles_units tiles_units_fast
#endif

/* Lines of the pseudo-code (tiles.c), which the narration lights. */
enum { L_SETUP, L_BIN, L_REJECT, L_ACCEPT, L_PARTIAL_TILE, L_TAKE, L_BIN_LOOP, L_FULL_TILE,
       L_SMALL, L_BLOCK_REJECT, L_BLOCK_ACCEPT, L_BLOCK_PARTIAL, L_STORE };

/* Has the narration reached the step the explorer shows? (Never in the
 * fast build.) */
static inline bool frozen(const struct trace *tr)
{
    return NARRATING && tr && tr->frozen;
}

#define TILE 64             /* tile side: 64 x 64 colour + depth = 32 KB, level-1 cache */
#define BLOCK 8             /* block side, and pixels a register (AVX2) */
#define LANES 8
#define MAX_THREADS 64
enum { P_THREADS };         /* the lesson's parameter rows: p->knob[P_THREADS] is --threads */
#define E_LIMIT (1 << 30)   /* |I i + J j| < 2^30 inside a tile: see (E) in tiles.c */

/* --- set-up (setup.c) ----------------------------------------------------- */

enum { ST_S, ST_T, ST_COUNT };      /* texture planes, N s / z and N t / z, apart */

/* One triangle after set-up: 136 bytes, what the tiles read, stored once;
 * the bins hold its number. */
struct tri {
    int64_t c[3];               /* F_k + bias_k at the centre of pixel (0, 0) */
    int32_t di[3], dj[3];       /* I_k, J_k: F_k grows by 256 I_k per pixel right, 256 J_k per row */
    int16_t minx, miny, maxx, maxy; /* pixels whose centre may be covered, on the target */
    uint8_t bias_neg;           /* bit k: bias_k = -1 (edge k neither top nor left) */
    bool textured;              /* st holds the planes of N s / z and N t / z */
    float p0[QUAD_PLANES], px[QUAD_PLANES], py[QUAD_PLANES];
    float st[3 * ST_COUNT];     /* P0, Px, Py of s, then of t */
};

void tri_record(struct tri *r, const struct tri_setup *t, int checker);
bool tri_set_up(struct tri *r, const struct tri_setup *t, int checker, struct trace *tr);

/* F_k + bias_k at the centre of pixel (x, y): exact, 64 bits. */
static inline int64_t edge_at(const struct tri *t, int k, int x, int y)
{
    return t->c[k] + SUBPIXEL_ONE * ((int64_t)t->di[k] * x + (int64_t)t->dj[k] * y);
}

/* For the narration only: which of the four corner pixel centres of x0..x1,
 * y0..y1 are inside edge k (bit 3 top-left, 2 top-right, 1 bottom-left, 0
 * bottom-right, as lesson 05 shows them). The tests themselves read two. */
static inline uint16_t corner_bits(const struct tri *t, int k, int x0, int y0, int x1, int y1)
{
    return (uint16_t)((edge_at(t, k, x0, y0) >= 0) << 3 | (edge_at(t, k, x1, y0) >= 0) << 2
                      | (edge_at(t, k, x0, y1) >= 0) << 1 | (edge_at(t, k, x1, y1) >= 0));
}

/* --- bins (bins.c) -------------------------------------------------------- */

struct rect {
    int x0, y0, w, h;           /* pixels x0 .. x0 + w - 1, y0 .. y0 + h - 1 */
};

/* Which corners decide: one per edge and test (the lesson), all four of
 * each edge as lesson 05 tests them (to measure the difference), or the
 * exhibit's wrong corner (the accept corner used to reject). */
enum corners { CORNERS_ONE, CORNERS_FOUR, CORNERS_WRONG };

enum block_class classify_rect(const struct tri *t, struct rect r, enum corners rule);

/* The tile grid over a w x h target. */
struct grid {
    int w, h, nx, ny, n;
};

static inline struct grid grid_of(int w, int h)
{
    struct grid g = { w, h, (w + TILE - 1) / TILE, (h + TILE - 1) / TILE, 0 };
    g.n = g.nx * g.ny;
    return g;
}

static inline struct rect tile_rect(const struct grid *g, int tile)
{
    struct rect r = { (tile % g->nx) * TILE, (tile / g->nx) * TILE, TILE, TILE };
    if (r.x0 + r.w > g->w)
        r.w = g->w - r.x0;
    if (r.y0 + r.h > g->h)
        r.h = g->h - r.y0;
    return r;
}

/* A bin: the triangles that may touch a tile, in scene order, each entry
 * the number of the triangle's one stored record (as llvmpipe's bins point
 * at its triangles) times two, plus one when the tile lies wholly inside
 * it (FULL). Blocks of BIN_BLOCK entries (256 bytes) in a chain: read one
 * after another, written without ever moving. */
#define BIN_BLOCK 62
#define CACHE_LINE 64

struct bin_block {
    struct bin_block *next;
    uint32_t n;
    uint32_t entry[BIN_BLOCK];
};

struct bin {
    struct bin_block *first, *last;
};

static inline uint32_t bin_entry_of(uint32_t index, bool full)
{
    return index << 1 | (full ? 1u : 0u);
}

/* One worker's memory for bins: chunks kept from run to run. */
struct chunk;
struct arena {
    struct chunk *first, *last, *cur;
};

void *arena_alloc(struct arena *a, size_t n);
void arena_reset(struct arena *a);
bool bin_triangle(const struct tri *t, uint32_t index, const struct grid *g, struct bin *bins,
                  struct arena *a, enum corners rule, struct trace *tr);

/* --- drawing (draw.c, strips.c) ------------------------------------------- */

/* Colour and depth of a w x h rectangle of pixels, rows `stride` apart,
 * and the coverage counts of the same pixels (what the checks read, not
 * the picture: always on the target, rows `count_stride` apart). Eight
 * lanes may be read and written at once from column i when i + 8 <= wide
 * (the tile buffer has room past its last column; the target, where
 * another thread may own the next tile, has none). */
struct dst {
    uint32_t *color;
    float *depth;
    uint8_t *count;             /* NULL: nobody counts coverage */
    int stride, w, h, wide, count_stride;
};

/* A tile's colour and depth in the worker's cache: 32 KB. */
struct tile_buf {
    _Alignas(32) uint32_t color[TILE * TILE + LANES];
    _Alignas(32) float depth[TILE * TILE + LANES];
};

struct dst tile_load(struct tile_buf *b, const struct target *fb, struct rect r, struct rect part);
void tile_store(const struct tile_buf *b, struct target *fb, struct rect r, struct rect part);
struct dst target_dst(struct target *fb, struct rect r);

/* What every pixel test and every shaded pixel of a triangle in a tile
 * needs. e0 is (E) at the tile's first pixel: covered <=> e0_k + I_k i +
 * J_k j >= 0 for k = 0, 1, 2, clamped so that a far edge stays a far edge. */
struct tri_in_tile {
    const struct tri *t;
    const float *st;            /* texture planes (s then t: P0, Px, Py), or NULL */
    int tx, ty;                 /* the tile's first pixel on the target */
    int32_t e0[3];
};

struct tri_in_tile tri_in_tile_make(const struct tri *t, struct rect r);

/* Row terms P0 + Py (y - miny) of the planes for row j, computed once a row. */
struct rows {
    float p[QUAD_PLANES], st[ST_COUNT];
};

/* Row terms P0 + Py (y - miny) of every plane, for row j of the tile
 * (inline: the twins call it once a row). */
static inline void plane_rows(const struct tri_in_tile *c, int j, struct rows *rw)
{
    const struct tri *t = c->t;
    float dyf = (float)(c->ty + j - t->miny);
    for (int q = 0; q < QUAD_PLANES; q++)
        rw->p[q] = t->p0[q] + t->py[q] * dyf;
    for (int q = 0; q < ST_COUNT; q++)
        rw->st[q] = c->st ? c->st[3 * q] + c->st[3 * q + 2] * dyf : 0.0f;
}
bool shade1_c(const struct tri_in_tile *c, const struct dst *d, const struct rows *rw, int i,
              int j, float *z_out, uint32_t *rgba_out);

/* A twin draws a strip: columns i .. i + 7 of rows y0 .. y1 of the tile,
 * the lanes of `mask` only, testing (E) when `test` (strips.c). */
typedef void (*strip_fn)(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
                         unsigned mask, bool test);
void strip_c(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
             unsigned mask, bool test);
void strip_sse2(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
                unsigned mask, bool test);
#if TILES_AVX2
__attribute__((target("avx2")))
void strip_avx2(const struct tri_in_tile *c, const struct dst *d, int i, int y0, int y1,
                unsigned mask, bool test);
#endif

/* Named costs (trace/trace.h) per pixel, for the explorer's counters:
 *   LANE_EDGE_COST   (E) of one edge in one lane: the row's value + I_k l
 *   PLANE_AT_COST    one plane at a pixel: the row's term + Px (x - minx)
 *   COLOUR_TIMES_Z_COST  r, g, b = (255 a / z) z
 * z = 1 / (1/z) is RECIPROCAL_COST (shade/shade.h); rounding and packing are
 * conversions, not arithmetic. */
#define LANE_EDGE_COST { .mul = 1, .add = 1 }
#define PLANE_AT_COST { .mul = 1, .add = 1 }
#define COLOUR_TIMES_Z_COST { .mul = 3, .add = 0 }

/* Which twin draws: chosen once per run. */
enum twin { TWIN_BEST, TWIN_AVX2, TWIN_SSE2, TWIN_C };

/* Draw triangle t into the tile r (pixels written through d). `full`: the
 * binning found the tile wholly inside; `four`: every corner of a block
 * tested (lesson 05's way, for the measurement). */
typedef void (*draw_fn)(const struct tri *t, struct rect r, bool full, const struct dst *d,
                        struct trace *tr, bool four);
draw_fn pick_twin(enum twin w);

/* --- the whole scene (threads.c) ----------------------------------------- */

/* Another lesson's pixels on these bins, shares and workers: lesson 08's
 * tiled twin sets up and draws its samples in tile buffers of its own. */
struct tile_pass {
    /* the record that bins triangle t: its box and edges reach every pixel a
     * sample of which may be covered (never FULL); false: nothing covered */
    bool (*set_up)(struct tri *r, const struct tri_setup *t, const struct raster_params *p,
                   struct trace *tr);
    /* worker `worker`'s tile buffer, holding the part `part` of tile r (NULL:
     * out of memory), triangle t drawn in it, the part stored */
    void *(*load)(int worker, struct target *fb, struct rect r, struct rect part);
    void (*draw)(void *buf, const struct tri_setup *t, struct rect r, const struct raster_params *p,
                 struct trace *tr);
    void (*store)(void *buf, struct target *fb, struct rect r, struct rect part);
};

struct tiles_options {
    enum twin twin;
    int threads;                /* 0: --threads, else one per core */
    bool tile_buffers;          /* false: draw into the target in place */
    enum corners corners;       /* CORNERS_ONE, or the measurement, or the exhibit */
    bool no_bins;               /* triangle after triangle through all its tiles, in place */
    bool unordered;             /* exhibit: each worker draws its own chunk's bins first */
    /* narrated only: the run as it is, its workers binning and taking the
     * tiles, each entry of a bin narrated where it would be drawn, but no
     * pixel drawn (the order of the explorer's steps, tiles.c) */
    bool order_only;
    const struct tile_pass *pass;   /* NULL: this lesson's pixels */
};

/* The scene is cut into a few shares per worker (more shares than workers:
 * the last ones go to whoever is free). */
#define SHARES_PER_THREAD 4

static inline int shares(int threads)
{
    return threads > 1 ? SHARES_PER_THREAD * threads : 1;
}

int default_threads(void);
bool draw_scene(const struct scene *s, const struct raster_params *p, struct target *fb,
                struct tiles_options o, struct trace *tr);
bool rasterize_one_tri(const struct tri_setup *ts, const struct raster_params *p,
                       struct target *fb, struct trace *tr, struct tiles_options o);
/* tiles.c: the units of a narrated run with options o (lesson_unit: each
 * triangle's set-up, then each entry of a bin drawn), or -1 when out of
 * memory; lesson_07.narration_units as a run that draws every pixel
 * records them (the tests hold the lesson's list to it) */
long tiles_units(const struct scene *s, const struct raster_params *p, struct tiles_options o,
                 struct lesson_unit *out, long cap);
long tiles_drawn_units(const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, struct lesson_unit *out, long cap);

#endif
