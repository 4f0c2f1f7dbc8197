/* harnesses.c - the list of fuzz harnesses (fuzz.h) and their failure report. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"

const struct fuzz_harness fuzz_harnesses[] = {
    { "scene", fuzz_scene },
    { "obj", fuzz_obj },
    { "keys", fuzz_keys },
    { "lessons", fuzz_lessons },
    { "explorer", fuzz_explorer },
    { NULL, NULL },
};

void fuzz_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("fuzz: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    abort();
}

void fuzz_check_message(const char *err, const char *name)
{
    size_t n = strlen(name);
    if (strncmp(err, name, n) != 0 || err[n] != ':' || err[n + 1] < '1' || err[n + 1] > '9'
        || strchr(err, '\n'))
        fuzz_fail("malformed message '%s'", err);
}
