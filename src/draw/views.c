/* views.c - the built-in views, in one table shaped like a lesson's own
 * views (struct lesson_view): a name, what a cell shows (its colour, and
 * the numbers written in it when zoomed in), and a legend. A lesson's views
 * follow the built-in ones in the view cycle. */
#include "views.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "painter.h"

const char *const edge_names[3] = { "F_ab", "F_bc", "F_ca" };
static const char *const edge_view_names[3] = { "edge-ab", "edge-bc", "edge-ca" };

const struct cell *cur_cell(const struct explorer *ex, int x, int y)
{
    return ex->cur >= 0 ? explorer_cell(ex, x, y) : NULL;
}

static int cell_flags(const struct explorer *ex, int x, int y)
{
    const struct cell *c = cur_cell(ex, x, y);
    return c ? c->flags : 0;
}

static size_t pixel(const struct explorer *ex, int x, int y)
{
    return (size_t)y * (size_t)ex->scene.w + (size_t)x;
}

/* The colour buffer at a pixel (on paper the scene is drawn on the page's
 * white: explorer_set_theme). */
static uint32_t buffer_colour(const struct view_ctx *v, int x, int y)
{
    return v->ex->fb.color[pixel(v->ex, x, y)] & 0xffffff;
}

/* A pixel the view says nothing about: the colour buffer, faded. */
static uint32_t dim(const struct view_ctx *v, int x, int y)
{
    return mix(buffer_colour(v, x, y), v->pal->canvas, 0.72);
}

void format_edge(char *buf, size_t n, int64_t F)
{
    double v = (double)F / (SUBPIXEL_ONE * SUBPIXEL_ONE);
    if (F == 0)
        snprintf(buf, n, "0");
    else if (fabs(v) < 10)
        snprintf(buf, n, "%.2f", v);
    else if (fabs(v) < 100)
        snprintf(buf, n, "%.1f", v);
    else
        snprintf(buf, n, "%.0f", v);
}

/* --- color: the colour buffer ---------------------------------------------------- */

static uint32_t color_cell(const struct view_ctx *v, int x, int y)
{
    return buffer_colour(v, x, y);
}

static int color_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    size_t i = pixel(v->ex, x, y);
    if (v->ex->fb.count[i] == 0)
        return 0;
    for (int k = 0; k < 3; k++)
        snprintf(out[k], 16, "%u", (unsigned)(v->ex->fb.color[i] >> (16 - 8 * k) & 255));
    return 3;
}

static int color_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    (void)note;
    out[0] = (struct swatch){ v->ex->fb.background & 0xffffff, "background (nothing drawn)" };
    return 1;
}

/* --- coverage: this triangle's tests, earlier triangles' counts ------------------- */

static bool in_box(const struct explorer *ex, int x, int y)
{
    return ex->cur >= 0 && !ex->tri.empty && x >= ex->tri.minx && x <= ex->tri.maxx
        && y >= ex->tri.miny && y <= ex->tri.maxy;
}

static uint32_t coverage_cell(const struct view_ctx *v, int x, int y)
{
    const struct palette *c = v->pal;
    int f = cell_flags(v->ex, x, y);
    if (f & CELL_INSIDE)
        return c->covered;
    if (f & CELL_TESTED)
        return c->outside;
    if (in_box(v->ex, x, y))
        return c->untested;
    uint8_t n = v->ex->fb.count[pixel(v->ex, x, y)];
    return n == 0 ? c->empty_px : n == 1 ? c->earlier1 : c->earlier2;
}

static int coverage_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    uint8_t n = v->ex->fb.count[pixel(v->ex, x, y)];
    if (n == 0)
        return 0;
    snprintf(out[0], 16, "%u", (unsigned)n);
    return 1;
}

static int coverage_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    (void)note;
    const struct palette *c = v->pal;
    out[0] = (struct swatch){ c->covered, "covered by this triangle" };
    out[1] = (struct swatch){ c->outside, "tested, outside" };
    out[2] = (struct swatch){ c->untested, "in the box, not tested yet" };
    if (v->ex->fb.samples && v->ex->fb.samples->n > 1) {
        /* lesson 08 counts covered samples, not pixels */
        out[3] = (struct swatch){ c->earlier1, "1 sample covered before" };
        out[4] = (struct swatch){ c->earlier2, "2 or more samples before" };
    } else {
        out[3] = (struct swatch){ c->earlier1, "covered once before" };
        out[4] = (struct swatch){ c->earlier2, "covered twice or more" };
    }
    return 5;
}

