/* figure.c - figures of the explorer's view (not built yet: see the explorer issue). */
#include "figure.h"

int figure_export(const struct lesson *l, const struct cli_options *o, const struct scene *s)
{
    (void)o;
    (void)s;
    fprintf(stderr, "%s: --figure is not there yet\n", l->id);
    return EXIT_RUN;
}
