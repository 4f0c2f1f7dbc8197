/* Lesson 07, what the explorer adds (compiled only in the narrated build;
 * the algorithm is tiles.c).
 *
 * The tiles view: the 64 x 64 tile grid over the picture, each tile tinted by
 * how many triangles its bin holds and labelled with its bin size and the
 * worker that drew it in the run the explorer steps through; the current
 * tile outlined, its bin listed with the current triangle in brackets.
 *
 * In the tiles, blocks and coverage views, for the tile or 8 x 8 block just
 * classified, each edge's two corners (Greene's test): a ring in the edge's
 * colour on its trivial-reject corner (where the edge function is largest:
 * negative there means the whole rectangle is outside) and a filled disc on
 * its trivial-accept corner (where it is smallest: non-negative there means
 * the whole rectangle is inside that edge). */
#include <stdio.h>
#include <string.h>

#include "lesson_explorer.h"

extern const struct lesson lesson_07;

#include "tiles.h"     /* TILE */

static const enum ink edge_ink[3] = { INK_EDGE_AB, INK_EDGE_BC, INK_EDGE_CA };

static void rect(const struct lesson_canvas *c, double x0, double y0, double x1, double y1,
                 struct pen pen)
{
    c->polygon(c, (const double[][2]){ { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } }, 4, pen);
}

/* The reject and accept corners of each edge on the rectangle of pixel
 * centres x0..x1, y0..y1: picked by the signs of I and J, as bins.c picks them. */
static void corners(const struct lesson_canvas *c, const struct tri_setup *t, int x0, int y0,
                    int x1, int y1)
{
    for (int k = 0; k < 3; k++) {
        double off = (k - 1) * 4.0 * c->unit;     /* three edges side by side */
        double rx = (t->I[k] > 0 ? x1 : x0) + 0.5 + off, ry = (t->J[k] > 0 ? y1 : y0) + 0.5;
        double ax = (t->I[k] < 0 ? x1 : x0) + 0.5 + off, ay = (t->J[k] < 0 ? y1 : y0) + 0.5;
        c->disc(c, rx, ry, 5, (struct pen){ .stroke = edge_ink[k], .width = 2 });
        c->disc(c, ax, ay, 3.5, (struct pen){ .fill = edge_ink[k] });
    }
}

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    bool tiles = strcmp(c->view, "tiles") == 0;
    if (last && last->kind == TRACE_BLOCK && last->klass < BLOCK_CLASS_COUNT && t->area2 > 0
        && (tiles || !strcmp(c->view, "blocks") || !strcmp(c->view, "coverage")))
        corners(c, t, last->x, last->y, last->x1, last->y1);
    const struct run_place *at = p->at;
    if (!tiles || !at || !at->units || t->target_w <= 0)
        return;

    /* bin sizes and workers per tile, from the run's steps: each tile's
     * first entry drawn says both */
    int nx = (t->target_w + TILE - 1) / TILE, ny = (t->target_h + TILE - 1) / TILE;
    int most = 1;
    for (int u = 0; u < at->nunits; u++)
        most = at->units[u].bin_size > most ? at->units[u].bin_size : most;
    for (int u = 0; u < at->nunits; u++) {
        const struct lesson_unit *un = &at->units[u];
        if (un->tile < 0 || un->bin_entry != 0)
            continue;
        double x0 = (un->tile % nx) * TILE, y0 = (double)(un->tile / nx) * TILE;
        double x1 = x0 + TILE < t->target_w ? x0 + TILE : t->target_w;
        double y1 = y0 + TILE < t->target_h ? y0 + TILE : t->target_h;
        rect(c, x0, y0, x1, y1, (struct pen){ .fill = INK_BRIGHTER,
                                              .alpha = 0.06 + 0.3 * un->bin_size / most });
        char text[64];
        snprintf(text, sizeof text, "bin %d, worker %d", un->bin_size, un->thread);
        c->label(c, x0 + 1, y0 + 1, text, 11, INK_TEXT);
    }
    for (int i = 1; i < nx; i++)
        c->line(c, i * TILE, 0, i * TILE, t->target_h, (struct pen){ .stroke = INK_MARK, .alpha = 0.6 });
    for (int j = 1; j < ny; j++)
        c->line(c, 0, j * TILE, t->target_w, j * TILE, (struct pen){ .stroke = INK_MARK, .alpha = 0.6 });

    /* the current tile and its bin, triangles numbered as the scene
     * numbers them from 1 */
    if (!at->unit || at->unit->tile < 0)
        return;
    int tile = at->unit->tile;
    double x0 = (tile % nx) * TILE, y0 = (double)(tile / nx) * TILE;
    double x1 = x0 + TILE < t->target_w ? x0 + TILE : t->target_w;
    double y1 = y0 + TILE < t->target_h ? y0 + TILE : t->target_h;
    rect(c, x0, y0, x1, y1, (struct pen){ .stroke = INK_MARK, .width = 2.5, .dashed = true });
    char list[256];
    int end = snprintf(list, sizeof list, "tile %d's bin, triangles:", tile);
    for (int u = 0; u < at->nunits && end < (int)sizeof list - 16; u++)
        if (at->units[u].tile == tile)
            end += snprintf(list + end, sizeof list - (size_t)end,
                            at->units[u].bin_entry == at->unit->bin_entry ? " [%u]" : " %u",
                            at->units[u].tri + 1);
    c->label(c, x0 + 1, y1 - 14 * c->unit * 1.4, list, 12, INK_TEXT);
}

/* The tiles view colours the pixels the current triangle wrote in this
 * tile; the rest of the picture is shown dimmed under the grid. */
static bool tiles_cell(const struct tri_setup *t, const struct trace_event *test,
                       const struct trace_event *write, double rgb[3])
{
    (void)t, (void)test;
    if (!write)
        return false;
    rgb[0] = (write->rgba >> 16 & 255) / 255.0;
    rgb[1] = (write->rgba >> 8 & 255) / 255.0;
    rgb[2] = (write->rgba & 255) / 255.0;
    return true;
}

static const struct lesson_view views[] = {
    { "tiles", "64 x 64 tiles tinted by bin size; bin and worker per tile; the current "
      "tile dashed, its bin listed; rings: reject corners, discs: accept corners", tiles_cell },
};

/* The watch panel: where the step stands in the run. */
static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    (void)t, (void)ev;
    const struct lesson_unit *u = p->at ? p->at->unit : NULL;
    if (!u) {
        buf[0] = '\0';
        return;
    }
    if (u->tile < 0) {
        snprintf(buf, n, "set-up and binning");
        return;
    }
    snprintf(buf, n, "tile = %d\nbin entry = %d of %d\ndrawn by worker %d", u->tile,
             u->bin_entry + 1, u->bin_size, u->thread);
}

const struct lesson_explorer lesson_07_explorer = {
    .lesson = &lesson_07,
    .views = views,
    .nviews = 1,
    .overlay = overlay,
    .watch = watch,
};
