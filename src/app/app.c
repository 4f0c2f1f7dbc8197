/* app.c - the explorer window (not built yet: see the explorer issue). */
#include "app.h"

int explorer_run(const struct lesson *l, const struct cli_options *o, struct scene *s)
{
    (void)o;
    (void)s;
    fprintf(stderr, "%s: the interactive explorer is not there yet; use --dump-coverage "
                    "or --dump-image (see --help)\n", l->id);
    return EXIT_RUN;
}
