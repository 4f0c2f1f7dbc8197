/* Exercise 08: write lesson 08's per-sample coverage (MSAA).
 *
 * The pixel loop of the README is here: the sample pattern
 * as offsets from the pixel centre, the box of pixels a sample of which may
 * be covered, the shading (one colour per pixel, at its centre, depth per
 * sample), the depth test of each sample and the resolve. Yours: each
 * sample's edge values as the pixel's plus a constant offset, the top-left
 * rule at every sample, the coverage mask, and writing the covered samples.
 * As given, the file compiles and runs, every mask is 0, and nothing is
 * drawn.
 *
 *     make exercise LESSON=08 SAMPLES=4   the explorer on this file, at 4
 *                                         samples per pixel
 *     make check LESSON=08                the checks, each scene at 4 and
 *                                         8 samples, then at 1 (a random
 *                                         one at one of them): every
 *                                         sample as the exact rule decides
 *                                         it, every pixel inside a mesh
 *                                         holding exactly N
 */
#include <string.h>

#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 08's pseudo-code, which the explorer lights. */
enum { L_SETUP, L_BOX, L_LOOP, L_EMPTY, L_FULL, L_PARTIAL, L_MASK, L_WRITE };

/* The pattern of n samples, as offsets from the pixel CENTRE in 1/256
 * pixel (sample_pattern gives them from the pixel's corner). */
struct pattern {
    int n;
    int dx[SAMPLES_MAX], dy[SAMPLES_MAX];
};

/* The edges: F0k + bias_k at the centre of pixel (x, y) is
 * f0[k] + dx[k] * x + dy[k] * y, and off[s][k] is sample s's offset. */
struct edges {
    int64_t f0[3], dx[3], dy[3];
    int64_t off[SAMPLES_MAX][3];
};

static int64_t edge_at(const struct edges *e, int k, int x, int y)
{
    return e->f0[k] + e->dx[k] * x + e->dy[k] * y;
}

/* TODO 1 and 2, README section 2, "A sample is a pixel centre somewhere else": the
 * offsets O_sk = I0k dx_s + J0k dy_s, the same in every pixel, once per
 * triangle; and the top-left rule at every sample: the bias folded into
 * f0 as lesson 05 does, so a sample on a shared edge belongs to one side. */
static void edges_setup(struct edges *e, const struct tri_setup *t, const struct pattern *pt)
{
    for (int k = 0; k < 3; k++) {
        e->dx[k] = t->I[k] * SUBPIXEL_ONE;
        e->dy[k] = t->J[k] * SUBPIXEL_ONE;
        /* TODO 1: fold the fill rule's bias t->bias[k] into f0 */
        e->f0[k] = t->I[k] * SUBPIXEL_HALF + t->J[k] * SUBPIXEL_HALF + t->K[k];
        /* TODO 2: sample s's offset on edge k, from pt->dx[s] and pt->dy[s] */
        for (int s = 0; s < pt->n; s++)
            e->off[s][k] = 0;
    }
}

/* TODO 3, README section 2, the coverage mask: bit s set when F0k + bias_k + O_sk >= 0 for
 * all three edges. */
static unsigned coverage_mask(const struct edges *e, const struct pattern *pt, const int64_t c[3])
{
    /* TODO 3: one bit per sample, from the centre's values c[] plus e->off[s] */
    (void)e, (void)pt, (void)c;
    return 0;
}

/* --- shading, the samples and the resolve, as the lesson has them --------------- */

/* Perspective-correct 1/z at a point whose edge values (bias removed) are
 * F[3]: the weights of A, B, C are F02, F03, F01 over Area2 (lesson 04). */
static double inv_z(const struct tri_setup *t, const int64_t F[3], double w[3])
{
    double sum = 0;
    for (int i = 0; i < 3; i++) {
        w[i] = (double)F[(i + 1) % 3] / (double)t->area2;
        sum += w[i] / t->v[i].z;
    }
    return sum;
}

/* The pixel's one colour, at its centre (MSAA shades once per pixel). */
static uint32_t centre_colour(const struct tri_setup *t, const struct raster_params *p,
                              struct trace *tr, const int64_t F[3])
{
    double w[3], z = 1.0 / inv_z(t, F, w), P[5] = { 0 };
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double a[5] = { v->r, v->g, v->b, v->s, v->t };
        for (int k = 0; k < 5; k++)
            P[k] += w[i] / v->z * a[k] * z;
    }
    return shade_pixel(p, tr, P[0], P[1], P[2], P[3], P[4]);
}

/* The samples of pixel i: n colours and depths (the pixel itself at n = 1). */
static uint32_t *sample_colour(struct target *fb, size_t i, int n)
{
    return n > 1 ? &fb->samples->color[i * (size_t)n] : &fb->color[i];
}

static float *sample_depth(struct target *fb, size_t i, int n)
{
    return n > 1 ? &fb->samples->depth[i * (size_t)n] : &fb->depth[i];
}

/* README section 5, "Resolve": the pixel after its samples changed, the rounded mean of its samples'
 * colours, the nearest sample's depth. */
static void resolve(struct target *fb, size_t i, int n)
{
    if (n == 1)
        return;
    const uint32_t *c = sample_colour(fb, i, n);
    const float *z = sample_depth(fb, i, n);
    unsigned sum[3] = { 0, 0, 0 };
    float nearest = z[0];
    for (int s = 0; s < n; s++) {
        for (int ch = 0; ch < 3; ch++)
            sum[ch] += c[s] >> (16 - 8 * ch) & 0xff;
        nearest = z[s] < nearest ? z[s] : nearest;
    }
    fb->color[i] = 0xff000000u;
    for (int ch = 0; ch < 3; ch++)
        fb->color[i] |= (sum[ch] + (unsigned)n / 2) / (unsigned)n << (16 - 8 * ch);
    fb->depth[i] = nearest;
}

