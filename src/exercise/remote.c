/* remote.c - the judge's end of the pipes (wire.h): the student's code runs
 * in the runner, a process of its own (in the sandbox when grading), and
 * what it drew comes back here to be checked. The runner is started on the
 * first scene, and again after it crashed, hung or sent garbage: that
 * scene's check fails with the reason, and the next scene gets a new
 * runner. */
#define _GNU_SOURCE               /* pipe2, open_memstream */

#include "remote.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "exercise/wire.h"
#include "front/front.h"

static struct remote_config cfg;
static bool configured;
static pid_t pid = -1;
static int to_runner = -1, from_runner = -1;
static struct runner_fault rfault;
static bool in_scene;           /* a WIRE_DRAW sent, its WIRE_DONE not yet read */
static int scene_w, scene_h;
static struct scene projected;  /* a 3-D scene's screen triangles, as the runner made them */
static bool have_projected;
static double deadline;         /* the scene's: CLOCK_MONOTONIC seconds */
static uint64_t runs;

void remote_configure(const struct remote_config *c)
{
    if (c)
        cfg = *c;
    configured = c && c->argv && c->argv[0];
    exercise_use_remote(configured ? remote_triangle : NULL);
}

bool remote_active(void)
{
    return configured;
}

const struct runner_fault *exercise_runner_fault(void)
{
    return &rfault;
}

uint64_t remote_starts(void)
{
    return runs;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Stop the runner, whatever it is doing, and every process it started
 * (its process group; in the sandbox its pid namespace dies with it). */
static int stop_runner(void)
{
    int status = 0;
    if (to_runner >= 0)
        close(to_runner);
    if (from_runner >= 0)
        close(from_runner);
    to_runner = from_runner = -1;
    if (pid > 0) {
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
            ;
    }
    pid = -1;
    in_scene = false;
    return status;
}

void remote_shutdown(void)
{
    stop_runner();
}

/* The runner failed: say why, once per scene, and stop it. */
static void fail(enum runner_wrong what, const char *why)
{
    if (rfault.what != RUNNER_OK)
        return;
    bool timed_out = what == RUNNER_TIMEOUT;
    int status = stop_runner();
    rfault.what = what;
    if (!timed_out && WIFSIGNALED(status)) {
        rfault.what = RUNNER_CRASHED;
        rfault.signal = WTERMSIG(status);
        snprintf(rfault.why, sizeof rfault.why, "your program was killed by signal %d (%s)%s", rfault.signal,
                 strsignal(rfault.signal), rfault.signal == SIGXCPU || rfault.signal == SIGKILL
                 ? ": a crash, or a limit of CPU time or memory reached" : "");
    } else if (!timed_out && WIFEXITED(status) && what == RUNNER_CRASHED) {
        snprintf(rfault.why, sizeof rfault.why, "your program ended (exit status %d) while drawing",
                 WEXITSTATUS(status));
    } else {
        snprintf(rfault.why, sizeof rfault.why, "%s", why);
    }
}

/* Read exactly n bytes before the scene's deadline. */
static bool get(void *buf, size_t n)
{
    char *p = buf;
    while (n > 0) {
        double left = deadline - now();
        if (left <= 0) {
            fail(RUNNER_TIMEOUT, "your code did not finish drawing within the time a scene may take");
            return false;
        }
        struct pollfd q = { .fd = from_runner, .events = POLLIN };
        int r = poll(&q, 1, (int)(left * 1000) + 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r == 0)
            continue;
        ssize_t got = read(from_runner, p, n);
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0) {
            fail(RUNNER_CRASHED, "your program closed its end of the results");
            return false;
        }
        p += got;
        n -= (size_t)got;
    }
    return true;
}

static bool garbage(const char *what)
{
    char why[200];
    snprintf(why, sizeof why, "your program sent what no drawing sends (%s)", what);
    fail(RUNNER_GARBAGE, why);
    return false;
}

static bool header(struct wire_header *h)
{
    if (!get(h, sizeof *h))
        return false;
    if (h->len > WIRE_MAX_LEN)
        return garbage("a record too long");
    return true;
}

static bool put(const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t w = write(to_runner, p, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            fail(RUNNER_CRASHED, "your program stopped reading its scenes");
            return false;
        }
        p += w;
        n -= (size_t)w;
    }
    return true;
}

