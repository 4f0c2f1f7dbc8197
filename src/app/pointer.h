/* pointer.h - the mouse on the explorer: dragging a vertex or the view, a
 * click that pins a cell's values, the wheel that zooms at the pointer. No
 * SDL here: the window passes positions in window units and the frame's
 * layout. */
#ifndef TRISTEP_POINTER_H
#define TRISTEP_POINTER_H

#include <stdbool.h>

#include "explore/explorer.h"

struct pointer {
    enum { DRAG_NONE, DRAG_VERTEX, DRAG_PAN } drag;
    int drag_vertex;
    double down_x, down_y, last_x, last_y;
    bool moved;                 /* more than 3 pixels from where the button went down */
    double drop_x, drop_y;      /* scene position the dragged vertex goes to */
    bool drop_pending;
};

void pointer_down(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                  double x, double y);
/* True when the frame must be painted again. */
bool pointer_move(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                  double x, double y);
/* Move the dragged vertex to where the mouse last was: once a frame, since
 * every move re-runs the lesson. False when out of memory. */
bool pointer_drop(struct pointer *m, struct explorer *ex);
/* The button released: drop, or pin (or unpin) the cell clicked. Sets
 * *dirty when the frame must be painted again; false when out of memory. */
bool pointer_up(struct pointer *m, struct explorer *ex, const struct explorer_layout *L,
                double x, double y, bool *dirty);
/* The wheel at (x, y): zoom by 1.25 a notch there. True when it zoomed. */
bool pointer_wheel(struct explorer *ex, const struct explorer_layout *L, double x, double y,
                   int notches);

#endif
