/* agree.c - how two pictures compare: coverage counts pixel by pixel, and
 * colours by agreement where a reference covers pixels, the bench's measure
 * of lesson 09 against llvmpipe on textured scenes (lessons/CONVENTIONS.md: real
 * samplers differ from the reference by design, so they are compared by
 * agreement, never held to equality). */
#include "bench.h"

struct bench_agree bench_agreement(const uint32_t *a, const uint32_t *b, const uint8_t *covered,
                                   size_t n)
{
    struct bench_agree g = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++) {
        if (!covered[i])
            continue;
        int most = 0;
        for (int shift = 0; shift < 24; shift += 8) {
            int d = (int)(a[i] >> shift & 255) - (int)(b[i] >> shift & 255);
            d = d < 0 ? -d : d;
            most = d > most ? d : most;
        }
        g.pixels++;
        g.within2 += most <= 2;
        g.within8 += most <= 8;
    }
    return g;
}

int64_t bench_count_diff(const uint8_t *a, const uint8_t *b, size_t n)
{
    int64_t d = 0;
    for (size_t i = 0; i < n; i++)
        d += a[i] != b[i];
    return d;
}
