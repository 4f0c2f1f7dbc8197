/* grade.h - make grade: a class's work graded by the judge (grade.c),
 * every submission compiled, linked and run in a sandbox (bubblewrap), the
 * verdict decided here (CONVENTIONS.md, "Grading a class").
 *
 *   judge-NN --grade --dir DIR --lib LIBDIR --out OUT --csv CSV
 *            [--timeout S] [--points FILE] [--seed N] [--commit HASH]
 *            [--one] [--unsafe] [--cc CC]
 *
 *   DIR     one .c file per student, or one folder per student holding the
 *           lesson's exercise file (exercise.c, or its only .c file), in any
 *           mix; --one: DIR is one student's folder (Gradescope's submission)
 *   LIBDIR  the lesson's student library (build/student/NN: include/,
 *           library.o), all a submission is compiled and linked with
 *   OUT     a folder per submission (a safe name of its own, whatever the
 *           student's: compile.txt, log.txt, check.txt, results.json and
 *           the counterexamples), and the CSV
 *   S       seconds one submission may take in all (compile, link, checks)
 *   FILE    points per check, lines "POINTS check name" (default: grade.c's
 *           table); N: the seed of the random scenes (hidden scenes)
 *   --unsafe  no sandbox (where bubblewrap cannot run); the CSV says so
 *
 * What a submission's commands get (grade.c says how): bubblewrap's new
 * namespaces (no network; a pid namespace, all of it killed at the end),
 * read-only /usr and the lesson's student library, a private /tmp of
 * 64 MiB, limits on CPU time, memory, processes and file size, and the
 * first 256 KiB of what they print kept (compile.txt, log.txt). Run as
 * root, each submission runs as a user id of its own; whatever is left of
 * a run, sandboxed or not, is killed before the next one begins. */
#ifndef TRISTEP_EXERCISE_GRADE_H
#define TRISTEP_EXERCISE_GRADE_H

#include <stdint.h>

#include "lesson.h"

int exercise_grade_main(const struct lesson *l, int argc, char **argv);
/* SEED=: a number, or any word (hashed) */
uint64_t grade_seed(const char *s);

#endif
