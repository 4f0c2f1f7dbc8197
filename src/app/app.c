/* app.c - the explorer window: SDL2 shows what the cairo painter draws.
 *
 * cairo paints the whole frame straight into a streaming ARGB8888 texture
 * (the two formats agree byte for byte, and SDL's pitch is cairo's stride),
 * which SDL copies to the window. Nothing is painted while nothing changes:
 * paused, the loop sleeps in SDL_WaitEvent; playing, it wakes on a timer at
 * the explorer's speed.
 *
 * --keys FILE feeds key names (and "wait", "drag X1 Y1 X2 Y2") into the same
 * event queue as the keyboard and mouse, so that a test can drive the real
 * program without a display.
 */
#define _POSIX_C_SOURCE 200809L   /* access */

#include "app.h"

#include <SDL.h>
#include <cairo.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>      /* access: a free name for a saved scene */

#include "display.h"
#include "params.h"
#include "pointer.h"
#include "draw/paint.h"
#include "script.h"
#include "util/file.h"

#if defined(__SANITIZE_ADDRESS__)
#define TRISTEP_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TRISTEP_LSAN 1
#endif
#endif
#ifdef TRISTEP_LSAN
#include <sanitizer/lsan_interface.h>
#endif

#define SPEED_MAX 40        /* 2^20 events per second */
#define FRAME_MS 16         /* at most one frame this often while playing */

struct app {
    const struct lesson *lesson;
    struct explorer ex;
    SDL_Window *win;
    SDL_Renderer *ren;
    SDL_Texture *tex;
    int tw, th;                 /* texture (= frame) size in pixels */
    double ratio;               /* pixels per window unit: 2 on a HiDPI screen that
                                 * counts windows and the mouse in points */
    bool dirty, quit, failed;

    struct pointer ptr;         /* the mouse */

    Uint64 count_shown;         /* when the counting progress was last shown */

    struct frame_times frames;  /* TRISTEP_FRAME_TIMES=FILE: every frame's milliseconds */

    /* playing: events owed to the clock */
    double play_debt;
    Uint64 play_last;

    /* --keys */
    struct script script;
    size_t at;
    bool scripted;
};

/* --- SDL errors ------------------------------------------------------------------- */

static bool sdl_failed(struct app *a, const char *call)
{
    fprintf(stderr, "%s: %s failed: %s\n", a->lesson->id, call, SDL_GetError());
    a->failed = true;
    return false;
}

/* An explorer call ran out of memory: nothing sensible is left to show. */
static void out_of_memory(struct app *a)
{
    fprintf(stderr, "%s: out of memory while re-running the lesson\n", a->lesson->id);
    a->failed = a->quit = true;
}

/* --- painting -------------------------------------------------------------------- */

/* The frame is as large as the window's drawable, in pixels; the layout
 * and the mouse count in window units (the same on X11 and Windows, points
 * on macOS and Wayland's scaled outputs). */
static bool make_texture(struct app *a)
{
    int w, h, ww, wh;
    if (SDL_GetRendererOutputSize(a->ren, &w, &h) != 0)
        return sdl_failed(a, "SDL_GetRendererOutputSize");
    SDL_GetWindowSize(a->win, &ww, &wh);
    a->ratio = ww > 0 && w > ww ? (double)w / ww : 1;
    if (a->tex && w == a->tw && h == a->th)
        return true;
    if (a->tex)
        SDL_DestroyTexture(a->tex);
    a->tex = SDL_CreateTexture(a->ren, SDL_PIXELFORMAT_ARGB8888, SDL_TEXTUREACCESS_STREAMING, w, h);
    if (!a->tex)
        return sdl_failed(a, "SDL_CreateTexture");
    if (SDL_SetTextureBlendMode(a->tex, SDL_BLENDMODE_NONE) != 0)
        return sdl_failed(a, "SDL_SetTextureBlendMode");
    a->tw = w, a->th = h;
    return true;
}

