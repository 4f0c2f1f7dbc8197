/* test_window.c - the real explorer program, driven as a user drives it.
 *
 * Under SDL's dummy video driver a --keys script steps, switches views,
 * exports and quits; the exported PNG must be the very figure that --figure
 * draws for the same step, view and size. Under Xvfb the window receives
 * real key presses and a vertex drag from xdotool, and a screenshot of the
 * screen must be that same figure, pixel for pixel.
 *
 * Xvfb, xdotool and ImageMagick's `import` are test dependencies (`make test`
 * installs them): without them the Xvfb test fails, it does not pass quietly.
 */
#define _XOPEN_SOURCE 700         /* mkdtemp, kill, nanosleep, putenv */

#include <cairo.h>
#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "app/app.h"
#include "lesson.h"
#include "util/file.h"
#include "draw/paint.h"
#include "testlib.h"

#define PROGRAM "02-barycentric"
#define WIN_W 1280
#define WIN_H 800

/* --- processes ----------------------------------------------------------------------- */

static char dir[256];                   /* the test's working folder */
static pid_t xvfb_pid = -1, app_pid = -1;

static void sleep_ms(int ms)
{
    struct timespec t = { ms / 1000, (long)(ms % 1000) * 1000000L };
    nanosleep(&t, NULL);
}

/* Start argv in `dir` with extra environment "NAME=VALUE" entries ("NAME"
 * alone removes it), stdout
 * and stderr into files of dir; returns the pid. */
static pid_t start(char *const argv[], const char *const env[], const char *out, const char *err)
{
    fflush(NULL);
    pid_t pid = fork();
    cr_assert_neq(pid, -1, "fork: %s", strerror(errno));
    if (pid == 0) {
        if (chdir(dir) != 0)
            _exit(126);
        for (int i = 0; env && env[i]; i++) {
            if (strchr(env[i], '='))
                putenv((char *)env[i]);
            else
                unsetenv(env[i]);       /* "NAME" alone: not set */
        }
        int in = open("/dev/null", O_RDONLY);
        int o = open(out ? out : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int e = open(err ? err : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in < 0 || o < 0 || e < 0)
            _exit(126);
        dup2(in, 0), dup2(o, 1), dup2(e, 2);
        execvp(argv[0], argv);
        _exit(127);
    }
    return pid;
}

/* Wait for pid at most ms milliseconds; returns its exit status, or -1 if
 * it is still running (then it is killed). */
static int finish(pid_t *pid, int ms)
{
    int st;
    for (int t = 0; t <= ms; t += 20) {
        pid_t got = waitpid(*pid, &st, WNOHANG);
        if (got == *pid) {
            *pid = -1;
            return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        }
        sleep_ms(20);
    }
    kill(*pid, SIGKILL);
    waitpid(*pid, &st, 0);
    *pid = -1;
    return -1;
}

/* Run to the end (at most ms); returns the exit status, -1 on a timeout. */
static int run(char *const argv[], const char *const env[], const char *out, const char *err,
               int ms)
{
    pid_t pid = start(argv, env, out, err);
    return finish(&pid, ms);
}

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/tristep-window-XXXXXX");
    cr_assert(mkdtemp(dir), "mkdtemp: %s", strerror(errno));
}

/* Every path, a failed assertion included: stop what we started, remove dir. */
static void cleanup(void)
{
    if (app_pid > 0)
        finish(&app_pid, 0);
    if (xvfb_pid > 0) {
        kill(xvfb_pid, SIGTERM);
        if (finish(&xvfb_pid, 2000) == -1)
            xvfb_pid = -1;
    }
    if (!dir[0])
        return;
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char p[600];
        while ((e = readdir(d)))
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
                snprintf(p, sizeof p, "%s/%s", dir, e->d_name), unlink(p);
        closedir(d);
    }
    rmdir(dir);
    dir[0] = '\0';
}

