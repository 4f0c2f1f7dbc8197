/* remote.h - the judge's end of the runner (remote.c, wire.h): the student's
 * code drawn in another process, whose results come back to be checked.
 * Once configured, the exercise variant (exercise.c) draws through it. */
#ifndef TRISTEP_EXERCISE_REMOTE_H
#define TRISTEP_EXERCISE_REMOTE_H

#include <stdbool.h>
#include <stdint.h>

#include "exercise/exercise.h"

struct remote_config {
    char **argv;                /* the runner's command: the program, or bwrap around it */
    const char *log;            /* where its prints go (appended); NULL: nowhere */
    int log_fd;                 /* > 2: where its prints go instead of log (a pipe) */
    void (*limits)(void *ctx);  /* run in the child before the exec (setrlimit, ...) */
    void *limits_ctx;
    double scene_seconds;       /* a scene drawn for longer: an endless loop (0: 10 s) */
    double start_seconds;       /* the runner's start (0: 10 s) */
};

/* From now on the student's code runs in the runner c starts (NULL: in
 * this process again). */
void remote_configure(const struct remote_config *c);
bool remote_active(void);
void remote_shutdown(void);
/* Runners started so far (the first, and one after each failure). */
uint64_t remote_starts(void);

/* Ask for triangles first .. first + count - 1 of s drawn on a fresh
 * target; a 3-D scene (with clip) is first projected by the front end
 * around the student's clipper (remote_projected, exercise_clip_fault).
 * trace: enum wire_trace (wire.h). Each triangle then comes back through remote_triangle, in order. */
bool remote_begin(const struct scene *s, const struct raster_params *p, int first, int count,
                  int trace, bool clip, bool both_ways, int write_line);
/* The next triangle: its changed pixels into fb, its events to tr's sink,
 * its counters into tr, its faults into exercise_fault(). False when the
 * runner failed (exercise_runner_fault). */
bool remote_triangle(struct target *fb, struct trace *tr);
/* Done with the scene (the rest, if any, is not drawn). */
void remote_end(void);
const struct scene *remote_projected(void);

#endif