static bool present(struct app *a)
{
    Uint64 t0 = SDL_GetPerformanceCounter();
    if (!make_texture(a))
        return false;
    void *pixels;
    int pitch;
    if (SDL_LockTexture(a->tex, NULL, &pixels, &pitch) != 0)
        return sdl_failed(a, "SDL_LockTexture");
    /* the lock is write-only: all of it */
    cairo_status_t st = explorer_paint_pixels(&a->ex, pixels, a->tw, a->th, pitch, a->ratio);
    SDL_UnlockTexture(a->tex);
    if (st != CAIRO_STATUS_SUCCESS) {
        fprintf(stderr, "%s: painting failed: %s\n", a->lesson->id, cairo_status_to_string(st));
        a->failed = true;
        return false;
    }
    if (SDL_RenderCopy(a->ren, a->tex, NULL, NULL) != 0)
        return sdl_failed(a, "SDL_RenderCopy");
    SDL_RenderPresent(a->ren);
    a->dirty = false;
    frame_times_add(&a->frames, (double)(SDL_GetPerformanceCounter() - t0) * 1e3
                                / (double)SDL_GetPerformanceFrequency());
    return true;
}

/* The frame's size in window units. */
static double frame_w(const struct app *a) { return a->tw / a->ratio; }
static double frame_h(const struct app *a) { return a->th / a->ratio; }

static void layout(struct app *a, struct explorer_layout *L)
{
    explorer_layout(&a->ex, frame_w(a), frame_h(a), L);
}

/* --- keys ------------------------------------------------------------------------ */

static void say(struct app *a, const char *fmt, const char *arg)
{
    snprintf(a->ex.message, sizeof a->ex.message, fmt, arg);
}

static void step(struct app *a, enum step_unit unit, int dir)
{
    a->ex.playing = false;
    if (!explorer_move(&a->ex, unit, dir))
        out_of_memory(a);
}

static void set_step(struct app *a, uint64_t s)
{
    a->ex.playing = false;
    if (!explorer_set_step(&a->ex, s))
        out_of_memory(a);
}

static void export_view(struct app *a)
{
    char png[200], svg[200], err[480];
    const char *view = explorer_view_name(&a->ex, a->ex.view);
    snprintf(png, sizeof png, "tristep-%s-step%llu-%s.png", a->lesson->id,
             (unsigned long long)a->ex.step, view);
    snprintf(svg, sizeof svg, "tristep-%s-step%llu-%s.svg", a->lesson->id,
             (unsigned long long)a->ex.step, view);
    a->ex.message[0] = '\0';            /* the figure shows the view, not the last message */
    bool help = a->ex.help;
    a->ex.help = false;
    int w = (int)lrint(frame_w(a)), h = (int)lrint(frame_h(a));  /* the window as laid out */
    bool ok = explorer_export(&a->ex, png, w, h, err, sizeof err)
              && explorer_export(&a->ex, svg, w, h, err, sizeof err);
    a->ex.help = help;
    if (ok) {
        snprintf(a->ex.message, sizeof a->ex.message, "exported %s and %s", png, svg);
        printf("%s: %s\n", a->lesson->id, a->ex.message);
        fflush(stdout);
    } else {
        snprintf(a->ex.message, sizeof a->ex.message, "export failed: %s", err);
        fprintf(stderr, "%s: %s\n", a->lesson->id, a->ex.message);
    }
}

static bool scene_writer(FILE *out, void *ctx)
{
    const struct explorer *ex = ctx;
    fprintf(out, "# saved from the %s explorer at step %llu (%s)\n", ex->lesson->id,
            (unsigned long long)ex->step, ex->scene_name);
    struct scene s = ex->scene;     /* with its own background, not the page's */
    memcpy(s.background, ex->own_background, sizeof s.background);
    return scene_write(&s, out);
}

/* S: the scene as it is now, dragged vertices included, to a new file
 * tristep-NN-name-K.scene in the current directory (K the first number
 * free), for --scene, and for `make check LESSON=NN SCENE=file`. A 3-D
 * scene is saved as a 3-D scene, its camera and world triangles (dragging
 * there moves the model's vertices, so they are saved with it). */
static void save_scene(struct app *a)
{
    char path[200], err[480];
    for (int k = 1; k < 10000; k++) {
        snprintf(path, sizeof path, "tristep-%s-%d.scene", a->lesson->id, k);
        if (access(path, F_OK) != 0)
            break;
    }
    if (write_file_atomic(path, scene_writer, &a->ex, err, sizeof err)) {
        snprintf(a->ex.message, sizeof a->ex.message, "saved the %s to %.160s: make check LESSON=%.2s "
                 "SCENE=%.160s adds it to the checks", a->ex.scene.world.camera_line
                 ? "3-D scene (its camera and world triangles)" : "scene",
                 path, a->lesson->id, path);
        printf("%s: %s\n", a->lesson->id, a->ex.message);
        fflush(stdout);
    } else {
        snprintf(a->ex.message, sizeof a->ex.message, "saving the scene failed: %s", err);
        fprintf(stderr, "%s: %s\n", a->lesson->id, a->ex.message);
    }
}

