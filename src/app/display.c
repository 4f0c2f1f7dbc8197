/* display.c - finding a display, its density, and the frame-time record. */
#include "display.h"

#include <SDL.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SDL_VIDEO_DRIVER_X11     /* SDL's X11 driver: Xlib's headers come with it */
#include <X11/Xlib.h>
#include <dlfcn.h>
#endif

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

#ifdef SDL_VIDEO_DRIVER_X11
/* An X request fails asynchronously: its error comes back later, while the
 * program goes on. Xlib's default handler then prints it and exits, which
 * SDL keeps (its handler passes errors on to the one before it). A request
 * can fail so with nothing wrong in the program: SDL talks to the server
 * over two connections (the second sends the window a message that wakes
 * the event loop), and the server may take a request of one after a later
 * request of the other, which may have closed the window; or another
 * client resizes or closes the window at the same moment. Here the error
 * is told in Xlib's words and the window goes on. At most X_ERRORS_SHOWN
 * are printed. */
#define X_ERRORS_SHOWN 8

static const char *x_id;
static int x_errors;
static int (*x_error_text)(Display *, int, char *, int);
static int (*x_database_text)(Display *, const char *, const char *, const char *, char *, int);

static int x_error(Display *dpy, XErrorEvent *e)
{
    if (++x_errors > X_ERRORS_SHOWN)
        return 0;
    /* no requests here (Xlib forbids them in a handler): names from its database */
    char text[160] = "", request[160] = "", number[16];
    x_error_text(dpy, e->error_code, text, sizeof text);
    snprintf(number, sizeof number, "%d", e->request_code);
    if (e->request_code < 128)
        x_database_text(dpy, "XRequest", number, "", request, sizeof request);
    fprintf(stderr,
            "%s: X Error of failed request:  %s\n"
            "  Major opcode of failed request:  %d%s%s%s\n"
            "  Minor opcode of failed request:  %d\n"
            "  Resource id in failed request:  0x%lx\n"
            "  Serial number of failed request:  %lu\n"
            "%s: the window goes on%s\n",
            x_id, text, e->request_code, *request ? " (" : "", request, *request ? ")" : "",
            e->minor_code, (unsigned long)e->resourceid, e->serial, x_id,
            x_errors == X_ERRORS_SHOWN ? "; further X errors are not shown" : "");
    return 0;
}

/* A function of a library opened with dlopen (POSIX: a dlsym result fits a
 * function pointer; ISO C has no cast from one to the other). */
static bool symbol(void *lib, const char *name, void *fn, size_t size)
{
    void *p = dlsym(lib, name);
    if (p && size == sizeof p)
        memcpy(fn, &p, size);
    return p && size == sizeof p;
}

/* The handler goes in before SDL_Init where Xlib is loaded already (SDL
 * linked with it): SDL's own handler then passes errors on to it (after
 * putting back the screen modes it changed), and SDL_Quit puts it back.
 * Where SDL loads Xlib itself, it goes in
 * after SDL_Init and lasts until SDL_Quit. RTLD_NOLOAD: only the Xlib
 * already there, never a second one. */
static bool x_errors_not_fatal(const char *id)
{
    void *xlib = dlopen("libX11.so.6", RTLD_LAZY | RTLD_NOLOAD);
    XErrorHandler (*set)(XErrorHandler) = NULL;
    bool done = xlib && symbol(xlib, "XSetErrorHandler", &set, sizeof set)
                && symbol(xlib, "XGetErrorText", &x_error_text, sizeof x_error_text)
                && symbol(xlib, "XGetErrorDatabaseText", &x_database_text, sizeof x_database_text);
    if (done) {
        x_id = id;
        set(x_error);
    }
    if (xlib)
        dlclose(xlib);          /* the reference SDL holds keeps it loaded */
    return done;
}
#endif

bool display_init(const char *id)
{
#ifdef SDL_VIDEO_DRIVER_X11
    bool x_handled = x_errors_not_fatal(id);
#endif
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
#ifdef SDL_VIDEO_DRIVER_X11
    if (!x_handled && driver && strcmp(driver, "x11") == 0)
        x_errors_not_fatal(id);
#endif
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
