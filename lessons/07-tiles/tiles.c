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
#include <stdlib.h>
#include <string.h>

#include "tiles.h"

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

/* trace_event.aux[] of this lesson: for a tile or block event its size and
 * level (0 tile, 1 block), the tile's bin size, the triangle's place in the
 * bin, and the worker thread that drew the tile in the real run. */
static const char *const aux_names[] = { "q", "level", "bin", "entry", "thread", NULL };

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
    int threads = p->threads > 0 ? p->threads : default_threads();
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

/* Each variant twice: one triangle (`rasterize`), the whole scene (its
 * scene-level twin), both with the same options; the names written out. */
#define VARIANT(rasterize_name, scene_name, ...)                                           \
    static void rasterize_name(const struct tri_setup *t, const struct raster_params *p,  \
                               struct target *fb, struct trace *tr)                       \
    {                                                                                      \
        rasterize_one_tri(t, p, fb, tr, (struct tiles_options){ __VA_ARGS__ });            \
    }                                                                                      \
    static bool scene_name(const struct scene *s, const struct raster_params *p,          \
                           struct target *fb)                                              \
    {                                                                                      \
        return draw_scene(s, p, fb, (struct tiles_options){ __VA_ARGS__ }, NULL);          \
    }

VARIANT(rasterize_tiles, scene_tiles, .twin = TWIN_BEST, .tile_buffers = true)
VARIANT(rasterize_one_thread, scene_one_thread, .twin = TWIN_BEST, .tile_buffers = true, .threads = 1)
VARIANT(rasterize_in_place, scene_in_place, .twin = TWIN_BEST, .threads = 1)
VARIANT(rasterize_four_corners, scene_four_corners, .twin = TWIN_BEST, .tile_buffers = true,
        .threads = 1, .corners = CORNERS_FOUR)
VARIANT(rasterize_sse2, scene_sse2, .twin = TWIN_SSE2, .tile_buffers = true, .threads = 1)
VARIANT(rasterize_scalar, scene_scalar, .twin = TWIN_C, .tile_buffers = true, .threads = 1)
VARIANT(rasterize_no_bins, scene_no_bins, .twin = TWIN_BEST, .threads = 1, .no_bins = true)
VARIANT(rasterize_wrong_corner, scene_wrong_corner, .twin = TWIN_BEST, .tile_buffers = true,
        .corners = CORNERS_WRONG)
VARIANT(rasterize_unordered, scene_unordered, .twin = TWIN_BEST, .tile_buffers = true,
        .unordered = true)

static const struct lesson_variant variants[] = {
    { "tiles", "64 x 64 tiles in cache, 8 x 8 blocks, 8 pixels a register (AVX2 where the CPU "
      "has it), one worker per core (or --threads N)", rasterize_tiles, false },
    { "1-thread", "the same on one thread", rasterize_one_thread, false },
    { "in-place", "one thread, no tile buffers: each tile drawn straight into the framebuffer",
      rasterize_in_place, false },
    { "four-corners", "one thread, every corner of every edge tested, as in lesson 05",
      rasterize_four_corners, false },
    { "sse2", "one thread, the SSE2 twin: two registers of four pixels", rasterize_sse2, false },
    { "scalar", "one thread, the plain C twin: one pixel at a time", rasterize_scalar, false },
    { "no-bins", "one thread, no bins: triangle after triangle through the tiles of its box",
      rasterize_no_bins, false },
    { "wrong-corner", "exhibit: tiles rejected with the accept corner of each edge",
      rasterize_wrong_corner, true },
    { "unordered", "exhibit: each worker draws its own share of a bin first, so the order "
      "within a tile depends on which thread took it", rasterize_unordered, true },
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
