/* wire.h - what the judge (the exercise program, which decides) and the
 * runner (the student's code and the student library, which only draws)
 * say to each other through two pipes (lessons/README.md, "How to
 * assess": what is isolated and what is trusted).
 *
 * Every message is a record: a header (type, length of what follows) and
 * that many bytes. The judge asks for a scene drawn; the runner answers
 * with the raw results, triangle by triangle, and the judge reads them
 * strictly: a record of an unknown type, a length that is not the one its
 * type has, a count beyond the scene's, a pixel outside the target, is a
 * failed check ("your program sent what no drawing sends"), never a crash
 * of the judge, which trusts nothing the runner says.
 *
 *   judge -> runner (fd 0)   WIRE_DRAW: a scene (as its text, scene_write),
 *                            which triangles, at how many samples, with
 *                            what kind of trace; WIRE_STOP: no more of it
 *   runner -> judge (fd 3)   WIRE_PROJECTED (a 3-D scene: the screen
 *                            triangles the front end made around the
 *                            student's clipper, and its fault), then per
 *                            triangle its WIRE_EVENTs (each a trace_event
 *                            and the texel_reads counted since the one
 *                            before) and one WIRE_TRI (the
 *                            pixels it changed, its faults and counters),
 *                            then WIRE_DONE
 *
 * Both ends are built from the same sources by the same compiler, so the
 * structures travel as they are in memory; nothing in them is trusted by
 * the judge beyond what it checks. */
#ifndef TRISTEP_EXERCISE_WIRE_H
#define TRISTEP_EXERCISE_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "exercise/exercise.h"

#define WIRE_FD_IN 0            /* the runner reads requests here */
#define WIRE_FD_OUT 3           /* ... and writes results here (1 and 2 are its log) */

enum wire_type {
    WIRE_DRAW = 0x7d01, WIRE_STOP, WIRE_PROJECTED, WIRE_EVENT, WIRE_TRI, WIRE_DONE, WIRE_HELLO,
};

struct wire_header {
    uint32_t type, len;
};

/* The longest record the judge accepts: a 3-D scene's screen triangles,
 * or a triangle's changed pixels at 8 samples on the largest target. */
#define WIRE_MAX_LEN (1u << 30)

/* How the runner traces the triangles of a WIRE_DRAW. */
enum wire_trace { WIRE_TRACE_NONE, WIRE_TRACE_COUNT, WIRE_TRACE_EVENTS };

struct wire_draw {
    int32_t first, count;       /* triangles first .. first + count - 1 (screen triangles of a 3-D scene) */
    int32_t samples;            /* 0 or 1: the centre; 4, 8 */
    int32_t trace;              /* enum wire_trace */
    int32_t write_line;         /* lesson_exercise.write_line */
    int32_t clip;               /* a 3-D scene through the front end around exercise_clip */
    int32_t both_ways;          /* exercise_clip_both_ways */
    int32_t subpixel_bits, checker;
    int32_t knob[LESSON_PARAMS_MAX];
    uint32_t text_len;          /* the scene's text follows */
};

/* A 3-D scene's screen triangles: this, then ntris scene_tri, then ntris
 * ints (the world triangle each came from), then nworld bytes (per world
 * triangle: did the clipper give the lesson's polygons, as cyclic
 * sequences; exercise_clip_as_lesson). */
struct wire_projected {
    int32_t ntris, nworld;
    struct clip_fault fault;
};

/* The end of one triangle: this, then npix changed pixels, each a
 * wire_pixel and, at n samples, n colours and n depths. */
struct wire_tri {
    struct exercise_fault fault;
    struct texel_fault texel;
    uint64_t events;            /* trace.count: events narrated */
    struct trace_counters c;    /* trace.c */
    uint32_t npix;
    int32_t samples;            /* of the target now: 1, 4 or 8 */
};

struct wire_pixel {
    uint32_t index;             /* y * w + x, increasing */
    uint32_t color;
    float depth;
    uint32_t count;             /* 0 .. 255 */
};

/* Write a whole record; false when the other end is gone. */
bool wire_send(int fd, uint32_t type, const void *a, size_t alen, const void *b, size_t blen);
/* Read exactly n bytes (false at end of file or an error). */
bool wire_read(int fd, void *buf, size_t n);

#endif
