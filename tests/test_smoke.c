#include <criterion/criterion.h>
#include "raster/raster.h"

Test(raster, snap_rounds_ties_to_even)
{
    cr_expect_eq(snap_coord(0.5 / 256, 8), 0);
    cr_expect_eq(snap_coord(1.5 / 256, 8), 2);
}