static const char *in_dir(const char *name)
{
    static char p[4][600];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static const char *program(void)
{
    static char p[512];
    const char *b = test_build_dir();
    if (b[0] == '/')
        snprintf(p, sizeof p, "%s/%s", b, PROGRAM);
    else {
        char cwd[400];
        cr_assert(getcwd(cwd, sizeof cwd));
        snprintf(p, sizeof p, "%s/%s/%s", cwd, b, PROGRAM);
    }
    cr_assert_eq(access(p, X_OK), 0, "%s: not built (TRISTEP_BUILD=%s)", p, b);
    return p;
}

/* A whole file, or NULL (the project's own reader: src/util/file.h). */
static char *read_all(const char *path, size_t *len)
{
    char *text = NULL, err[256];
    size_t n = 0;
    if (!read_text_file(path, &text, &n, err, sizeof err))
        return NULL;
    if (len)
        *len = n;
    return text;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    cr_assert(f, "%s: %s", path, strerror(errno));
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

/* --- pictures ---------------------------------------------------------------------- */

static cairo_surface_t *load_png(const char *path)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    cr_assert_eq(cairo_surface_status(s), CAIRO_STATUS_SUCCESS, "%s: not a readable PNG: %s",
                 path, cairo_status_to_string(cairo_surface_status(s)));
    return s;
}

static uint32_t pixel(cairo_surface_t *s, int x, int y)
{
    cairo_surface_flush(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    return *(const uint32_t *)(d + (size_t)y * (size_t)cairo_image_surface_get_stride(s)
                               + (size_t)x * 4) & 0xffffff;
}

/* How many pixels of two same-sized pictures differ in colour (in a box). */
static long differing(cairo_surface_t *a, cairo_surface_t *b, int x0, int y0, int x1, int y1)
{
    long n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            n += pixel(a, x, y) != pixel(b, x, y);
    return n;
}

static void assert_svg(const char *path)
{
    size_t n;
    char *t = read_all(path, &n);
    cr_assert(t, "%s: missing", path);
    cr_assert(strncmp(t, "<?xml", 5) == 0 && strstr(t, "<svg") && strstr(t, "</svg>"),
              "%s: not an SVG document", path);
    free(t);
}

/* The figure the program draws headless for this step and view. */
static cairo_surface_t *figure(const char *name, const char *step, const char *view)
{
    char size[32];
    snprintf(size, sizeof size, "%dx%d", WIN_W, WIN_H);
    char *argv[] = { (char *)program(), "--figure", (char *)name, "--step", (char *)step,
                     "--view", (char *)view, "--size", size, NULL };
    cr_assert_eq(run(argv, NULL, NULL, "figure.err", 30000), 0, "--figure %s failed", name);
    return load_png(in_dir(name));
}

/* --- under SDL's dummy driver --------------------------------------------------------- */

static const char *const dummy_env[] = { "SDL_VIDEODRIVER=dummy", "SDL_RENDER_VSYNC=0", NULL };

Test(window, dummy_driver_keys_step_switch_views_export_quit, .fini = cleanup, .timeout = 60)
{
    make_dir();
    /* to step 3, coverage view, export; a tour of every key that changes
     * nothing lasting; back to step 3 in the colour view, export, quit */
    write_text(in_dir("keys"),
               "Right\nRight\nRight\nv\ne\n"
               "Shift+Right\nCtrl+Right\nEnd\nHome\nPageDown\nPageUp\n"
               "h\nwait\nF1\nn\nn\nn\n1\n0\n+\nKeypad +\n-\nKeypad -\n"
               "drag 10 10 60 40\nf\nwait\n"
               "Right\nRight\nRight\nShift+v\nShift+v\nSpace\nSpace\nHome\nRight\nRight\n"
               "Right\ne\nx\nx\nx\nt\nEnd\nq\nRight\n");
    char size[32];
    snprintf(size, sizeof size, "%dx%d", WIN_W, WIN_H);
    char *argv[] = { (char *)program(), "--keys", "keys", "--size", size, NULL };
    int st = run(argv, dummy_env, "out", "err", 30000);
    char *err = read_all(in_dir("err"), NULL), *out = read_all(in_dir("out"), NULL);
    cr_assert_eq(st, 0, "exit status %d; stderr:\n%s", st, err ? err : "");
    const char *png1 = "tristep-" PROGRAM "-step3-coverage.png";
    const char *svg1 = "tristep-" PROGRAM "-step3-coverage.svg";
    const char *png2 = "tristep-" PROGRAM "-step3-color.png";
    const char *svg2 = "tristep-" PROGRAM "-step3-color.svg";
    cr_assert(out && strstr(out, png1) && strstr(out, svg1) && strstr(out, png2)
              && strstr(out, svg2), "the export messages name the files; stdout:\n%s",
              out ? out : "");
    free(err);
    free(out);
    assert_svg(in_dir(svg1));
    assert_svg(in_dir(svg2));
    /* the exports are the figures of step 3, byte for byte */
    const char *pairs[2][2] = { { png1, "coverage" }, { png2, "color" } };
    for (int i = 0; i < 2; i++) {
        cairo_surface_t *got = load_png(in_dir(pairs[i][0]));
        cr_assert_eq(cairo_image_surface_get_width(got), WIN_W);
        cr_assert_eq(cairo_image_surface_get_height(got), WIN_H);
        cairo_surface_t *want = figure("want.png", "3", pairs[i][1]);
        cr_assert_eq(differing(got, want, 0, 0, WIN_W, WIN_H), 0,
                     "%s differs from --figure --step 3 --view %s", pairs[i][0], pairs[i][1]);
        cairo_surface_destroy(got);
        cairo_surface_destroy(want);
    }
}

/* S saves the scene as it is now, dragged vertex included, to a new file
 * each time; the file is what --scene and make check's SCENE= read. */
Test(window, s_saves_the_scene_with_its_dragged_vertex, .fini = cleanup, .timeout = 60)
{
    make_dir();
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "triangle", err, sizeof err));
    const struct lesson *l = NULL;
    for (int i = 0; all_lessons[i]; i++)
        if (strcmp(all_lessons[i]->id, PROGRAM) == 0)
            l = all_lessons[i];
    cr_assert(l);
    struct explorer ex;
    struct explorer_desc d = { .lesson = l, .scene = &s, .scene_name = "builtin:triangle" };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    struct explorer_layout L;
    explorer_layout(&ex, WIN_W, WIN_H, &L);
    int hx = (int)lrint(L.ox + L.zoom * ex.tri.x[0] / SUBPIXEL_ONE);
    int hy = (int)lrint(L.oy + L.zoom * ex.tri.y[0] / SUBPIXEL_ONE);
    cr_assert_eq(explorer_hit_vertex(&ex, &L, hx, hy), 0);
    char keys[128];
    snprintf(keys, sizeof keys, "drag %d %d %d %d\ns\ns\nq\n", hx, hy, hx + 40, hy + 30);
    write_text(in_dir("keys"), keys);
    char size[32];
    snprintf(size, sizeof size, "%dx%d", WIN_W, WIN_H);
    char *argv[] = { (char *)program(), "--keys", "keys", "--size", size, NULL };
    int st = run(argv, dummy_env, "out", "err", 30000);
    char *out = read_all(in_dir("out"), NULL);
    cr_assert_eq(st, 0, "exit status %d", st);
    const char *first = "tristep-" PROGRAM "-1.scene", *second = "tristep-" PROGRAM "-2.scene";
    cr_assert(out && strstr(out, first) && strstr(out, second) && strstr(out, "SCENE="),
              "the messages name two new files and how to check them:\n%s", out ? out : "");
    free(out);
    struct scene saved;
    cr_assert(scene_load(&saved, in_dir(first), err, sizeof err), "%s", err);
    cr_assert_eq(saved.ntris, s.ntris);
    /* A dropped where the mouse let go, snapped to 1/256; B and C stayed */
    struct vertex a = s.tris[0].v[0], got = saved.tris[0].v[0];
    cr_expect_eq(got.x, lrint((hx + 40 - L.ox) / L.zoom * 256) / 256.0, "x %g, was %g", got.x, a.x);
    cr_expect_eq(got.y, lrint((hy + 30 - L.oy) / L.zoom * 256) / 256.0, "y %g, was %g", got.y, a.y);
    for (int k = 1; k < 3; k++) {
        cr_expect_eq(saved.tris[0].v[k].x, s.tris[0].v[k].x);
        cr_expect_eq(saved.tris[0].v[k].y, s.tris[0].v[k].y);
    }
    scene_free(&saved);
    explorer_free(&ex);
    scene_free(&s);
}

