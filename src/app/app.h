/* app.h - the SDL2 explorer window. */
#ifndef TRISTEP_APP_H
#define TRISTEP_APP_H

#include "cli/cli.h"

/* Open the explorer on a scene; returns the program's exit status. */
int explorer_run(const struct lesson *l, const struct cli_options *o, struct scene *s);

#endif
