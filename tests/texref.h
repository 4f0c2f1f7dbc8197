/* texref.h - an independent reference for textured pixels, written from
 * lessons/CONVENTIONS.md ("Textures") alone: it shares no code with src/ (its own
 * pyramid, wrap, coverage, interpolation, derivatives, level of detail and
 * five filters), so that lesson 09's pictures can be checked against it,
 * within 2 levels per channel, as the conventions say.
 *
 * Everything is computed in double precision, straight from the rules:
 *   - coverage: vertices snapped to 1/256 (lrint), integer edge functions,
 *     the top-left rule;
 *   - (s, t), colour and 1/z at every pixel centre of every 2 x 2 quad that
 *     has a covered pixel (helper pixels included), perspective-correct,
 *     with barycentric weights of the snapped vertices;
 *   - coarse derivatives at the quad's top-left pixel, in level-0 texels;
 *     a quad with a helper beyond the horizon (1/z <= 0) uses the last level;
 *   - the filtered texel times the vertex colour, rounded once to 8 bits.
 * Only the data of src/ is used: struct vertex and a scene's triangles, and
 * the level-0 texels of its textures (never its pyramid). */
#ifndef TRISTEP_TEXREF_H
#define TRISTEP_TEXREF_H

#include <stdbool.h>
#include <stdint.h>

#include "scene/scene.h"

enum texref_filter { TEXREF_NEAREST, TEXREF_BILINEAR, TEXREF_MIP_BILINEAR, TEXREF_TRILINEAR,
                     TEXREF_ANISO, TEXREF_FILTERS };
enum texref_wrap { TEXREF_REPEAT, TEXREF_CLAMP };

const char *texref_filter_name(enum texref_filter f);   /* "mip-bilinear", as --filter takes it */

#define TEXREF_LEVELS 16

struct texref {
    enum texref_wrap wrap;
    int nlevels;
    int w[TEXREF_LEVELS], h[TEXREF_LEVELS];
    uint8_t *rgb[TEXREF_LEVELS];       /* 3 bytes per texel, row-major, row 0 at the top */
};

/* The pyramid of a w x h image (powers of two; texels 0x..RRGGBB, the top
 * byte ignored), built here. False when out of memory or a size is wrong. */
bool texref_init(struct texref *r, int w, int h, const uint32_t *image, enum texref_wrap wrap);
void texref_free(struct texref *r);
/* Texel (i, j) of level k, wrapped (repeat: mathematical mod; clamp). */
void texref_texel(const struct texref *r, int k, long long i, long long j, double out[3]);

/* The derivatives of a pixel's quad, in level-0 texels. */
struct texref_deriv {
    double dudx, dvdx, dudy, dvdy;
    bool beyond_horizon;               /* a helper pixel with 1/z <= 0: the last level */
};

/* rho and lambda = log2(rho) of the derivatives (lambda may be -inf). */
double texref_rho(const struct texref_deriv *d);
double texref_lambda(const struct texref_deriv *d);

/* The filtered texel at (s, t), each channel in 0..255 (not rounded):
 * nearest, bilinear, mip-bilinear, trilinear, aniso with max_aniso 1..16. */
void texref_sample(const struct texref *r, enum texref_filter f, int max_aniso, double s, double t,
                   const struct texref_deriv *d, double out[3]);

/* One level's bilinear tap and the trilinear mix at lambda (clamped to
 * [0, last level]), in 0..255: the pieces texref_sample is made of. */
void texref_bilinear(const struct texref *r, int k, double s, double t, double out[3]);
void texref_trilinear(const struct texref *r, double lambda, double s, double t, double out[3]);

/* A colour buffer with depth, the pixels a triangle covered marked. */
struct texref_target {
    int w, h;
    uint32_t *color;                   /* 0xAARRGGBB, starting at the background */
    double *z;                         /* +infinity at the start; smaller z wins */
    uint8_t *covered;                  /* how many triangles covered the pixel */
    long helpers;                      /* helper pixels evaluated (in covered quads, not covered) */
    long shaded;                       /* covered pixels shaded */
    /* optional (NULL: not kept), for each textured pixel written: lambda =
     * log2(rho) of its quad (INFINITY beyond the horizon), and P_max / P_min
     * (the footprint's elongation, INFINITY when P_min = 0); malloc'ed by
     * the caller (w x h floats), freed with the target */
    float *lambda, *elongation;
};

bool texref_target_init(struct texref_target *fb, int w, int h, uint32_t background);
void texref_target_free(struct texref_target *fb);

/* One screen triangle: covered pixels that pass the depth test get the
 * modulated colour; tex NULL draws the vertex colour alone. */
void texref_draw_tri(struct texref_target *fb, const struct vertex v[3], const struct texref *tex,
                     enum texref_filter f, int max_aniso);
/* A whole 2-D scene (or a 3-D one after the front end), triangle after
 * triangle, each under its image texture (scene_texture), with the wrap the
 * scene gives it. The checker is not drawn (untextured: vertex colour).
 * False when out of memory. */
bool texref_draw_scene(struct texref_target *fb, const struct scene *s, enum texref_filter f,
                       int max_aniso);

/* The ideal picture: each pixel's colour the mean of the texture over the
 * pixel's square, the box filter every filter approximates, by brute
 * force: n x n samples (1..256), each with its own perspective-correct
 * (s, t) and the level-0 texel under it (those beyond the plane's horizon
 * left out), times the vertex colour at the centre. Coverage and depth as
 * above. Lesson 09's exhibits measure its filters against it. */
struct texref_ideal {
    int w, h;
    double *rgb;                       /* 3 per pixel, 0..255, not rounded */
    bool *textured;                    /* the pixel shows an image texture */
};
bool texref_ideal_scene(struct texref_ideal *id, const struct scene *s, int n);
void texref_ideal_free(struct texref_ideal *id);

/* How a lesson's picture compares with the reference's: the pixels whose
 * coverage count differs, and the covered pixels whose colour differs by
 * more than `levels` in a channel (the first of them in *x, *y, -1 when
 * none). lessons/CONVENTIONS.md allows 2 levels. */
struct texref_diff {
    long coverage, colour;
    int x, y;
};
struct texref_diff texref_compare(const struct texref_target *ref, const struct target *fb, int levels);

#endif
