/* Lesson 08, what the explorer adds (compiled only in the narrated build;
 * the algorithm is multisampling.c).
 *
 * Views: "samples" (the share of each pixel's samples the triangle covers,
 * from the narrated mask), "area" (the exact share of the pixel it covers,
 * computed analytically) and "area-error" (the one minus the other).
 * Overlay, zoomed in: every sample of the triangle's box drawn at its true
 * position, lit where the triangle covers it, and the samples of the pixel
 * just tested numbered, with its mask. Watch: the mask and each sample's
 * three edge values (the pixel centre's plus the sample's constant offset).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lesson_explorer.h"

extern const struct lesson lesson_08;

/* What the lesson narrates in trace_event.aux[] (multisampling.c). */
enum { AUX_SAMPLES, AUX_COVERED, AUX_MASK, AUX_GRID };

/* The pattern an event was decided with (the standard one unless the grid exhibit). */
static const struct sample_pattern *pattern_of(const struct raster_params *p, const struct trace_event *ev)
{
    int n = p->samples > 1 ? p->samples : 1;
    if (ev && ev->aux[AUX_SAMPLES] >= 1)
        n = (int)ev->aux[AUX_SAMPLES];
    const struct sample_pattern *sp = ev && ev->aux[AUX_GRID] > 0 ? sample_grid(n) : sample_pattern(n);
    return sp ? sp : sample_pattern(1);
}

/* The share of the pixel's samples covered: from the narrated count, or 1 for
 * a pixel of a full block (covered without a test of its own). */
static double estimate(const struct trace_event *test)
{
    if (test->aux[AUX_SAMPLES] < 1)
        return test->flags & TRACE_INSIDE ? 1 : 0;
    return test->aux[AUX_COVERED] / test->aux[AUX_SAMPLES];
}

/* "samples": grey, the share of the samples covered (white: all of them). */
static bool samples_cell(const struct tri_setup *t, const struct trace_event *test,
                         const struct trace_event *write, double rgb[3])
{
    (void)t, (void)write;
    if (!test)
        return false;
    rgb[0] = rgb[1] = rgb[2] = 0.1 + 0.9 * estimate(test);
    return true;
}

/* "area": grey, the exact share of the pixel inside the triangle. */
static bool area_cell(const struct tri_setup *t, const struct trace_event *test,
                      const struct trace_event *write, double rgb[3])
{
    (void)write;
    if (!test)
        return false;
    rgb[0] = rgb[1] = rgb[2] = 0.1 + 0.9 * reference_pixel_area(t, test->x, test->y);
    return true;
}

/* "area-error": samples' estimate minus the exact area, red where the samples
 * say more, blue where they say less; full colour at a quarter pixel. */
static bool area_error_cell(const struct tri_setup *t, const struct trace_event *test,
                            const struct trace_event *write, double rgb[3])
{
    (void)write;
    if (!test)
        return false;
    double e = estimate(test) - reference_pixel_area(t, test->x, test->y);
    double k = fmin(fabs(e) * 4, 1);
    rgb[0] = e > 0 ? 0.1 + 0.9 * k : 0.1;
    rgb[1] = 0.1;
    rgb[2] = e < 0 ? 0.1 + 0.9 * k : 0.1;
    return true;
}

/* The samples of the box, each a small disc at its true position: filled
 * where the triangle covers it (by the exact rule: the reference), a ring
 * where not. Only when a pixel is at least 16 screen pixels wide, and the
 * box small enough to draw sample by sample. */
static void draw_samples(const struct lesson_canvas *c, const struct tri_setup *t,
                         const struct sample_pattern *sp, const int box[4])
{
    for (int y = box[1]; y <= box[3]; y++)
        for (int x = box[0]; x <= box[2]; x++)
            for (int s = 0; s < sp->n; s++) {
                int64_t sx = (int64_t)x * SUBPIXEL_ONE + sp->x[s], sy = (int64_t)y * SUBPIXEL_ONE + sp->y[s];
                bool in = reference_point_covered(t, sx, sy);
                double r = 2.5;
                c->disc(c, sx / (double)SUBPIXEL_ONE, sy / (double)SUBPIXEL_ONE, r,
                        in ? (struct pen){ .fill = INK_MARK, .stroke = INK_OUTLINE, .width = 0.75 }
                           : (struct pen){ .stroke = INK_MARK, .width = 0.75, .alpha = 0.55 });
            }
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    if (t->area2 <= 0 || c->unit > 1.0 / 16)
        return;
    const struct sample_pattern *sp = pattern_of(p, last);
    /* the box of every pixel one of whose samples may be covered (a pixel more than the centres') */
    int box[4] = { t->minx - 1, t->miny - 1, t->maxx + 1, t->maxy + 1 };
    int w = t->target_w, h = t->target_h;
    box[0] = box[0] < 0 ? 0 : box[0], box[1] = box[1] < 0 ? 0 : box[1];
    box[2] = box[2] >= w ? w - 1 : box[2], box[3] = box[3] >= h ? h - 1 : box[3];
    if ((int64_t)(box[2] - box[0] + 1) * (box[3] - box[1] + 1) <= 4096)
        draw_samples(c, t, sp, box);
    if (!last || (last->kind != TRACE_PIXEL_TEST && last->kind != TRACE_PIXEL_WRITE))
        return;
    /* the pixel just tested: its samples ringed and numbered, each number
     * level with its ring, on the side away from the pixel's centre (the
     * samples of a pattern lie at different heights, so no number sits
     * beside another sample's ring) */
    unsigned mask = (unsigned)last->aux[AUX_MASK];
    const double ring = 4.5, size = 9;      /* screen pixels */
    for (int s = 0; s < sp->n; s++) {
        double x = last->x + sp->x[s] / (double)SUBPIXEL_ONE, y = last->y + sp->y[s] / (double)SUBPIXEL_ONE;
        c->disc(c, x, y, ring, (mask >> s & 1) ? (struct pen){ .fill = INK_PROBE, .stroke = INK_OUTLINE }
                                               : (struct pen){ .stroke = INK_PROBE, .width = 1.5 });
        char label[4];
        snprintf(label, sizeof label, "%d", s);
        double w = 0.61 * size * (double)strlen(label);     /* DejaVu Sans Mono's advance */
        double lx = sp->x[s] >= SUBPIXEL_HALF ? x + (ring + 3) * c->unit : x - (ring + 3 + w) * c->unit;
        c->label(c, lx, y - 0.65 * size * c->unit, label, size, INK_PROBE);
    }
}

