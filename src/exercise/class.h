/* class.h - a class's work as make grade finds it (class.c): one .c file
 * or one folder per student in DIR, each a submission with a folder name
 * of its own; and untrusted text (a name, a log) made safe to show. */
#ifndef TRISTEP_EXERCISE_CLASS_H
#define TRISTEP_EXERCISE_CLASS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

struct sub {
    char *entry;            /* its name in DIR, as it is (untrusted bytes) */
    char *file;             /* the file graded, or NULL (problem says why) */
    const char *problem;
    char safe[64];          /* its folder under OUT: unique, safe */
};

/* The submissions of dir, sorted by name, n of them (one: dir is one
 * student's folder); NULL if dir cannot be read. */
struct sub *list_class(const char *dir, bool one, int *n);
void free_class(struct sub *subs, int n);

/* Text as it may go into a CSV field or a JSON string: valid UTF-8, no
 * control characters (each a space), invalid bytes as '?'. */
void clean_text(const char *in, char *out, size_t n);
/* A CSV field (after a comma unless first): clean, quoted, one that a
 * spreadsheet would read as a formula led by a quote mark. */
void csv_field(FILE *f, const char *s, bool first);
/* A JSON string of s's len bytes: clean, its newlines kept as \n. */
void json_string(FILE *f, const char *s, size_t len);

#endif