/* Figures for print in the window too: L switches to the light theme, C to
 * the pixel grid alone, and E exports exactly what --figure draws with
 * --theme light --figure-part canvas. */
Test(window, light_theme_and_canvas_part_from_keys_export_the_print_figure, .fini = cleanup,
     .timeout = 60)
{
    make_dir();
    write_text(in_dir("keys"), "Right\nRight\nRight\nl\nc\ne\nq\n");
    char size[32];
    snprintf(size, sizeof size, "%dx%d", WIN_W, WIN_H);
    char *argv[] = { (char *)program(), "--keys", "keys", "--size", size, NULL };
    int st = run(argv, dummy_env, "out", "err", 30000);
    char *err = read_all(in_dir("err"), NULL);
    cr_assert_eq(st, 0, "exit status %d; stderr:\n%s", st, err ? err : "");
    free(err);
    cairo_surface_t *got = load_png(in_dir("tristep-" PROGRAM "-step3-color.png"));
    char *fargv[] = { (char *)program(), "--figure", "want.png", "--step", "3", "--view", "color",
                      "--size", size, "--theme", "light", "--figure-part", "canvas", NULL };
    cr_assert_eq(run(fargv, NULL, NULL, "figure.err", 30000), 0, "--figure failed");
    cairo_surface_t *want = load_png(in_dir("want.png"));
    cr_assert_eq(differing(got, want, 0, 0, WIN_W, WIN_H), 0,
                 "the window's export after L and C is not the light canvas figure");
    /* and it is the light one: a white page where the dark theme is dark */
    cairo_surface_flush(got);
    const uint32_t *px = (const uint32_t *)cairo_image_surface_get_data(got);
    cr_expect_eq(px[2] & 0xffffff, 0xffffffu, "the corner is %06x, not white",
                 (unsigned)(px[2] & 0xffffff));
    cairo_surface_destroy(got);
    cairo_surface_destroy(want);
}

/* A lesson's parameter keys are keys the window leaves to it: the window
 * reads its own first (lesson 09's filter on f was zoom-to-fit instead). */
Test(window, no_lesson_parameter_key_is_a_window_key)
{
    int keys = 0;
    for (int i = 0; all_lessons[i]; i++)
        for (const struct lesson_param *r = all_lessons[i]->params; r && r->option; r++) {
            int k[2] = { r->key, r->key_down };
            for (int j = 0; j < 2; j++) {
                if (!k[j])
                    continue;
                keys++;
                cr_expect(!app_window_key(k[j]), "%s: --%s's key '%c' is the window's own",
                          all_lessons[i]->id, r->option, k[j]);
            }
        }
    cr_assert_gt(keys, 4, "the lessons' tables have keys");
    cr_assert(app_window_key('f') && app_window_key('v') && !app_window_key('g'));
}

/* Every lesson's window opens, paints its first frame before its steps are
 * all counted (the panel's comparison said "counting" through an index of
 * -1 for the lesson's own run: a crash in lessons 03 and 05, found by the
 * soak test) and quits on Q. */
