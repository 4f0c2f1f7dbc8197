/* views.h - the explorer's views by name: the built-in ones (their table is
 * in views.c), then the lesson's own (its
 * lesson_explorer's views). */
#ifndef TRISTEP_VIEWS_H
#define TRISTEP_VIEWS_H

#include <stdbool.h>

#include "explore/explorer.h"

/* The built-in views, in the order V cycles through them. */
enum view {
    VIEW_COLOR, VIEW_COVERAGE, VIEW_EDGES, VIEW_BARY, VIEW_DEPTH, VIEW_BLOCKS, VIEW_SPANS,
    VIEW_BUILTIN_COUNT
};

/* Views: built-in ones then the lesson's own. */
int explorer_view_count(const struct explorer *ex);
const char *explorer_view_name(const struct explorer *ex, int view);
/* Accepts every view name, and "edge-ab", "edge-bc", "edge-ca" for one edge;
 * returns false for an unknown name. */
bool explorer_set_view_name(struct explorer *ex, const char *name);

#endif
