/* patch.c - the changed pixels of a picture (see patch.h). */
#include "patch.h"

#include <stdlib.h>
#include <string.h>

/* Unchanged pixels between two runs that join them: a run costs its
 * 8 bytes and a copy more, a pixel its 9 bytes. */
#define JOIN_GAP 2

static int samples_of(const struct target *t)
{
    return t->samples ? t->samples->n : 0;
}

/* One block for runs and values (every part 4-byte aligned, count last). */
static bool patch_alloc(struct patch *p, int nruns, size_t npix, int samples)
{
    memset(p, 0, sizeof *p);
    size_t s = (size_t)samples;
    size_t bytes = npix * (4 + 4 + 1) + npix * s * (4 + 4) + (size_t)nruns * 2 * sizeof *p->runs;
    unsigned char *b = malloc(bytes ? bytes : 1);
    if (!b)
        return false;
    p->nruns = nruns;
    p->npix = npix;
    p->samples = samples;
    p->bytes = bytes;
    p->color = (uint32_t *)b;
    p->depth = (float *)(b + 4 * npix);
    p->scolor = (uint32_t *)(b + 8 * npix);
    p->sdepth = (float *)(b + 8 * npix + 4 * npix * s);
    p->runs = (uint32_t *)(b + 8 * npix + 8 * npix * s);
    p->count = b + 8 * npix + 8 * npix * s + (size_t)nruns * 2 * sizeof *p->runs;
    return true;
}

void patch_free(struct patch *p)
{
    free(p->color);             /* the start of the block */
    memset(p, 0, sizeof *p);
}

/* n pixels' colour, depth and count from one place to another. Most runs
 * are a few pixels long (a small triangle's row): 4 to 8 pixels are two
 * overlapping copies of 4 (fixed sizes, a register each), 1 to 3 three
 * overlapping copies of one: faster than three calls to memcpy. */
static inline void copy_pixels(uint32_t *restrict color, float *restrict depth,
                               uint8_t *restrict count, const uint32_t *from_color,
                               const float *from_depth, const uint8_t *from_count, size_t n)
{
    if (n > 8) {
        memcpy(color, from_color, 4 * n);
        memcpy(depth, from_depth, 4 * n);
        memcpy(count, from_count, n);
        return;
    }
    if (n >= 4) {
        memcpy(color, from_color, 16);
        memcpy(color + n - 4, from_color + n - 4, 16);
        memcpy(depth, from_depth, 16);
        memcpy(depth + n - 4, from_depth + n - 4, 16);
        memcpy(count, from_count, 4);
        memcpy(count + n - 4, from_count + n - 4, 4);
        return;
    }
    if (n == 0)
        return;
    size_t mid = n / 2, last = n - 1;   /* 1 to 3 pixels: 0, mid and last are all of them */
    color[0] = from_color[0], color[mid] = from_color[mid], color[last] = from_color[last];
    depth[0] = from_depth[0], depth[mid] = from_depth[mid], depth[last] = from_depth[last];
    count[0] = from_count[0], count[mid] = from_count[mid], count[last] = from_count[last];
}

/* Where the values of pixels start, in a target or in a patch. */
struct pixels {
    uint32_t *color;
    float *depth;
    uint8_t *count;
    uint32_t *scolor;       /* NULL without samples */
    float *sdepth;
};

static struct pixels in_target(const struct target *t, size_t at)
{
    size_t s = t->samples ? (size_t)t->samples->n : 0;
    return (struct pixels){ t->color + at, t->depth + at, t->count + at,
                            s ? t->samples->color + at * s : NULL,
                            s ? t->samples->depth + at * s : NULL };
}

static struct pixels in_patch(const struct patch *p, size_t k)
{
    size_t s = (size_t)p->samples;
    return (struct pixels){ p->color + k, p->depth + k, p->count + k, p->scolor + k * s,
                            p->sdepth + k * s };
}

/* n pixels, s samples each. */
static void copy(struct pixels to, struct pixels from, size_t n, size_t s)
{
    copy_pixels(to.color, to.depth, to.count, from.color, from.depth, from.count, n);
    if (s) {
        memcpy(to.scolor, from.scolor, 4 * n * s);
        memcpy(to.sdepth, from.sdepth, 4 * n * s);
    }
}

/* Between t and the patch, run after run: into the patch, or out of it.
 * (The pixels without samples directly: this is a jump's inner loop.) */
static void transfer(const struct patch *p, struct target *t, bool into_patch)
{
    size_t k = 0, s = (size_t)p->samples;
    for (int r = 0; r < p->nruns; r++) {
        size_t at = p->runs[2 * r], n = p->runs[2 * r + 1];
        if (s && into_patch)
            copy(in_patch(p, k), in_target(t, at), n, s);
        else if (s)
            copy(in_target(t, at), in_patch(p, k), n, s);
        else if (into_patch)
            copy_pixels(p->color + k, p->depth + k, p->count + k, t->color + at, t->depth + at,
                        t->count + at, n);
        else
            copy_pixels(t->color + at, t->depth + at, t->count + at, p->color + k, p->depth + k,
                        p->count + k, n);
        k += n;
    }
}

void patch_apply(const struct patch *p, struct target *t)
{
    transfer(p, t, false);
}

bool patch_whole(struct patch *p, const struct target *t)
{
    size_t n = (size_t)t->w * (size_t)t->h;
    if (!patch_alloc(p, 1, n, samples_of(t)))
        return false;
    p->runs[0] = 0;
    p->runs[1] = (uint32_t)n;
    transfer(p, (struct target *)t, true);     /* read only */
    return true;
}

