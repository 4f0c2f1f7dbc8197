/* Lesson 08: anti-aliasing with coverage samples (MSAA), exact per sample.
 *
 * What it shows: one sample per pixel is exactly what makes edges jagged. A
 * pixel is either in or out, however little of it the triangle covers. So
 * decide coverage at N points of the pixel instead of one (the standard
 * positions of Direct3D and Vulkan, src/raster/raster.h: sample_pattern),
 * keep a coverage MASK of N bits per pixel, a depth per sample, and resolve
 * the pixel to the mean of its samples' colours.
 *
 *     pixel (px, py), N = 4          F0k at a sample = F0k at the centre
 *     +-------------------+                          + I0k dx_s + J0k dy_s
 *     |      o            |
 *     |               o   |          dx_s, dy_s: the sample's offset from
 *     |   o     +         |          the centre, the same in every pixel,
 *     |            o      |          so I0k dx_s + J0k dy_s is a constant:
 *     +-------------------+          ONE addition per sample and edge
 *
 * Each sample is decided exactly like a pixel centre in lessons 02 to 05:
 * integer edge values, the top-left bias. So everything that made those
 * lessons exact holds per sample: in a mesh of triangles sharing edges every
 * sample is covered exactly once, and a pixel inside the mesh holds exactly
 * N samples.
 *
 * Builds on lesson 05 (block classification): the blocks are classified by
 * the corners of their SAMPLES' extent, not of their pixel centres, since a
 * pixel's samples reach out to 1/16 pixel from its border. The twin `tiles`
 * (tiled.c) runs this very code on lesson 07's tiles, bins and threads.
 *
 * Two ways of shading what the mask covers:
 *   MSAA (multisampling, Akeley's RealityEngine): ONE colour per pixel,
 *        evaluated at the centre, written to every covered sample; depth
 *        per sample, so intersecting triangles are still resolved per sample;
 *   SSAA (supersampling): a colour per covered sample, N times the shading.
 * Both count what they cost (COUNT, named costs), so the explorer's
 * counters and make bench show the difference. Two ways of resolving: the
 * mean of the pixel's own samples (a box filter), or (variant tent) a tent
 * that also weighs its neighbours' nearer samples: smoother, softer.
 *
 * This file reads: the sample patterns, the edges at the samples, the box,
 * shading and resolving one pixel, the tent, the blocks, the variants.
 */
#include <stdlib.h>           /* abs */

#include "multisampling.h"

/* Lines 6-8 (as the explorer numbers them) are the whole algorithm, as the
 * exercise's skeleton writes it; lines 3-5, in [ ], lesson 05's shortcut that
 * this file takes: whole blocks skipped or filled, no pixel of them tested. */
static const char *const pseudocode[] = {
    "setup: F0k at pixel centres, O_sk = I0k dx_s + J0k dy_s per sample s",   /* 0 */
    "box = pixels with a sample that may be covered, clipped to the screen",  /* 1 */
    "[blocks: the box in q x q blocks, corners of their SAMPLE extent]",      /* 2 */
    "[  outside one edge at all four corners: skip the block  (empty)]",      /* 3 */
    "[  inside every edge at all four: every sample covered   (full)]",       /* 4 */
    "for each pixel of the box [of a partial block]:",                        /* 5 */
    "  mask = { s : F0k + O_sk >= 0 for k = 1, 2, 3 }",                       /* 6 */
    "  if mask: shade (once, or per sample), depth test each sample, resolve",  /* 7 */
    NULL,
};

enum { L_SETUP, L_BOX, L_LOOP, L_EMPTY, L_FULL, L_PARTIAL, L_MASK, L_WRITE };
_Static_assert(L_LOOP == MS_LINE_BLOCKS, "the tiled twin's steps show at the blocks' line");
_Static_assert(L_MASK == MS_LINE_MASK && L_WRITE == MS_LINE_WRITE, "the twin's pixels tell these lines");