/* --- edges: the three edge values, or one of them ---------------------------------- */

static uint32_t edges_cell(const struct view_ctx *v, int x, int y)
{
    const struct explorer *ex = v->ex;
    const struct palette *pal = v->pal;
    const struct cell *c = cur_cell(ex, x, y);
    if (!c || !(c->flags & CELL_TESTED))
        return dim(v, x, y);
    if (ex->edge >= 0) {
        int64_t F = c->e[ex->edge];
        if (F == 0)
            return pal->zero;
        double t = sqrt(fmin(1.0, fabs((double)F) / (double)(ex->tri.area2 ? ex->tri.area2 : 1)));
        return mix(pal->canvas, F > 0 ? pal->pos : pal->neg, 0.25 + 0.75 * t);
    }
    int fails = 0;
    for (int k = 0; k < 3; k++)
        fails += !edge_inside(&ex->tri, k, c->e[k]);
    return (c->flags & CELL_INSIDE) ? pal->covered : fails == 1 ? pal->fail_one : pal->fail_two;
}

static int edges_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    const struct cell *c = cur_cell(v->ex, x, y);
    if (!c || !(c->flags & CELL_TESTED))
        return 0;
    if (v->ex->edge >= 0) {
        format_edge(out[0], 16, c->e[v->ex->edge]);
        return 1;
    }
    for (int k = 0; k < 3; k++)
        format_edge(out[k], 16, c->e[k]);
    return 3;
}

static int edges_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    (void)note;
    const struct palette *c = v->pal;
    if (v->ex->edge >= 0) {
        out[0] = (struct swatch){ c->pos, "F > 0: inner side" };
        out[1] = (struct swatch){ c->neg, "F < 0: outer side" };
        out[2] = (struct swatch){ c->zero, "F = 0: centre on the edge" };
    } else {
        out[0] = (struct swatch){ c->covered, "inside all three (fill rule)" };
        out[1] = (struct swatch){ c->fail_one, "outside one edge" };
        out[2] = (struct swatch){ c->fail_two, "outside two edges" };
    }
    return 3;
}

/* --- bary: the weights of A, B, C as red, green, blue ------------------------------ */

static uint32_t bary_cell(const struct view_ctx *v, int x, int y)
{
    const struct cell *c = cur_cell(v->ex, x, y);
    if (!c || !(c->flags & CELL_TESTED))
        return dim(v, x, y);
    uint32_t b = from_rgb(c->bary[0], c->bary[1], c->bary[2]);
    return (c->flags & CELL_INSIDE) ? b : mix(b, v->pal->canvas, 0.65);
}

static int bary_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    const struct cell *c = cur_cell(v->ex, x, y);
    if (!c || !(c->flags & CELL_TESTED))
        return 0;
    for (int k = 0; k < 3; k++)
        snprintf(out[k], 16, "%.2f", c->bary[k]);
    return 3;
}

static int bary_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    (void)v, (void)note;
    out[0] = (struct swatch){ 0xff0000, "alpha: weight of A (red)" };
    out[1] = (struct swatch){ 0x00ff00, "beta: weight of B (green)" };
    out[2] = (struct swatch){ 0x0000ff, "gamma: weight of C (blue)" };
    return 3;
}

/* --- depth: the depth buffer as grey, near is light --------------------------------- */

static uint32_t depth_cell(const struct view_ctx *v, int x, int y)
{
    float z = v->ex->fb.depth[pixel(v->ex, x, y)];
    if (!isfinite(z))
        return v->pal->empty_px;
    double t = 1 - (z - v->zmin) / (v->zmax - v->zmin);
    t = 0.2 + 0.8 * fmin(fmax(t, 0), 1);
    return from_rgb(t, t, t * 0.95 + 0.05);
}

