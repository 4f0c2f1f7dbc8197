/* Lesson 08 on lesson 07's tiles: the twin `tiles` of msaa.
 *
 * The same samples, the same per-sample test, shading and depth test as
 * msaa (multisampling.c: ms_box, ms_setup, ms_blocks run here unchanged;
 * a block's pixels four samples a register, pixels.c, narrated as msaa's),
 * inside lesson 07's production architecture (lessons/07-tiles/: its
 * shares, bins and workers, threads.c), with what a tile holds changed:
 *
 *   - a tile's SAMPLES are loaded into the worker's buffer (64 x 64 pixels
 *     x N samples, colour and depth: 128 KB at 4 samples), so every
 *     triangle of the bin tests and writes samples in cache;
 *   - the resolve (the mean of a pixel's samples) runs once per pixel, at
 *     the tile's store, for the pixels a triangle wrote: not after every
 *     triangle, as the narrated algorithm shows it.
 *
 * The mean of the final samples is the mean msaa writes last, so the
 * picture is the same bytes, for any number of threads.
 *
 * A triangle is binned by the box of pixels whose samples it may cover and
 * by its edges moved out to its most favourable sample: conservative, never
 * a tile wholly inside (the tile's blocks decide, by their sample extent).
 * Narrated, lesson 07's steps (bins, tiles, stores) show on the line of the
 * blocks, lesson 08's own at their lines. */
#define _POSIX_C_SOURCE 200809L     /* aligned_alloc */
#include <stdlib.h>
#include <string.h>

#include "multisampling.h"
#include "../07-tiles/tiles.h"

/* A worker's tile: its samples (n per pixel, rows of TILE pixels), which
 * pixels were written, and the target they belong to. */
struct ms_tile {
    _Alignas(CACHE_LINE) uint32_t color[TILE * TILE * SAMPLES_MAX];   /* (a size of whole lines) */
    float depth[TILE * TILE * SAMPLES_MAX];
    uint64_t touched[TILE];
    struct target *fb;
    int n;
};

/* Kept from run to run, one per worker (a run at a time: lesson 07's frame
 * lock). */
static struct ms_tile *kept[MAX_THREADS];

/* The lesson 07 code a step runs is shown on the blocks' line, lesson 08's
 * own code at its own lines: tr->one_line around the one, not the other. */
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

/* The target's samples (the pixels themselves at one sample). */
static uint32_t *target_color(const struct target *fb)
{
    return fb->samples ? fb->samples->color : fb->color;
}

static float *target_depth(const struct target *fb)
{
    return fb->samples ? fb->samples->depth : fb->depth;
}

/* --- the pass over lesson 07's bins --------------------------------------- */

static bool set_up(struct tri *rec, const struct tri_setup *t, const struct raster_params *p,
                   struct trace *tr)
{
    struct pattern pt;
    int box[4];
    bool was = own_lines(tr);
    bool any = ms_box(t, sample_pattern(p->samples > 1 ? p->samples : 1), &pt, box, tr, false);
    restore_lines(tr, was);
    memset(rec, 0, sizeof *rec);
    rec->minx = 0, rec->maxx = -1, rec->miny = 0, rec->maxy = -1;  /* no tile */
    if (!any)
        return false;
    for (int k = 0; k < 3; k++) {
        int64_t most = INT64_MIN;   /* the edge at its most favourable sample */
        for (int s = 0; s < pt.n; s++) {
            int64_t o = t->I[k] * pt.dx[s] + t->J[k] * pt.dy[s];
            most = o > most ? o : most;
        }
        rec->c[k] = edge_value(t, k, 0, 0) + t->bias[k] + most;
        rec->di[k] = (int32_t)t->I[k];
        rec->dj[k] = (int32_t)t->J[k];
    }
    rec->bias_neg = (uint8_t)((t->bias[0] ? 1 : 0) | (t->bias[1] ? 2 : 0) | (t->bias[2] ? 4 : 0));
    rec->minx = (int16_t)box[0], rec->miny = (int16_t)box[1];
    rec->maxx = (int16_t)box[2], rec->maxy = (int16_t)box[3];
    return true;
}

/* Rows of the part of tile r: from the target (load) or back (store). */
static void copy_part(struct ms_tile *b, struct target *fb, struct rect r, struct rect part, bool load)
{
    size_t n = (size_t)b->n, w = (size_t)part.w * n;
    uint32_t *color = target_color(fb);
    float *depth = target_depth(fb);
    for (int j = 0; j < part.h; j++) {
        size_t at = ((size_t)(part.y0 - r.y0 + j) * TILE + (size_t)(part.x0 - r.x0)) * n;
        size_t on = ((size_t)(part.y0 + j) * (size_t)fb->w + (size_t)part.x0) * n;
        memcpy(load ? b->color + at : color + on, load ? color + on : b->color + at, w * sizeof *color);
        memcpy(load ? b->depth + at : depth + on, load ? depth + on : b->depth + at, w * sizeof *depth);
    }
}

