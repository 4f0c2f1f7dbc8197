/* Lesson 09 on lesson 07's tiles: the twin `tiles` of quads.
 *
 * The quads of the fast twin (quads_sse.c: the same blocks, quads, helper
 * pixels, derivatives and texture unit, the same bytes as textures.c),
 * inside lesson 07's production architecture (lessons/07-tiles/: its
 * shares, bins and workers, threads.c), with what a tile holds:
 *
 *   - a tile's colour and depth are loaded into the worker's buffer
 *     (64 x 64 pixels, 32 KB: the level-1 cache), so every triangle of the
 *     bin tests depth and writes in cache, and the tile is stored once;
 *   - the textures are shared by every worker, read only: a worker reads
 *     the texels its tile's quads need, wherever they are.
 *
 * A quad never straddles two tiles (tiles and quads start on even pixels),
 * and its helper pixels are evaluated wherever they lie, in the tile or
 * not, so each quad is the quad the lesson draws: the picture is the same
 * bytes, for any number of threads.
 *
 * Narrated, lesson 07's steps (bins, tiles, stores) show on the line of
 * the blocks, lesson 09's own at their lines. */
#define _POSIX_C_SOURCE 200809L     /* aligned_alloc */
#include <stdlib.h>
#include <string.h>

#include "tiled.h"
#include "../07-tiles/tiles.h"

/* A worker's tile: lesson 07's buffer, and where it lies on the target. */
struct tex_tile_buf {
    struct tile_buf b;
    struct tex_tile d;
};

/* Kept from run to run, one per worker (a run at a time: lesson 07's frame
 * lock). */
static struct tex_tile_buf *kept[MAX_THREADS];

/* Lesson 07's code runs shown on the blocks' line (tr->one_line), lesson
 * 09's own code at its own lines. */
static bool own_lines(struct trace *tr)
{
    bool was = tr && tr->one_line;
    if (tr)
        tr->one_line = false;
    return was;
}

static void restore_lines(struct trace *tr, bool was)
{
    if (tr)
        tr->one_line = was;
}

/* --- the pass over lesson 07's bins --------------------------------------- */

/* The record that bins t: its edges and its box of pixel centres (the
 * quads' helpers lie outside it, but are never written). */
static bool set_up(struct tri *rec, const struct tri_setup *t, const struct raster_params *p,
                   struct trace *tr)
{
    (void)p;
    bool was = own_lines(tr);
    NARRATE_SETUP(tr, t, TEX_LINE_SETUP);
    restore_lines(tr, was);
    memset(rec, 0, sizeof *rec);
    rec->minx = 0, rec->maxx = -1, rec->miny = 0, rec->maxy = -1;  /* no tile */
    if (t->empty)
        return false;
    for (int k = 0; k < 3; k++) {
        rec->c[k] = edge_value(t, k, 0, 0) + t->bias[k];
        rec->di[k] = (int32_t)t->I[k];
        rec->dj[k] = (int32_t)t->J[k];
    }
    rec->bias_neg = (uint8_t)((t->bias[0] ? 1 : 0) | (t->bias[1] ? 2 : 0) | (t->bias[2] ? 4 : 0));
    rec->minx = (int16_t)t->minx, rec->miny = (int16_t)t->miny;
    rec->maxx = (int16_t)t->maxx, rec->maxy = (int16_t)t->maxy;
    return true;
}

static void *load(int worker, struct target *fb, struct rect r, struct rect part)
{
    if (!kept[worker] && !(kept[worker] = aligned_alloc(CACHE_LINE, sizeof *kept[worker])))
        return NULL;
    struct tex_tile_buf *b = kept[worker];
    struct dst d = tile_load(&b->b, fb, r, part);
    b->d = (struct tex_tile){ d.color, d.depth, d.count, r.x0, r.y0, r.w, r.h, d.stride, d.count_stride };
    return b;
}

/* Triangle t's quads in the tile, written in the tile buffer. */
static void draw(void *buf, const struct tri_setup *t, struct rect rc, const struct raster_params *p,
                 struct trace *tr)
{
    (void)rc;
    struct tex_tile_buf *b = buf;
    bool was = own_lines(tr);
    tex_draw_in_tile(t, p, &b->d, tr);
    restore_lines(tr, was);
}

static void store(void *buf, struct target *fb, struct rect r, struct rect part)
{
    struct tex_tile_buf *b = buf;
    tile_store(&b->b, fb, r, part);
}

static const struct tile_pass pass = { set_up, load, draw, store };

/* --- the variant --------------------------------------------------------- */

static struct tiles_options tiled(const struct raster_params *p)
{
    int threads = p->knob[TEX_P_THREADS] > 0 ? p->knob[TEX_P_THREADS] : default_threads();
    return (struct tiles_options){ .threads = threads, .pass = &pass };
}

/* One triangle (the tests, the narrated replay: p->at->unit, a unit of the
 * scene's run, threads.c of lesson 07), its lesson 07 steps on the blocks'
 * line. */
void tex_rasterize_tiled(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                         struct trace *tr)
{
    bool was = tr && tr->one_line;
    uint8_t line = tr ? tr->line : 0;
    if (tr)
        tr->one_line = true, tr->line = TEX_LINE_BLOCKS;
    rasterize_one_tri(t, p, fb, tr, tiled(p));
    if (tr)
        tr->one_line = was, tr->line = line;
}

bool tex_tiled_scene(const struct scene *s, const struct raster_params *p, struct target *fb)
{
    return draw_scene(s, p, fb, tiled(p), NULL);
}

/* The explorer's order: the tiled run's own units (each triangle set up and
 * binned, then each entry of a bin as its worker drew it), recorded without
 * drawing; for the other variants, scene order. */
long tex_units(const struct scene *s, const struct lesson_variant *v, const struct raster_params *p,
               struct lesson_unit *out, long cap)
{
    if (v->rasterize == tex_rasterize_tiled) {
        struct tiles_options o = tiled(p);
        o.order_only = true;
        return tiles_units(s, p, o, out, cap);
    }
    for (long i = 0; i < s->ntris && i < cap; i++)
        out[i] = (struct lesson_unit){ .tri = (uint32_t)i, .tile = -1, .bin_entry = -1 };
    return s->ntris;
}
