/* display.h - what the window needs to know of the screen before it opens:
 * whether there is one, how dense it is; and the frame-time record that
 * the soak test reads. */
#ifndef TRISTEP_DISPLAY_H
#define TRISTEP_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>

/* SDL_Init for video. False, with the reason on stderr, when SDL failed or
 * found no display (an SSH session, a container: SDL would fall back to a
 * driver that shows nothing and wait for a window no one sees); the
 * message then shows the commands that make pictures without a window. A
 * driver chosen in SDL_VIDEODRIVER is obeyed, offscreen or dummy too. */
bool display_init(const char *id);

/* The interface scale a high-density screen wants where windows count in
 * pixels (X11, Windows): 1, 2 or 3. */
double display_scale(int display);

/* TRISTEP_FRAME_TIMES=FILE: every frame's milliseconds (paint, upload,
 * present), kept while the window runs and written to FILE at the end. */
struct frame_times {
    float *ms;
    size_t n, cap;
};
void frame_times_add(struct frame_times *f, double ms);
/* Write them (when TRISTEP_FRAME_TIMES is set) and free them. */
void frame_times_write(struct frame_times *f, const char *id);

#endif
