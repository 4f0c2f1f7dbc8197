/* lesson.c - looking things up in a lesson's descriptor (lesson.h). */
#include "lesson.h"

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
