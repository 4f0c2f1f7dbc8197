/* png_none.c - texture_read_png for the builds without cairo (the portable
 * exactness driver, lesson 07's ThreadSanitizer program): a scene naming a
 * PNG texture is refused there, as any unreadable texture is; the textures
 * made by code (builtin:NAME) are read as everywhere. */
#include <stdio.h>

#include "scene/texture.h"

bool texture_read_png(const char *path, int *w, int *h, uint32_t **image, char *why, size_t n)
{
    (void)path;
    *w = *h = 0;
    *image = NULL;
    snprintf(why, n, "this build reads no PNG files (it is built without cairo)");
    return false;
}
