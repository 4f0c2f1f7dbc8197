/* figure.h - the explorer's view written to a PNG, SVG or PDF file. */
#ifndef TRISTEP_FIGURE_H
#define TRISTEP_FIGURE_H

#include "cli/cli.h"

/* Headless --figure: draw what the window would show at the chosen step and
 * view. Returns the exit status; prints FILE:LINE-style messages itself. */
int figure_export(const struct lesson *l, const struct cli_options *o, const struct scene *s);

#endif