static void set_params(struct app *a, const struct raster_params *p, const char *what)
{
    if (!explorer_set_params(&a->ex, p)) {
        out_of_memory(a);
        return;
    }
    snprintf(a->ex.message, sizeof a->ex.message, "%s", what);
}

static bool has_twins(const struct lesson *l)
{
    for (int i = 1; i < l->nvariants; i++)
        if (!variant_against_exact(&l->variants[i]))
            return true;
    return false;
}

/* The window's own keys: key() reads these and no others, before a
 * lesson's parameter keys (params.c), so a lesson's table must use none of
 * them (tests/test_window.c holds every lesson to it). */
static const SDL_Keycode window_keys[] = {
    SDLK_RIGHT, SDLK_LEFT, SDLK_PAGEDOWN, SDLK_PAGEUP, SDLK_HOME, SDLK_END, SDLK_SPACE,
    SDLK_PLUS, SDLK_EQUALS, SDLK_KP_PLUS, SDLK_MINUS, SDLK_KP_MINUS, SDLK_v,
    SDLK_0, SDLK_1, SDLK_2, SDLK_3, SDLK_n, SDLK_x, SDLK_t, SDLK_e, SDLK_l, SDLK_c,
    SDLK_s, SDLK_f, SDLK_h, SDLK_F1, SDLK_q, SDLK_ESCAPE,
};

bool app_window_key(int k)
{
    for (size_t i = 0; i < sizeof window_keys / sizeof *window_keys; i++)
        if (window_keys[i] == k)
            return true;
    return false;
}

static void key(struct app *a, SDL_Keycode k, Uint16 mod)
{
    struct explorer *ex = &a->ex;
    enum step_unit unit = mod & KMOD_CTRL ? STEP_TRIANGLE : mod & KMOD_SHIFT ? STEP_GROUP : STEP_EVENT;
    char buf[96];
    struct raster_params p = ex->params;
    ex->message[0] = '\0';
    a->dirty = true;
    if (!app_window_key(k)) {   /* a key of a row of the lesson's parameter table, or none */
        if (params_key(a->lesson, (int)k, &p, buf, sizeof buf))
            set_params(a, &p, buf);
        else
            a->dirty = false;
        return;
    }
    switch (k) {
    case SDLK_RIGHT: step(a, unit, +1); break;
    case SDLK_LEFT: step(a, unit, -1); break;
    case SDLK_PAGEDOWN: step(a, STEP_EVENT, +1); break;
    case SDLK_PAGEUP: step(a, STEP_EVENT, -1); break;
    case SDLK_HOME: set_step(a, 0); break;
    case SDLK_END: set_step(a, ex->replay.total); break;
    case SDLK_SPACE:
        ex->playing = !ex->playing;
        if (ex->playing && ex->step >= ex->replay.total && !explorer_set_step(ex, 0))
            out_of_memory(a);
        a->play_debt = 0;
        a->play_last = SDL_GetTicks64();
        break;
    case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS:
    case SDLK_MINUS: case SDLK_KP_MINUS: {
        int d = k == SDLK_MINUS || k == SDLK_KP_MINUS ? -1 : +1;
        ex->speed = ex->speed + d < 0 ? 0 : ex->speed + d > SPEED_MAX ? SPEED_MAX : ex->speed + d;
        snprintf(buf, sizeof buf, "speed %.4g events per second", exp2(ex->speed / 2.0));
        say(a, "%s", buf);
        break;
    }
    case SDLK_v: {
        int n = explorer_view_count(ex);
        ex->view = (ex->view + (mod & KMOD_SHIFT ? n - 1 : 1)) % n;
        break;
    }
    case SDLK_0: case SDLK_1: case SDLK_2: case SDLK_3:
        ex->view = VIEW_EDGES;
        ex->edge = (int)(k - SDLK_0) - 1;
        break;
    case SDLK_n: ex->numbers = (ex->numbers + 1) % NUMBERS_MODE_COUNT; break;
    case SDLK_x:
        if (!explorer_cycle_exhibit(ex))
            out_of_memory(a);
        break;
    case SDLK_t:
        if (has_twins(a->lesson) && !explorer_cycle_twin(ex))
            out_of_memory(a);
        break;
    case SDLK_e: export_view(a); break;
    case SDLK_l:    /* figures for print: the light theme, also in the window */
        if (!explorer_set_theme(ex, ex->theme == THEME_LIGHT ? THEME_DARK : THEME_LIGHT))
            out_of_memory(a);
        else
            say(a, "%s theme", theme_name(ex->theme));
        break;
    case SDLK_c:    /* the pixel grid alone, as --figure-part canvas */
        ex->part = ex->part == PART_CANVAS ? PART_ALL : PART_CANVAS;
        say(a, "%s", ex->part == PART_CANVAS ? "the pixel grid alone (C: panel and bar back)"
                                             : "panel and scrub bar");
        break;
    case SDLK_s: save_scene(a); break;
    case SDLK_f: ex->zoom = 0; break;
    case SDLK_h: case SDLK_F1: ex->help = !ex->help; break;
    case SDLK_q: case SDLK_ESCAPE: a->quit = true; break;
    default: break;     /* none: window_keys holds only the keys above */
    }
}

