/* palette.c - the colours of the interface, named once (painter.h). The
 * explorer is dark on screen; another theme is another palette. */
#include "painter.h"

const struct palette palette_dark = {
    .bg = 0x15171c, .canvas = 0x1c1f26, .panel = 0x23262e, .rule = 0x343946,
    .text = 0xdde3ec, .dim = 0x8c95a6, .accent = 0xffd166, .hilite = 0x3a4358,
    .track = 0x3a4150,
    .grid = 0x000000, .centre = 0xffffff, .border = 0xffffff,
    .shadow = 0x000000,
    .box = 0x88c0d0, .pin = 0x5ce1e6, .handle_rim = 0x101014,
    .edge = { 0xf5a623, 0x4fc3f7, 0xc792ea },
    .vertex = { 0xff6b6b, 0x6bdc7a, 0x6b9dff },
    .covered = 0x7ec87e, .outside = 0x8f3b46, .untested = 0x3a4150,
    .earlier1 = 0x5b6270, .earlier2 = 0x9aa3b5, .empty_px = 0x1e2128,
    .pos = 0x3f8fd2, .neg = 0xd0505a, .zero = 0xffe066,
    .fail_one = 0xc0605f, .fail_two = 0x7a3440,
    .block_empty = 0x5a2a33, .block_full = 0x4f9d69, .block_partial = 0xd9a441,
    .partial_inside = 0xf0c674, .partial_outside = 0x8a6d2c,
    .span = 0x4fb3bf, .row = 0x39404e,
    .extra = 0xff4fd8, .missing = 0x00e5ff, .exhibit = 0xe0565b, .on_exhibit = 0xffffff,
    .wrong_colour = 0xb5f23d,
    .mark = 0xffffff, .probe = 0xff5080, .upper = 0x9e73ff, .lower = 0xff9933,
    .brighter = 0xffff8c, .deeper = 0x8cffbf,
};

/* For paper: dark ink on white, every cell light enough for black numbers
 * and dark enough to stand apart from the white page, the data colours
 * (the scene's own colours, barycentrics, depth) as they are. Printed in
 * grey, or seen by a red-green colour-blind reader, colour is lost, so the
 * cells a lesson is read by and the three edges are apart in lightness
 * alone, in CIE L*: not tested yet 93, outside 82, covered 69; outside one
 * edge 85, two 51; blocks empty 91, partial 77 (its pixels inside 78,
 * outside 61), full 47; edges 64, 46 and 21 (tests/test_print.c holds the
 * steps). */
const struct palette palette_light = {
    .bg = 0xffffff, .canvas = 0xffffff, .panel = 0xf4f4f2, .rule = 0xc4c8d0,
    .text = 0x111318, .dim = 0x50586a, .accent = 0xd9480f, .hilite = 0xffe3a3,
    .track = 0xd8dce4,
    .grid = 0xc8ccd4, .centre = 0x6a7282, .border = 0x111318,
    .shadow = 0xffffff,
    .box = 0x1f6f8b, .pin = 0x00838f, .handle_rim = 0xffffff,
    .edge = { 0xe8820c, 0x1f6fc0, 0x4a1a6e },
    .vertex = { 0xd32f2f, 0x2e8b3a, 0x2f5fd0 },
    .covered = 0x6fb86f, .outside = 0xf2bfc6, .untested = 0xe8ebf0,
    .earlier1 = 0xd3d8e2, .earlier2 = 0xa9b1c2, .empty_px = 0xffffff,
    .pos = 0x3f8fd2, .neg = 0xd0505a, .zero = 0xf2c200,
    .fail_one = 0xf4c9ce, .fail_two = 0xb5606b,
    .block_empty = 0xf7dfe1, .block_full = 0x2f7f45, .block_partial = 0xe8b845,
    .partial_inside = 0xe6bb52, .partial_outside = 0xb38d3c,
    .span = 0x86cdd6, .row = 0xe3e7ee,
    .extra = 0xe020b8, .missing = 0x00a8c6, .exhibit = 0xc0303a, .on_exhibit = 0xffffff,
    .wrong_colour = 0x5f9e00,
    .mark = 0x111318, .probe = 0xd6246e, .upper = 0x7a4fe0, .lower = 0xe07000,
    .brighter = 0x8a6d00, .deeper = 0x0f8a5f,
};

const struct palette *palette_of(enum theme t)
{
    return t == THEME_LIGHT ? &palette_light : &palette_dark;
}

uint32_t mix(uint32_t a, uint32_t b, double t)
{
    uint32_t out = 0;
    for (int sh = 0; sh <= 16; sh += 8) {
        double v = (a >> sh & 255) * (1 - t) + (b >> sh & 255) * t;
        out |= (uint32_t)(v + 0.5) << sh;
    }
    return out;
}

uint32_t from_rgb(double r, double g, double b)
{
    return pack_rgb(r, g, b) & 0xffffff;
}

double luma(uint32_t c)
{
    return (0.299 * (c >> 16 & 255) + 0.587 * (c >> 8 & 255) + 0.114 * (c & 255)) / 255;
}
