/* lesson_explorer.c - pairing a lesson with its explorer side. */
#include "lesson_explorer.h"

#include <string.h>

const struct lesson_explorer *lesson_explorer_of(const struct lesson *l)
{
    for (const struct lesson_explorer *const *x = all_lesson_explorers; l && *x; x++)
        if (strcmp((*x)->lesson->id, l->id) == 0)
            return *x;
    return NULL;
}