Test(window, every_lesson_opens_and_quits, .fini = cleanup, .timeout = 120)
{
    make_dir();
    write_text(in_dir("keys"), "Right\nEnd\nq\n");
    int n = 0;
    for (int i = 0; all_lessons[i]; i++, n++) {
        char path[700];
        snprintf(path, sizeof path, "%s", program());
        char *slash = strrchr(path, '/');
        snprintf(slash + 1, sizeof path - (size_t)(slash + 1 - path), "%s", all_lessons[i]->id);
        char *argv[] = { path, "--keys", "keys", NULL };
        int st = run(argv, dummy_env, NULL, "err", 60000);
        char *err = read_all(in_dir("err"), NULL);
        cr_assert_eq(st, 0, "%s: exit status %d; stderr:\n%s", all_lessons[i]->id, st, err ? err : "");
        free(err);
    }
    cr_assert_geq(n, 5);
}

Test(window, space_plays_at_the_speed_and_pauses, .fini = cleanup, .timeout = 60)
{
    make_dir();
    /* 16 events a second, doubled twice by "+": about 64 in 1.2 s */
    write_text(in_dir("keys"), "+\n+\n+\n+\nSpace\nwait\nwait\nwait\nwait\nwait\nwait\n"
                               "wait\nwait\nwait\nwait\nwait\nwait\nSpace\ne\nwait\nwait\ne\nq\n");
    char *argv[] = { (char *)program(), "--keys", "keys", NULL };
    int st = run(argv, dummy_env, "out", "err", 30000);
    cr_assert_eq(st, 0, "exit status %d", st);
    char *out = read_all(in_dir("out"), NULL);
    const char *at = out ? strstr(out, "tristep-" PROGRAM "-step") : NULL;
    cr_assert(at, "no export message:\n%s", out ? out : "");
    unsigned long step = strtoul(at + strlen("tristep-" PROGRAM "-step"), NULL, 10);
    cr_assert(step >= 20 && step <= 200, "played to step %lu in about 1.2 s at 64/s", step);
    const char *again = strstr(at + 1, "tristep-" PROGRAM "-step");
    cr_assert(again && strtoul(again + strlen("tristep-" PROGRAM "-step"), NULL, 10) == step,
              "paused: the second export is of the same step:\n%s", out);
    free(out);
}

Test(window, sdl_failure_names_the_call, .fini = cleanup, .timeout = 30)
{
    make_dir();
    const char *const env[] = { "SDL_VIDEODRIVER=no-such-driver", NULL };
    char *argv[] = { (char *)program(), NULL };
    int st = run(argv, env, NULL, "err", 20000);
    char *err = read_all(in_dir("err"), NULL);
    cr_assert_eq(st, 1, "exit status %d", st);
    cr_assert(err && strstr(err, "SDL_Init failed: ") && strlen(strstr(err, "failed: ")) > 10,
              "the message names the call and SDL's reason:\n%s", err ? err : "");
    free(err);
}

/* No display (an SSH session, a container): SDL would fall back to its
 * offscreen driver and wait for a window no one sees. The program says so,
 * shows how to get pictures anyway and exits 1, unless a driver was chosen. */
Test(window, no_display_says_so_and_how_to_get_pictures, .fini = cleanup, .timeout = 60)
{
    make_dir();
    const char *const env[] = { "DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER", NULL };
    char *argv[] = { (char *)program(), NULL };
    int st = run(argv, env, "out", "err", 20000);
    char *err = read_all(in_dir("err"), NULL);
    cr_assert_neq(st, -1, "still waiting after 20 s with no display");
    cr_assert_eq(st, 1, "exit status %d; stderr:\n%s", st, err ? err : "");
    cr_assert(err && strstr(err, "no display found"), "the message says why:\n%s", err ? err : "");
    char example[200];
    snprintf(example, sizeof example, "%s --figure ", PROGRAM);
    cr_assert(strstr(err, example) && strstr(err, "--dump-image "),
              "the message shows the commands that make pictures without a window:\n%s", err);
    /* the example it gives works, headless, in the same environment */
    char *fig[] = { (char *)program(), "--figure", "step40.png", "--step", "40", "--view",
                    "coverage", NULL };
    cr_assert_eq(run(fig, env, NULL, "fig.err", 30000), 0, "the suggested --figure failed");
    cairo_surface_destroy(load_png(in_dir("step40.png")));
    free(err);

    /* a driver chosen on purpose is obeyed: offscreen runs the script (it
     * probes EGL, loading and unloading Mesa, whose leaks LeakSanitizer
     * cannot name: not checked here, the dummy driver's test does) */
    write_text(in_dir("keys"), "Right\nq\n");
    const char *const chosen[] = { "DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER=offscreen",
                                   "SDL_RENDER_VSYNC=0", "ASAN_OPTIONS=detect_leaks=0", NULL };
    char *keys[] = { (char *)program(), "--keys", "keys", NULL };
    st = run(keys, chosen, NULL, "err2", 30000);
    err = read_all(in_dir("err2"), NULL);
    cr_assert_eq(st, 0, "SDL_VIDEODRIVER=offscreen: exit status %d; stderr:\n%s", st, err ? err : "");
    free(err);
}