/* --- the mouse (pointer.c) ------------------------------------------------------------ */

static void mouse_down(struct app *a, double x, double y)
{
    struct explorer_layout L;
    layout(a, &L);
    pointer_down(&a->ptr, &a->ex, &L, x, y);
}

static void mouse_move(struct app *a, double x, double y)
{
    struct explorer_layout L;
    layout(a, &L);
    if (pointer_move(&a->ptr, &a->ex, &L, x, y))
        a->dirty = true;
}

static void drop_vertex(struct app *a)
{
    if (!pointer_drop(&a->ptr, &a->ex))
        out_of_memory(a);
}

static void mouse_up(struct app *a, double x, double y)
{
    struct explorer_layout L;
    layout(a, &L);
    bool dirty;
    if (!pointer_up(&a->ptr, &a->ex, &L, x, y, &dirty))
        out_of_memory(a);
    if (dirty)
        a->dirty = true;
}

static void wheel(struct app *a, int dy)
{
    int mx, my;
    SDL_GetMouseState(&mx, &my);
    struct explorer_layout L;
    layout(a, &L);
    if (pointer_wheel(&a->ex, &L, mx, my, dy))
        a->dirty = true;
}

/* --- --keys ------------------------------------------------------------------------- */

static void play(struct app *a);

static bool push_key(SDL_Keycode k, Uint16 mod)
{
    SDL_Event ev = { .type = SDL_KEYDOWN };
    ev.key.state = SDL_PRESSED;
    ev.key.keysym.sym = k;
    ev.key.keysym.scancode = SDL_GetScancodeFromKey(k);
    ev.key.keysym.mod = mod;
    return SDL_PushEvent(&ev) >= 0;
}

static bool push_mouse(Uint32 type, int x, int y)
{
    SDL_Event ev = { .type = type };
    if (type == SDL_MOUSEMOTION) {
        ev.motion.x = x, ev.motion.y = y;
        ev.motion.state = SDL_BUTTON_LMASK;
    } else {
        ev.button.button = SDL_BUTTON_LEFT;
        ev.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
        ev.button.clicks = 1;
        ev.button.x = x, ev.button.y = y;
    }
    return SDL_PushEvent(&ev) >= 0;
}

/* Every key name of the script is one SDL knows (after SDL_Init: the names
 * of keys come from the keyboard map); an unknown one is an input error. */
static bool check_script_keys(struct app *a)
{
    for (size_t i = 0; i < a->script.n; i++) {
        const struct script_cmd *c = &a->script.cmd[i];
        if (c->kind == SCRIPT_KEY && SDL_GetKeyFromName(c->key) == SDLK_UNKNOWN) {
            fprintf(stderr, "%s:%d: unknown key '%s' (SDL's key names: Right, PageDown, v, ...)\n",
                    a->script.name, c->line, c->key);
            return false;
        }
    }
    return true;
}

