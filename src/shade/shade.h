/* shade.h - the colour of a covered pixel, shared by every lesson, and the
 * named costs of interpolating it.
 *
 * Not a lesson's idea: every lesson shades a pixel the same way (the
 * Gouraud colour, darkened on the dark squares of the scene's "texture
 * checker N"), so that their pictures can be compared byte for byte. Each
 * function counts what it costs into the trace (COUNT, trace/trace.h), so
 * the operation counters include the shading of every covered pixel.
 */
#ifndef TRISTEP_SHADE_H
#define TRISTEP_SHADE_H

#include <math.h>

#include "lesson.h"

#define CHECKER_DARK 0.35   /* brightness of the checkerboard's dark squares */

/* Named costs of interpolation, for COUNT:
 *   INTERPOLATE_COST   one attribute from three weights: u a_A + v a_B + w a_C
 *   PLANE_STEP_COST    one linear value (an attribute, 1/z, a/z) one pixel on
 *   RECIPROCAL_COST    z = 1 / (1/z), a division counted as one multiplication
 *   CHECKER_COST       which square: floor(s N) + floor(t N)
 *   CHECKER_SCALED_COST  the same with s, t already times N: floor(s) + floor(t)
 *   CHECKER_DARK_COST  r, g, b times CHECKER_DARK, on a dark square only
 *   PACK_SCALED_COST   channels already in 0..255: + 0.5 each, no product */
#define INTERPOLATE_COST { .mul = 3, .add = 2 }
#define PLANE_STEP_COST { .mul = 0, .add = 1 }
#define RECIPROCAL_COST { .mul = 1, .add = 0 }
#define CHECKER_COST { .mul = 2, .add = 1 }
#define CHECKER_SCALED_COST { .mul = 0, .add = 1 }
#define CHECKER_DARK_COST { .mul = 3, .add = 0 }
#define PACK_SCALED_COST { .mul = 0, .add = 3 }

/* Whether square (floor s, floor t) of the checker is a dark one: the parity
 * of the sum, with NaN and out-of-range sums kept out of the integer cast. */
static inline bool checker_dark(double s, double t)
{
    double k = floor(s) + floor(t);
    return fabs(k) < 0x1p62 && ((long long)k & 1);
}

/* Colour of a covered pixel from interpolated values: r, g, b in [0, 1], and
 * texture coordinates s, t in [0, 1] when the scene has a checker. */
static inline uint32_t shade_pixel(const struct raster_params *p, struct trace *tr, double r,
                                   double g, double b, double s, double t)
{
    if (p->checker > 0) {
        COUNT(tr, 1, CHECKER_COST);
        if (checker_dark(s * p->checker, t * p->checker)) {
            COUNT(tr, 1, CHECKER_DARK_COST);
            r *= CHECKER_DARK;
            g *= CHECKER_DARK;
            b *= CHECKER_DARK;
        }
    }
    COUNT(tr, 1, PACK_RGB_COST);
    return pack_rgb(r, g, b);
}

/* Pre-scaled attributes: a lesson that steps its attributes pixel by pixel
 * multiplies the vertices' values once per triangle, so the pixel loop has
 * no multiplication left (lesson 03). */
#define SHADE_SCALE_RGB 255.0                                   /* r, g, b */
static inline double shade_scale_st(const struct raster_params *p)   /* s, t */
{
    return p->checker > 0 ? p->checker : 1;
}

/* The same as shade_pixel() from pre-scaled values: r, g, b in [0, 255],
 * s and t already multiplied by the checker's N. */
static inline uint32_t shade_scaled(const struct raster_params *p, struct trace *tr, double r,
                                    double g, double b, double s, double t)
{
    if (p->checker > 0) {
        COUNT(tr, 1, CHECKER_SCALED_COST);
        if (checker_dark(s, t)) {
            COUNT(tr, 1, CHECKER_DARK_COST);
            r *= CHECKER_DARK;
            g *= CHECKER_DARK;
            b *= CHECKER_DARK;
        }
    }
    COUNT(tr, 1, PACK_SCALED_COST);
    double c[3] = { r, g, b };
    uint32_t out = 0xff000000u;
    for (int i = 0; i < 3; i++) {
        double v = c[i] > 0 ? (c[i] < 255 ? c[i] : 255) : 0;   /* a NaN becomes 0 */
        out |= (uint32_t)(v + 0.5) << (16 - 8 * i);
    }
    return out;
}

#endif
