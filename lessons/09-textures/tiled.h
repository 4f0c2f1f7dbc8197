/* tiled.h - what lesson 09's tiled twin (tiled.c, on lesson 07's bins and
 * workers) shares with the quads it draws (quads_sse.c). Apart from
 * textures.h because tiled.c also includes lesson 07's tiles.h, whose
 * pseudo-code lines have the same names as lesson 09's. */
#ifndef TRISTEP_TEXTURES_TILED_H
#define TRISTEP_TEXTURES_TILED_H

#include <stdint.h>

#include "lesson.h"

#ifndef TRISTEP_NARRATE
#define tex_draw_in_tile tex_draw_in_tile_fast
#define tex_tiled_scene tex_tiled_scene_fast
#define tex_rasterize_tiled tex_rasterize_tiled_fast
#define tex_units tex_units_fast
#endif

/* The pseudo-code's lines (textures.c) of the set-up, which the tiled twin
 * tells as the lesson does, and of the blocks, where it shows its steps of
 * lesson 07 (bins, tiles, stores); the row of --threads among the lesson's
 * parameters (p->knob[TEX_P_THREADS]). */
#define TEX_LINE_SETUP 0
#define TEX_LINE_BLOCKS 1
#define TEX_P_THREADS 3

/* A tile of the target in a worker's buffer: pixel (x, y) of the target,
 * x0 <= x < x0 + w and y0 <= y < y0 + h, at color[(y - y0) * stride +
 * (x - x0)] (and depth); its coverage count on the target itself, rows
 * count_stride apart from the tile's first pixel (NULL: not counted). */
struct tex_tile {
    uint32_t *color;
    float *depth;
    uint8_t *count;
    int x0, y0, w, h, stride, count_stride;
};

/* The twin's quads of triangle t that lie in tile d, written there
 * (quads_sse.c), narrated block by block and quad by quad. */
void tex_draw_in_tile(const struct tri_setup *t, const struct raster_params *p,
                      const struct tex_tile *d, struct trace *tr);

/* The tiled twin (tiled.c): one triangle (the tests, the explorer's steps:
 * p->at->unit, a unit of the scene's run), the whole scene, and the
 * explorer's order (its run's units for `tiles`, scene order for the
 * other variants). */
void tex_rasterize_tiled(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr);
bool tex_tiled_scene(const struct scene *s, const struct raster_params *p, struct target *fb);
long tex_units(const struct scene *s, const struct lesson_variant *v, const struct raster_params *p,
               struct lesson_unit *out, long cap);

#endif
