/* test_patch.c - the changed pixels of a picture (src/explore/patch.h), as
 * the replay keeps its checkpoints: a patch taken between two pictures
 * turns the first into the second, two patches merged do what both do in
 * turn, and a whole patch is the picture, samples included. */
#include <criterion/criterion.h>
#include <string.h>

#include "explore/patch.h"
#include "testlib.h"

static bool same(const struct target *a, const struct target *b)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    if (memcmp(a->color, b->color, n * sizeof *a->color) || memcmp(a->depth, b->depth, n * 4)
        || memcmp(a->count, b->count, n) || !a->samples != !b->samples)
        return false;
    if (!a->samples)
        return true;
    size_t m = n * (size_t)a->samples->n;
    return a->samples->n == b->samples->n
           && !memcmp(a->samples->color, b->samples->color, m * sizeof *a->samples->color)
           && !memcmp(a->samples->depth, b->samples->depth, m * sizeof *a->samples->depth);
}

/* Change `k` random pixels of t, a part of them in one field only (a
 * sample, the sign of a zero depth), a part in clusters. */
static void scribble(struct target *t, struct rng *r, int k)
{
    size_t n = (size_t)t->w * (size_t)t->h;
    for (int j = 0; j < k; j++) {
        size_t i = (size_t)rng_int(r, 0, (int)n - 1);
        int len = rng_chance(r, 0.3) ? rng_int(r, 1, 12) : 1;
        for (size_t e = i; e < i + (size_t)len && e < n; e++)
            switch (rng_int(r, 0, 4)) {
            case 0: t->color[e] = (uint32_t)rng_next(r); break;
            case 1: t->depth[e] = t->depth[e] == 0.0f ? -0.0f : (float)rng_unit(r); break;
            case 2: t->count[e]++; break;
            case 3:
                if (t->samples)
                    t->samples->color[e * (size_t)t->samples->n + (size_t)rng_int(r, 0, t->samples->n - 1)]
                        ^= 1;
                else
                    t->depth[e] = 0.0f;
                break;
            default: t->color[e] ^= 0x10101; t->count[e] += 2; break;
            }
    }
}

Test(patch, diff_merge_and_whole_rebuild_every_picture)
{
    for (int samples = 1; samples <= 4; samples += 3) {
        struct rng r = rng_for(0x9a7c4 + (uint64_t)samples);
        struct target pic[4] = { 0 };
        cr_assert(target_init(&pic[0], 97, 61, 0xff102030u));
        cr_assert(target_multisample(&pic[0], samples));
        for (int k = 1; k < 4; k++) {
            cr_assert(target_copy(&pic[k], &pic[k - 1]));
            scribble(&pic[k], &r, 40 + 30 * k);
        }
        struct patch whole, d[3], merged;
        cr_assert(patch_whole(&whole, &pic[0]));
        cr_assert(patch_is_whole(&whole, (size_t)97 * 61));
        for (int k = 0; k < 3; k++) {
            cr_assert(patch_diff(&d[k], &pic[k + 1], &pic[k]));
            cr_assert_not(patch_is_whole(&d[k], (size_t)97 * 61));
            cr_assert_lt(d[k].bytes, whole.bytes / 4, "a few changes cost a few pixels");
        }
        cr_assert(patch_merge(&merged, &d[0], &d[1]));

        struct target t = { 0 };    /* anything of the size: the whole patch makes it picture 0 */
        cr_assert(target_copy(&t, &pic[3]));
        scribble(&t, &r, 500);
        patch_apply(&whole, &t);
        cr_assert(same(&t, &pic[0]), "%d samples: the whole patch", samples);
        patch_apply(&d[0], &t);
        cr_assert(same(&t, &pic[1]), "%d samples: picture 0 and a patch", samples);
        patch_apply(&d[1], &t);
        patch_apply(&d[2], &t);
        cr_assert(same(&t, &pic[3]), "%d samples: the patches in turn", samples);

        patch_apply(&whole, &t);
        patch_apply(&merged, &t);
        cr_assert(same(&t, &pic[2]), "%d samples: two patches merged", samples);

        struct patch all;           /* merged with the whole: whole again, of the later picture */
        cr_assert(patch_merge(&all, &whole, &merged));
        cr_assert(patch_is_whole(&all, (size_t)97 * 61));
        scribble(&t, &r, 500);
        patch_apply(&all, &t);
        cr_assert(same(&t, &pic[2]), "%d samples: whole and merged patches merged", samples);

        struct patch none;          /* no change: no pixel */
        cr_assert(patch_diff(&none, &pic[2], &pic[2]));
        cr_assert_eq(none.npix, 0);
        cr_assert_eq(none.nruns, 0);

        patch_free(&none);
        patch_free(&all);
        patch_free(&merged);
        for (int k = 0; k < 3; k++)
            patch_free(&d[k]);
        patch_free(&whole);
        target_free(&t);
        for (int k = 0; k < 4; k++)
            target_free(&pic[k]);
    }
}