static void *load(int worker, struct target *fb, struct rect r, struct rect part)
{
    if (!kept[worker] && !(kept[worker] = aligned_alloc(CACHE_LINE, sizeof *kept[worker])))
        return NULL;
    struct ms_tile *b = kept[worker];
    b->fb = fb;
    b->n = fb->samples ? fb->samples->n : 1;
    memset(b->touched, 0, sizeof b->touched);
    copy_part(b, fb, r, part, true);
    return b;
}

/* Triangle t in the tile: msaa's run, its box cut to the tile, its samples
 * in the tile buffer. */
static void draw(void *buf, const struct tri_setup *t, struct rect rc, const struct raster_params *p,
                 struct trace *tr)
{
    struct ms_tile *b = buf;
    struct run r;
    int box[4];
    if (!ms_box(t, sample_pattern(b->n), &r.pt, box, NULL, false))
        return;
    box[0] = box[0] > rc.x0 ? box[0] : rc.x0, box[1] = box[1] > rc.y0 ? box[1] : rc.y0;
    box[2] = box[2] < rc.x0 + rc.w - 1 ? box[2] : rc.x0 + rc.w - 1;
    box[3] = box[3] < rc.y0 + rc.h - 1 ? box[3] : rc.y0 + rc.h - 1;
    if (box[0] > box[2] || box[1] > box[3])
        return;
    bool was = own_lines(tr);
    ms_setup(&r, t, p, b->fb, tr, (struct ms_options){ .fill_rule = true });
    r.scolor = b->color, r.sdepth = b->depth;
    r.sx = rc.x0, r.sy = rc.y0, r.srow = TILE, r.touched = b->touched;
    r.pixels = ms_pixels(&r);     /* SIMD pixels (pixels.c), narrated too */
    ms_blocks(&r, box, p->knob[MS_P_BLOCK] > 0 ? p->knob[MS_P_BLOCK] : Q_DEFAULT);
    restore_lines(tr, was);
}

/* The samples back, and each written pixel resolved, once. */
static void store(void *buf, struct target *fb, struct rect r, struct rect part)
{
    struct ms_tile *b = buf;
    copy_part(b, fb, r, part, false);
    if (b->n == 1)
        return;         /* one sample: it is the pixel */
    for (int j = part.y0 - r.y0; j < part.y0 - r.y0 + part.h; j++)
        for (uint64_t m = b->touched[j]; m; m &= m - 1) {
            int i = __builtin_ctzll(m);
            size_t at = ((size_t)j * TILE + (size_t)i) * (size_t)b->n;
            size_t px = (size_t)(r.y0 + j) * (size_t)fb->w + (size_t)(r.x0 + i);
            ms_resolve(b->n, b->color + at, b->depth + at, &fb->color[px], &fb->depth[px]);
        }
}

static const struct tile_pass pass = { set_up, load, draw, store };

/* --- the variant --------------------------------------------------------- */

/* The run's options, and its params with the samples the target has (msaa
 * falls back to one when memory for them runs out). */
static struct tiles_options tiled(struct raster_params *q, const struct raster_params *p,
                                  struct target *fb)
{
    *q = *p;
    q->samples = fb ? ms_target(fb, p, false)->n : sample_pattern(p->samples) ? p->samples : 1;
    int threads = p->knob[MS_P_THREADS] > 0 ? p->knob[MS_P_THREADS] : default_threads();
    return (struct tiles_options){ .threads = threads, .pass = &pass };
}

/* One triangle (the tests, the narrated replay: p->at->unit, a unit of the
 * scene's run, threads.c of lesson 07), its lesson 07 steps on the blocks'
 * line. */
void rasterize_tiled(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                     struct trace *tr)
{
    struct raster_params q;
    struct tiles_options o = tiled(&q, p, fb);
    bool was = tr && tr->one_line;
    uint8_t line = tr ? tr->line : 0;
    if (tr)
        tr->one_line = true, tr->line = MS_LINE_BLOCKS;
    rasterize_one_tri(t, &q, fb, tr, o);
    if (tr)
        tr->one_line = was, tr->line = line;
}

bool ms_tiled_scene(const struct scene *s, const struct raster_params *p, struct target *fb)
{
    struct raster_params q;
    struct tiles_options o = tiled(&q, p, fb);
    return draw_scene(s, &q, fb, o, NULL);
}

/* The explorer's order: the tiled run's own units (each triangle set up and
 * binned, then each entry of a bin as its worker drew it), recorded without
 * drawing; for the other variants, scene order. */
long ms_units(const struct scene *s, const struct lesson_variant *v, const struct raster_params *p,
              struct lesson_unit *out, long cap)
{
    if (v->rasterize == rasterize_tiled) {
        struct raster_params q;
        struct tiles_options o = tiled(&q, p, NULL);
        o.order_only = true;
        return tiles_units(s, &q, o, out, cap);
    }
    for (long i = 0; i < s->ntris && i < cap; i++)
        out[i] = (struct lesson_unit){ .tri = (uint32_t)i, .tile = -1, .bin_entry = -1 };
    return s->ntris;
}
