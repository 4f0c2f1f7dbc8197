/* texture.h - image textures and their mip-map pyramids (lessons/CONVENTIONS.md,
 * "Textures"), as a scene names them:
 *
 *     texture FILE.png [repeat|clamp]      a PNG beside the scene, read through cairo
 *     texture builtin:NAME [repeat|clamp]  a texture made by code (textures.c)
 *
 * Texture space: (s, t) = (0, 0) is the image's top-left corner, s to the
 * right, t down. At level k, u = s W_k and v = t H_k are in texels, and
 * texel (i, j) covers [i, i+1) x [j, j+1):
 *
 *      (0,0) +-----+-----+---> u          repeat: i -> i mod W_k  (never negative)
 *            | 0,0 | 1,0 |                clamp:  i -> 0 .. W_k - 1
 *            +-----+-----+
 *            | 0,1 | 1,1 |    centre of texel (i, j): (i + 1/2, j + 1/2)
 *            +-----+-----+
 *            v
 *
 * The pyramid: level 0 is the image; level k + 1 has max(1, W_k / 2) x
 * max(1, H_k / 2) texels, each the mean of the 2 x 2 (or 2 x 1, 1 x 2)
 * texels of level k it covers, per channel, in integers, rounded half up:
 * (a + b + c + d + 2) / 4, (a + b + 1) / 2. Down to 1 x 1.
 *
 * Filtering (the level of detail, the five filters) is lesson 09's; what is
 * here is the image, its levels and the one way of addressing a texel. */
#ifndef TRISTEP_TEXTURE_H
#define TRISTEP_TEXTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define TEXTURE_SIZE_MAX 4096      /* width and height: powers of two in 1..4096 */
#define TEXTURE_LEVELS_MAX 13      /* log2(4096) + 1 */

enum texture_wrap { TEXTURE_REPEAT, TEXTURE_CLAMP };

/* One level of the pyramid: w x h texels, row-major, row 0 at the top,
 * each 0xAARRGGBB (the target's packing), always opaque. */
struct texture_level {
    int w, h;
    const uint32_t *texel;
};

struct texture {
    char *name;                    /* as a written scene names it: builtin:NAME or a full path */
    enum texture_wrap wrap;
    int nlevels;                   /* level 0 .. nlevels - 1, the last one 1 x 1 */
    struct texture_level level[TEXTURE_LEVELS_MAX];
    uint32_t *texels;              /* every level, one allocation */
};

/* Is n a power of two in 1..TEXTURE_SIZE_MAX? */
bool texture_size_ok(long n);

/* Make t of a w x h image (sizes as texture_size_ok wants them; texels
 * 0xAARRGGBB, alpha ignored, stored opaque): level 0 is a copy, the levels
 * below are built. False only when out of memory (t is then empty). The
 * name is copied. */
bool texture_make(struct texture *t, const char *name, enum texture_wrap wrap, int w, int h,
                  const uint32_t *image);
void texture_free(struct texture *t);

/* Level k + 1 of level k: `to` holds max(1, w/2) x max(1, h/2) texels. */
void texture_downsample(const struct texture_level *from, uint32_t *to);

/* A texel index i (any integer, e.g. floor(u)) mapped into 0 .. n - 1. */
static inline int texture_wrap_index(int64_t i, int n, enum texture_wrap wrap)
{
    if (wrap == TEXTURE_CLAMP)
        return i < 0 ? 0 : i >= n ? n - 1 : (int)i;
    int64_t m = i % n;                  /* C's % keeps the sign of i: -1 % 4 is -1 */
    return (int)(m < 0 ? m + n : m);    /* the mathematical mod: -1 mod 4 is 3 */
}

/* Texel (i, j) of level k, wrapped as the texture says. */
static inline uint32_t texture_fetch(const struct texture *t, int k, int64_t i, int64_t j)
{
    const struct texture_level *l = &t->level[k];
    int x = texture_wrap_index(i, l->w, t->wrap), y = texture_wrap_index(j, l->h, t->wrap);
    return l->texel[(size_t)y * (size_t)l->w + (size_t)x];
}

/* --- where images come from ------------------------------------------------------ */

/* A PNG file through cairo (png.c): opaque (an alpha below 255 anywhere is
 * refused), width and height powers of two in 1..4096. On success *image
 * is a fresh w x h array of 0xAARRGGBB (free it). On failure false with a
 * message (no file name, no newline) in why. */
bool texture_read_png(const char *path, int *w, int *h, uint32_t **image, char *why, size_t n);

/* The textures made by code (textures.c), by name ("checker-numbers"), and
 * "noise-WxH" (W, H powers of two in 1..4096: hashed texels of high
 * contrast, any shape): the same arguments and results as texture_read_png. */
bool texture_builtin(const char *name, int *w, int *h, uint32_t **image, char *why, size_t n);

struct builtin_texture {
    const char *name, *what;
};
extern const struct builtin_texture builtin_textures[];   /* ends with { NULL } */

#endif