Test(window, keys_file_missing_is_a_usage_error, .fini = cleanup, .timeout = 30)
{
    make_dir();
    char *argv[] = { (char *)program(), "--keys", "no-such-file", NULL };
    int st = run(argv, dummy_env, NULL, "err", 20000);
    cr_assert_eq(st, 2, "exit status %d", st);
}

/* A script is untrusted input, checked whole before the window opens:
 * FILE:LINE and exit status 2, like a bad scene. */
Test(window, keys_unknown_key_is_an_input_error_with_its_line, .fini = cleanup, .timeout = 30)
{
    make_dir();
    write_text(in_dir("keys"), "# steps\nRight\nShift+Nokey\nq\n");
    char *argv[] = { (char *)program(), "--keys", "keys", NULL };
    int st = run(argv, dummy_env, NULL, "err", 20000);
    cr_assert_eq(st, 2, "exit status %d", st);
    char *err = read_all(in_dir("err"), NULL);
    cr_assert(err && strstr(err, "keys:3: unknown key 'Nokey'"), "stderr: %s", err ? err : "");
    free(err);
}

/* --- under Xvfb, with xdotool ----------------------------------------------------------- */

static int xdotool(const char *display, const char *const args[])
{
    char *argv[32] = { "xdotool" };
    int n = 1;
    for (int i = 0; args[i] && n < 31; i++)
        argv[n++] = (char *)args[i];
    argv[n] = NULL;
    char denv[32];
    snprintf(denv, sizeof denv, "DISPLAY=%s", display);
    const char *const env[] = { denv, NULL };
    return run(argv, env, "xdotool.out", "xdotool.err", 15000);
}

static cairo_surface_t *screenshot(const char *display, const char *name)
{
    char *argv[] = { "import", "-display", (char *)display, "-window", "root", (char *)name, NULL };
    int st = run(argv, NULL, NULL, "import.err", 30000);
    cr_assert_eq(st, 0, "import (ImageMagick) failed with %d: make test installs it", st);
    return load_png(in_dir(name));
}

/* User plus system CPU time of a process, in clock ticks (/proc/PID/stat). */
static long cpu_ticks(pid_t pid)
{
    char path[64];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    char *t = read_all(path, NULL);
    const char *p = t ? strrchr(t, ')') : NULL;      /* the name may hold spaces */
    unsigned long ut, st;
    long r = p && sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &ut,
                         &st) == 2 ? (long)(ut + st) : -1;
    free(t);
    return r;
}

/* Start Xvfb on a display it picks itself and names on a pipe once it
 * accepts connections (-displayfd); returns its name. Two test runs at once
 * never take the same display, as they could when each looked for a free
 * number first. `timeout` ends it even if this process dies before cleanup. */
static const char *start_xvfb(void)
{
    static char display[16];
    int fds[2];
    cr_assert_eq(pipe(fds), 0, "pipe: %s", strerror(errno));
    char fd[16];
    snprintf(fd, sizeof fd, "%d", fds[1]);
    char *argv[] = { "timeout", "120", "Xvfb", "-displayfd", fd, "-screen", "0", "1280x800x24",
                     "-nolisten", "tcp", NULL };
    xvfb_pid = start(argv, NULL, NULL, "xvfb.err");
    close(fds[1]);
    char line[16];
    size_t n = 0;
    struct pollfd in = { .fd = fds[0], .events = POLLIN };
    while (n < sizeof line - 1 && !memchr(line, '\n', n) && poll(&in, 1, 30000) > 0) {
        ssize_t got = read(fds[0], line + n, sizeof line - 1 - n);
        if (got <= 0)
            break;
        n += (size_t)got;
    }
    close(fds[0]);
    line[n] = '\0';
    if (n > 1 && line[n - 1] == '\n') {
        snprintf(display, sizeof display, ":%d", atoi(line));
        return display;
    }
    int st;
    if (xvfb_pid > 0 && waitpid(xvfb_pid, &st, WNOHANG) == xvfb_pid) {
        xvfb_pid = -1;
        cr_assert(!(WIFEXITED(st) && WEXITSTATUS(st) == 127),
                  "Xvfb is not installed (make test installs it)");
    }
    char *err = read_all(in_dir("xvfb.err"), NULL);
    cr_assert_fail("Xvfb did not name its display within 30 s; its stderr:\n%s", err ? err : "");
    return NULL;
}

/* Q ends the program started as app_pid, with status 0 and nothing on stderr
 * that matters (a sanitizer report would make the status non-zero). */
static void quit_app(const char *display)
{
    const char *quit[] = { "key", "q", NULL };
    cr_assert_eq(xdotool(display, quit), 0);
    int status = finish(&app_pid, 10000);
    char *app_err = read_all(in_dir("app.err"), NULL);
    cr_assert_eq(status, 0, "exit status %d after q; stderr:\n%s", status, app_err ? app_err : "");
    free(app_err);
}

