/* bench.h - the pieces of `make bench`: seeded scenes, the llvmpipe peer and
 * the chart. bench.c times every lesson's fast build; see its header. */
#ifndef TRISTEP_BENCH_H
#define TRISTEP_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "scene/scene.h"

#define BENCH_MAX_RUNS 32

/* One benchmark scene and what the exact reference says it covers. */
struct bench_scene {
    const char *name;           /* "large", "small", "mixed" */
    const char *what;           /* one line for the table */
    struct scene s;             /* w x h, triangles (both windings, Gouraud, z in [1.5, 99.5]) */
    uint64_t pixels;            /* covered pixels, overdraw included */
    uint8_t *coverage;          /* w * h reference counts, saturating at 255 */
};

/* Fill the three scenes from a seed. `quick` makes them tiny. */
bool bench_scenes_make(struct bench_scene sc[3], uint64_t seed, bool quick);
/* The three textured scenes ("floor", "small-tex", "mixed-tex"): image
 * textures of 256 x 256 texels (builtin), perspective, from magnified to
 * minified; the same seed, other streams. */
bool bench_tex_scenes_make(struct bench_scene sc[3], uint64_t seed, bool quick);
void bench_scenes_free(struct bench_scene sc[3]);

/* Times of one program on one scene, seconds, and its coverage check. */
struct bench_timing {
    double t[BENCH_MAX_RUNS];
    int runs;
    double median, lo, hi;      /* over the timed runs (warm-up excluded) */
    double cycles[BENCH_MAX_RUNS];  /* bench_cycles() over each run, on the calling thread */
    double cycles_median;
    double cpu[BENCH_MAX_RUNS];     /* processor time of all the program's threads, seconds */
    double cpu_median;
    int64_t diff_ref;           /* pixels whose coverage count differs from the reference */
    int64_t diff_peer;          /* ... from llvmpipe's, or -1 when llvmpipe did not run */
};
void bench_timing_stats(struct bench_timing *bt);
double bench_now(void);                 /* seconds, monotonic */
/* Pixels whose counts differ. */
int64_t bench_count_diff(const uint8_t *a, const uint8_t *b, size_t n);

struct lesson;
struct lesson_variant;
struct raster_params;
struct target;
/* The whole scene by variant v of lesson l: through the lesson's
 * scene-level twin when it has one (lesson 07 bins every triangle, then
 * draws tile by tile on every core), else tri_setup + rasterize triangle
 * after triangle, each with its image texture in p->texture. */
void bench_draw(const struct lesson *l, const struct lesson_variant *v, const struct scene *s,
                const struct raster_params *p, struct target *fb);

/* How two pictures (0xAARRGGBB, n pixels each) agree where `covered` is
 * not 0: per pixel the largest difference of its R, G and B, in levels. */
struct bench_agree {
    int64_t pixels;             /* covered pixels compared */
    int64_t within2, within8;   /* ... differing by at most 2 (8) levels in every channel */
};
struct bench_agree bench_agreement(const uint32_t *a, const uint32_t *b, const uint8_t *covered,
                                   size_t n);

/* The limits of this machine (limits.c). A read-modify-write pass over n
 * pixels of colour and depth (8 bytes each) on `threads` cores, each
 * taking an equal part: Mpix/s, and GB/s in *gbs (0: not measured). */
double bench_memory_limit(size_t n, int threads, int runs, double *gbs);
/* The same pass over one 64 x 64 tile again and again (cache-resident). */
double bench_cache_limit(size_t n, int runs, double *gbs);
/* A count of cycles on the calling thread while it runs: the core's own if
 * the system counts them, else its processor time in time-stamp counter
 * cycles; what it counts, in words, into buf (NULL: no counter,
 * bench_cycles() stays 0). */
const char *bench_cycles_source(char *buf, size_t n);
uint64_t bench_cycles(void);

/* Mesa's llvmpipe through OSMesa, drawing the same scenes with the same
 * state. threads = 0 is LP_NUM_THREADS=0 (single-threaded), -1 llvmpipe's
 * default; samples > 1: into a multisampled framebuffer object resolved by a
 * blit (timed with the drawing). Runs in a child process because llvmpipe
 * reads its thread count once per process. On success fills out[i] (times)
 * and coverage[i] (w * h counts, from an untimed stencil pass; with samples,
 * covered samples summed over the triangles, as lesson 08 counts them) for
 * every scene, and colour[i] (w * h pixels 0xAARRGGBB, row 0 at the top,
 * from the last timed run) when colour is not NULL. A scene with image
 * textures is drawn textured (peer.c says how: trilinear, modulate, mip-maps
 * from glGenerateMipmap, the sampler's exact paths, PEER_EXACT_OPTIONS).
 * On failure returns false and says why (OSMesa missing, no
 * GL_ARB_clip_control, too few samples, ...). */