/* Turn the next script command into events (script.h). */
static void next_script_line(struct app *a)
{
    const struct script_cmd *c = &a->script.cmd[a->at++];
    switch (c->kind) {
    case SCRIPT_WAIT:
        a->dirty = true;            /* one frame, and a tenth of a second to play in */
        if (!present(a))
            a->quit = true;
        SDL_Delay(100);
        if (a->ex.playing)
            play(a);
        return;
    case SCRIPT_DRAG:
        push_mouse(SDL_MOUSEBUTTONDOWN, c->x1, c->y1);
        for (int i = 1; i <= 4; i++)
            push_mouse(SDL_MOUSEMOTION, c->x1 + (c->x2 - c->x1) * i / 4,
                       c->y1 + (c->y2 - c->y1) * i / 4);
        push_mouse(SDL_MOUSEBUTTONUP, c->x2, c->y2);
        return;
    case SCRIPT_KEY:
        push_key(SDL_GetKeyFromName(c->key), (c->mods & SCRIPT_SHIFT ? KMOD_LSHIFT : 0)
                                             | (c->mods & SCRIPT_CTRL ? KMOD_LCTRL : 0));
        return;
    }
}

/* --- the loop --------------------------------------------------------------------- */

static void handle(struct app *a, const SDL_Event *ev)
{
    switch (ev->type) {
    case SDL_QUIT: a->quit = true; break;
    case SDL_KEYDOWN: key(a, ev->key.keysym.sym, ev->key.keysym.mod); break;
    case SDL_MOUSEBUTTONDOWN:
        if (ev->button.button == SDL_BUTTON_LEFT)
            mouse_down(a, ev->button.x, ev->button.y);
        break;
    case SDL_MOUSEMOTION: mouse_move(a, ev->motion.x, ev->motion.y); break;
    case SDL_MOUSEBUTTONUP:
        if (ev->button.button == SDL_BUTTON_LEFT)
            mouse_up(a, ev->button.x, ev->button.y);
        break;
    case SDL_MOUSEWHEEL:
        wheel(a, ev->wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -ev->wheel.y : ev->wheel.y);
        break;
    case SDL_WINDOWEVENT:
        if (ev->window.event == SDL_WINDOWEVENT_SIZE_CHANGED
            || ev->window.event == SDL_WINDOWEVENT_EXPOSED)
            a->dirty = true;
        break;
    default: break;
    }
}

/* Playing: advance by the events the clock owes (2^(speed/2) per second). */
static void play(struct app *a)
{
    struct explorer *ex = &a->ex;
    Uint64 now = SDL_GetTicks64();
    a->play_debt += (double)(now - a->play_last) / 1000.0 * exp2(ex->speed / 2.0);
    a->play_last = now;
    if (a->play_debt < 1)
        return;
    uint64_t n = (uint64_t)a->play_debt;
    a->play_debt -= (double)n;
    uint64_t to = ex->step + n > ex->replay.total ? ex->replay.total : ex->step + n;
    if (!explorer_set_step(ex, to))
        out_of_memory(a);
    if (ex->step >= ex->replay.total)
        ex->playing = false;
    a->dirty = true;
}

/* Milliseconds until the next played event is due. */
static int play_wait(const struct app *a)
{
    double eps = exp2(a->ex.speed / 2.0);
    double ms = (1.0 - a->play_debt) / eps * 1000.0;
    return ms < FRAME_MS ? FRAME_MS : ms > 1000 ? 1000 : (int)ms;
}

/* A large scene's steps are counted while nothing else happens, a slice at
 * a time, so keys and the mouse still answer; the scrub bar shows the
 * progress a few times a second. */
#define COUNT_SLICE_MS 20
#define COUNT_SHOW_MS 250

static void count_some(struct app *a)
{
    if (!explorer_count(&a->ex, COUNT_SLICE_MS)) {
        out_of_memory(a);
        return;
    }
    Uint64 now = SDL_GetTicks64();
    if (now - a->count_shown >= COUNT_SHOW_MS || !explorer_counting(&a->ex)) {
        a->count_shown = now;
        a->dirty = true;
    }
}