/* The window's pixels at the screen's top-left corner equal a figure's. */
static long differing_from_figure(cairo_surface_t *shot, const char *name, const char *size,
                                  const char *scale, int w, int h)
{
    char *argv[] = { (char *)program(), "--figure", (char *)name, "--size", (char *)size,
                     "--scale", (char *)scale, NULL };
    cr_assert_eq(run(argv, NULL, NULL, "figure.err", 30000), 0, "--figure %s failed", name);
    cairo_surface_t *want = load_png(in_dir(name));
    cr_assert_eq(cairo_image_surface_get_width(want), w);
    long n = differing(shot, want, 0, 0, w, h);
    cairo_surface_destroy(want);
    return n;
}

/* A HiDPI desktop on X11 (windows count in pixels; GDK_SCALE=2, as such
 * desktops set it, since SDL cannot read Xvfb's dots per inch): the
 * interface is drawn at scale 2. The window is resized with xdotool: the
 * canvas and panel lay themselves out again, and each screenshot is the
 * figure of that size, pixel for pixel. */
Test(window, xvfb_high_dpi_and_resize, .fini = cleanup, .timeout = 120)
{
    make_dir();
    const char *version[] = { "--version", NULL };
    cr_assert_eq(xdotool(":0", version), 0, "xdotool is not installed (make test installs it)");
    const char *display = start_xvfb();
    char denv[32];
    snprintf(denv, sizeof denv, "DISPLAY=%s", display);
    const char *const env[] = { denv, "SDL_RENDER_VSYNC=0", "SDL_VIDEODRIVER=x11", "GDK_SCALE=2",
                                NULL };
    char *argv[] = { (char *)program(), "--size", "1280x800", NULL };
    app_pid = start(argv, env, "app.out", "app.err");
    char *search[] = { "timeout", "15", "xdotool", "search", "--sync", "--onlyvisible",
                       "--name", "^tristep " PROGRAM, NULL };
    cr_assert_eq(run(search, env, "search.out", "search.err", 20000), 0,
                 "the window did not appear within 15 s");
    char *ids = read_all(in_dir("search.out"), NULL);
    cr_assert(ids && ids[0], "no window id");
    char id[32];
    snprintf(id, sizeof id, "%.*s", (int)strcspn(ids, "\n"), ids);
    free(ids);
    sleep_ms(700);

    cairo_surface_t *big = screenshot(display, "dpi.png");
    long d = differing_from_figure(big, "scale2.png", "1280x800", "2", 1280, 800);
    cr_assert_eq(d, 0, "at GDK_SCALE=2 the window differs from --figure --scale 2 in %ld pixels", d);

    static const int sizes[][2] = { { 900, 600 }, { 1200, 420 }, { 520, 760 } };
    for (int i = 0; i < 3; i++) {
        char w[16], h[16], size[32];
        snprintf(w, sizeof w, "%d", sizes[i][0]);
        snprintf(h, sizeof h, "%d", sizes[i][1]);
        snprintf(size, sizeof size, "%dx%d", sizes[i][0], sizes[i][1]);
        const char *resize[] = { "windowsize", id, w, h, "sleep", "0.7", NULL };
        cr_assert_eq(xdotool(display, resize), 0);
        cairo_surface_t *shot = screenshot(display, "resized.png");
        d = differing_from_figure(shot, "resized-want.png", size, "2", sizes[i][0], sizes[i][1]);
        cr_assert_eq(d, 0, "resized to %s the window differs from --figure --size %s in %ld pixels",
                     size, size, d);
        cr_assert_eq(pixel(shot, sizes[i][0] + 5, 5), 0, "nothing drawn right of the window");
        cairo_surface_destroy(shot);
    }
    quit_app(display);
    cairo_surface_destroy(big);
}

/* The lesson of PROGRAM. */
static const struct lesson *program_lesson(void)
{
    for (int i = 0; all_lessons[i]; i++)
        if (strcmp(all_lessons[i]->id, PROGRAM) == 0)
            return all_lessons[i];
    cr_assert_fail("no lesson %s", PROGRAM);
    return NULL;
}

/* Colours within 3 levels a channel: antialiasing of the lines nearby
 * reaches a sample a little differently at two resolutions; a layout out
 * of place gives another colour altogether (grid, cell, background). */
static bool close_colours(uint32_t a, uint32_t b)
{
    for (int k = 0; k < 24; k += 8)
        if (abs((int)(a >> k & 255) - (int)(b >> k & 255)) > 3)
            return false;
    return true;
}

/* Where windows count in points (macOS, Wayland), the frame is painted at
 * twice the pixels: the same layout, every flat area where it was. */
