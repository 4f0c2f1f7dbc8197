/* figure.h - the explorer's view written to a PNG, SVG or PDF file. */
#ifndef TRISTEP_FIGURE_H
#define TRISTEP_FIGURE_H

#include "cli/cli.h"

/* Headless --figure: draw what the window would show at the chosen step and
 * view. Returns the exit status; prints FILE:LINE-style messages itself. */
int figure_export(const struct lesson *l, const struct cli_options *o, const struct scene *s);

struct explorer_desc;
/* The explorer as the command line describes it, for the window and for
 * figures alike: fills *d (its scene name into name[n]) and returns -1, or
 * prints why --view is wrong and returns EXIT_USAGE. */
int explorer_desc_from_cli(const struct lesson *l, const struct cli_options *o,
                           const struct scene *s, char *name, size_t n,
                           struct explorer_desc *d);

#endif
