/* params.c - the keys that change a lesson's parameters (params.h): read
 * from the rows of the lesson's table (lesson.h, struct lesson_param). */
#include "params.h"

#include <stdio.h>

/* The value after (dir > 0) or before v among row r's values, wrapping
 * when wrap, else stopping at the ends. */
static int next_value(const struct lesson_param *r, int v, int dir, bool wrap)
{
    if (r->values) {
        int n = 0, at = 0;
        while (r->values[n] >= 0)
            at = r->values[n] == v ? n : at, n++;
        at += dir;
        return r->values[wrap ? (at + n) % n : at < 0 ? 0 : at >= n ? n - 1 : at];
    }
    v += dir;
    if (v < r->min)
        return wrap ? r->max : r->min;
    if (v > r->max)
        return wrap ? r->min : r->max;
    return v;
}

bool params_key(const struct lesson *l, int key, struct raster_params *p, char *what, size_t n)
{
    for (int i = 0; key && l->params && l->params[i].option; i++) {
        const struct lesson_param *r = &l->params[i];
        if (key != r->key && key != r->key_down)
            continue;
        int *v = lesson_param_slot(l, i, p);
        int now = lesson_param_allows(r, *v) ? *v : r->def;   /* 0: the lesson's default */
        *v = next_value(r, now, key == r->key_down ? -1 : +1, !r->key_down);
        if (lesson_param_word(r, *v))
            snprintf(what, n, "%s: %s", r->name, lesson_param_word(r, *v));
        else
            snprintf(what, n, "%s: %d", r->name, *v);
        return true;
    }
    return false;
}
