/* main.c - every lesson program is this file linked with one lesson.
 * The Makefile defines LESSON as the lesson's descriptor (lesson_02, ...). */
#include "cli/cli.h"

extern const struct lesson LESSON;

int main(int argc, char **argv)
{
    return lesson_main(&LESSON, argc, argv);
}
