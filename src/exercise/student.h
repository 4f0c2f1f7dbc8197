/* student.h - what the exercise build puts in front of a student's file
 * (compiled with `-include exercise/student.h`; the file itself includes
 * only "lesson.h", as every lesson does).
 *
 * It changes nothing a student writes, only where some of it goes:
 *
 *   - every pixel written, by target_write, PLOT or FILL, goes through the
 *     exercise's checked write: a pixel outside the target is reported (not
 *     written, never a crash), and a bare target_write becomes a step of
 *     its own in the explorer, so code that narrates nothing still shows
 *     every pixel it writes;
 *   - edge_value() and pixel_centre(), the direct evaluations of raster.h,
 *     count their multiplications in the counters (lesson 03's check: no
 *     multiplication between two pixels of a row);
 *   - a texel read through exercise_texel() outside its level is reported,
 *     not read (lesson 09).
 *
 * The macros are defined after lesson.h, so raster.h's own inline functions
 * keep the real ones. */
#ifndef TRISTEP_EXERCISE_STUDENT_H
#define TRISTEP_EXERCISE_STUDENT_H

#include "lesson.h"

/* The whole rasterizer a FILE defines (lessons/CONVENTIONS.md, "Exercises"). */
void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr);

/* Lesson 06's exercise: the clipper against one plane (front/front.h),
 * which the front end runs for near, then far. A FILE that does not define
 * it gets the lesson's own (src/exercise/clip_default.c, linked only then). */
struct poly;
struct plane;
void exercise_clip(struct poly *out, const struct poly *in, const struct plane *pl);

/* Lesson 09's exercise: texel (i, j) of level k of tex, read as it is
 * (no wrap: that is the student's): one outside the level, or a level the
 * texture does not have, is reported by make check and read as opaque
 * black, never out of bounds. */
uint32_t exercise_texel(const struct texture *tex, int k, int64_t i, int64_t j);

void exercise_write(struct target *fb, int x, int y, float z, uint32_t rgba);
void exercise_plot(struct target *fb, struct trace *tr, int line, int x, int y, float z,
                   uint32_t rgba);
void exercise_fill(struct target *fb, struct trace *tr, int x, int y, float z, uint32_t rgba);
int64_t exercise_edge_value(const struct tri_setup *t, int k, int px, int py);
int64_t exercise_pixel_centre(int p);

#undef PLOT
#undef FILL
#define target_write(fb, x, y, z, rgba) exercise_write((fb), (x), (y), (z), (rgba))
#define PLOT(fb, tr, line, x, y, z, rgba) exercise_plot((fb), (tr), (line), (x), (y), (z), (rgba))
#define FILL(fb, tr, x, y, z, rgba) exercise_fill((fb), (tr), (x), (y), (z), (rgba))
#define edge_value(t, k, px, py) exercise_edge_value((t), (k), (px), (py))
#define pixel_centre(p) exercise_pixel_centre(p)

#endif
