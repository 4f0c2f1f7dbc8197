/* patch.h - the pixels of a picture that changed, with their new values:
 * how the replay keeps its checkpoints (replay.h) in a fraction of a
 * picture's memory each.
 *
 * A patch holds runs of pixels (row-major indices, ascending, apart) and,
 * pixel after pixel in run order, their colour, depth, coverage count and
 * samples. Applied to the picture it was taken against, it gives the
 * picture it was taken from. A patch of every pixel (patch_whole) applies
 * to any picture of that size: it is the picture itself.
 *
 * Between two checkpoints of a scene of small triangles most pixels stay
 * as they were, so a checkpoint kept as a patch against the one before
 * costs what its triangles wrote, not a whole picture; a picture far back
 * is a whole patch followed by the patches after it. */
#ifndef TRISTEP_PATCH_H
#define TRISTEP_PATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "raster/raster.h"

struct patch {
    int nruns;
    uint32_t *runs;         /* nruns pairs: first pixel, number of pixels */
    size_t npix;            /* pixels in the runs */
    int samples;            /* samples per pixel stored (0: the target has none) */
    uint32_t *color;        /* npix of each, in run order */
    float *depth;
    uint8_t *count;
    uint32_t *scolor;       /* npix * samples of these */
    float *sdepth;
    size_t bytes;           /* the one block holding all of the above */
};

/* Every pixel of t. */
bool patch_whole(struct patch *p, const struct target *t);
/* The pixels where now differs from before (the same size and samples):
 * colour, depth bits, count or any sample. A few unchanged pixels between
 * two changed ones join their runs (cheaper than a run more). */
bool patch_diff(struct patch *p, const struct target *now, const struct target *before);
/* One patch doing what `older` then `newer` do: their pixels, the newer's
 * values where both have one. */
bool patch_merge(struct patch *p, const struct patch *older, const struct patch *newer);
/* Write p's pixels into t (of the size and samples it was taken from). */
void patch_apply(const struct patch *p, struct target *t);
/* Does p hold every one of n pixels? */
bool patch_is_whole(const struct patch *p, size_t n);
void patch_free(struct patch *p);

#endif
