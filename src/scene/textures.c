/* textures.c - the textures made by code for tristep (MIT licence, as the
 * rest of it; no image is downloaded): `texture builtin:NAME` in a scene.
 * Each is drawn texel by texel below, in integers, so it is the same on
 * every machine. All have fine detail (thin lines, small digits) that
 * aliases as soon as a pixel covers more than a texel: what lesson 09's
 * filters are about. */
#include "texture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const struct builtin_texture builtin_textures[] = {
    { "checker-numbers", "256 x 256: 8 x 8 cells in two tones, each with its number 0..63" },
    { "bricks", "256 x 256: rows of bricks in mortar, every other row shifted by half a brick" },
    { "grid", "256 x 256: a red-green gradient under a grid of lines every 8, 32 and 128 texels" },
    { "rgby", "2 x 2: red, green / blue, yellow (the smallest texture to reason about)" },
    { "plaid", "32 x 8: stripes one texel wide under bands eight across and four down (not square)" },
    { NULL, NULL },
};

static uint32_t rgb(unsigned r, unsigned g, unsigned b)
{
    return 0xff000000u | (r & 255u) << 16 | (g & 255u) << 8 | (b & 255u);
}

/* Digits 0..9 on 3 x 5 cells, a row of three bits per line, top line first. */
static const unsigned short digit_rows[10] = {
    075557, 026227, 071747, 071717, 055711, 074717, 074757, 071111, 075757, 075717,
};

static bool digit_pixel(int d, int x, int y)       /* x in 0..2, y in 0..4 */
{
    unsigned row = (digit_rows[d] >> (3 * (4 - y))) & 7u;
    return (row >> (2 - x)) & 1u;
}

/* 8 x 8 cells of 32 x 32 texels, light and dark in turn, the hue changing
 * across the rows and columns (red with the column, green and blue with the row); cell n = 8 row + column shows n in digits of
 * 3 x 5 blocks of 3 x 3 texels, in the opposite tone. */
static void checker_numbers(uint32_t *im, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int cx = x / 32, cy = y / 32, n = 8 * cy + cx;
            bool dark = (cx + cy) & 1;
            unsigned r = 60 + 25 * (unsigned)cx, g = 200 - 15 * (unsigned)cy, b = 120 + 15 * (unsigned)cy;
            /* two digits, each 9 x 15 texels, with 3 texels between them,
             * centred in the cell: from (5, 8) to (26, 22) */
            int lx = x % 32 - 5, ly = y % 32 - 8;
            bool ink = false;
            if (ly >= 0 && ly < 15 && lx >= 0 && lx < 21 && lx % 12 < 9) {
                int d = lx < 12 ? n / 10 : n % 10;
                ink = digit_pixel(d, (lx % 12) / 3, ly / 3);
            }
            bool bright = dark == ink;
            im[(size_t)y * (size_t)w + (size_t)x] = bright ? rgb(r, g, b) : rgb(r / 3, g / 3, b / 3);
        }
}

/* A brick colour from its row and column, varied by a small hash. */
static uint32_t brick_colour(int row, int col)
{
    unsigned k = (unsigned)(row * 7919 + col * 104729) * 2654435761u >> 26;  /* 0..63 */
    return rgb(150 + k, 60 + k / 2, 40 + k / 4);
}

/* Bricks of 64 x 32 texels, mortar 4 texels wide along the top and left of
 * each brick, odd rows shifted by 32 texels. */
static void bricks(uint32_t *im, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int row = y / 32, sx = x + (row & 1) * 32, col = sx / 64;
            bool mortar = y % 32 < 4 || sx % 64 < 4;
            im[(size_t)y * (size_t)w + (size_t)x] = mortar ? rgb(200, 195, 185) : brick_colour(row, col % (w / 64));
        }
}

/* A gradient (red across, green down) under lines: one texel wide every 8
 * texels, two every 32, white and four wide every 128. */
