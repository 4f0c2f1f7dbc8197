/* display.c - finding a display, its density, and the frame-time record. */
#include "display.h"

#include <SDL.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool no_display(const char *id, const char *why)
{
    fprintf(stderr,
            "%s: no display found (%s): the explorer needs a window.\n"
            "Pictures without one:\n"
            "  %s --figure step40.png --step 40 --view coverage   the explorer's view (.png, .svg, .pdf)\n"
            "  %s --dump-image final.png                          the finished picture\n"
            "Over SSH, 'ssh -X' brings the window to your screen; SDL_VIDEODRIVER=x11 or\n"
            "wayland names a display driver, SDL_VIDEODRIVER=offscreen runs without one.\n",
            id, why, id, id);
    return false;
}

bool display_init(const char *id)
{
    const char *chosen = SDL_getenv("SDL_VIDEODRIVER");
    bool explicit = chosen && *chosen;
    bool named = SDL_getenv("DISPLAY") || SDL_getenv("WAYLAND_DISPLAY");
    if (SDL_Init(SDL_INIT_VIDEO | SDL_INIT_TIMER) != 0) {
        if (!explicit && !named) {
            char why[300];
            snprintf(why, sizeof why, "DISPLAY and WAYLAND_DISPLAY are not set; SDL_Init: %s",
                     SDL_GetError());
            return no_display(id, why);
        }
        fprintf(stderr, "%s: SDL_Init failed: %s\n", id, SDL_GetError());
        return false;
    }
    const char *driver = SDL_GetCurrentVideoDriver();
    if (!explicit && driver && (strcmp(driver, "offscreen") == 0 || strcmp(driver, "dummy") == 0)) {
        char why[200];
        snprintf(why, sizeof why, "SDL fell back to its '%s' video driver%s", driver,
                 named ? "" : "; DISPLAY and WAYLAND_DISPLAY are not set");
        return no_display(id, why);
    }
    return true;
}

/* GDK_SCALE where the desktop set it (HiDPI desktops set it for every
 * program), else from the screen's dots per inch where SDL knows them:
 * whole steps from 168 dpi (192 gives 2), at most 3, since a physical DPI
 * a little above 96 is usually meant to be used at 1. */
double display_scale(int display)
{
    const char *gdk = SDL_getenv("GDK_SCALE");
    int n = gdk ? SDL_atoi(gdk) : 0;
    if (n >= 1 && n <= 4)
        return n;
    float dpi;
    if (SDL_GetDisplayDPI(display, &dpi, NULL, NULL) == 0 && dpi >= 168)
        return fmin(round(dpi / 96), 3);
    return 1;
}

void frame_times_add(struct frame_times *f, double ms)
{
    if (!SDL_getenv("TRISTEP_FRAME_TIMES"))
        return;
    if (f->n == f->cap) {
        size_t cap = f->cap ? 2 * f->cap : 1024;
        float *m = cap < ((size_t)1 << 24) ? realloc(f->ms, cap * sizeof *m) : NULL;
        if (!m)
            return;
        f->ms = m;
        f->cap = cap;
    }
    f->ms[f->n++] = (float)ms;
}

void frame_times_write(struct frame_times *f, const char *id)
{
    const char *path = SDL_getenv("TRISTEP_FRAME_TIMES");
    FILE *out = path ? fopen(path, "w") : NULL;
    if (path && !out)
        fprintf(stderr, "%s: TRISTEP_FRAME_TIMES '%s': cannot write\n", id, path);
    for (size_t i = 0; out && i < f->n; i++)
        fprintf(out, "%.3f\n", f->ms[i]);
    if (out)
        fclose(out);
    free(f->ms);
    *f = (struct frame_times){ 0 };
}