/* trace_event.aux[]: samples per pixel, how many the test found covered, the
 * mask (bit s = sample s; also mask[0]), 1 on the exhibit's regular grid;
 * unnamed: the explorer's watch shows them in one notation, its own. */


/* Named costs of this lesson (trace/trace.h):
 *   SAMPLE_EDGE_COST   a sample's edge value: the pixel's plus its offset
 *   EXTENT_CORNERS_COST  one edge at the four corners of a block's sample
 *                      extent: F at the top-left corner (2 mul, 2 add), its
 *                      offset, then the other three corners from it
 *   PLANE_AT_COST      a plane (1/z, a/z) at a pixel: P0 + Px dx + Py dy
 *   ATTRIBUTE_COST     one attribute a = (a/z) * z
 *   RESOLVE_COST       one sample's r, g, b added to the pixel's sums (the
 *                      division by N = 4 or 8 is a shift)
 *   TENT_TAP_COST      one sample in the tent resolve: r, g, b times its
 *                      weight, added to the sums, and the weight to theirs */
#define SAMPLE_EDGE_COST { .mul = 0, .add = 1 }
#define EXTENT_CORNERS_COST { .mul = 4, .add = 9 }
#define PLANE_AT_COST { .mul = 2, .add = 2 }
#define ATTRIBUTE_COST { .mul = 1, .add = 0 }
#define RESOLVE_COST { .mul = 0, .add = 3 }
#define TENT_TAP_COST { .mul = 3, .add = 4 }

/* --- the samples ------------------------------------------------------------ */


static void pattern_setup(struct pattern *pt, const struct sample_pattern *sp)
{
    pt->n = sp->n;
    pt->lo_x = pt->lo_y = SUBPIXEL_ONE;
    pt->hi_x = pt->hi_y = -SUBPIXEL_ONE;
    for (int s = 0; s < sp->n; s++) {
        pt->dx[s] = sp->x[s] - SUBPIXEL_HALF;
        pt->dy[s] = sp->y[s] - SUBPIXEL_HALF;
        pt->lo_x = pt->dx[s] < pt->lo_x ? pt->dx[s] : pt->lo_x;
        pt->hi_x = pt->dx[s] > pt->hi_x ? pt->dx[s] : pt->hi_x;
        pt->lo_y = pt->dy[s] < pt->lo_y ? pt->dy[s] : pt->lo_y;
        pt->hi_y = pt->dy[s] > pt->hi_y ? pt->dy[s] : pt->hi_y;
    }
}

/* --- the edges at the samples ---------------------------------------------- */


static void edges_setup(struct edges *e, const struct tri_setup *t, const struct pattern *pt,
                        bool fill_rule)
{
    biased_edges_setup(&e->b, t, fill_rule);
    for (int k = 0; k < 3; k++) {
        for (int s = 0; s < pt->n; s++)
            e->off[s][k] = t->I[k] * pt->dx[s] + t->J[k] * pt->dy[s];
        e->ext0[k] = t->I[k] * pt->lo_x + t->J[k] * pt->lo_y;
        e->ext_w[k] = t->I[k] * (pt->hi_x - pt->lo_x);
        e->ext_h[k] = t->J[k] * (pt->hi_y - pt->lo_y);
    }
}

/* --- the box ------------------------------------------------------------------ */

/* Pixels any sample of which may be covered: sample s of pixel px sits at
 * 256 px + 128 + dx_s, so px reaches from the leftmost vertex minus the
 * rightmost sample to the rightmost vertex minus the leftmost sample. Wider
 * than the box of centres (tri_setup's) by up to a pixel each side. */