static void grid(uint32_t *im, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t c = rgb((unsigned)(255 * x / (w - 1)), (unsigned)(255 * y / (h - 1)), 96);
            if (x % 128 < 4 || y % 128 < 4)
                c = rgb(255, 255, 255);
            else if (x % 32 < 2 || y % 32 < 2)
                c = rgb(20, 20, 40);
            else if (x % 8 == 0 || y % 8 == 0)
                c = rgb(60, 60, 90);
            im[(size_t)y * (size_t)w + (size_t)x] = c;
        }
}

static void rgby(uint32_t *im, int w, int h)
{
    (void)w, (void)h;
    im[0] = rgb(255, 0, 0), im[1] = rgb(0, 255, 0);
    im[2] = rgb(0, 0, 255), im[3] = rgb(255, 255, 0);
}

/* Red stripes one texel wide across, green ones down, under bands of eight
 * texels across and four down: every level of its pyramid differs from the
 * next, and its width is not its height. */
static void plaid(uint32_t *im, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            im[(size_t)y * (size_t)w + (size_t)x] = rgb(110 * (unsigned)(x & 1) + 145 * (unsigned)(x >> 3 & 1),
                                                        90 * (unsigned)(y & 1) + 165 * (unsigned)(y >> 2 & 1),
                                                        (unsigned)(8 * x));
}

static const struct {
    int w, h;
    void (*make)(uint32_t *im, int w, int h);
} makers[] = { { 256, 256, checker_numbers }, { 256, 256, bricks }, { 256, 256, grid }, { 2, 2, rgby }, { 32, 8, plaid } };

/* noise-WxH: texels of hashed colours, any two neighbours far apart, at any
 * size the format allows (1 x 1 to 4096 x 4096): the textures of every
 * shape that make check's search draws. */
static bool noise_size(const char *name, int *w, int *h)
{
    long a, b;
    char tail;
    if (sscanf(name, "noise-%ldx%ld%c", &a, &b, &tail) != 2 || !texture_size_ok(a) || !texture_size_ok(b))
        return false;
    char canon[40];
    snprintf(canon, sizeof canon, "noise-%ldx%ld", a, b);
    if (strcmp(canon, name) != 0)
        return false;
    *w = (int)a, *h = (int)b;
    return true;
}

static void noise(uint32_t *im, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t k = ((uint32_t)x * 73856093u) ^ ((uint32_t)y * 19349663u) ^ 0x5bd1e995u;
            k ^= k >> 13, k *= 0x5bd1e995u, k ^= k >> 15;
            /* a checkerboard's parity under the hash: neighbours differ by 128 or more in red */
            unsigned r = ((unsigned)(x + y) & 1) * 160 + (k & 63), g = k >> 8 & 255, b = k >> 16 & 255;
            im[(size_t)y * (size_t)w + (size_t)x] = rgb(r, g, b);
        }
}

bool texture_builtin(const char *name, int *w, int *h, uint32_t **image, char *why, size_t n)
{
    *image = NULL;
    if (noise_size(name, w, h)) {
        *image = malloc((size_t)*w * (size_t)*h * sizeof **image);
        if (!*image) {
            snprintf(why, n, "out of memory");
            return false;
        }
        noise(*image, *w, *h);
        return true;
    }
    for (int i = 0; builtin_textures[i].name; i++)
        if (strcmp(builtin_textures[i].name, name) == 0) {
            *w = makers[i].w;
            *h = makers[i].h;
            *image = malloc((size_t)*w * (size_t)*h * sizeof **image);
            if (!*image) {
                snprintf(why, n, "out of memory");
                return false;
            }
            makers[i].make(*image, *w, *h);
            return true;
        }
    int len = snprintf(why, n, "no built-in texture '%.40s' (there are", name);
    for (int i = 0; builtin_textures[i].name && len >= 0 && (size_t)len < n; i++)
        len += snprintf(why + len, n - (size_t)len, " builtin:%s", builtin_textures[i].name);
    if (len >= 0 && (size_t)len < n)
        snprintf(why + len, n - (size_t)len, " builtin:noise-WxH)");
    return false;
}
