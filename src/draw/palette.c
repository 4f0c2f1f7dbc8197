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
    .mark = 0xffffff, .probe = 0xff5080, .upper = 0x9e73ff, .lower = 0xff9933,
    .brighter = 0xffff8c, .deeper = 0x8cffbf,
};

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