static bool sample_box(const struct tri_setup *t, const struct pattern *pt, int box[4])
{
    int64_t xs[2] = { t->x[0], t->x[0] }, ys[2] = { t->y[0], t->y[0] };
    for (int i = 1; i < 3; i++) {
        xs[0] = t->x[i] < xs[0] ? t->x[i] : xs[0], xs[1] = t->x[i] > xs[1] ? t->x[i] : xs[1];
        ys[0] = t->y[i] < ys[0] ? t->y[i] : ys[0], ys[1] = t->y[i] > ys[1] ? t->y[i] : ys[1];
    }
    int64_t x0 = ceil_div(xs[0] - SUBPIXEL_HALF - pt->hi_x, SUBPIXEL_ONE);
    int64_t x1 = floor_div(xs[1] - SUBPIXEL_HALF - pt->lo_x, SUBPIXEL_ONE);
    int64_t y0 = ceil_div(ys[0] - SUBPIXEL_HALF - pt->hi_y, SUBPIXEL_ONE);
    int64_t y1 = floor_div(ys[1] - SUBPIXEL_HALF - pt->lo_y, SUBPIXEL_ONE);
    box[0] = (int)(x0 < 0 ? 0 : x0);
    box[1] = (int)(y0 < 0 ? 0 : y0);
    box[2] = (int)(x1 > t->target_w - 1 ? t->target_w - 1 : x1);
    box[3] = (int)(y1 > t->target_h - 1 ? t->target_h - 1 : y1);
    return t->area2 > 0 && box[0] <= box[2] && box[1] <= box[3];
}

/* --- shading and resolving one pixel ------------------------------------------ */

/* What one pixel's covered samples receive: a colour and a depth each. */
struct fragment {
    unsigned mask;
    uint32_t color[SAMPLES_MAX];
    float z[SAMPLES_MAX];
};

/* The colour at plane values v[] (1/z, 255 r/z, ...) and depth z = 1 / (1/z):
 * each attribute (a/z) * z, then src/shade/'s checker and packing. */
static uint32_t colour_of(const struct run *r, const double v[PL_COUNT], double z)
{
    COUNT(r->tr, r->nplanes - 1, ATTRIBUTE_COST);
    return shade_scaled(r->p, r->tr, v[PL_R] * z, v[PL_G] * z, v[PL_B] * z, v[PL_S] * z,
                        v[PL_T] * z);
}

/* Shade pixel (x, y) for the samples of `mask`: the planes at the centre,
 * then per covered sample its depth (1/z at the sample: the centre's plus a
 * constant offset) and, for MSAA, the centre's colour; for SSAA every plane
 * at the sample and a colour of its own. */
static void shade(const struct run *r, int x, int y, unsigned mask, struct fragment *f)
{
    const struct planes *pl = &r->pl;
    double v[PL_COUNT] = { 0 };
    for (int q = 0; q < r->nplanes; q++)
        v[q] = pl->p0[q] + pl->px[q] * (x - pl->x0) + pl->py[q] * (y - pl->y0);
    COUNT(r->tr, r->nplanes, PLANE_AT_COST);
    uint32_t centre = 0;
    if (!r->per_sample) {
        centre = colour_of(r, v, 1.0 / v[PL_INV_Z]);
        COUNT(r->tr, 1, RECIPROCAL_COST);
    }
    f->mask = mask;
    for (int s = 0; s < r->pt.n; s++) {
        if (!(mask >> s & 1))
            continue;
        double vs[PL_COUNT] = { 0 };
        int used = r->per_sample ? r->nplanes : 1;     /* MSAA: only 1/z per sample */
        for (int q = 0; q < used; q++)
            vs[q] = v[q] + r->plane_off[s][q];
        COUNT(r->tr, used, PLANE_STEP_COST);
        double z = 1.0 / vs[PL_INV_Z];
        COUNT(r->tr, 1, RECIPROCAL_COST);
        f->z[s] = (float)z;
        f->color[s] = r->per_sample ? colour_of(r, vs, z) : centre;
    }
}

/* --- a wider resolve: the tent ---------------------------------------------- */

/* resolve() is a BOX filter: each of the pixel's own N samples weighs 1/N,
 * nothing beyond its square counts. The tent (Bartlett's) reaches a pixel
 * out: a sample (dx, dy) pixels from the centre weighs (1 - |dx|)(1 - |dy|),
 * neighbours' samples too. Its spectrum falls off faster (sinc^2 against
 * sinc): less of what lies beyond the pixel rate aliases back, at the price
 * of a softer picture. Weights in 1/256 pixel, the same for every pixel. */
