/* Lesson 05, what the explorer adds (compiled only in the narrated build;
 * the algorithm is block_classification.c).
 *
 * In the blocks and coverage views, at each of the four corner pixel centres
 * of the block just classified, three small discs, one per edge in the
 * edge's colour from left to right (F01, F02, F03): filled with a "+" when the
 * corner is inside that edge (its bit of the mask is set), hollow with a "-"
 * when it is outside. The class follows from the twelve signs: one edge all
 * "-" is empty, all twelve "+" is full, anything else partial. */
#include <string.h>

#include "lesson_explorer.h"

extern const struct lesson lesson_05;

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    (void)t, (void)p;
    if (!last || last->kind != TRACE_BLOCK)
        return;
    if (strcmp(c->view, "blocks") != 0 && strcmp(c->view, "coverage") != 0)
        return;
    static const enum ink edge_ink[3] = { INK_EDGE_AB, INK_EDGE_BC, INK_EDGE_CA };
    const double u = c->unit, r = 4.5 * u, gap = 10.5 * u;
    /* corners as corner_masks() numbers them: bit 3 top-left ... bit 0 bottom-right */
    const int cx[4] = { last->x1, last->x, last->x1, last->x };
    const int cy[4] = { last->y1, last->y1, last->y, last->y };
    for (int bit = 0; bit < 4; bit++) {
        double x = cx[bit] + 0.5, y = cy[bit] + 0.5;
        double w = 1.5 * gap, h = 0.6 * gap;
        c->polygon(c, (const double[][2]){ { x - w, y - h }, { x + w, y - h }, { x + w, y + h },
                                           { x - w, y + h } }, 4,
                   (struct pen){ .fill = INK_BACKING, .alpha = 0.75 });
        for (int k = 0; k < 3; k++) {
            double dx = x + (k - 1) * gap;
            bool in = (last->mask[k] >> bit) & 1;
            /* inside: a filled disc with a dark "+"; outside: a ring with a "-" */
            c->disc(c, dx, y, r / u, in ? (struct pen){ .fill = edge_ink[k] }
                                        : (struct pen){ .stroke = edge_ink[k], .width = 1.5 });
            struct pen sign = { .stroke = in ? INK_OUTLINE : edge_ink[k], .width = 1.5 };
            c->line(c, dx - r * 0.6, y, dx + r * 0.6, y, sign);
            if (in)
                c->line(c, dx, y - r * 0.6, dx, y + r * 0.6, sign);
        }
    }
}

const struct lesson_explorer lesson_05_explorer = {
    .lesson = &lesson_05,
    .overlay = overlay,
};
