/* multisampling.h - what lesson 08's algorithm (multisampling.c) shares with
 * its tiled twin (tiled.c, over lesson 07's bins and workers): one
 * triangle's run, its set-up, its blocks and the resolve of one pixel. */
#ifndef TRISTEP_MULTISAMPLING_H
#define TRISTEP_MULTISAMPLING_H

#include "lesson.h"
#include "shade/quad.h"      /* struct planes: lesson 04's planes of 1/z and a/z */

/* Both builds link into one program: the fast build's names end in _fast. */
#ifndef TRISTEP_NARRATE
#define ms_target ms_target_fast
#define ms_box ms_box_fast
#define ms_setup ms_setup_fast
#define ms_blocks ms_blocks_fast
#define ms_resolve ms_resolve_fast
#define ms_units ms_units_fast
#define ms_tiled_scene ms_tiled_scene_fast
#define rasterize_tiled rasterize_tiled_fast
#define ms_pixels ms_pixels_fast
#endif

/* The pseudo-code's line of the blocks (multisampling.c), where the tiled
 * twin's steps of lesson 07 (bins, tiles, stores) are shown. */
#define MS_LINE_BLOCKS 2
/* ... and of a partial pixel's mask and its write, which the twin's SIMD
 * pixels (pixels.c) tell as msaa's do */
#define MS_LINE_MASK 6
#define MS_LINE_WRITE 7
#define Q_DEFAULT 8
/* the lesson's parameter rows: p->knob[MS_P_BLOCK] is --block-size */
enum { MS_P_BLOCK, MS_P_SAMPLES, MS_P_THREADS };

/* A sample pattern as the loops use it: each sample's offset from the pixel
 * CENTRE, in 1/256 pixel (the standard positions are given from the pixel's
 * corner), and the extent of the pattern. */
struct pattern {
    int n;
    int dx[SAMPLES_MAX], dy[SAMPLES_MAX];
    int lo_x, hi_x, lo_y, hi_y;     /* smallest and largest dx, dy */
};

/* The edge-function notes' edge functions with the fill rule folded into the constant, as
 * in lesson 05: a sample is covered when F0k + bias_k + O_sk >= 0 for all
 * three edges, a plain sign test. O_sk = I0k dx_s + J0k dy_s is sample s's
 * offset on edge k: the same in every pixel, computed once per triangle. */
struct edges {
    struct biased_edges b;          /* F0k + bias_k at the pixel centres (lesson 05's) */
    int64_t off[SAMPLES_MAX][3];    /* O_sk */
    int64_t ext0[3];                /* the extent's top-left corner from the centre */
    int64_t ext_w[3], ext_h[3];     /* the extent's width and height, on edge k */
};

/* The tent filter's n taps: neighbour (di, dj), sample s, weight w (tent_setup). */
struct tent {
    int n, di[9 * SAMPLES_MAX], dj[9 * SAMPLES_MAX], s[9 * SAMPLES_MAX];
    int64_t w[9 * SAMPLES_MAX];
};

struct run {
    const struct tri_setup *t;
    const struct raster_params *p;
    struct target *fb;
    struct trace *tr;
    struct pattern pt;
    struct edges e;
    struct planes pl;
    struct tent taps;                   /* the tent's (when tent) */
    int nplanes;                        /* 1/z, r, g, b (and s, t with a checker) */
    double plane_off[SAMPLES_MAX][PL_COUNT];    /* a plane's offset at sample s */
    bool per_sample;                    /* SSAA: shade every covered sample */
    bool tent;                          /* resolve with the tent over neighbours' samples */
    float grid;                         /* 1: the exhibit's grid (narrated, for the explorer) */
    uint32_t *scolor;                   /* the samples: n per pixel, or the pixels */
    float *sdepth;                      /*   themselves when n = 1 ... */
    int sx, sy;                         /* ... from pixel (sx, sy) on, */
    size_t srow;                        /* rows of srow pixels (the target's, or a tile's) */
    /* NULL: each pixel resolved as it is written; else (the tiled twin) bit i
     * of touched[j] says pixel (sx + i, sy + j) was, to be resolved once, at
     * the tile's store */
    uint64_t *touched;
    /* the tiled twin: a FULL or PARTIAL block's pixels, SIMD (pixels.c),
     * narrated as partial_block narrates them, instead of full_block and
     * partial_block; NULL: theirs */
    void (*pixels)(const struct run *r, int x0, int y0, int x1, int y1, bool full);
};

struct ms_options {
    bool per_sample;        /* SSAA: shade every sample */
    bool tent;              /* resolve with the tent filter, not the box */
    bool grid;              /* exhibit: a regular grid instead of the standard pattern */
    bool fill_rule;         /* false: exhibit, a sample on an edge is covered by both sides */
};

/* The pattern of the run (p->samples, or the exhibit's grid), with the
 * target's storage for its samples made when it has none. */
const struct sample_pattern *ms_target(struct target *fb, const struct raster_params *p, bool grid);
/* The pattern as the loops use it, and the box of pixels a sample of which
 * may be covered, narrated (the set-up's line); false: no sample covered. */
bool ms_box(const struct tri_setup *t, const struct sample_pattern *sp, struct pattern *pt,
            int box[4], struct trace *tr, bool grid);
/* The rest of the run's set-up: edges at the samples, planes; the samples
 * in the target's storage. */
void ms_setup(struct run *r, const struct tri_setup *t, const struct raster_params *p,
              struct target *fb, struct trace *tr, struct ms_options o);
/* The q x q blocks of the box, aligned on the screen, each classified,
 * narrated, drawn. */
void ms_blocks(const struct run *r, const int box[4], int q);
/* A pixel's n samples resolved: the mean colour (rounded), the nearest depth. */
void ms_resolve(int n, const uint32_t *color, const float *z, uint32_t *rgba, float *nearest);

/* The tiled twin's SIMD pixels for run r (pixels.c): NULL where the CPU or
 * the run has none (then msaa's own loops draw). */
typedef void (*ms_pixels_fn)(const struct run *r, int x0, int y0, int x1, int y1, bool full);
ms_pixels_fn ms_pixels(const struct run *r);

/* The tiled twin (tiled.c): one triangle, the whole scene, the explorer's order. */
void rasterize_tiled(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                     struct trace *tr);
bool ms_tiled_scene(const struct scene *s, const struct raster_params *p, struct target *fb);
long ms_units(const struct scene *s, const struct lesson_variant *v, const struct raster_params *p,
              struct lesson_unit *out, long cap);

#endif
