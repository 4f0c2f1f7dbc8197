/* png.c - a PNG texture read through cairo (lessons/CONVENTIONS.md, "Textures").
 *
 * Before cairo decodes anything, the file's signature and its IHDR chunk
 * (the first 33 bytes) are read here: a size that is not a power of two in
 * 1..4096 is refused without decoding, so a file that claims 30,000 x
 * 30,000 texels never costs the memory. cairo then reads grey, palette and
 * RGB images as opaque RGB24, and anything with alpha as ARGB32, whose
 * alpha must be 255 everywhere. */
#include "texture.h"

#include <cairo.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint32_t big_endian(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* The size the PNG's header gives, checked. */
static bool png_header(const char *path, long *w, long *h, char *why, size_t n)
{
    static const unsigned char signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, n, "cannot open: %s", strerror(errno));
        return false;
    }
    unsigned char b[24];
    size_t got = fread(b, 1, sizeof b, f);
    fclose(f);
    if (got < 8 || memcmp(b, signature, 8) != 0) {
        snprintf(why, n, "not a PNG file (no PNG signature)");
        return false;
    }
    if (got < sizeof b || memcmp(b + 12, "IHDR", 4) != 0) {
        snprintf(why, n, "malformed PNG (no IHDR chunk after the signature)");
        return false;
    }
    *w = (long)big_endian(b + 16);
    *h = (long)big_endian(b + 20);
    if (!texture_size_ok(*w) || !texture_size_ok(*h)) {
        snprintf(why, n, "texture size %ld x %ld: width and height must be powers of two "
                 "in 1..%d", *w, *h, TEXTURE_SIZE_MAX);
        return false;
    }
    return true;
}

bool texture_read_png(const char *path, int *w, int *h, uint32_t **image, char *why, size_t n)
{
    long hw, hh;
    *image = NULL;
    if (!png_header(path, &hw, &hh, why, n))
        return false;
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    cairo_status_t st = cairo_surface_status(s);
    if (st != CAIRO_STATUS_SUCCESS) {
        snprintf(why, n, "malformed PNG (cairo: %s)", cairo_status_to_string(st));
        cairo_surface_destroy(s);
        return false;
    }
    cairo_format_t format = cairo_image_surface_get_format(s);
    int sw = cairo_image_surface_get_width(s), sh = cairo_image_surface_get_height(s);
    int stride = cairo_image_surface_get_stride(s);
    bool ok = (format == CAIRO_FORMAT_RGB24 || format == CAIRO_FORMAT_ARGB32) && sw == hw && sh == hh;
    if (!ok)
        snprintf(why, n, "malformed PNG (cairo read it as %d x %d of format %d)", sw, sh, (int)format);
    uint32_t *out = ok ? malloc((size_t)sw * (size_t)sh * sizeof *out) : NULL;
    if (ok && !out) {
        snprintf(why, n, "out of memory for %d x %d texels", sw, sh);
        ok = false;
    }
    cairo_surface_flush(s);
    const unsigned char *data = cairo_image_surface_get_data(s);
    for (int y = 0; ok && y < sh; y++) {
        const uint32_t *row = (const uint32_t *)(const void *)(data + (size_t)y * (size_t)stride);
        for (int x = 0; x < sw; x++) {
            uint32_t c = row[x];
            if (format == CAIRO_FORMAT_ARGB32 && (c >> 24) != 255) {
                snprintf(why, n, "texel (%d, %d) has alpha %u: textures are opaque (alpha 255 "
                         "everywhere)", x, y, (unsigned)(c >> 24));
                ok = false;
                break;
            }
            out[(size_t)y * (size_t)sw + (size_t)x] = c | 0xff000000u;
        }
    }
    cairo_surface_destroy(s);
    if (!ok) {
        free(out);
        return false;
    }
    *w = sw;
    *h = sh;
    *image = out;
    return true;
}