static void tent_setup(struct tent *tn, const struct pattern *pt)
{
    tn->n = 0;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++)
            for (int s = 0; s < pt->n; s++) {
                int ax = abs(SUBPIXEL_ONE * i + pt->dx[s]), ay = abs(SUBPIXEL_ONE * j + pt->dy[s]);
                if (ax >= SUBPIXEL_ONE || ay >= SUBPIXEL_ONE)
                    continue;       /* a pixel or more away: weight 0 */
                tn->di[tn->n] = i, tn->dj[tn->n] = j, tn->s[tn->n] = s;
                tn->w[tn->n++] = (int64_t)(SUBPIXEL_ONE - ax) * (SUBPIXEL_ONE - ay);
            }
}

/* Pixel (x, y) resolved by the tent: the weighted mean of the samples in
 * reach (on the screen), rounded. */
static uint32_t tent_pixel(const struct run *r, int x, int y)
{
    int n = r->pt.n, w = r->fb->w, h = r->fb->h;
    int64_t sum[3] = { 0, 0, 0 }, total = 0;    /* at most 9 N x 65536 x 255: 64 bits */
    for (int k = 0; k < r->taps.n; k++) {
        int nx = x + r->taps.di[k], ny = y + r->taps.dj[k], s = r->taps.s[k];
        if (nx < 0 || ny < 0 || nx >= w || ny >= h)
            continue;
        uint32_t c = r->scolor[((size_t)ny * (size_t)w + (size_t)nx) * (size_t)n + (size_t)s];
        for (int ch = 0; ch < 3; ch++)
            sum[ch] += r->taps.w[k] * (c >> (16 - 8 * ch) & 0xff);
        total += r->taps.w[k];
        COUNT(r->tr, 1, TENT_TAP_COST);
    }
    uint32_t rgba = 0xff000000u;
    for (int ch = 0; ch < 3; ch++)
        rgba |= (uint32_t)((sum[ch] + total / 2) / total) << (16 - 8 * ch);
    return rgba;
}

/* A GPU resolves when the frame is done; the tent here when the triangle is
 * (so that the explorer shows each one finished), on the pixels that reach
 * its samples: the box and one more around it (the box filter's until then). */
static void tent_resolve(const struct run *r, const int box[4])
{
    for (int y = box[1] - 1; y <= box[3] + 1; y++)
        for (int x = box[0] - 1; x <= box[2] + 1; x++)
            if (x >= 0 && y >= 0 && x < r->fb->w && y < r->fb->h)
                r->fb->color[(size_t)y * (size_t)r->fb->w + (size_t)x] = tent_pixel(r, x, y);
}

/* A pixel after a fragment: its N samples depth-tested (nearer wins) and
 * resolved. The pixel's colour is the mean of its N samples' colours
 * (rounded), its depth the nearest sample's. */
struct outcome {
    uint32_t color[SAMPLES_MAX];
    float z[SAMPLES_MAX];
    uint32_t rgba;          /* resolved */
    float nearest;
    bool passed;            /* a sample passed the depth test */
};

/* Where pixel (x, y)'s samples are: n in a row. */
static size_t samples_at(const struct run *r, int x, int y)
{
    return ((size_t)(y - r->sy) * r->srow + (size_t)(x - r->sx)) * (size_t)r->pt.n;
}

void ms_resolve(int n, const uint32_t *color, const float *z, uint32_t *rgba, float *nearest)
{
    unsigned sum[3] = { 0, 0, 0 };
    *nearest = z[0];
    for (int s = 0; s < n; s++) {
        for (int c = 0; c < 3; c++)
            sum[c] += color[s] >> (16 - 8 * c) & 0xff;
        *nearest = z[s] < *nearest ? z[s] : *nearest;
    }
    *rgba = 0xff000000u;
    for (int c = 0; c < 3; c++)
        *rgba |= (sum[c] + (unsigned)n / 2) / (unsigned)n << (16 - 8 * c);
}