static bool start_runner(void)
{
    int in[2], out[2];
    if (pipe2(in, O_CLOEXEC) < 0)
        return false;
    if (pipe2(out, O_CLOEXEC) < 0) {
        close(in[0]), close(in[1]);
        return false;
    }
    int log = cfg.log_fd > 2 ? fcntl(cfg.log_fd, F_DUPFD_CLOEXEC, 10)
              : cfg.log ? open(cfg.log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
    fflush(NULL);
    pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        signal(SIGPIPE, SIG_DFL);
        dup2(in[0], WIRE_FD_IN);
        dup2(out[1], WIRE_FD_OUT);
        int null = open("/dev/null", O_WRONLY);
        dup2(log >= 0 ? log : null, 1);
        dup2(log >= 0 ? log : null, 2);
        for (int fd = 4; fd < 1024; fd++)
            close(fd);
        if (cfg.limits)
            cfg.limits(cfg.limits_ctx);
        execvp(cfg.argv[0], cfg.argv);
        _exit(127);
    }
    close(in[0]);
    close(out[1]);
    if (log >= 0)
        close(log);
    if (pid < 0) {
        close(in[1]), close(out[0]);
        return false;
    }
    setpgid(pid, pid);
    signal(SIGPIPE, SIG_IGN);
    to_runner = in[1];
    from_runner = out[0];
    runs++;
    /* its first word: it started (a program that prints, loops or dies in
     * a constructor fails here, on the scene it was given) */
    deadline = now() + (cfg.start_seconds > 0 ? cfg.start_seconds : 10);
    struct wire_header h;
    if (!header(&h))
        return false;
    if (h.type != WIRE_HELLO || h.len != 0)
        return garbage("not the runner's greeting");
    return true;
}

/* Read and drop records up to the scene's end. */
static void drain(void)
{
    char buf[1 << 16];
    while (in_scene && pid > 0) {
        struct wire_header h;
        if (!header(&h))
            return;
        if (h.type == WIRE_DONE) {
            in_scene = false;
            return;
        }
        for (size_t left = h.len; left > 0;) {
            size_t k = left < sizeof buf ? left : sizeof buf;
            if (!get(buf, k))
                return;
            left -= k;
        }
    }
}

void remote_end(void)
{
    if (in_scene && pid > 0) {
        struct wire_header stop = { WIRE_STOP, 0 };
        if (put(&stop, sizeof stop))
            drain();
    }
    in_scene = false;
}

static bool finite_vertex(const struct vertex *v)
{
    const double *d[] = { &v->x, &v->y, &v->z, &v->r, &v->g, &v->b, &v->s, &v->t };
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        if (!isfinite(*d[k]))
            return false;
    return fabs(v->x) <= COORD_LIMIT && fabs(v->y) <= COORD_LIMIT && v->z > 0;
}

/* A 3-D scene's screen triangles from the runner, checked, into projected. */
static bool read_projected(const struct scene *s)
{
    struct wire_header h;
    struct wire_projected pr;
    if (!header(&h))
        return false;
    if (h.type != WIRE_PROJECTED || h.len < sizeof pr || !get(&pr, sizeof pr))
        return h.type == WIRE_PROJECTED ? false : garbage("no screen triangles where a 3-D scene's are due");
    size_t per = sizeof(struct scene_tri) + sizeof(int);
    if (pr.ntris < 0 || pr.ntris > 64 * (s->world.ntris + 1) || pr.nworld != s->world.ntris
        || h.len - sizeof pr != (size_t)pr.ntris * per + (size_t)pr.nworld)
        return garbage("a count of screen triangles that no front end makes");
    if (!scene_copy(&projected, s))
        return garbage("out of memory");
    have_projected = true;
    char *b = malloc((size_t)pr.ntris * per + (size_t)pr.nworld + 1);
    if (!b || !get(b, (size_t)pr.ntris * per + (size_t)pr.nworld)) {
        free(b);
        return false;
    }
    exercise_clip_as_lesson_set((const unsigned char *)b + (size_t)pr.ntris * per, pr.nworld);
    projected.ntris = 0;
    const int *from = (const int *)(b + (size_t)pr.ntris * sizeof(struct scene_tri));
    int last = 0;
    for (int i = 0; i < pr.ntris; i++) {
        struct scene_tri t;
        memcpy(&t, b + (size_t)i * sizeof t, sizeof t);
        int f;
        memcpy(&f, &from[i], sizeof f);
        bool ok = f >= last && f < s->world.ntris && t.texture >= 0 && t.texture <= scene_texture_count(s);
        for (int k = 0; k < 3 && ok; k++)
            ok = finite_vertex(&t.v[k]);
        if (!ok || !scene_add_textured(&projected, t.v, t.texture)) {
            free(b);
            return garbage("a screen triangle that no front end makes");
        }
        int *fr = realloc(projected.world.from, (size_t)(i + 1) * sizeof *fr);
        if (!fr) {
            free(b);
            return garbage("out of memory");
        }
        projected.world.from = fr;
        fr[i] = last = f;
    }
    free(b);
    unsigned char *rev = (unsigned char *)&pr.fault.reversed;
    *rev = *rev != 0;
    struct clip_fault cf = pr.fault;
    if ((unsigned)cf.what > CLIP_ORDER || (cf.what != CLIP_OK && (cf.tri < 0 || cf.tri >= s->world.ntris
        || (cf.plane != PLANE_NEAR && cf.plane != PLANE_FAR))))
        return garbage("a clipper's fault that no front end reports");
    exercise_clip_fault_set(&cf);
    return true;
}

