/* fuzz.h - the fuzz harnesses: each takes one input of untrusted bytes,
 * feeds it where the programs would, checks what must hold whatever the
 * input, and aborts on a violation (libFuzzer and the sanitizers report it).
 *
 *     make fuzz [SECONDS=N]          each harness under libFuzzer (clang), N s each
 *     build/sanitize/fuzz-replay DIR  every file of DIR/NAME through harness NAME
 *
 * The replay needs no libFuzzer: `make test` runs it over the committed
 * corpus (tests/fuzz/corpus/NAME: seeds, and every input that ever failed)
 * in the sanitizer build, with gcc or clang. */
#ifndef TRISTEP_FUZZ_H
#define TRISTEP_FUZZ_H

#include <stddef.h>
#include <stdint.h>

/* Scene text (2-D and 3-D) -> scene_parse: accepted scenes hold only values
 * in range; a 3-D scene's front end makes screen triangles in the guard band
 * at depths in [near, far]; scene_write reads back the same. */
int fuzz_scene(const uint8_t *data, size_t size);
/* Wavefront OBJ text -> obj_read: accepted models hold only world points
 * within 10^6, in the obj line's colour, appended to what was there. */
int fuzz_obj(const uint8_t *data, size_t size);
/* --keys text -> script_parse: accepted scripts hold only valid commands. */
int fuzz_keys(const uint8_t *data, size_t size);
/* Scene text -> every exact variant of every lesson, narrated and fast, on
 * a small target: coverage equal to the reference rasterizer's. */
int fuzz_lessons(const uint8_t *data, size_t size);
/* Scene text -> the explorer (every lesson): replay to several steps,
 * stepping by every unit, every view painted into a small frame. */
int fuzz_explorer(const uint8_t *data, size_t size);

struct fuzz_harness {
    const char *name;
    int (*run)(const uint8_t *data, size_t size);
};
extern const struct fuzz_harness fuzz_harnesses[];   /* NULL-terminated */

/* A rejected input's message must be one line "name:LINE: ..." with a line
 * number from 1: abort otherwise. */
void fuzz_check_message(const char *err, const char *name);

/* Report a violated property and abort. */
_Noreturn void fuzz_fail(const char *fmt, ...);

#endif
