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
 * and a/z (the edge-function notes, formula 23), z = 1 / (1/z) by a true division, the same
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

/* trace_event.aux[] of this lesson, for a tile or block event: its size
 * and level (0 tile, 1 block), and for the steps of a tile the bin's size,
 * the entry's place in it and the worker drawing it. Not named for the
 * panel: the explorer's watch (tiles_explorer.c) says where a step stands,
 * for every event of the step. */

/* --- the variants ------------------------------------------------------------- */

enum { V_TILES, V_ONE_THREAD, V_IN_PLACE, V_FOUR_CORNERS, V_SSE2, V_SCALAR, V_NO_BINS,
       V_WRONG_CORNER, V_UNORDERED, V_COUNT };

static const struct tiles_options options[V_COUNT] = {
    [V_TILES] = { .twin = TWIN_BEST, .tile_buffers = true },
    [V_ONE_THREAD] = { .twin = TWIN_BEST, .tile_buffers = true, .threads = 1 },
    [V_IN_PLACE] = { .twin = TWIN_BEST, .threads = 1 },
    [V_FOUR_CORNERS] = { .twin = TWIN_BEST, .tile_buffers = true, .threads = 1,
                         .corners = CORNERS_FOUR },
    [V_SSE2] = { .twin = TWIN_SSE2, .tile_buffers = true, .threads = 1 },
    [V_SCALAR] = { .twin = TWIN_C, .tile_buffers = true, .threads = 1 },
    [V_NO_BINS] = { .twin = TWIN_BEST, .threads = 1, .no_bins = true },
    [V_WRONG_CORNER] = { .twin = TWIN_BEST, .tile_buffers = true, .corners = CORNERS_WRONG },
    [V_UNORDERED] = { .twin = TWIN_BEST, .tile_buffers = true, .unordered = true },
};

/* Each variant twice: one triangle (`rasterize`) and the whole scene (its
 * scene-level twin), both through the stages with its options. */
#define VARIANT(rasterize_name, scene_name, v)                                            \
    static void rasterize_name(const struct tri_setup *t, const struct raster_params *p, \
                               struct target *fb, struct trace *tr)                      \
    {                                                                                     \
        rasterize_one_tri(t, p, fb, tr, options[v]);                                      \
    }                                                                                     \
    static bool scene_name(const struct scene *s, const struct raster_params *p,         \
                           struct target *fb)                                             \
    {                                                                                     \
        return draw_scene(s, p, fb, options[v], NULL);                                    \
    }

VARIANT(rasterize_tiles, scene_tiles, V_TILES)
VARIANT(rasterize_one_thread, scene_one_thread, V_ONE_THREAD)
VARIANT(rasterize_in_place, scene_in_place, V_IN_PLACE)
VARIANT(rasterize_four_corners, scene_four_corners, V_FOUR_CORNERS)
VARIANT(rasterize_sse2, scene_sse2, V_SSE2)
VARIANT(rasterize_scalar, scene_scalar, V_SCALAR)
VARIANT(rasterize_no_bins, scene_no_bins, V_NO_BINS)
VARIANT(rasterize_wrong_corner, scene_wrong_corner, V_WRONG_CORNER)
VARIANT(rasterize_unordered, scene_unordered, V_UNORDERED)

static const struct lesson_variant variants[V_COUNT] = {
    [V_TILES] = { .name = "tiles", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_tiles,
                  .what = "64 x 64 tiles in cache, 8 x 8 blocks, 8 pixels a register (AVX2 "
                  "where the CPU has it), one worker per core (or --threads N)" },
    [V_ONE_THREAD] = { .name = "1-thread", .kind = VARIANT_TWIN, .rasterize = rasterize_one_thread,
                       .what = "the same on one thread" },
    [V_IN_PLACE] = { .name = "in-place", .kind = VARIANT_TWIN, .rasterize = rasterize_in_place,
                     .what = "one thread, no tile buffers: each tile drawn straight into the "
                     "framebuffer" },
    [V_FOUR_CORNERS] = { .name = "four-corners", .kind = VARIANT_TWIN,
                         .rasterize = rasterize_four_corners,
                         .what = "one thread, every corner of every edge tested, as in lesson 05" },
    [V_SSE2] = { .name = "sse2", .kind = VARIANT_TWIN, .rasterize = rasterize_sse2,
                 .what = "one thread, the SSE2 twin: two registers of four pixels" },
    [V_SCALAR] = { .name = "scalar", .kind = VARIANT_TWIN, .rasterize = rasterize_scalar,
                   .what = "one thread, the plain C twin: one pixel at a time" },
    [V_NO_BINS] = { .name = "no-bins", .kind = VARIANT_TWIN, .rasterize = rasterize_no_bins,
                    .what = "one thread, no bins: triangle after triangle through the tiles of "
                    "its box" },
    [V_WRONG_CORNER] = { .name = "wrong-corner", .kind = VARIANT_EXHIBIT,
                         .rasterize = rasterize_wrong_corner,
                         .what = "exhibit: tiles rejected with the accept corner of each edge" },
    [V_UNORDERED] = { .name = "unordered", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_unordered,
                      .what = "exhibit: each worker draws its own share of a bin first, so the "
                      "order within a tile depends on which worker took it" },
};

