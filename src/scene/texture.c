/* texture.c - a texture's pyramid of mip-map levels (see texture.h). */
#include "texture.h"

#include <stdlib.h>
#include <string.h>

bool texture_size_ok(long n)
{
    return n >= 1 && n <= TEXTURE_SIZE_MAX && (n & (n - 1)) == 0;
}

/* The mean of n texels (n = 1, 2 or 4), per channel, rounded half up:
 * (a + b + n/2) / n in integers, so (1 + 2 + 1) / 2 = 2, (a + b + c + d + 2) / 4. */
static uint32_t mean(const uint32_t *c, int n)
{
    uint32_t out = 0xff000000u;
    for (int shift = 0; shift < 24; shift += 8) {
        unsigned sum = (unsigned)n / 2;
        for (int i = 0; i < n; i++)
            sum += (c[i] >> shift) & 255u;
        out |= (sum / (unsigned)n) << shift;
    }
    return out;
}

/* Level k is w x h; level k + 1 is max(1, w/2) x max(1, h/2). Texel (x, y)
 * of level k + 1 covers texels 2x .. 2x+1 and 2y .. 2y+1 of level k, of
 * which a level one texel wide (or high) has only the one column (row):
 *
 *     +---+---+                   +---+---+
 *     | a | b |      -->  (a + b + c + d + 2) / 4     a 2 x 1 pair: (a + b + 1) / 2
 *     +---+---+                   +---+---+
 *     | c | d |
 *     +---+---+                                                                */
void texture_downsample(const struct texture_level *from, uint32_t *to)
{
    int sx = from->w > 1 ? 2 : 1, sy = from->h > 1 ? 2 : 1;
    int w = from->w / sx, h = from->h / sy;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t c[4];
            int n = 0;
            for (int j = 0; j < sy; j++)
                for (int i = 0; i < sx; i++)
                    c[n++] = from->texel[(size_t)(sy * y + j) * (size_t)from->w + (size_t)(sx * x + i)];
            to[(size_t)y * (size_t)w + (size_t)x] = mean(c, n);
        }
}

bool texture_make(struct texture *t, const char *name, enum texture_wrap wrap, int w, int h,
                  const uint32_t *image)
{
    memset(t, 0, sizeof *t);
    if (!texture_size_ok(w) || !texture_size_ok(h))
        return false;
    size_t total = 0;
    int n = 0;
    for (int lw = w, lh = h;; lw = lw > 1 ? lw / 2 : 1, lh = lh > 1 ? lh / 2 : 1) {
        t->level[n++] = (struct texture_level){ .w = lw, .h = lh };
        total += (size_t)lw * (size_t)lh;
        if (lw == 1 && lh == 1)
            break;
    }
    t->texels = malloc(total * sizeof *t->texels);
    t->name = malloc(strlen(name) + 1);
    if (!t->texels || !t->name) {
        texture_free(t);
        return false;
    }
    strcpy(t->name, name);
    t->wrap = wrap;
    t->nlevels = n;
    uint32_t *at = t->texels;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        at[i] = image[i] | 0xff000000u;             /* opaque, whatever the alpha byte said */
    for (int k = 0; k < n; k++) {
        t->level[k].texel = at;
        at += (size_t)t->level[k].w * (size_t)t->level[k].h;
        if (k + 1 < n)
            texture_downsample(&t->level[k], at);
    }
    return true;
}

void texture_free(struct texture *t)
{
    free(t->texels);
    free(t->name);
    memset(t, 0, sizeof *t);
}
