/* cracks.c - the seeded search behind lesson 06's walk-order exhibit: look
 * through the floors of cracks.h, seed by seed, for one where the float
 * clipper in each triangle's own walking order cracks the mesh, and report
 * every floor's counts beside those of the same float clipper in the
 * canonical order and of the exact front end (doubled pixels).
 *
 *     make build/crack-search && build/crack-search [FIRST [COUNT]]
 *
 * The seed it prints as the first with the most cracks is the one the
 * lesson text quotes and tests/test_lesson06.c recounts. */
#include <stdio.h>
#include <stdlib.h>

#include "cracks.h"

extern const struct lesson lesson_06;

int main(int argc, char **argv)
{
    uint64_t first = argc > 1 ? strtoull(argv[1], NULL, 0) : 1;
    int count = argc > 2 ? atoi(argv[2]) : 200;
    front_fn walk = lesson_front(&lesson_06, lesson_variant(&lesson_06, "walk-order"));
    front_fn canon = lesson_front(&lesson_06, lesson_variant(&lesson_06, "float-canonical"));
    uint64_t best = 0;
    int best_n = -1, found = 0;
    long canon_total = 0, exact_doubled = 0;
    for (uint64_t seed = first; seed < first + (uint64_t)count; seed++) {
        struct scene s;
        if (!crack_floor(&s, seed))
            return 1;
        int *want = crack_coverage(&s, front_scene), *w = crack_coverage(&s, walk), *c = crack_coverage(&s, canon);
        if (!want || !w || !c)
            return 1;
        struct cracks kw = crack_compare(want, w, s.w, s.h), kc = crack_compare(want, c, s.w, s.h),
                      ke = crack_compare(want, want, s.w, s.h);
        int n = kw.missed + kw.doubled;
        found += n > 0;
        canon_total += kc.missed + kc.doubled;
        exact_doubled += ke.doubled;
        if (n > 0)
            printf("seed %llu: %d world triangles; walk-order %d missed, %d doubled; canonical %d, %d\n",
                   (unsigned long long)seed, s.world.ntris, kw.missed, kw.doubled, kc.missed, kc.doubled);
        if (n > best_n)
            best_n = n, best = seed;
        free(want), free(w), free(c);
        scene_free(&s);
    }
    printf("%d of %d floors crack in walk order; the canonical order: %ld cracked pixels in all; exact: %ld doubled\n"
           "first with the most: seed %llu, %d pixels\n", found, count, canon_total, exact_doubled,
           (unsigned long long)best, best_n);
    return 0;
}