Test(window, painted_at_pixel_ratio_2_is_the_same_layout_twice_as_sharp)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "triangle", err, sizeof err));
    const struct lesson *l = program_lesson();
    struct explorer ex;
    struct explorer_desc desc = { .lesson = l, .scene = &s, .scene_name = "builtin:triangle", .step = 40 };
    cr_assert(explorer_init(&ex, &desc, err, sizeof err), "%s", err);
    cr_assert(explorer_fonts(err, sizeof err), "%s", err);
    enum { W = 640, H = 400 };
    unsigned char *one = malloc((size_t)W * H * 4), *two = malloc((size_t)W * H * 16);
    cr_assert_eq(explorer_paint_pixels(&ex, one, W, H, W * 4, 1), CAIRO_STATUS_SUCCESS);
    cr_assert_eq(explorer_paint_pixels(&ex, two, 2 * W, 2 * H, W * 8, 2), CAIRO_STATUS_SUCCESS);
    struct explorer_layout L;
    explorer_layout(&ex, W, H, &L);
    /* inside every scene pixel away from the edges, the vertex handles and
     * the current pixel (lines and text are drawn finer at ratio 2), and the
     * panel's background */
    int checked = 0;
    for (int py = 0; py < s.h; py++)
        for (int px = 0; px < s.w; px++) {
            double x = L.ox + (px + 0.3) * L.zoom, y = L.oy + (py + 0.3) * L.zoom;
            if (x < 0 || y < 0 || x >= L.cx + L.cw || y >= L.cy + L.ch)
                continue;
            bool near = false;
            for (int k = 0; k < 3; k++) {
                double ax = L.ox + L.zoom * ex.tri.x[k] / SUBPIXEL_ONE;
                double ay = L.oy + L.zoom * ex.tri.y[k] / SUBPIXEL_ONE;
                double bx = L.ox + L.zoom * ex.tri.x[(k + 1) % 3] / SUBPIXEL_ONE;
                double by = L.oy + L.zoom * ex.tri.y[(k + 1) % 3] / SUBPIXEL_ONE;
                double len = hypot(bx - ax, by - ay);
                double dist = fabs((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / len;
                near = near || dist < 6 || hypot(x - ax, y - ay) < 24;
            }
            if (near || (ex.has_last && abs(px - ex.last.x) <= 1 && abs(py - ex.last.y) <= 1))
                continue;           /* and the current pixel's marker */
            uint32_t a = *(uint32_t *)(one + ((size_t)(int)y * W + (size_t)(int)x) * 4);
            uint32_t b = *(uint32_t *)(two + ((size_t)(int)(2 * y) * 2 * W + (size_t)(int)(2 * x)) * 4);
            cr_assert(close_colours(a, b), "scene pixel (%d, %d): %08x at ratio 1, %08x at ratio 2",
                      px, py, a, b);
            checked++;
        }
    cr_assert_gt(checked, 100);
    uint32_t a = *(uint32_t *)(one + ((size_t)(H - 60) * W + (size_t)(W - 4)) * 4);
    uint32_t b = *(uint32_t *)(two + ((size_t)(2 * H - 120) * 2 * W + (size_t)(2 * W - 8)) * 4);
    cr_assert(close_colours(a, b), "panel background: %08x at ratio 1, %08x at ratio 2", a, b);
    free(one);
    free(two);
    explorer_free(&ex);
    scene_free(&s);
}

Test(window, xvfb_keys_drag_and_screenshot, .fini = cleanup, .timeout = 120)
{
    make_dir();
    const char *version[] = { "--version", NULL };
    cr_assert_eq(xdotool(":0", version), 0, "xdotool is not installed (make test installs it)");
    const char *display = start_xvfb();

    char denv[32], size[32];
    snprintf(denv, sizeof denv, "DISPLAY=%s", display);
    snprintf(size, sizeof size, "%dx%d", WIN_W, WIN_H);
    /* Under the sanitizer the program checks for leaks before SDL_Quit
     * unloads the X11 backend's libraries, so their leaks have names (and
     * tests/lsan.supp suppresses D-Bus's); leak checking stays on. */
    const char *const env[] = { denv, "SDL_RENDER_VSYNC=0", "SDL_VIDEODRIVER=x11", NULL };
    char *argv[] = { (char *)program(), "--size", size, NULL };
    app_pid = start(argv, env, "app.out", "app.err");

    char *timeout_argv[] = { "timeout", "15", "xdotool", "search", "--sync", "--onlyvisible",
                             "--name", "^tristep " PROGRAM, NULL };
    cr_assert_eq(run(timeout_argv, env, "search.out", "search.err", 20000), 0,
                 "the window did not appear within 15 s");

    /* nothing changes, nothing is drawn: a second of idle costs (almost) no CPU */
    sleep_ms(300);
    long cpu0 = cpu_ticks(app_pid);
    sleep_ms(1000);
    long cpu1 = cpu_ticks(app_pid);
    cr_assert(cpu0 >= 0 && cpu1 - cpu0 <= 3, "idle for 1 s, the program used %ld clock ticks",
              cpu1 - cpu0);

    /* the window fills the 1280x800 screen from (0, 0): screen = window
     * coordinates. Three steps by key. */
    const char *keys[] = { "mousemove", "3", "3", "key", "--delay", "60", "Right", "Right",
                           "Right", NULL };
    cr_assert_eq(xdotool(display, keys), 0);
    sleep_ms(700);
    cairo_surface_t *shot = screenshot(display, "shot1.png");
    cr_assert_eq(cairo_image_surface_get_width(shot), WIN_W);

    /* the panel and the grid where the layout puts them */
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, "triangle", err, sizeof err));
    const struct lesson *l = program_lesson();
    struct explorer ex;
    struct explorer_desc d = { .lesson = l, .scene = &s, .scene_name = "builtin:triangle" };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    struct explorer_layout L;
    explorer_layout(&ex, WIN_W, WIN_H, &L);
    cr_assert_eq(pixel(shot, (int)(L.px + L.pw - 6), (int)(L.h / 2)), 0x23262e,
                 "panel background at its right edge");
    /* a grid line between two cells in the scene's corner, a cell's inside */
    int gx = (int)(L.ox + 2 * L.zoom), gy = (int)(L.oy + 2.5 * L.zoom);
    uint32_t cell = pixel(shot, gx + (int)(L.zoom / 4), gy);
    cr_assert(pixel(shot, gx - 1, gy) != cell || pixel(shot, gx, gy) != cell,
              "the grid line at scene x = 2 stands out from the cell");

    /* the same picture as --figure at step 3 in the colour view */
    cairo_surface_t *want = figure("want.png", "3", "color");
    long diff = differing(shot, want, 0, 0, WIN_W, WIN_H);
    cr_assert_eq(diff, 0, "the screen differs from --figure --step 3 in %ld pixels", diff);

    /* drag vertex A by (40, 30) screen pixels: the step stays at 3 */
    int hx = (int)lrint(L.ox + L.zoom * ex.tri.x[0] / SUBPIXEL_ONE);
    int hy = (int)lrint(L.oy + L.zoom * ex.tri.y[0] / SUBPIXEL_ONE);
    cr_assert_eq(explorer_hit_vertex(&ex, &L, hx, hy), 0, "A's handle at (%d, %d)", hx, hy);
    char x0[16], y0[16], x1[16], y1[16], xm[16], ym[16];
    snprintf(x0, sizeof x0, "%d", hx), snprintf(y0, sizeof y0, "%d", hy);
    snprintf(xm, sizeof xm, "%d", hx + 20), snprintf(ym, sizeof ym, "%d", hy + 15);
    snprintf(x1, sizeof x1, "%d", hx + 40), snprintf(y1, sizeof y1, "%d", hy + 30);
    const char *drag[] = { "mousemove", x0, y0, "sleep", "0.2", "mousedown", "1", "mousemove", xm,
                           ym, "sleep", "0.2", NULL };
    cr_assert_eq(xdotool(display, drag), 0);
    const char *drop[] = { "mousemove", x1, y1, "sleep", "0.2", "mouseup", "1", "sleep", "0.2",
                           "mousemove", "3", "3", "sleep", "0.3", "key", "e", NULL };
    cr_assert_eq(xdotool(display, drop), 0);
    sleep_ms(1500);
    cairo_surface_t *shot2 = screenshot(display, "shot2.png");
    long moved = differing(shot, shot2, (int)L.cx, (int)L.cy, (int)(L.cx + L.cw), (int)(L.cy + L.ch));
    cr_assert_gt(moved, 200, "the drag changed only %ld pixels of the canvas", moved);
    cr_assert_eq(pixel(shot2, (int)(L.px + L.pw - 6), (int)(L.h / 2)), 0x23262e);
    /* A is drawn where it was dropped: the handle's pixels, not the background */
    cr_assert_neq(pixel(shot2, hx + 40, hy + 30), pixel(shot, hx + 40, hy + 30),
                  "nothing new drawn at the drop point");
    struct stat st;
    char *said = read_all(in_dir("app.out"), NULL);
    cr_assert_eq(stat(in_dir("tristep-" PROGRAM "-step3-color.png"), &st), 0,
                 "E after the drag exports step 3: the drag kept the step; stdout:\n%s",
                 said ? said : "");
    free(said);

    /* the wheel zooms the canvas at the pointer; a click pins a cell's
     * values in the watch panel */
    char cx[16], cy[16];
    snprintf(cx, sizeof cx, "%d", (int)(L.ox + 10.5 * L.zoom));
    snprintf(cy, sizeof cy, "%d", (int)(L.oy + 12.5 * L.zoom));
    const char *zoom[] = { "mousemove", cx, cy, "sleep", "0.2", "click", "4", "sleep", "0.5", NULL };
    cr_assert_eq(xdotool(display, zoom), 0);
    cairo_surface_t *shot3 = screenshot(display, "shot3.png");
    long zoomed = differing(shot2, shot3, (int)L.cx, (int)L.cy, (int)(L.cx + L.cw), (int)(L.cy + L.ch));
    long panel = differing(shot2, shot3, (int)L.px, 0, WIN_W, WIN_H);
    cr_assert_gt(zoomed, 20000, "the wheel changed only %ld pixels of the canvas", zoomed);
    const char *pin[] = { "click", "1", "sleep", "0.5", NULL };
    cr_assert_eq(xdotool(display, pin), 0);
    cairo_surface_t *shot4 = screenshot(display, "shot4.png");
    long pinned = differing(shot3, shot4, (int)L.px, 0, WIN_W, WIN_H);
    cr_assert_gt(pinned, panel + 50, "the click changed only %ld pixels of the panel", pinned);
    cairo_surface_destroy(shot3);
    cairo_surface_destroy(shot4);

    quit_app(display);
    cairo_surface_destroy(shot);
    cairo_surface_destroy(shot2);
    cairo_surface_destroy(want);
    explorer_free(&ex);
    scene_free(&s);
}
