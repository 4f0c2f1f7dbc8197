/* panel.c - the side panel (the lesson, its variant and scene, the view's
 * legend, the pseudo-code with the current line lit, the watch, the
 * counters) and the help overlay. */
#include "painter.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "views.h"

static const char *const kind_names[TRACE_KIND_COUNT] = {
    "setup", "row", "span", "block", "pixel test", "pixel write", "front end", "step",
};
static const char *const class_names[BLOCK_CLASS_COUNT] = { "empty", "full", "partial" };

static int pseudocode_lines(const struct lesson *l)
{
    int n = 0;
    while (l->pseudocode && l->pseudocode[n])
        n++;
    return n;
}

static double heading(struct painter *p, double x, double y, double w, const char *title)
{
    set_rgb(p->cr, p->pal->rule);
    cairo_rectangle(p->cr, x, y + 9 * p->s, w, 1);
    cairo_fill(p->cr);
    double tw = text_width(p, title, 11);
    set_rgb(p->cr, p->pal->panel);
    cairo_rectangle(p->cr, x, y, tw + 8 * p->s, 18 * p->s);
    cairo_fill(p->cr);
    draw_text(p, x, y + 1 * p->s, 0, title, 11, p->pal->dim, false);
    return 20 * p->s;
}

static double swatch(struct painter *p, double x, double y, double w, uint32_t colour,
                     const char *label)
{
    set_rgb(p->cr, colour);
    cairo_rectangle(p->cr, x, y + 3 * p->s, 12 * p->s, 12 * p->s);
    cairo_fill(p->cr);
    set_rgba(p->cr, p->pal->border, 0.3);
    cairo_set_line_width(p->cr, 1);
    cairo_rectangle(p->cr, x + 0.5, y + 3 * p->s + 0.5, 12 * p->s - 1, 12 * p->s - 1);
    cairo_stroke(p->cr);
    return draw_text(p, x + 18 * p->s, y, w - 18 * p->s, label, 11.5, p->pal->text, false);
}

static double legend(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    double y0 = y, s = p->s;
    if (ex->view >= VIEW_BUILTIN_COUNT) {
        const struct lesson_view *lv = &ex->side->views[ex->view - VIEW_BUILTIN_COUNT];
        y += draw_text(p, x, y, w, lv->legend, 11.5, p->pal->text, false);
        struct lesson_swatch own[VIEW_LEGEND_MAX];
        struct run_place at;
        struct raster_params params = replay_params(&ex->replay, ex->cur, &at);
        int n = ex->side->swatches ? ex->side->swatches(lv->name, &params, own, VIEW_LEGEND_MAX) : 0;
        for (int i = 0; i < n && i < VIEW_LEGEND_MAX; i++)
            y += swatch(p, x, y, w, from_rgb(own[i].rgb[0], own[i].rgb[1], own[i].rgb[2]),
                        own[i].label) + 1 * s;
    }
    struct view_ctx v;
    view_ctx_init(&v, ex, p->pal);
    struct swatch items[VIEW_LEGEND_MAX];
    const char *note;
    int n = view_legend(&v, items, &note);
    for (int i = 0; i < n; i++)
        y += swatch(p, x, y, w, items[i].colour, items[i].label) + 1 * s;
    if (note)
        y += draw_text(p, x, y, w, note, 11, p->pal->dim, false);
    if (variant_against_exact(&ex->lesson->variants[ex->variant])) {
        y += swatch(p, x, y, w, p->pal->extra, "extra: more than the exact rule") + s;
        y += swatch(p, x, y, w, p->pal->missing, "missing: a crack") + s;
        if (ex->wrong_colour)
            y += swatch(p, x, y, w, p->pal->wrong_colour, "wrong colour or depth: not within "
                        "2 levels, 0.1%") + s;
    }
    y += swatch(p, x, y, w, p->pal->accent, "the current step") + s;
    return y - y0;
}

