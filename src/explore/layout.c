/* layout.c - where the explorer's parts go in a frame of a given size, the
 * zoom and pan that move the pixel grid in it, the vertex under the mouse,
 * the names of the themes and figure parts, and a theme's background. */
#include "explorer.h"

#include <math.h>
#include <string.h>

static const char *const theme_names[THEME_COUNT] = { "dark", "light" };
static const char *const part_names[PART_COUNT] = { "all", "canvas" };
static const char *const paper_names[PAPER_COUNT] = { "", "a4", "letter" };

/* The index of `name` in names[0..n), or -1. */
static int name_index(const char *const *names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *theme_name(enum theme t)
{
    return t >= 0 && t < THEME_COUNT ? theme_names[t] : "?";
}

bool theme_from_name(const char *name, enum theme *out)
{
    int i = name_index(theme_names, THEME_COUNT, name);
    if (i >= 0)
        *out = (enum theme)i;
    return i >= 0;
}

void theme_background(struct explorer *ex, enum theme t)
{
    ex->theme = t;
    for (int c = 0; c < 3; c++)
        ex->scene.background[c] = t == THEME_LIGHT ? 1.0 : ex->own_background[c];
}

const char *figure_part_name(enum figure_part f)
{
    return f >= 0 && f < PART_COUNT ? part_names[f] : "?";
}

bool paper_from_name(const char *name, enum paper *out)
{
    int i = name_index(paper_names + 1, PAPER_COUNT - 1, name);
    if (i >= 0)
        *out = (enum paper)(i + 1);
    return i >= 0;
}

bool figure_part_from_name(const char *name, enum figure_part *out)
{
    int i = name_index(part_names, PART_COUNT, name);
    if (i >= 0)
        *out = (enum figure_part)i;
    return i >= 0;
}

void explorer_layout(const struct explorer *ex, double w, double h, struct explorer_layout *L)
{
    double s = ex->scale;
    L->s = s;
    L->w = w, L->h = h;
    bool canvas_only = ex->part == PART_CANVAS;   /* the grid alone fills the frame */
    L->pw = canvas_only ? 0 : fmin(430 * s, w * 0.45);
    L->px = w - L->pw;
    L->bar_h = canvas_only ? 0 : 46 * s;
    L->cx = 0, L->cy = 0;
    L->cw = L->px, L->ch = h - L->bar_h;
    L->bar_y = L->ch;
    double zoom = ex->zoom, cx = ex->centre_x, cy = ex->centre_y;
    if (zoom <= 0) {
        /* fit the scene with a margin; whole screen pixels per pixel when
         * large enough, so every cell is crisp */
        double mx = 28 * s, my = 28 * s;
        zoom = fmin((L->cw - 2 * mx) / ex->scene.w, (L->ch - 2 * my) / ex->scene.h);
        if (zoom >= 4)
            zoom = floor(zoom);
        if (!(zoom > 0))
            zoom = 1;
        cx = ex->scene.w / 2.0, cy = ex->scene.h / 2.0;
    }
    L->zoom = zoom;
    L->ox = L->cx + L->cw / 2 - cx * zoom;
    L->oy = L->cy + L->ch / 2 - cy * zoom;
    if (zoom >= 4) {
        L->ox = round(L->ox);
        L->oy = round(L->oy);
    }
}

void explorer_zoom_at(struct explorer *ex, const struct explorer_layout *L, double sx, double sy,
                      double factor)
{
    double px = (sx - L->ox) / L->zoom, py = (sy - L->oy) / L->zoom;
    double z = fmin(fmax(L->zoom * factor, 0.05), 512);
    ex->zoom = z;
    ex->centre_x = px + (L->cx + L->cw / 2 - sx) / z;
    ex->centre_y = py + (L->cy + L->ch / 2 - sy) / z;
}

void explorer_pan(struct explorer *ex, const struct explorer_layout *L, double dx, double dy)
{
    if (ex->zoom <= 0) {
        ex->centre_x = (L->cx + L->cw / 2 - L->ox) / L->zoom;
        ex->centre_y = (L->cy + L->ch / 2 - L->oy) / L->zoom;
        ex->zoom = L->zoom;
    }
    ex->centre_x -= dx / ex->zoom;
    ex->centre_y -= dy / ex->zoom;
}

int explorer_hit_vertex(const struct explorer *ex, const struct explorer_layout *L,
                        double sx, double sy)
{
    if (ex->scene.ntris == 0)
        return -1;
    int best = -1;
    double best_d = 12 * L->s;
    for (int k = 0; k < 3; k++) {
        double vx = L->ox + L->zoom * ex->tri.x[k] / SUBPIXEL_ONE;
        double vy = L->oy + L->zoom * ex->tri.y[k] / SUBPIXEL_ONE;
        double d = hypot(sx - vx, sy - vy);
        if (d < best_d)
            best = k, best_d = d;
    }
    return best;
}
