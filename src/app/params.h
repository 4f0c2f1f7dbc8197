/* params.h - the keys that change a lesson's parameters in the explorer:
 * [ and ] sub-pixel bits (lesson 03), B block size (lesson 05), P affine
 * texturing (lesson 04), M samples per pixel (lesson 08). No SDL here: the
 * window passes the key as its character. */
#ifndef TRISTEP_PARAMS_KEY_H
#define TRISTEP_PARAMS_KEY_H

#include <stdbool.h>
#include <stddef.h>

#include "lesson.h"

/* Change *p as key `key` asks, if the lesson has that parameter (`params`,
 * its LESSON_PARAM_ bits), and write what it now is into what[0..n). False
 * when the key changes nothing in this lesson. */
bool params_key(unsigned params, int key, struct raster_params *p, char *what, size_t n);

#endif