static double pseudocode(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    double y0 = y, lh = 17 * p->s;
    int lit = ex->has_last ? ex->last.line : -1;
    int from = ex->has_last ? lit - ex->last.span : -1;     /* a step may light a few lines */
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
    for (int i = 0; ex->lesson->pseudocode && ex->lesson->pseudocode[i]; i++) {
        bool on = i >= from && i <= lit;
        if (on) {
            set_rgb(p->cr, p->pal->hilite);
            cairo_rectangle(p->cr, x - 4 * p->s, y, w + 8 * p->s, lh);
            cairo_fill(p->cr);
            set_rgb(p->cr, p->pal->accent);
            cairo_rectangle(p->cr, x - 4 * p->s, y, 3 * p->s, lh);
            cairo_fill(p->cr);
        }
        char buf[160];
        snprintf(buf, sizeof buf, "%2d %s", i + 1, ex->lesson->pseudocode[i]);
        draw_text(p, x, y + 1 * p->s, w, buf, 11.5, on ? p->pal->accent : p->pal->text, false);
        y += lh;
    }
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    return y - y0;
}

/* Append to buf[n] at `at`; returns the new end (>= n once full). */
static size_t cat(char *buf, size_t n, size_t at, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static size_t cat(char *buf, size_t n, size_t at, const char *fmt, ...)
{
    if (at >= n)
        return at;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(buf + at, n - at, fmt, ap);
    va_end(ap);
    return k < 0 ? at : at + (size_t)k;
}

static size_t watch_values(const struct explorer *ex, char *buf, size_t n, size_t at,
                           const struct trace_event *ev)
{
    switch ((enum trace_kind)ev->kind) {
    case TRACE_SETUP:
        at = cat(buf, n, at, "box x %d..%d, y %d..%d\n", ev->x, ev->x1, ev->y, ev->y1);
        at = cat(buf, n, at, "area2 = %lld (%.4g px\u00b2)%s\n", (long long)ex->tri.area2,
                 (double)ex->tri.area2 / 65536, ex->tri.swapped ? "  B, C swapped" : "");
        break;
    case TRACE_ROW:
        at = cat(buf, n, at, "row y = %d, x %d..%d\n", ev->y, ev->x, ev->x1);
        break;
    case TRACE_SPAN:
        at = cat(buf, n, at, "span y = %d, x %d..%d\n", ev->y, ev->x, ev->x1);
        break;
    case TRACE_BLOCK:
        if (ev->klass >= BLOCK_CLASS_COUNT) {   /* a rectangle, no class (lesson 07's tiles) */
            at = cat(buf, n, at, "pixels (%d, %d)..(%d, %d)\n", ev->x, ev->y, ev->x1, ev->y1);
            break;
        }
        at = cat(buf, n, at, "block (%d, %d)..(%d, %d): %s\n", ev->x, ev->y, ev->x1, ev->y1,
                 class_names[ev->klass]);
        at = cat(buf, n, at, "corner masks %x %x %x\n", ev->mask[0], ev->mask[1], ev->mask[2]);
        break;
    case TRACE_PIXEL_TEST:
        at = cat(buf, n, at, "pixel (%d, %d): %s\n", ev->x, ev->y,
                 ex->side && ex->side->verdict ? ex->side->verdict[(ev->flags & TRACE_INSIDE) != 0]
                 : (ev->flags & TRACE_INSIDE) ? "inside" : "outside");
        for (int k = 0; k < 3; k++) {
            char v[24];
            format_edge(v, sizeof v, ev->e[k]);
            at = cat(buf, n, at, "%s = %lld (%s px\u00b2)\n", edge_names[k], (long long)ev->e[k], v);
        }
        if (ex->tri.area2 > 0) {       /* the weights follow from the edge values */
            double b[3];
            barycentric(&ex->tri, ev->e, b);
            at = cat(buf, n, at, "alpha %.4f beta %.4f gamma %.4f\n", (float)b[0], (float)b[1],
                     (float)b[2]);
        }
        break;
    case TRACE_PIXEL_WRITE:
        at = cat(buf, n, at, "write (%d, %d): z %.5g, depth %s\n", ev->x, ev->y, ev->z,
                 (ev->flags & TRACE_DEPTH_PASS) ? "pass" : "fail");
        at = cat(buf, n, at, "colour #%06x\n", (unsigned)(ev->rgba & 0xffffff));
        break;
    case TRACE_STEP: {          /* the lit line says what: its words */
        const char *w = ev->line < pseudocode_lines(ex->lesson) ? ex->lesson->pseudocode[ev->line] : "?";
        at = cat(buf, n, at, "%s\n", w + strspn(w, " "));
        for (int k = 0; k < 3 && (ev->e[0] || ev->e[1] || ev->e[2]); k++) {    /* F, if stepped */
            char v[24];
            format_edge(v, sizeof v, ev->e[k]);
            at = cat(buf, n, at, "%s = %lld (%s px\u00b2)\n", edge_names[k], (long long)ev->e[k], v);
        }
        break;
    }
    case TRACE_FRONT:           /* the shared front end's step: what it did is the lesson's
                                 * watch's to say (lesson 06, clipping_explorer.c) */
    case TRACE_KIND_COUNT:
        break;
    }
    if (ex->lesson->aux_names && (ev->kind == TRACE_PIXEL_TEST || ev->kind == TRACE_ROW
                                  || ev->kind == TRACE_SPAN || ev->kind == TRACE_BLOCK
                                  || (ev->kind == TRACE_STEP && ev->aux[0] != 0))) {
        for (int k = 0; k < 6 && ex->lesson->aux_names[k]; k++)
            at = cat(buf, n, at, "%s%s %.6g", k ? ", " : "", ex->lesson->aux_names[k], ev->aux[k]);
        if (ex->lesson->aux_names[0])
            at = cat(buf, n, at, "\n");
    }
    if (ex->side && ex->side->watch && (ex->tri.area2 > 0 || ev->kind == TRACE_FRONT) && at < n) {
        struct run_place place;
        struct raster_params params = replay_params(&ex->replay, ex->cur, &place);  /* the unit's, lesson 07 */
        place.told = ex->told;
        ex->side->watch(&ex->tri, &params, ev, buf + at, n - at);
        at += strlen(buf + at);
    }
    return at;
}

static double watch(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    char buf[2048];
    size_t at = 0, n = sizeof buf;
    buf[0] = '\0';
    if (!ex->has_last) {
        at = cat(buf, n, at, "nothing has happened yet: step forward (Right)\n");
    } else {
        char lines[24];
        if (ex->last.span)
            snprintf(lines, sizeof lines, "lines %d-%d", ex->last.line - ex->last.span + 1,
                     ex->last.line + 1);
        else
            snprintf(lines, sizeof lines, "line %d", ex->last.line + 1);
        at = cat(buf, n, at, "%s, %s, triangle %d\n",
                 ex->last.kind < TRACE_KIND_COUNT ? kind_names[ex->last.kind] : "?", lines,
                 replay_unit_tri(&ex->replay, ex->cur) + 1);  /* the scene's */
        at = watch_values(ex, buf, n, at, &ex->last);
    }
    if (ex->pinned) {
        int px = ex->pin_x, py = ex->pin_y;
        size_t i = (size_t)py * (size_t)ex->scene.w + (size_t)px;
        at = cat(buf, n, at, "\npinned (%d, %d): colour #%06x, covered %u\u00d7", px, py,
                 (unsigned)(ex->fb.color[i] & 0xffffff), (unsigned)ex->fb.count[i]);
        if (isfinite(ex->fb.depth[i]))
            at = cat(buf, n, at, ", z %.5g", ex->fb.depth[i]);
        at = cat(buf, n, at, "\n");
        const struct cell *c = cur_cell(ex, px, py);
        if (c && (c->flags & CELL_TESTED)) {
            for (int k = 0; k < 3; k++) {
                char v[24];
                format_edge(v, sizeof v, c->e[k]);
                at = cat(buf, n, at, "%s = %lld (%s)%s", edge_names[k], (long long)c->e[k], v,
                         k < 2 ? ", " : "\n");
            }
            at = cat(buf, n, at, "alpha %.4f beta %.4f gamma %.4f: %s\n", c->bary[0], c->bary[1],
                     c->bary[2], (c->flags & CELL_INSIDE) ? "inside" : "outside");
        } else if (!c || !(c->flags & CELL_INSIDE)) {
            at = cat(buf, n, at, "not reached by this triangle yet\n");
        }
    }
    while (at > 0 && at <= n && buf[at - 1] == '\n')
        buf[--at] = '\0';
    return draw_text(p, x, y, w, buf, 11.5, p->pal->text, false);
}

/* The lesson beside earlier ones on the triangles finished so far: pixels
 * tested, and arithmetic per tested pixel. */
static double compare_lines(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    int done = explorer_finished(ex), mine = done;
    if (ex->replay.units) {
        /* drawn tile by tile (lesson 07): a triangle is finished when the run is */
        bool all = done >= ex->replay.ntris;
        done = all ? ex->scene.ntris : 0;
        mine = all ? ex->replay.ntris : 0;
    }
    char buf[1024];
    size_t at = 0, n = sizeof buf;
    if (done == 0) {
        /* nothing finished yet: compare the whole scene rather than show zeros */
        done = ex->scene.ntris;
        mine = ex->replay.ntris;    /* the same, in this lesson's units */
        at = cat(buf, n, at, "whole scene, %d triangle%s:\n", done, done == 1 ? "" : "s");
    } else {
        at = cat(buf, n, at, "same %d triangle%s finished:\n", done, done == 1 ? "" : "s");
    }
    at = cat(buf, n, at, "%-18s %9s %7s %7s\n", "", "tested", "mul/px", "add/px");
    for (int i = -1; i < ex->ncompare; i++) {
        const struct replay *r = i < 0 ? &ex->replay : &ex->compare_replay[i];
        const char *name = i < 0 ? "this lesson" : ex->compare[i]->id;
        int upto = i < 0 ? mine : done;     /* in the run's own units */
        if (r->counted < upto) {        /* a large scene, still being counted */
            at = cat(buf, n, at, "%-18s counting: %.0f%%\n", name,
                     100.0 * r->counted / (r->ntris ? r->ntris : 1));
            continue;
        }
        const struct trace_counters *c = &r->sums[upto];
        double px = c->tested ? (double)c->tested : 1;
        at = cat(buf, n, at, "%-18s %9llu %7.1f %7.1f\n", name, (unsigned long long)c->tested,
                 (double)c->mul / px, (double)c->add / px);
    }
    while (at > 0 && at <= n && buf[at - 1] == '\n')
        buf[--at] = '\0';
    return draw_text(p, x, y, w, buf, 11.5, p->pal->dim, false);
}

static double counters(struct painter *p, double x, double y, double w)
{
    struct explorer *ex = p->ex;
    struct trace_counters c;
    explorer_counters(ex, &c);
    char buf[1024];
    size_t at = 0, n = sizeof buf;
    at = cat(buf, n, at, "pixels tested  %10llu   covered %10llu\n", (unsigned long long)c.tested,
             (unsigned long long)c.covered);
    at = cat(buf, n, at, "pixels written %10llu   rows    %10llu\n", (unsigned long long)c.written,
             (unsigned long long)c.rows);
    const struct trace_counters *all = &ex->replay.sums[ex->replay.counted];
    if (all->blocks[0] + all->blocks[1] + all->blocks[2])
        at = cat(buf, n, at, "blocks empty %llu  full %llu  partial %llu\n",
                 (unsigned long long)c.blocks[0], (unsigned long long)c.blocks[1],
                 (unsigned long long)c.blocks[2]);
    if (all->spans)
        at = cat(buf, n, at, "spans %llu\n", (unsigned long long)c.spans);
    at = cat(buf, n, at, "multiplications %9llu   adds %10llu", (unsigned long long)c.mul,
             (unsigned long long)c.add);
    double h = draw_text(p, x, y, w, buf, 11.5, p->pal->text, false);
    if (ex->ncompare > 0)
        h += compare_lines(p, x, y + h + 4 * p->s, w) + 4 * p->s;
    if (variant_against_exact(&ex->lesson->variants[ex->variant])) {
        char e[256];
        int at;
        if (ex->replay.units)   /* a run in parts of its own (lesson 07) */
            at = snprintf(e, sizeof e, "vs %s, %d of %d parts done:\nextra %llu   missing (cracks) %llu",
                          ex->lesson->variants[0].name, ex->diff_done, ex->replay.ntris,
                          (unsigned long long)ex->extra, (unsigned long long)ex->missing);
        else
            at = snprintf(e, sizeof e, "vs %s, %d triangle%s finished:\nextra %llu   missing (cracks) %llu",
                          ex->lesson->variants[0].name, ex->diff_done, ex->diff_done == 1 ? "" : "s",
                          (unsigned long long)ex->extra, (unsigned long long)ex->missing);
        if (ex->wrong_colour && at > 0 && (size_t)at < sizeof e)
            snprintf(e + at, sizeof e - (size_t)at, "   wrong colour %llu", (unsigned long long)ex->wrong_colour);
        h += 4 * p->s;
        h += draw_text(p, x, y + h, w, e, 11.5, ex->extra + ex->missing + ex->wrong_colour ? p->pal->extra : p->pal->covered, false);
    }
    return h;
}

void paint_panel(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    set_rgb(cr, p->pal->panel);
    cairo_rectangle(cr, L->px, 0, L->pw, L->h);
    cairo_fill(cr);
    set_rgb(cr, p->pal->rule);
    cairo_rectangle(cr, L->px, 0, 1, L->h);
    cairo_fill(cr);
    cairo_save(cr);
    cairo_rectangle(cr, L->px, 0, L->pw, L->h);
    cairo_clip(cr);
    double x = L->px + 16 * s, w = L->pw - 32 * s, y = 12 * s;
    y += draw_text(p, x, y, w, ex->lesson->id, 15, p->pal->accent, false);
    y += draw_text(p, x, y, w, ex->lesson->title, 11.5, p->pal->dim, false) + 6 * s;

    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    char buf[512];
    if (variant_against_exact(v)) {
        /* shown against the exact rule: a badge says why */
        const char *badge = v->kind == VARIANT_EXERCISE ? "YOUR CODE"
                            : v->kind == VARIANT_CONTRAST ? "COMPARED" : "EXHIBIT";
        double bw = text_width(p, badge, 11) + 10 * s;
        set_rgb(cr, p->pal->exhibit);
        cairo_rectangle(cr, x, y + 1 * s, bw, 17 * s);
        cairo_fill(cr);
        draw_text(p, x + 5 * s, y + 2 * s, 0, badge, 11, p->pal->on_exhibit, false);
        snprintf(buf, sizeof buf, "%s: %s", v->name, v->what);
        y += draw_text(p, x + bw + 8 * s, y + 1 * s, w - bw - 8 * s, buf, 11.5, p->pal->text, false) + 4 * s;
    } else {
        snprintf(buf, sizeof buf, "variant %s%s", v->name, v->kind == VARIANT_TWIN ? " (faster twin)"
                 : v->kind == VARIANT_ALTERNATIVE ? " (alternative)" : "");
        y += draw_text(p, x, y, w, buf, 11.5, p->pal->text, false);
    }
    snprintf(buf, sizeof buf, "scene %s, %dx%d, %d triangle%s", ex->scene_name, ex->scene.w,
             ex->scene.h, ex->scene.ntris, ex->scene.ntris == 1 ? "" : "s");
    y += draw_text(p, x, y, w, buf, 11.5, p->pal->text, false);
    if (ex->lesson->params) {     /* the rows of its table that a key changes */
        size_t at = 0;
        buf[0] = '\0';
        for (int i = 0; ex->lesson->params[i].option; i++) {
            const struct lesson_param *r = &ex->lesson->params[i];
            struct raster_params prm = ex->params;
            int v = *lesson_param_slot(ex->lesson, i, &prm);
            v = lesson_param_allows(r, v) ? v : r->def;     /* 0: the lesson's default */
            if (!r->key)
                continue;
            if (lesson_param_word(r, v))
                at = cat(buf, sizeof buf, at, "%s  ", lesson_param_word(r, v));
            else
                at = cat(buf, sizeof buf, at, "%s %d  ", r->name, v);
        }
        if (at > 0)
            y += draw_text(p, x, y, w, buf, 11.5, p->pal->text, false);
    }
    y += 8 * s;

    snprintf(buf, sizeof buf, "VIEW: %s", explorer_view_name(ex, ex->view));
    y += heading(p, x, y, w, buf);
    y += legend(p, x, y, w) + 8 * s;
    y += heading(p, x, y, w, "PSEUDO-CODE");
    y += pseudocode(p, x, y, w) + 8 * s;
    y += heading(p, x, y, w, "WATCH");
    y += watch(p, x, y, w) + 8 * s;
    if (ex->side && ex->side->constants && ex->scene.ntris > 0 && !ex->tri.empty) {
        buf[0] = '\0';
        struct run_place at;
        struct raster_params params = replay_params(&ex->replay, ex->cur >= 0 ? ex->cur : 0, &at);  /* its texture */
        ex->side->constants(&ex->tri, &params, buf, sizeof buf);
        for (size_t e = strlen(buf); e > 0 && buf[e - 1] == '\n'; e--)
            buf[e - 1] = '\0';
        y += heading(p, x, y, w, "TRIANGLE");
        y += draw_text(p, x, y, w, buf, 11.5, p->pal->text, false) + 8 * s;
    }
    y += heading(p, x, y, w, "SO FAR");
    y += counters(p, x, y, w) + 8 * s;
    /* the key hints at the bottom, unless the panel's text reaches down there */
    if (y <= L->h - 24 * s) {
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
        draw_text(p, x, L->h - 24 * s, w, "H help  V view  \u2190\u2192 step  E export  Q quit", 11,
                  p->pal->dim, false);
        pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
    }
    cairo_restore(cr);
}

/* --- help ------------------------------------------------------------------------------ */

void paint_help(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    char keys[2048];
    size_t at = 0, n = sizeof keys;
    at = cat(keys, n, at,
        "Right / Left         one event forward / back\n"
        "Shift+Right / Left   to the next / previous row or block\n"
        "Ctrl+Right / Left    to the next / previous triangle\n"
        "Home / End           to the start / the end\n"
        "PgDn / PgUp          one event (presentation clickers)\n"
        "Space                play / pause\n"
        "+ / -                play faster / slower\n"
        "V / Shift+V          next / previous view\n"
        "0 1 2 3              edges view: all three, F_ab, F_bc, F_ca\n"
        "N                    numbers in cells: auto, always, off\n"
        "S                    save the scene as it is now to a new file\n");
    bool exhibits = false, twins = false, alternatives = false;
    for (int i = 1; i < ex->lesson->nvariants; i++) {
        const struct lesson_variant *v = &ex->lesson->variants[i];
        exhibits |= variant_against_exact(v);
        twins |= v->kind == VARIANT_TWIN, alternatives |= v->kind == VARIANT_ALTERNATIVE;
    }
    if (exhibits)
        at = cat(keys, n, at, "X                    next exhibit (against the exact rule)\n");
    if (twins || alternatives)
        at = cat(keys, n, at, alternatives ? twins ? "T                    next twin or alternative\n"
                                                   : "T                    next alternative\n"
                                           : "T                    next faster twin\n");
    for (int i = 0; ex->lesson->params && ex->lesson->params[i].option; i++) {
        const struct lesson_param *r = &ex->lesson->params[i];
        char range[64], key[8];
        lesson_param_range(r, range, sizeof range);
        if (r->key && r->key_down) {
            snprintf(key, sizeof key, "%c / %c", toupper(r->key_down), toupper(r->key));
            at = cat(keys, n, at, "%-21sless / more %s (%s)\n", key, r->name, range);
        } else if (r->key && r->words && !r->arg) {
            snprintf(key, sizeof key, "%c", toupper(r->key));
            at = cat(keys, n, at, "%-21s%s / %s\n", key, r->words[1], r->words[0]);
        } else if (r->key) {
            snprintf(key, sizeof key, "%c", toupper(r->key));
            at = cat(keys, n, at, "%-21s%s %s\n", key, r->name, range);
        }
    }
    at = cat(keys, n, at,
        "E                    export the view (PNG and SVG)\n"
        "L                    light theme (for paper) / dark\n"
        "C                    the pixel grid alone / with panel and bar\n"
        "F                    fit the scene to the window\n"
        "H / F1               this help\n"
        "Q / Esc              quit\n"
        "\n"
        "mouse: drag a vertex A, B, C (snaps to 1/256 px)\n"
        "       wheel to zoom, drag the background to pan\n"
        "       click a pixel to pin its values in the watch");
    double tw = fmin(L->w - 40 * s, 600 * s);
    double x = (L->w - tw) / 2, y = 40 * s;
    /* the text first, into a group, so the box can be as tall as it is */
    cairo_push_group(cr);
    double h = draw_text(p, x + 20 * s, y + 16 * s, tw - 40 * s, "Keys", 15, p->pal->accent, false);
    h += draw_text(p, x + 20 * s, y + 24 * s + h, tw - 40 * s, keys, 12, p->pal->text, false);
    cairo_pattern_t *words = cairo_pop_group(cr);
    set_rgba(cr, p->pal->shadow, 0.55);
    cairo_paint(cr);
    set_rgb(cr, p->pal->panel);
    cairo_rectangle(cr, x, y, tw, fmin(L->h - 2 * y, h + 44 * s));
    cairo_fill_preserve(cr);
    set_rgb(cr, p->pal->accent);
    cairo_set_line_width(cr, 1.5 * s);
    cairo_stroke(cr);
    cairo_set_source(cr, words);
    cairo_paint(cr);
    cairo_pattern_destroy(words);
}