static int depth_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    float z = v->ex->fb.depth[pixel(v->ex, x, y)];
    if (!isfinite(z))
        return 0;
    snprintf(out[0], 16, "%.3g", z);
    return 1;
}

static int depth_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    (void)v, (void)note;
    out[0] = (struct swatch){ 0xffffff, "near (small z)" };
    out[1] = (struct swatch){ 0x333333, "far" };
    return 2;
}

/* --- blocks and spans: what the later lessons narrate ------------------------------ */

static const char none_yet[] = "(this lesson narrates none: they come in later lessons)";

static uint32_t blocks_cell(const struct view_ctx *v, int x, int y)
{
    const struct palette *pal = v->pal;
    const struct cell *c = cur_cell(v->ex, x, y);
    if (!c || !(c->flags & CELL_BLOCK))
        return dim(v, x, y);
    if (c->klass == BLOCK_FULL)
        return pal->block_full;
    if (c->klass == BLOCK_PARTIAL)
        return (c->flags & CELL_INSIDE) ? pal->partial_inside
               : (c->flags & CELL_TESTED) ? pal->partial_outside : pal->block_partial;
    return pal->block_empty;
}

static int blocks_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    const struct trace_counters *all = &v->ex->replay.sums[v->ex->replay.counted];
    if (all->blocks[BLOCK_EMPTY] + all->blocks[BLOCK_FULL] + all->blocks[BLOCK_PARTIAL] == 0)
        *note = none_yet;
    out[0] = (struct swatch){ v->pal->block_empty, "empty block: skipped" };
    out[1] = (struct swatch){ v->pal->block_full, "full block: filled, no tests" };
    out[2] = (struct swatch){ v->pal->block_partial, "partial block: tested per pixel" };
    return 3;
}

static uint32_t spans_cell(const struct view_ctx *v, int x, int y)
{
    int f = cell_flags(v->ex, x, y);
    return (f & CELL_SPAN) ? v->pal->span : (f & CELL_ROW) ? v->pal->row : dim(v, x, y);
}

static int spans_legend(const struct view_ctx *v, struct swatch *out, const char **note)
{
    if (v->ex->replay.sums[v->ex->replay.counted].spans == 0)
        *note = none_yet;
    out[0] = (struct swatch){ v->pal->span, "span: filled from left to right edge" };
    out[1] = (struct swatch){ v->pal->row, "row walked" };
    return 2;
}

/* --- the table ---------------------------------------------------------------------- */

struct builtin_view {
    const char *name;           /* what --view accepts */
    uint32_t (*cell)(const struct view_ctx *v, int x, int y);
    /* the numbers written in a cell when zoomed in (NULL: none), at most
     * `lines` of them (the edges view shows one line when one edge is chosen) */
    int (*numbers)(const struct view_ctx *v, int x, int y, char out[3][16]);
    int lines;
    int (*legend)(const struct view_ctx *v, struct swatch *out, const char **note);
};

static const struct builtin_view builtin_views[VIEW_BUILTIN_COUNT] = {
    [VIEW_COLOR] = { "color", color_cell, color_numbers, 3, color_legend },
    [VIEW_COVERAGE] = { "coverage", coverage_cell, coverage_numbers, 1, coverage_legend },
    [VIEW_EDGES] = { "edges", edges_cell, edges_numbers, 3, edges_legend },
    [VIEW_BARY] = { "bary", bary_cell, bary_numbers, 3, bary_legend },
    [VIEW_DEPTH] = { "depth", depth_cell, depth_numbers, 1, depth_legend },
    [VIEW_BLOCKS] = { "blocks", blocks_cell, NULL, 1, blocks_legend },
    [VIEW_SPANS] = { "spans", spans_cell, NULL, 1, spans_legend },
};

