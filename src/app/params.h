/* params.h - the keys that change a lesson's parameters in the explorer,
 * as the rows of its table name them (B block size, [ and ] sub-pixel
 * bits, ...). No SDL here: the window passes the key as its character. */
#ifndef TRISTEP_PARAMS_KEY_H
#define TRISTEP_PARAMS_KEY_H

#include <stdbool.h>
#include <stddef.h>

#include "lesson.h"

/* Change *p as key `key` asks, if a row of lesson l's table has that key,
 * and write what it now is into what[0..n). False when the key changes
 * nothing in this lesson. */
bool params_key(const struct lesson *l, int key, struct raster_params *p, char *what, size_t n);

#endif