static void resolve(const struct run *r, int x, int y, const struct fragment *f, struct outcome *o)
{
    int n = r->pt.n;
    size_t base = samples_at(r, x, y);
    o->passed = false;
    for (int s = 0; s < n; s++) {
        o->color[s] = r->scolor[base + (size_t)s];
        o->z[s] = r->sdepth[base + (size_t)s];
        if ((f->mask >> s & 1) && f->z[s] < o->z[s]) {
            o->color[s] = f->color[s];
            o->z[s] = f->z[s];
            o->passed = true;
        }
    }
    o->rgba = o->color[0];
    o->nearest = o->z[0];
    if (n == 1 || (r->touched && !r->tr))
        return;     /* one sample: it is the pixel; tiled: resolved at the store (narrated: shown now) */
    ms_resolve(n, o->color, o->z, &o->rgba, &o->nearest);
    COUNT(r->tr, n, RESOLVE_COST);
}

/* Write the outcome: the samples, the resolved pixel, and the count of
 * covered samples (saturating, lessons/CONVENTIONS.md "Samples"). */
static void store(const struct run *r, int x, int y, unsigned mask, const struct outcome *o)
{
    int n = r->pt.n;
    size_t i = (size_t)y * (size_t)r->fb->w + (size_t)x, base = samples_at(r, x, y);
    for (int s = 0; s < n; s++) {
        r->scolor[base + (size_t)s] = o->color[s];
        r->sdepth[base + (size_t)s] = o->z[s];
    }
    if (r->touched)
        r->touched[y - r->sy] |= (uint64_t)1 << (x - r->sx);
    else if (n > 1) {
        r->fb->color[i] = o->rgba;
        r->fb->depth[i] = o->nearest;
    }
    if (r->fb->count) {
        unsigned c = r->fb->count[i] + (unsigned)__builtin_popcount(mask);
        r->fb->count[i] = (uint8_t)(c > 255 ? 255 : c);
    }
}

/* --- the blocks ------------------------------------------------------------------ */

/* Which samples of pixel (x, y) are covered, from the pixel's centre values
 * cx[] (bias folded in) plus each sample's offsets. */
static unsigned sample_mask(const struct run *r, const int64_t cx[3])
{
    unsigned mask = 0;
    for (int s = 0; s < r->pt.n; s++) {
        const int64_t *o = r->e.off[s];
        if (cx[0] + o[0] >= 0 && cx[1] + o[1] >= 0 && cx[2] + o[2] >= 0)
            mask |= 1u << s;
    }
    COUNT(r->tr, 3 * r->pt.n, SAMPLE_EDGE_COST);
    return mask;
}

/* FULL: every sample of every pixel is covered; no test, no narration per
 * pixel (as lesson 05's RenderBlock). */
static void full_block(const struct run *r, int x0, int y0, int x1, int y1)
{
    unsigned all = (1u << r->pt.n) - 1;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            struct fragment f;
            struct outcome o;
            shade(r, x, y, all, &f);
            resolve(r, x, y, &f, &o);
            store(r, x, y, all, &o);
        }
}

/* PARTIAL: pixel by pixel, the centre values stepped from the block's corner
 * (+256 I0k right, +256 J0k down), each sample one addition away. */