static const rasterize_scene_fn scenes[V_COUNT] = {
    [V_TILES] = scene_tiles, [V_ONE_THREAD] = scene_one_thread, [V_IN_PLACE] = scene_in_place,
    [V_FOUR_CORNERS] = scene_four_corners, [V_SSE2] = scene_sse2, [V_SCALAR] = scene_scalar,
    [V_NO_BINS] = scene_no_bins, [V_WRONG_CORNER] = scene_wrong_corner,
    [V_UNORDERED] = scene_unordered,
};

/* --- the narrated order ------------------------------------------------------ */

/* The explorer steps through the scene's own run, narrated: its workers
 * taking turns (threads.c), the steps written down as the run makes them.
 * One step per triangle set up and binned, in scene order (tile -1, entry
 * -1), then one per entry of a bin drawn: the tiles in the order the
 * workers took them, each bin in the order its worker drew it, with that
 * worker. */
struct recorder {
    struct lesson_unit *out;
    long cap, n;
    int nx;
};

static void record(void *ctx, const struct trace_event *ev)
{
    struct recorder *rec = ctx;
    struct lesson_unit u;
    if (ev->kind == TRACE_SETUP)
        u = (struct lesson_unit){ .tri = ev->tri, .tile = -1, .bin_entry = -1 };
    else if (ev->kind == TRACE_BLOCK && (ev->line == L_BIN_LOOP || ev->line == L_FULL_TILE))
        u = (struct lesson_unit){ .tri = ev->tri, .tile = ev->y / TILE * rec->nx + ev->x / TILE,
                                  .bin_size = (int32_t)ev->aux[2], .bin_entry = (int32_t)ev->aux[3],
                                  .thread = (int32_t)ev->aux[4] };
    else
        return;
    if (rec->n < rec->cap)
        rec->out[rec->n] = u;
    rec->n++;
}

long tiles_units(const struct scene *s, const struct raster_params *p, struct tiles_options o,
                 struct lesson_unit *out, long cap)
{
    struct target fb;
    if (!target_init(&fb, s->w, s->h, scene_background(s)))
        return -1;
    struct recorder rec = { out, cap, 0, grid_of(s->w, s->h).nx };
    struct trace tr = { .sink = record, .ctx = &rec };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    bool ok = draw_scene(s, p, &fb, o, &tr);
    target_free(&fb);
    return ok ? rec.n : -1;
}

static long units_of(const struct scene *s, const struct lesson_variant *v,
                     const struct raster_params *p, struct lesson_unit *out, long cap, bool pixels)
{
    if (v < variants || v >= variants + V_COUNT)
        return -1;
    struct tiles_options o = options[v - variants];
    o.order_only = !pixels;
    return tiles_units(s, p, o, out, cap);
}

/* The run records its order without drawing its pixels: the order does
 * not depend on them (threads.c, order_only), and on a large scene the
 * explorer's first picture waits for it. */
static long narration_units(const struct scene *s, const struct lesson_variant *v,
                            const struct raster_params *p, struct lesson_unit *out, long cap)
{
    return units_of(s, v, p, out, cap, false);
}

long tiles_drawn_units(const struct scene *s, const struct lesson_variant *v,
                       const struct raster_params *p, struct lesson_unit *out, long cap)
{
    return units_of(s, v, p, out, cap, true);
}

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
     * small-triangle path is tested, not classified; a tile is called FULL
     * by its own step, when it is filled, not by the binning) */
    .exercise = { .write_line = L_BLOCK_PARTIAL, .full_blocks = true, .tiles = true,
                  .class_lines = (const int[]){ L_REJECT, L_PARTIAL_TILE, L_FULL_TILE,
                                                L_BLOCK_REJECT, L_BLOCK_ACCEPT, L_BLOCK_PARTIAL,
                                                -1 } },
};