bool patch_is_whole(const struct patch *p, size_t n)
{
    return p->nruns == 1 && p->runs[0] == 0 && p->npix == n;
}

/* Runs being collected: pairs, grown as needed. */
struct runs {
    uint32_t *r;
    int n, cap;
    size_t npix;
    size_t join;            /* pixels between two runs that may join them */
};

static bool runs_add(struct runs *rs, size_t at, size_t n)
{
    if (rs->n > 0) {
        uint32_t *last = &rs->r[2 * (rs->n - 1)];
        size_t end = (size_t)last[0] + last[1];
        if (at <= end + rs->join) {        /* touching, overlapping or nearly: one run */
            if (at + n > end) {
                rs->npix += at + n - end;
                last[1] = (uint32_t)(at + n - last[0]);
            }
            return true;
        }
    }
    if (rs->n == rs->cap) {
        int cap = rs->cap ? 2 * rs->cap : 1024;
        uint32_t *r = realloc(rs->r, (size_t)cap * 2 * sizeof *r);
        if (!r)
            return false;
        rs->r = r;
        rs->cap = cap;
    }
    rs->r[2 * rs->n] = (uint32_t)at;
    rs->r[2 * rs->n + 1] = (uint32_t)n;
    rs->n++;
    rs->npix += n;
    return true;
}

static bool patch_from_runs(struct patch *p, struct runs *rs, int samples)
{
    bool ok = patch_alloc(p, rs->n, rs->npix, samples);
    if (ok && rs->n > 0)        /* none: nothing changed, and rs->r is NULL */
        memcpy(p->runs, rs->r, (size_t)rs->n * 2 * sizeof *rs->r);
    free(rs->r);
    return ok;
}

static bool pixel_differs(const struct target *a, const struct target *b, size_t i, size_t s)
{
    uint32_t da, db;
    memcpy(&da, &a->depth[i], sizeof da);       /* depth by its bits: -0 is not 0 */
    memcpy(&db, &b->depth[i], sizeof db);
    if (a->color[i] != b->color[i] || da != db || a->count[i] != b->count[i])
        return true;
    return s && (memcmp(a->samples->color + i * s, b->samples->color + i * s, 4 * s) != 0
                 || memcmp(a->samples->depth + i * s, b->samples->depth + i * s, 4 * s) != 0);
}

/* Do `bytes` (a multiple of 8) differ? Eight at a time. */
static uint64_t bytes_differ(const void *a, const void *b, size_t bytes)
{
    uint64_t d = 0;
    for (size_t k = 0; k < bytes; k += 8) {
        uint64_t x, y;
        memcpy(&x, (const unsigned char *)a + k, 8);
        memcpy(&y, (const unsigned char *)b + k, 8);
        d |= x ^ y;
    }
    return d;
}

/* Pixels [i, i + BLOCK) the same in colour, depth bits and count? One
 * test for them all: most of a picture has not changed since the
 * checkpoint before. */
#define BLOCK 16

static bool block_same(const struct target *a, const struct target *b, size_t i)
{
    return !(bytes_differ(a->color + i, b->color + i, 4 * BLOCK)
             | bytes_differ(a->depth + i, b->depth + i, 4 * BLOCK)
             | bytes_differ(a->count + i, b->count + i, BLOCK));
}

bool patch_diff(struct patch *p, const struct target *now, const struct target *before)
{
    size_t n = (size_t)now->w * (size_t)now->h, s = (size_t)samples_of(now);
    struct runs rs = { .join = JOIN_GAP };  /* the pixels joined keep their value */
    for (size_t i = 0; i < n; i++) {
        if (i % BLOCK == 0 && i + BLOCK <= n && !s && block_same(now, before, i)) {
            i += BLOCK - 1;
            continue;
        }
        if (pixel_differs(now, before, i, s) && !runs_add(&rs, i, 1)) {
            free(rs.r);
            return false;
        }
    }
    if (!patch_from_runs(p, &rs, (int)s))
        return false;
    transfer(p, (struct target *)now, true);   /* read only */
    return true;
}

/* Copy the values of q's runs into p, whose runs cover them. */
static void copy_runs(struct patch *p, const struct patch *q)
{
    size_t k = 0, pk = 0;
    int u = 0;
    for (int r = 0; r < q->nruns; r++) {
        size_t at = q->runs[2 * r], n = q->runs[2 * r + 1];
        while ((size_t)p->runs[2 * u] + p->runs[2 * u + 1] <= at)
            pk += p->runs[2 * u + 1], u++;
        copy(in_patch(p, pk + (at - p->runs[2 * u])), in_patch(q, k), n, (size_t)p->samples);
        k += n;
    }
}

bool patch_merge(struct patch *p, const struct patch *older, const struct patch *newer)
{
    if (older->samples != newer->samples)
        return false;
    struct runs rs = { .join = 0 };     /* a pixel in neither has no value to give */
    int i = 0, j = 0;
    while (i < older->nruns || j < newer->nruns) {     /* the union, in order */
        bool from_older = j == newer->nruns
                          || (i < older->nruns && older->runs[2 * i] < newer->runs[2 * j]);
        const uint32_t *r = from_older ? &older->runs[2 * i++] : &newer->runs[2 * j++];
        if (!runs_add(&rs, r[0], r[1])) {
            free(rs.r);
            return false;
        }
    }
    if (!patch_from_runs(p, &rs, older->samples))
        return false;
    copy_runs(p, older);
    copy_runs(p, newer);
    return true;
}