static void partial_block(const struct run *r, int x0, int y0, int x1, int y1)
{
    const struct biased_edges *e = &r->e.b;
    int64_t cy[3] = { biased_edge_at(e, 0, x0, y0), biased_edge_at(e, 1, x0, y0),
                      biased_edge_at(e, 2, x0, y0) };
    for (int y = y0; y <= y1; y++) {
        int64_t cx[3] = { cy[0], cy[1], cy[2] };
        for (int x = x0; x <= x1; x++) {
            unsigned mask = sample_mask(r, cx);
            NARRATE(r->tr, .kind = TRACE_PIXEL_TEST, .line = L_MASK, .x = x, .y = y,
                    .e = { cx[0] - e->bias[0], cx[1] - e->bias[1], cx[2] - e->bias[2] },
                    .flags = mask ? TRACE_INSIDE : 0, .mask = { (uint16_t)mask },
                    .aux = { (float)r->pt.n, (float)__builtin_popcount(mask), (float)mask, r->grid });
            if (mask) {
                struct fragment f;
                struct outcome o;
                shade(r, x, y, mask, &f);
                resolve(r, x, y, &f, &o);
                NARRATE(r->tr, .kind = TRACE_PIXEL_WRITE, .line = L_WRITE, .x = x, .y = y,
                        .z = o.nearest, .rgba = o.rgba, .flags = o.passed ? TRACE_DEPTH_PASS : 0,
                        .mask = { (uint16_t)mask },
                        .aux = { (float)r->pt.n, (float)__builtin_popcount(mask), (float)mask, r->grid });
                if (!trace_frozen(r->tr))
                    store(r, x, y, mask, &o);
            }
            for (int k = 0; k < 3; k++)
                cx[k] += e->dx[k];
            COUNT(r->tr, 3, EDGE_STEP_COST);
        }
        for (int k = 0; k < 3; k++)
            cy[k] += e->dy[k];
    }
}

/* Classify the block of pixels x0..x1, y0..y1 by the corners of its samples'
 * extent (lesson 05's corners, moved out to the outermost samples: with one
 * sample they are the corner pixels' centres, as there), narrate, act. */
static void block(const struct run *r, int x0, int y0, int x1, int y1)
{
    const struct edges *e = &r->e;
    const struct biased_edges *b = &e->b;
    unsigned m[3];
    for (int k = 0; k < 3; k++) {
        int64_t tl = biased_edge_at(b, k, x0, y0) + e->ext0[k];
        int64_t tr = tl + b->dx[k] * (x1 - x0) + e->ext_w[k];
        int64_t bl = tl + b->dy[k] * (y1 - y0) + e->ext_h[k];
        int64_t br = tr + (bl - tl);
        m[k] = (unsigned)(tl >= 0) << 3 | (unsigned)(tr >= 0) << 2
             | (unsigned)(bl >= 0) << 1 | (unsigned)(br >= 0);
    }
    COUNT(r->tr, 3, EXTENT_CORNERS_COST);
    enum block_class klass = m[0] == 0 || m[1] == 0 || m[2] == 0 ? BLOCK_EMPTY
                           : m[0] == 0xF && m[1] == 0xF && m[2] == 0xF ? BLOCK_FULL
                           : BLOCK_PARTIAL;
    int line = klass == BLOCK_EMPTY ? L_EMPTY : klass == BLOCK_FULL ? L_FULL : L_PARTIAL;
    NARRATE(r->tr, .kind = TRACE_BLOCK, .line = (uint8_t)line, .span = (uint8_t)(line - L_LOOP),
            .x = x0, .y = y0, .x1 = x1, .y1 = y1, .klass = (uint8_t)klass,
            .mask = { (uint16_t)m[0], (uint16_t)m[1], (uint16_t)m[2] },
            .e = { biased_edge_at(b, 0, x0, y0) - b->bias[0], biased_edge_at(b, 1, x0, y0) - b->bias[1],
                   biased_edge_at(b, 2, x0, y0) - b->bias[2] },
            .aux = { (float)r->pt.n, 0, 0, r->grid });
    if (r->pixels && klass != BLOCK_EMPTY) {    /* the tiled twin's SIMD pixels (pixels.c) */
        if (klass == BLOCK_PARTIAL || !trace_frozen(r->tr))
            r->pixels(r, x0, y0, x1, y1, klass == BLOCK_FULL);
    } else if (klass == BLOCK_FULL && !trace_frozen(r->tr))
        full_block(r, x0, y0, x1, y1);
    else if (klass == BLOCK_PARTIAL)
        partial_block(r, x0, y0, x1, y1);
}

/* --- the rasterizer ------------------------------------------------------------- */


