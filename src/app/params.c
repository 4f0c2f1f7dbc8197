/* params.c - the keys that change a lesson's parameters (params.h). */
#include "params.h"

#include <stdio.h>

bool params_key(unsigned params, int key, struct raster_params *p, char *what, size_t n)
{
    switch (key) {
    case '[': case ']':
        if (!(params & LESSON_PARAM_SUBPIXEL))
            return false;
        p->subpixel_bits += key == '[' ? -1 : 1;
        p->subpixel_bits = p->subpixel_bits < 0 ? 0 : p->subpixel_bits > 8 ? 8 : p->subpixel_bits;
        snprintf(what, n, "sub-pixel bits: %d", p->subpixel_bits);
        return true;
    case 'b': {
        if (!(params & LESSON_PARAM_BLOCK))
            return false;
        int q = p->block_size ? p->block_size : 8;
        p->block_size = q == 4 ? 8 : q == 8 ? 16 : 4;
        snprintf(what, n, "block size %d x %d", p->block_size, p->block_size);
        return true;
    }
    case 'm': {
        if (!(params & LESSON_PARAM_SAMPLES))
            return false;
        int s = p->samples > 1 ? p->samples : 1;
        p->samples = s == 1 ? 4 : s == 4 ? 8 : 1;
        snprintf(what, n, "%d sample%s per pixel", p->samples, p->samples == 1 ? "" : "s");
        return true;
    }
    case 'p':
        if (!(params & LESSON_PARAM_AFFINE))
            return false;
        p->affine = !p->affine;
        snprintf(what, n, "%s", p->affine ? "affine texturing (the exhibit)" : "perspective-correct");
        return true;
    default:
        return false;
    }
}
