/* pointer.c - the mouse on the explorer (see pointer.h). */
#include "pointer.h"

#include <math.h>

void pointer_down(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                  double x, double y)
{
    m->down_x = m->last_x = x;
    m->down_y = m->last_y = y;
    m->moved = false;
    m->drag = DRAG_NONE;
    if (x >= L->cx + L->cw || y >= L->cy + L->ch)
        return;                         /* the panel or the scrub bar */
    m->drag_vertex = explorer_hit_vertex(ex, L, x, y);
    m->drag = m->drag_vertex >= 0 ? DRAG_VERTEX : DRAG_PAN;
}

bool pointer_move(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                  double x, double y)
{
    bool dirty = false;
    if (fabs(x - m->down_x) > 3 || fabs(y - m->down_y) > 3)
        m->moved = true;
    if (m->drag == DRAG_VERTEX) {
        ex->hover_vertex = m->drag_vertex;
        m->drop_x = (x - L->ox) / L->zoom, m->drop_y = (y - L->oy) / L->zoom;
        m->drop_pending = true;
        dirty = true;
    } else if (m->drag == DRAG_PAN && m->moved) {
        explorer_pan(ex, L, x - m->last_x, y - m->last_y);
        dirty = true;
    } else if (m->drag == DRAG_NONE) {
        int h = explorer_hit_vertex(ex, L, x, y);
        if (h != ex->hover_vertex)
            ex->hover_vertex = h, dirty = true;
    }
    m->last_x = x, m->last_y = y;
    return dirty;
}

bool pointer_drop(struct pointer *m, struct explorer *ex)
{
    if (!m->drop_pending)
        return true;
    m->drop_pending = false;
    return explorer_move_vertex(ex, m->drag_vertex, m->drop_x, m->drop_y);
}

bool pointer_up(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                double x, double y, bool *dirty)
{
    *dirty = pointer_move(m, ex, L, x, y);
    bool ok = pointer_drop(m, ex);
    if (m->drag == DRAG_PAN && !m->moved) {
        /* a click on a cell pins its values; a second click unpins */
        int px = (int)floor((x - L->ox) / L->zoom), py = (int)floor((y - L->oy) / L->zoom);
        if (px < 0 || py < 0 || px >= ex->scene.w || py >= ex->scene.h
            || (ex->pinned && ex->pin_x == px && ex->pin_y == py))
            ex->pinned = false;
        else
            ex->pinned = true, ex->pin_x = px, ex->pin_y = py;
        *dirty = true;
    }
    m->drag = DRAG_NONE;
    return ok;
}

bool pointer_wheel(struct explorer *ex, const struct explorer_layout *L, double x, double y,
                   int notches)
{
    if (x >= L->cx + L->cw || y >= L->cy + L->ch || notches == 0)
        return false;
    explorer_zoom_at(ex, L, x, y, pow(1.25, notches));
    return true;
}
