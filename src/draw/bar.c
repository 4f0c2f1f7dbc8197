/* bar.c - the scrub bar under the canvas: where the step is in the run,
 * the triangles' boundaries, and the step, triangle and event numbers. */
#include "painter.h"

#include <math.h>
#include <stdio.h>

void paint_bar(struct painter *p)
{
    cairo_t *cr = p->cr;
    struct explorer *ex = p->ex;
    const struct explorer_layout *L = &p->L;
    double s = p->s;
    set_rgb(cr, p->pal->panel);
    cairo_rectangle(cr, L->cx, L->bar_y, L->cw, L->bar_h);
    cairo_fill(cr);
    set_rgb(cr, p->pal->rule);
    cairo_rectangle(cr, L->cx, L->bar_y, L->cw, 1);
    cairo_fill(cr);
    double tx = L->cx + 14 * s, tw = L->cw - 28 * s, ty = L->bar_y + 9 * s, th = 6 * s;
    uint64_t total = ex->replay.total;
    double f = total ? (double)ex->step / (double)total : 0;
    set_rgb(cr, p->pal->track);
    cairo_rectangle(cr, tx, ty, tw, th);
    cairo_fill(cr);
    set_rgb(cr, p->pal->accent);
    cairo_rectangle(cr, tx, ty, tw * f, th);
    cairo_fill(cr);
    if (ex->replay.counted > 1 && ex->replay.counted <= 400 && total) {   /* triangle boundaries */
        set_rgba(cr, p->pal->shadow, 0.8);
        for (int i = 1; i < ex->replay.counted; i++) {
            double x = tx + tw * (double)ex->replay.start[i] / (double)total;
            cairo_rectangle(cr, floor(x), ty, 1, th);
        }
        cairo_fill(cr);
    }
    cairo_arc(cr, tx + tw * f, ty + th / 2, 6 * s, 0, 2 * G_PI);
    set_rgb(cr, p->pal->text);
    cairo_fill(cr);
    char buf[256];
    int n = ex->replay.ntris;
    uint64_t ev = ex->cur >= 0 ? ex->local + 1 : 0;
    uint64_t evn = ex->cur >= 0 ? ex->replay.start[ex->cur + 1] - ex->replay.start[ex->cur] : 0;
    double e = pow(2, ex->speed / 2.0);
    char counting[48] = "";
    if (!replay_counted(&ex->replay))   /* a large scene: its steps are counted a part at a time */
        snprintf(counting, sizeof counting, " so far (counting: %.0f%%)",
                 100.0 * ex->replay.counted / n);
    /* a lesson that runs in parts of its own (lesson 07: set-up and
     * binning, then tile by tile): the part, and the scene's triangle in it */
    char unit[64];
    if (ex->replay.units && ex->cur >= 0)
        snprintf(unit, sizeof unit, "part %d / %d, triangle %d / %d", ex->cur + 1, n,
                 replay_unit_tri(&ex->replay, ex->cur) + 1, ex->scene.ntris);
    else if (ex->replay.units)
        snprintf(unit, sizeof unit, "part 0 / %d", n);
    else
        snprintf(unit, sizeof unit, "triangle %d / %d", ex->cur + 1, n);
    snprintf(buf, sizeof buf, "%s  step %llu / %llu%s   %s   event %llu / %llu   %s%.4g/s",
             ex->playing ? "\u25b6" : "\u275a\u275a", (unsigned long long)ex->step,
             (unsigned long long)total, counting, unit, (unsigned long long)ev,
             (unsigned long long)evn, "speed ", e);
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_END);
    draw_text(p, tx, ty + th + 7 * s, tw, buf, 12, p->pal->text, false);
    pango_layout_set_ellipsize(p->layout, PANGO_ELLIPSIZE_NONE);
}
