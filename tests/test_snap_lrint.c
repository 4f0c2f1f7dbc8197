/* test_snap_lrint.c - snap_coord() rounds without calling lrint(); it must
 * still be lrint(ldexp(v, bits)) on every input, as lessons/CONVENTIONS.md defines
 * snapping: for every precision, on ties, just beside ties, across the whole
 * coordinate range and at its ends. */
#include <criterion/criterion.h>
#include <math.h>

#include "testlib.h"

/* The definition, with the library's rounding. */
static int32_t snap_by_lrint(double v, int bits)
{
    if (!(v > -COORD_LIMIT))
        v = -COORD_LIMIT;
    if (v > COORD_LIMIT)
        v = COORD_LIMIT;
    return (int32_t)(lrint(ldexp(v, bits)) * (1L << (SUBPIXEL_BITS - bits)));
}

static void check(double v, int bits)
{
    cr_assert_eq(snap_coord(v, bits), snap_by_lrint(v, bits), "snap_coord(%.17g, %d) = %d, lrint says %d",
                 v, bits, snap_coord(v, bits), snap_by_lrint(v, bits));
}

Test(snap_lrint, equals_lrint_on_ties_their_neighbours_and_random_values)
{
    struct rng r = rng_for(0x5a4b);
    int checked = 0;
    for (int bits = 0; bits <= SUBPIXEL_BITS; bits++) {
        double unit = ldexp(1.0, -bits);
        for (int i = 0; i < 40000; i++) {
            double v = rng_range(&r, -COORD_LIMIT, COORD_LIMIT);
            double tie = (floor(v / unit) + 0.5) * unit;   /* exactly halfway */
            check(v, bits);
            check(tie, bits);
            check(nextafter(tie, INFINITY), bits);
            check(nextafter(tie, -INFINITY), bits);
            checked += 4;
        }
    }
    double ends[] = { -COORD_LIMIT, COORD_LIMIT, nextafter(COORD_LIMIT, 0), nextafter(-COORD_LIMIT, 0),
                      -COORD_LIMIT + 1.0 / 512, COORD_LIMIT - 1.0 / 512, 0.0, -0.0,
                      0.5 / 256, -0.5 / 256, 1.5 / 256, -1.5 / 256, 0x1p-30, -0x1p-30 };
    for (int bits = 0; bits <= SUBPIXEL_BITS; bits++)
        for (size_t i = 0; i < sizeof ends / sizeof ends[0]; i++, checked++)
            check(ends[i], bits);
    cr_assert_gt(checked, 1000000);
}