bool peer_run(const struct bench_scene *sc, int nscenes, int threads, int samples, int warmup,
              int runs, struct bench_timing *out, uint8_t *const coverage[], uint32_t *const colour[],
              char *why, size_t whylen);
/* The environment llvmpipe runs in: its sampler's faster approximations off. */
#define PEER_EXACT_OPTIONS "GALLIVM_PERF=no_quad_lod,no_aos_sampling (brilinear and rho_approx not set), LP_PERF unset"
/* "Mesa 22.3.6 llvmpipe (LLVM 15, 256 bits)" after a successful peer_run;
 * after one with samples, where they are in the scene (1/256 pixel from the
 * pixel's top-left corner, as sample_pattern() gives lesson 08's). */
extern char peer_renderer[160];
extern int peer_sample_pos[SAMPLES_MAX][2];

/* The textured scenes (textured.c): every lesson that maps image textures
 * (its descriptor's .texturing), each exact variant at its defaults
 * (trilinear), beside llvmpipe on one thread, interleaved round after
 * round; coverage against the reference and llvmpipe, colour agreement with
 * llvmpipe (struct bench_agree). `only` and `only_variant` as the bench's
 * --lesson and --variant; exhibits: the variants shown against the exact
 * rule too. False when out of memory. */
struct bench_tex_options {
    int runs;
    uint64_t seed;
    bool quick, peer, exhibits;
    const char *only, *only_variant;
};
bool bench_textured_run(const struct bench_tex_options *o);
void bench_textured_print(void);                /* the tables on stdout */
void bench_textured_markdown(FILE *f);          /* ... as BENCH.md's section */
void bench_textured_csv(FILE *f);               /* ... as rows of bench.csv (its 20 columns) */
/* Pixels of the exact rows whose coverage differs from the reference or llvmpipe. */
int64_t bench_textured_differences(void);
/* Scene i's name, and the speed of the last texture-mapping lesson's fastest
 * exact variant over llvmpipe's (1 thread each, or all: every core each; 0
 * when either is missing), its lesson ("09") and variant in *lesson, *variant. */
const char *bench_textured_scene(int i);
double bench_textured_speedup(int i, bool all, const char **lesson, const char **variant);
/* The fastest one-thread variant's cycles per covered pixel on each
 * textured scene, against the bound of its counted arithmetic; one line
 * each (md: a markdown item), cycles_what: what bench_cycles() counts. */
void bench_textured_cycles(FILE *f, bool md, const char *cycles_what);

/* The 3-D front end (front.c): a 100,000-triangle torus seen from inside
 * its tube, through look-at, clipping, projection, guard band, fan and cull. */
struct bench_front {
    int in, out;                /* world triangles in, screen triangles out */
    int depth_clipped;          /* cut by the near or the far plane */
    int culled_whole;           /* wholly behind near or beyond far */
    int guard_clipped;          /* reaching past the guard band */
    struct bench_timing t;      /* seconds for the whole mesh */
};
bool bench_front_run(struct bench_front *bf, int runs);

/* A bar of the chart: one program on one scene. */
struct chart_bar {
    const char *label;
    double value;               /* in the panel's unit */
    bool peer;                  /* llvmpipe: drawn in another colour */
};
struct chart_panel {
    const char *title, *unit;
    struct chart_bar bars[48];
    int nbars;
    double limit;               /* a dashed line (bandwidth ceiling), 0 = none */
    const char *limit_label;
};
/* Write the panels side by side as SVG and PNG. */
bool chart_write(const struct chart_panel *p, int npanels, const char *title,
                 const char *svg_path, const char *png_path, char *err, size_t errlen);

/* The large scene in the explorer, one lesson (big.c). Seconds, MiB. */
struct big_result {
    const char *program;
    bool ok;
    char why[600];
    int ntris;
    uint64_t steps;
    int checkpoints;
    double load_s, first_frame_s, first_frame_cpu_s, counted_s;
    double step_median_s, step_worst_s, end_s, back_worst_s;
    double step_worst_cpu_s;        /* the worst of them all in CPU time */
    double peak_rss_mib;
};
/* Write a scene of ntris small triangles to path, open it in the explorer
 * of every lesson (whose id starts with `only`, if given), each in a child
 * process, and remove the file. Fills out[0..*n). */
bool bench_big_scene(const char *path, long ntris, const char *only, struct big_result *out,
                     int max, int *n);

#endif