/* The watch: the mask, then each sample's edge values F_k + O_sk. */
static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    buf[0] = '\0';
    if (ev->kind != TRACE_PIXEL_TEST && ev->kind != TRACE_PIXEL_WRITE)
        return;
    const struct sample_pattern *sp = pattern_of(p, ev);
    unsigned mask = (unsigned)ev->aux[AUX_MASK];
    char bits[SAMPLES_MAX + 1];
    for (int s = 0; s < sp->n; s++)
        bits[s] = (mask >> s & 1) ? '1' : '0';   /* sample 0 first */
    bits[sp->n] = '\0';
    size_t at = (size_t)snprintf(buf, n, "mask = %s (sample 0 first): %d of %d covered%s\n", bits,
                                 (int)ev->aux[AUX_COVERED], sp->n, ev->aux[AUX_GRID] > 0 ? ", grid" : "");
    if (ev->kind != TRACE_PIXEL_TEST)
        return;
    for (int s = 0; s < sp->n && at < n; s++) {
        int dx = sp->x[s] - SUBPIXEL_HALF, dy = sp->y[s] - SUBPIXEL_HALF;
        double f[3];
        for (int k = 0; k < 3; k++)
            f[k] = (double)(ev->e[k] + t->I[k] * dx + t->J[k] * dy) / (SUBPIXEL_ONE * SUBPIXEL_ONE);
        at += (size_t)snprintf(buf + at, n - at, "s%d (%3d,%3d): %7.3f %7.3f %7.3f %s\n", s, sp->x[s],
                               sp->y[s], f[0], f[1], f[2], (mask >> s & 1) ? "in" : "out");
    }
}

/* The triangle's constants: each sample's offsets O_sk = I_k dx_s + J_k dy_s. */
static void constants(const struct tri_setup *t, const struct raster_params *p, char *buf, size_t n)
{
    const struct sample_pattern *sp = pattern_of(p, NULL);
    size_t at = (size_t)snprintf(buf, n, "offsets O_sk = I dx_s + J dy_s (px^2):\n");
    for (int s = 0; s < sp->n && at < n; s++) {
        int dx = sp->x[s] - SUBPIXEL_HALF, dy = sp->y[s] - SUBPIXEL_HALF;
        at += (size_t)snprintf(buf + at, n - at, "O_%d = %.3f, %.3f, %.3f\n", s,
                               (double)(t->I[0] * dx + t->J[0] * dy) / (SUBPIXEL_ONE * SUBPIXEL_ONE),
                               (double)(t->I[1] * dx + t->J[1] * dy) / (SUBPIXEL_ONE * SUBPIXEL_ONE),
                               (double)(t->I[2] * dx + t->J[2] * dy) / (SUBPIXEL_ONE * SUBPIXEL_ONE));
    }
}

static const struct lesson_view views[] = {
    { "samples", "share of the pixel's samples the triangle covers: dark none, white all",
      samples_cell },
    { "area", "exact share of the pixel the triangle covers (analytic): dark none, white all",
      area_cell },
    { "area-error", "samples' estimate - exact area: red more, blue less; full at 1/4 pixel",
      area_error_cell },
};

/* The pixel test covers a pixel when ANY of its samples is inside; the edge
 * values the panel prints after the verdict are the centre's (the samples'
 * follow in the watch, from the mask line on). */
static const char *const verdict[] = { "no sample inside; at the centre:",
                                       "a sample inside; at the centre:" };

const struct lesson_explorer lesson_08_explorer = {
    .lesson = &lesson_08,
    .views = views,
    .nviews = sizeof views / sizeof views[0],
    .overlay = overlay,
    .constants = constants,
    .watch = watch,
    .verdict = verdict,
};