const struct sample_pattern *ms_target(struct target *fb, const struct raster_params *p, bool grid)
{
    int n = p->samples > 1 ? p->samples : 1;
    const struct sample_pattern *sp = sample_pattern(n);
    if (!sp)
        sp = sample_pattern(n = 1);
    if (grid)
        sp = sample_grid(n);    /* the exhibit's regular grid instead */
    /* The target's per-sample storage: made by the driver (render_scene,
     * replay), or here for a target that has none; without memory for it,
     * the pixel centre alone. One sample needs none: it is the pixel. */
    if (n == 1)
        target_multisample(fb, 1);
    else if ((!fb->samples || fb->samples->n != n) && !target_multisample(fb, n))
        sp = sample_pattern(1);
    return sp;
}

bool ms_box(const struct tri_setup *t, const struct sample_pattern *sp, struct pattern *pt,
            int box[4], struct trace *tr, bool grid)
{
    pattern_setup(pt, sp);
    bool any = sample_box(t, pt, box);
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_BOX, .span = any ? L_BOX - L_SETUP : 0, .x = box[0],
            .y = box[1], .x1 = box[2], .y1 = box[3], .e = { t->area2, 0, 0 },
            .aux = { (float)pt->n, 0, 0, grid && pt->n > 1 });
    return any;
}

void ms_setup(struct run *r, const struct tri_setup *t, const struct raster_params *p,
              struct target *fb, struct trace *tr, struct ms_options o)
{
    int n = r->pt.n;
    edges_setup(&r->e, t, &r->pt, o.fill_rule);     /* F0k and each sample's offsets O_sk */
    r->t = t, r->p = p, r->fb = fb, r->tr = tr;
    r->scolor = n > 1 ? fb->samples->color : fb->color;
    r->sdepth = n > 1 ? fb->samples->depth : fb->depth;
    r->sx = r->sy = 0, r->srow = (size_t)fb->w, r->touched = NULL, r->pixels = NULL;
    r->per_sample = o.per_sample;
    r->tent = o.tent && n > 1;       /* one sample: the tent weighs only the pixel's own */
    if (r->tent)
        tent_setup(&r->taps, &r->pt);
    r->grid = o.grid && n > 1;
    planes_setup(&r->pl, t, p);
    r->nplanes = p->checker > 0 ? PL_COUNT : PL_S;
    for (int s = 0; s < n; s++)
        for (int q = 0; q < PL_COUNT; q++)
            r->plane_off[s][q] = (r->pl.px[q] * r->pt.dx[s] + r->pl.py[q] * r->pt.dy[s]) / SUBPIXEL_ONE;
}

void ms_blocks(const struct run *r, const int box[4], int q)
{
    for (int by = box[1] - box[1] % q; by <= box[3]; by += q) {
        int ya = by < box[1] ? box[1] : by, yb = by + q - 1 > box[3] ? box[3] : by + q - 1;
        for (int bx = box[0] - box[0] % q; bx <= box[2]; bx += q) {
            int xa = bx < box[0] ? box[0] : bx, xb = bx + q - 1 > box[2] ? box[2] : bx + q - 1;
            block(r, xa, ya, xb, yb);
        }
    }
}

static void rasterize_ms(const struct tri_setup *t, const struct raster_params *p,
                         struct target *fb, struct trace *tr, struct ms_options o)
{
    struct run r;       /* set field by field: an initializer would clear all of it, per triangle */
    int box[4];
    if (!ms_box(t, ms_target(fb, p, o.grid), &r.pt, box, tr, o.grid))
        return;
    ms_setup(&r, t, p, fb, tr, o);
    /* lesson 05's grid of q x q blocks, aligned on the screen, clipped to the box */
    ms_blocks(&r, box, p->knob[MS_P_BLOCK] > 0 ? p->knob[MS_P_BLOCK] : Q_DEFAULT);
    if (r.tent && !trace_frozen(tr))
        tent_resolve(&r, box);
}

/* --- the variants ----------------------------------------------------------------- */

