/* lesson.c - looking things up in a lesson's descriptor (lesson.h). */
#include "lesson.h"

#include <stdio.h>
#include <string.h>

#include "front/front.h"

front_fn lesson_front(const struct lesson *l, const struct lesson_variant *v)
{
    (void)l;
    return v->front ? v->front : front_scene;
}

const struct lesson_variant *lesson_variant(const struct lesson *l, const char *name)
{
    for (int i = 0; i < l->nvariants; i++)
        if (strcmp(l->variants[i].name, name) == 0)
            return &l->variants[i];
    return NULL;
}

const struct lesson_param *lesson_param(const struct lesson *l, const char *option, int *row)
{
    for (int i = 0; l->params && l->params[i].option; i++)
        if (strcmp(l->params[i].option, option) == 0) {
            if (row)
                *row = i;
            return &l->params[i];
        }
    return NULL;
}

int *lesson_param_slot(const struct lesson *l, int row, struct raster_params *p)
{
    switch (l->params[row].slot) {
    case PARAM_SUBPIXEL_BITS: return &p->subpixel_bits;
    case PARAM_SAMPLES: return &p->samples;
    case PARAM_OWN: break;
    }
    return &p->knob[row];
}

bool lesson_param_set(const struct lesson *l, struct raster_params *p, const char *option, int v)
{
    int row;
    if (!lesson_param(l, option, &row))
        return false;
    *lesson_param_slot(l, row, p) = v;
    return true;
}

struct raster_params lesson_params_default(const struct lesson *l)
{
    struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS };
    for (int i = 0; l->params && l->params[i].option; i++)
        *lesson_param_slot(l, i, &p) = l->params[i].def;
    return p;
}

struct raster_params lesson_params_as(const struct lesson *to, const struct lesson *from,
                                      const struct raster_params *p)
{
    struct raster_params out = *p;
    memset(out.knob, 0, sizeof out.knob);
    for (int i = 0; to->params && to->params[i].option; i++) {
        int j;
        if (to->params[i].slot != PARAM_OWN)
            continue;
        struct raster_params from_p = *p;
        out.knob[i] = lesson_param(from, to->params[i].option, &j)
                      ? *lesson_param_slot(from, j, &from_p) : to->params[i].def;
    }
    return out;
}

bool lesson_param_allows(const struct lesson_param *r, int v)
{
    if (v < r->min || v > r->max)
        return false;
    if (!r->values)
        return true;
    for (const int *x = r->values; *x >= 0; x++)
        if (*x == v)
            return true;
    return false;
}

const char *lesson_param_word(const struct lesson_param *r, int v)
{
    if (!r->words)
        return NULL;
    if (!r->arg)
        return r->words[v != 0];
    return lesson_param_allows(r, v) ? r->words[v - r->min] : NULL;
}

int lesson_param_named(const struct lesson_param *r, const char *word)
{
    for (int v = r->min; r->arg && r->words && v <= r->max; v++)
        if (strcmp(r->words[v - r->min], word) == 0)
            return v;
    return -1;
}

void lesson_param_range(const struct lesson_param *r, char *buf, size_t n)
{
    if (r->arg && r->words) {
        size_t at = 0;
        buf[0] = '\0';
        for (int v = r->min; v <= r->max && at < n; v++) {
            const char *sep = v == r->min ? "" : v == r->max ? " or " : ", ";
            int k = snprintf(buf + at, n - at, "%s%s", sep, r->words[v - r->min]);
            at += k > 0 ? (size_t)k : 0;
        }
        return;
    }
    if (!r->values) {
        snprintf(buf, n, "%d..%d", r->min, r->max);
        return;
    }
    size_t at = 0;
    buf[0] = '\0';
    for (const int *x = r->values; *x >= 0 && at < n; x++) {
        const char *sep = x == r->values ? "" : x[1] < 0 ? " or " : ", ";
        int k = snprintf(buf + at, n - at, "%s%d", sep, *x);
        at += k > 0 ? (size_t)k : 0;
    }
}