bool remote_begin(const struct scene *s, const struct raster_params *p, int first, int count,
                  int trace, bool clip, bool both_ways, int write_line)
{
    remote_end();
    rfault = (struct runner_fault){ .what = RUNNER_OK };
    if (have_projected)
        scene_free(&projected);
    have_projected = false;
    if (pid <= 0 && !start_runner())
        return false;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return false;
    bool written = scene_write(s, f);
    fclose(f);
    if (!written) {
        free(text);
        return false;
    }
    struct wire_draw d = { .first = first, .count = count, .samples = p->samples, .trace = (int32_t)trace,
                           .write_line = write_line, .clip = clip, .both_ways = both_ways,
                           .subpixel_bits = p->subpixel_bits, .checker = p->checker,
                           .text_len = (uint32_t)len };
    memcpy(d.knob, p->knob, sizeof d.knob);
    struct wire_header h = { WIRE_DRAW, (uint32_t)(sizeof d + len) };
    deadline = now() + (cfg.scene_seconds > 0 ? cfg.scene_seconds : 10);
    bool ok = put(&h, sizeof h) && put(&d, sizeof d) && put(text, len);
    free(text);
    if (!ok)
        return false;
    in_scene = true;
    scene_w = s->w, scene_h = s->h;
    if (s->world.camera_line)   /* the runner's front end first */
        return read_projected(s);
    return true;
}

const struct scene *remote_projected(void)
{
    return have_projected ? &projected : NULL;
}

bool remote_triangle(struct target *fb, struct trace *tr)
{
    if (rfault.what != RUNNER_OK || !in_scene)
        return false;
    for (;;) {
        struct wire_header h;
        if (!header(&h))
            return false;
        if (h.type == WIRE_EVENT) {
            struct trace_event ev;
            struct texel_reads reads;
            if (h.len != sizeof ev + sizeof reads)
                return garbage("an event of the wrong size");
            if (!get(&ev, sizeof ev) || !get(&reads, sizeof reads))
                return false;
            exercise_texel_reads_add(&reads);   /* read where the event was narrated */
            if (tr && tr->sink)
                tr->sink(tr->ctx, &ev);
            continue;
        }
        if (h.type == WIRE_DONE) {
            in_scene = false;
            return garbage("fewer triangles drawn than asked for");
        }
        struct wire_tri w;
        if (h.type != WIRE_TRI || h.len < sizeof w || !get(&w, sizeof w))
            return h.type == WIRE_TRI ? false : garbage("a record of no known kind");
        /* the flags as bytes first: a bool holding anything but 0 or 1 is
         * undefined behaviour to read */
        unsigned char *any = (unsigned char *)&w.fault.any, *texel_any = (unsigned char *)&w.texel.any;
        *any = *any != 0;
        *texel_any = *texel_any != 0;
        int n = w.samples;
        size_t npix = (size_t)scene_w * (size_t)scene_h;
        size_t rec = sizeof(struct wire_pixel) + (n > 1 ? 8 * (size_t)n : 0);
        if ((n != 1 && n != 4 && n != 8) || w.npix > npix || h.len - sizeof w != (size_t)w.npix * rec
            || fb->w != scene_w || fb->h != scene_h)
            return garbage("a triangle's pixels that do not fit its target");
        if ((fb->samples ? fb->samples->n : 1) != n && !target_multisample(fb, n))
            return garbage("out of memory");
        char *b = malloc((size_t)w.npix * rec + 1);
        if (!b || !get(b, (size_t)w.npix * rec)) {
            free(b);
            return false;
        }
        long long last = -1;
        for (uint32_t k = 0; k < w.npix; k++) {
            struct wire_pixel px;
            memcpy(&px, b + k * rec, sizeof px);
            if (px.index >= npix || (long long)px.index <= last || px.count > 255) {
                free(b);
                return garbage("a pixel outside its target, twice, or covered more than 255 times");
            }
            last = px.index;
            fb->color[px.index] = px.color;
            fb->depth[px.index] = px.depth;
            fb->count[px.index] = (uint8_t)px.count;
            if (n > 1) {
                memcpy(&fb->samples->color[px.index * (size_t)n], b + k * rec + sizeof px, 4 * (size_t)n);
                memcpy(&fb->samples->depth[px.index * (size_t)n], b + k * rec + sizeof px + 4 * (size_t)n,
                       4 * (size_t)n);
            }
        }
        free(b);
        if (tr) {
            tr->count = w.events;
            tr->c = w.c;
        }
        exercise_fault_set(&w.fault, &w.texel);
        return true;
    }
}