/* TODO 4, README section 4, "Depth per sample, colour once": each sample of the mask gets its
 * own depth (1/z at the sample) and, if nearer than what it holds, the
 * pixel's colour; the pixel counts its covered samples. */
static void write_samples(const struct tri_setup *t, const struct edges *e, const struct pattern *pt,
                          struct target *fb, int x, int y, unsigned mask, uint32_t colour)
{
    size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
    uint32_t *c = sample_colour(fb, i, pt->n);
    float *z = sample_depth(fb, i, pt->n);
    /* TODO 4: for each sample s of the mask, its edge values
     *     F[k] = edge_at(e, k, x, y) - t->bias[k] + e->off[s][k],
     * its depth 1.0 / inv_z(t, F, w) as a float, and, when nearer than
     * z[s], z[s] and c[s] = colour; then fb->count[i] plus the number of
     * covered samples (saturating at 255; fb->count may be NULL). */
    (void)t, (void)e, (void)x, (void)y, (void)mask, (void)colour, (void)c, (void)z, (void)i;
}

/* --- the pixel loop --------------------------------------------------------------- */

/* A pixel's samples as they were before a write: the step narrates what the
 * write changed, and a step past the one the explorer shows (a frozen
 * trace) puts them back. */
struct pixel_keep {
    uint32_t c[SAMPLES_MAX], colour;
    float z[SAMPLES_MAX], depth;
    uint8_t count;
};

static struct pixel_keep keep_pixel(struct target *fb, size_t i, int n)
{
    struct pixel_keep k = { .colour = fb->color[i], .depth = fb->depth[i],
                            .count = fb->count ? fb->count[i] : 0 };
    memcpy(k.c, sample_colour(fb, i, n), (size_t)n * sizeof k.c[0]);
    memcpy(k.z, sample_depth(fb, i, n), (size_t)n * sizeof k.z[0]);
    return k;
}

static bool any_sample_passed(const struct pixel_keep *k, struct target *fb, size_t i, int n)
{
    return memcmp(k->z, sample_depth(fb, i, n), (size_t)n * sizeof k->z[0]) != 0;
}

static void put_back(const struct pixel_keep *k, struct target *fb, size_t i, int n)
{
    memcpy(sample_colour(fb, i, n), k->c, (size_t)n * sizeof k->c[0]);
    memcpy(sample_depth(fb, i, n), k->z, (size_t)n * sizeof k->z[0]);
    fb->color[i] = k->colour;
    fb->depth[i] = k->depth;
    if (fb->count)
        fb->count[i] = k->count;
}

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    int n = p->samples > 1 ? p->samples : 1;
    const struct sample_pattern *sp = sample_pattern(n);
    if (!sp || (n > 1 && (!fb->samples || fb->samples->n != n) && !target_multisample(fb, n)))
        sp = sample_pattern(n = 1);
    if (n == 1)
        target_multisample(fb, 1);
    struct pattern pt = { .n = n };
    for (int s = 0; s < n; s++) {
        pt.dx[s] = sp->x[s] - SUBPIXEL_HALF;
        pt.dy[s] = sp->y[s] - SUBPIXEL_HALF;
    }
    /* a sample reaches up to half a pixel from its centre: the box of
     * centres and one pixel more each side, clipped to the target */
    int x0 = t->minx > 0 ? t->minx - 1 : 0, y0 = t->miny > 0 ? t->miny - 1 : 0;
    int x1 = t->maxx + 1 < fb->w ? t->maxx + 1 : fb->w - 1;
    int y1 = t->maxy + 1 < fb->h ? t->maxy + 1 : fb->h - 1;
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_BOX, .x = x0, .y = y0, .x1 = x1, .y1 = y1,
            .e = { t->area2, 0, 0 }, .aux = { (float)n, 0, 0, 0 });
    if (t->area2 <= 0)
        return;
    struct edges e;
    edges_setup(&e, t, &pt);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            int64_t c[3] = { edge_at(&e, 0, x, y), edge_at(&e, 1, x, y), edge_at(&e, 2, x, y) };
            unsigned mask = coverage_mask(&e, &pt, c);
            int64_t F[3] = { c[0] - t->bias[0], c[1] - t->bias[1], c[2] - t->bias[2] };
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = L_MASK, .x = x, .y = y, .e = { F[0], F[1], F[2] },
                    .flags = mask ? TRACE_INSIDE : 0, .mask = { (uint16_t)mask },
                    .aux = { (float)n, (float)__builtin_popcount(mask), (float)mask, 0 });
            if (!mask)
                continue;
            uint32_t colour = centre_colour(t, p, tr, F);
            size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
            struct pixel_keep keep = keep_pixel(fb, i, n);
            write_samples(t, &e, &pt, fb, x, y, mask, colour);
            resolve(fb, i, n);
            /* the step says what the write did: the nearest sample's depth,
             * and whether any sample passed its depth test */
            NARRATE(tr, .kind = TRACE_PIXEL_WRITE, .line = L_WRITE, .x = x, .y = y, .rgba = colour,
                    .z = fb->depth[i], .flags = any_sample_passed(&keep, fb, i, n) ? TRACE_DEPTH_PASS : 0,
                    .mask = { (uint16_t)mask },
                    .aux = { (float)n, (float)__builtin_popcount(mask), (float)mask, 0 });
            if (trace_frozen(tr))
                put_back(&keep, fb, i, n);     /* a step past the one shown */
        }
}