static void run(struct app *a)
{
    SDL_Event ev;
    while (!a->quit) {
        if (a->dirty && !present(a))
            return;
        bool got;
        if (explorer_counting(&a->ex) && !SDL_PollEvent(NULL)) {
            count_some(a);      /* before a script's next line: scripts see every step */
            continue;
        }
        if (a->at < a->script.n && !SDL_PollEvent(NULL)) {
            next_script_line(a);
            continue;
        }
        if (a->scripted && a->at >= a->script.n && !SDL_PollEvent(NULL)) {
            a->quit = true;             /* the script ran out without "q" */
            break;
        }
        if (a->ex.playing)
            got = SDL_WaitEventTimeout(&ev, play_wait(a));
        else if (!(got = SDL_WaitEvent(&ev))) {
            sdl_failed(a, "SDL_WaitEvent");
            return;
        }
        if (got) {
            handle(a, &ev);
            while (!a->quit && SDL_PollEvent(&ev))
                handle(a, &ev);
            drop_vertex(a);
        }
        if (a->ex.playing && !a->quit)
            play(a);
    }
}

/* Resizable, and sharp on HiDPI screens: where windows count in points
 * (macOS, Wayland) the drawable has more pixels than the window and the
 * frame is painted at that ratio; where they count in pixels (X11,
 * Windows) a screen of high density gets a larger interface scale and
 * window, unless --scale or --size says otherwise. */
static bool open_window(struct app *a, const struct app_desc *d)
{
    char title[160];
    snprintf(title, sizeof title, "tristep %s: %s", a->lesson->id, a->lesson->title);
    int w = d->width ? d->width : 1280, h = d->height ? d->height : 800;
    a->win = SDL_CreateWindow(title, SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, w, h,
                              SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (!a->win)
        return sdl_failed(a, "SDL_CreateWindow");
    SDL_SetWindowMinimumSize(a->win, 320, 240);
    a->ren = SDL_CreateRenderer(a->win, -1, 0);
    if (!a->ren)
        return sdl_failed(a, "SDL_CreateRenderer");
    if (!make_texture(a))
        return false;
    int display = SDL_GetWindowDisplayIndex(a->win);
    if (a->ratio == 1 && d->explorer.scale <= 0 && display >= 0 && display_scale(display) != 1) {
        /* pixels, not points: the interface grows instead, and the window with it */
        a->ex.scale = display_scale(display);
        SDL_Rect usable;
        if (!d->width && SDL_GetDisplayUsableBounds(display, &usable) == 0) {
            w = (int)fmin(w * a->ex.scale, usable.w);
            h = (int)fmin(h * a->ex.scale, usable.h);
            SDL_SetWindowSize(a->win, w, h);
            SDL_SetWindowPosition(a->win, SDL_WINDOWPOS_CENTERED_DISPLAY(display),
                                  SDL_WINDOWPOS_CENTERED_DISPLAY(display));
            return make_texture(a);
        }
    }
    return true;
}

int explorer_run(const struct app_desc *d)
{
    const struct lesson *l = d->explorer.lesson;
    struct app a = { .lesson = l, .dirty = true };
    char err[512];
    if (d->keys) {
        if (!script_load(&a.script, d->keys, err, sizeof err)) {
            fprintf(stderr, "%s\n", err);
            return EXIT_USAGE;
        }
        a.scripted = true;
        if (!check_script_keys(&a)) {
            script_free(&a.script);
            return EXIT_USAGE;
        }
    }
    int status = EXIT_OK;
    if (!explorer_fonts(err, sizeof err))
        fprintf(stderr, "%s: %s; the text will not look as in the figures\n", l->id, err);
    if (!display_init(l->id)) {
        status = EXIT_RUN;             /* no display, or SDL could not start */
    } else if (!explorer_init(&a.ex, &d->explorer, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = EXIT_RUN;
    } else {
        if (d->view)
            explorer_set_view_name(&a.ex, d->view);
        if (open_window(&a, d))
            run(&a);
        if (a.failed)
            status = EXIT_RUN;
        explorer_free(&a.ex);
    }
    if (a.tex)
        SDL_DestroyTexture(a.tex);
    if (a.ren)
        SDL_DestroyRenderer(a.ren);
    if (a.win)
        SDL_DestroyWindow(a.win);
    script_free(&a.script);
    frame_times_write(&a.frames, l->id);
#ifdef TRISTEP_LSAN
    /* everything of ours is freed: look for leaks now, while the libraries
     * SDL loaded are still there to name theirs (SDL_Quit unloads them) */
    __lsan_do_leak_check();
#endif
    SDL_Quit();
    return status;
}