/* A lesson's own view: its cell() gets the pixel's last test and write. */
static uint32_t lesson_cell(const struct view_ctx *v, int x, int y)
{
    const struct explorer *ex = v->ex;
    const struct lesson_view *lv = &ex->side->views[ex->view - VIEW_BUILTIN_COUNT];
    const struct cell *c = cur_cell(ex, x, y);
    int f = c ? c->flags : 0;
    if (!(f & (CELL_TESTED | CELL_WRITTEN | CELL_INSIDE)))
        return dim(v, x, y);
    /* covered without a test of its own (a full block, a span): a test event
     * with the pixel and TRACE_INSIDE, its aux zero */
    bool tested = f & (CELL_TESTED | CELL_INSIDE);
    struct trace_event test = { .kind = TRACE_PIXEL_TEST, .x = x, .y = y, .line = c->line,
                                .flags = (f & CELL_INSIDE) ? TRACE_INSIDE : 0 };
    memcpy(test.e, c->e, sizeof test.e);
    memcpy(test.aux, c->aux, sizeof test.aux);
    struct trace_event write = { .kind = TRACE_PIXEL_WRITE, .x = x, .y = y, .z = c->z,
                                 .rgba = c->rgba,
                                 .flags = (f & CELL_DEPTH_PASS) ? TRACE_DEPTH_PASS : 0 };
    double rgb[3];
    if (!lv->cell(&ex->tri, tested ? &test : NULL, (f & CELL_WRITTEN) ? &write : NULL,
                  rgb))
        return dim(v, x, y);
    return from_rgb(rgb[0], rgb[1], rgb[2]);
}

static const struct builtin_view *builtin(const struct explorer *ex)
{
    return ex->view < VIEW_BUILTIN_COUNT ? &builtin_views[ex->view] : NULL;
}

/* The scene's depth range (from its first 4096 triangles: enough for a scale). */
void view_ctx_init(struct view_ctx *v, const struct explorer *ex, const struct palette *pal)
{
    *v = (struct view_ctx){ .ex = ex, .pal = pal, .zmin = INFINITY, .zmax = -INFINITY };
    int n = ex->scene.ntris < 4096 ? ex->scene.ntris : 4096;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            v->zmin = fmin(v->zmin, ex->scene.tris[i].v[k].z);
            v->zmax = fmax(v->zmax, ex->scene.tris[i].v[k].z);
        }
    if (!(v->zmax > v->zmin))
        v->zmax = v->zmin + 1;
}

uint32_t view_cell(const struct view_ctx *v, int x, int y)
{
    const struct builtin_view *b = builtin(v->ex);
    return b ? b->cell(v, x, y) : lesson_cell(v, x, y);
}

int view_numbers(const struct view_ctx *v, int x, int y, char out[3][16])
{
    const struct builtin_view *b = builtin(v->ex);
    return b && b->numbers ? b->numbers(v, x, y, out) : 0;
}

int view_lines(const struct explorer *ex)
{
    const struct builtin_view *b = builtin(ex);
    if (!b)
        return 1;
    return ex->view == VIEW_EDGES && ex->edge >= 0 ? 1 : b->lines;
}

int view_legend(const struct view_ctx *v, struct swatch out[VIEW_LEGEND_MAX], const char **note)
{
    const struct builtin_view *b = builtin(v->ex);
    *note = NULL;
    return b ? b->legend(v, out, note) : 0;
}

/* --- names ---------------------------------------------------------------------------- */

int explorer_view_count(const struct explorer *ex)
{
    return VIEW_BUILTIN_COUNT + (ex->side && ex->side->views ? ex->side->nviews : 0);
}

const char *explorer_view_name(const struct explorer *ex, int view)
{
    if (view < VIEW_BUILTIN_COUNT)
        return view == VIEW_EDGES && ex->edge >= 0 ? edge_view_names[ex->edge]
                                                   : builtin_views[view].name;
    return ex->side->views[view - VIEW_BUILTIN_COUNT].name;
}

bool explorer_set_view_name(struct explorer *ex, const char *name)
{
    for (int k = 0; k < 3; k++)
        if (strcmp(name, edge_view_names[k]) == 0) {
            ex->view = VIEW_EDGES;
            ex->edge = k;
            return true;
        }
    for (int i = 0; i < explorer_view_count(ex); i++) {
        const char *n = i < VIEW_BUILTIN_COUNT ? builtin_views[i].name
                                               : ex->side->views[i - VIEW_BUILTIN_COUNT].name;
        if (strcmp(name, n) == 0) {
            ex->view = i;
            if (i == VIEW_EDGES)
                ex->edge = -1;
            return true;
        }
    }
    return false;
}
