/* bigscene.c - very large scene files (see bigscene.h). */
#include "bigscene.h"

#include <math.h>

#define TAU 6.283185307179586

/* splitmix64, as every seeded generator of tristep */
static uint64_t next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static double range(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (double)(next(s) >> 11) * 0x1p-53;
}

bool big_scene_write(FILE *out, long n, uint64_t seed)
{
    uint64_t s = seed;
    fprintf(out, "# %ld small triangles, seed %llu (tests/bench/bigscene.c)\nsize %d %d\n", n,
            (unsigned long long)seed, BIG_SCENE_W, BIG_SCENE_H);
    for (long i = 0; i < n; i++) {
        /* three points about 120 degrees apart around a centre, 1.5 to
         * 4.5 pixels from it; every other triangle wound the other way */
        double r = range(&s, 1.5, 4.5), a = range(&s, 0, TAU);
        double cx = range(&s, 6, BIG_SCENE_W - 6), cy = range(&s, 6, BIG_SCENE_H - 6);
        double z = range(&s, 2, 99);
        int dir = next(&s) & 1 ? 1 : -1;
        fputs("tri", out);
        for (int k = 0; k < 3; k++, a += dir * (TAU / 3 + range(&s, -0.5, 0.5)))
            fprintf(out, "  %.4f %.4f %.3f %.6f %.6f %.6f", cx + r * cos(a), cy + r * sin(a),
                    z + range(&s, -0.5, 0.5), range(&s, 0, 1), range(&s, 0, 1), range(&s, 0, 1));
        if (fputc('\n', out) == EOF)
            return false;
    }
    return !ferror(out);
}

bool big_scene_file(const char *path, long n, uint64_t seed)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    bool ok = big_scene_write(f, n, seed);
    ok = fclose(f) == 0 && ok;
    if (!ok)
        remove(path);
    return ok;
}