static void rasterize_msaa(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_ms(t, p, fb, tr, (struct ms_options){ .fill_rule = true });
}

static void rasterize_ssaa(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_ms(t, p, fb, tr, (struct ms_options){ .per_sample = true, .fill_rule = true });
}

static void rasterize_tent(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_ms(t, p, fb, tr, (struct ms_options){ .tent = true, .fill_rule = true });
}

static void rasterize_grid(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    rasterize_ms(t, p, fb, tr, (struct ms_options){ .grid = true, .fill_rule = true });
}

static void rasterize_no_fill_rule(const struct tri_setup *t, const struct raster_params *p,
                                   struct target *fb, struct trace *tr)
{
    rasterize_ms(t, p, fb, tr, (struct ms_options){ .fill_rule = false });
}

static const struct lesson_variant variants[] = {
    { .name = "msaa", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_msaa,
      .what = "multisampling: coverage and depth per sample, colour once per pixel" },
    { .name = "tiles", .kind = VARIANT_TWIN, .rasterize = rasterize_tiled,
      .what = "msaa on lesson 07's 64 x 64 tiles, bins and workers: a tile's samples in cache, "
      "resolved once, at the tile's store" },
    { .name = "ssaa", .kind = VARIANT_ALTERNATIVE, .rasterize = rasterize_ssaa,
      .what = "supersampling: colour shaded at every covered sample" },
    { .name = "tent", .kind = VARIANT_ALTERNATIVE, .rasterize = rasterize_tent,
      .what = "msaa resolved by a tent filter: the neighbours' samples count too" },
    { .name = "grid", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_grid,
      .what = "exhibit: samples on a regular grid (4: the quarter points) instead of the rotated pattern" },
    { .name = "no-fill-rule", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_no_fill_rule,
      .what = "exhibit: a sample exactly on an edge is covered by both triangles" },
};

const struct lesson lesson_08 = {
    .id = "08-multisampling",
    .title = "Anti-aliasing with coverage samples, exact per sample",
    .pseudocode = pseudocode,
    .builtin_scene = "samples",
    .exhibit_scene = "samples-exhibits",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .params = (const struct lesson_param[]){
        [MS_P_BLOCK] = { .option = "block-size", .arg = "Q", .name = "block", .key = 'b', .min = 4,
                      .max = 16, .values = (const int[]){ 4, 8, 16, -1 }, .def = Q_DEFAULT,
                      .help = "block size for block lessons (4, 8 or 16)" },
        [MS_P_SAMPLES] = { .option = "samples", .arg = "N", .name = "samples", .key = 'm', .def = 4,
                        .min = 1, .max = 8, .values = (const int[]){ 1, 4, 8, -1 }, .slot = PARAM_SAMPLES,
                        .help = "samples per pixel, 1, 4 or 8 (lesson 08; default 4)" },
        [MS_P_THREADS] = { .option = "threads", .arg = "N", .name = "threads",
                           .help = "worker threads of a tiled lesson, 1..64 (default: one per core)",
                           .min = 1, .max = 64 },
        { 0 } },
    .rasterize_scene = (const rasterize_scene_fn[]){ NULL, ms_tiled_scene, NULL, NULL, NULL, NULL },
    .narration_units = ms_units,
    /* at one sample (what the recount runs): the edges at the sample, the step
     * to the next pixel; covered: four planes at the centre, colour, depth */
    .cost_tested = (const struct cost_term[]){
        COST_TERM(3, SAMPLE_EDGE_COST), COST_TERM(3, EDGE_STEP_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(4, PLANE_AT_COST), COST_TERM(2, RECIPROCAL_COST), COST_TERM(3, ATTRIBUTE_COST),
        COST_TERM(1, PACK_SCALED_COST), COST_TERM(1, PLANE_STEP_COST), { 0 } },
    .compare = (const char *const[]){ "05-block-classification", NULL },
    /* make check draws every scene at 4 and 8 samples, then at the centre */
    .exercise = { .write_line = L_WRITE, .samples = (const int[]){ 4, 8, 1, 0 } },
};
