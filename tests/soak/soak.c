/* soak.c - `make soak [MINUTES=10]`: every lesson's explorer window under
 * Xvfb, fed random keys, drags, clicks, wheel turns and window resizes
 * through xdotool, built with the sanitizers (make soak builds them).
 *
 * Each lesson program runs in turn for its share of the time. What fails
 * the soak (exit status 1): a program that dies, does not quit on Q, exits
 * with another status than 0, or writes a sanitizer report (AddressSanitizer,
 * UndefinedBehaviorSanitizer, LeakSanitizer: the program looks for leaks
 * before SDL unloads its libraries); a failure names the program's last
 * words on stderr (all of an X error's: the failed request and the error;
 * an X error the program told and survived is shown beside its result). Two failures are not the lesson's and are told apart:
 * Xvfb ending under the program (the soak starts it again), and
 * LeakSanitizer's own fatal error, "Tracer caught signal 11", when its
 * tracer crashes while it stops the program's threads to look for leaks
 * (seen in 2 of 250 quits of lesson 03 on a loaded machine; the leak check
 * never ran). Either way the lesson runs once more, said so in the report,
 * and that run decides. And, for a run of at least FLAT_AFTER_S + 30 seconds, memory that keeps growing after the first
 * minute: the largest resident size after it above the size at one minute
 * by more than FLAT_SLACK (allocator caches settle, ASan's quarantine is
 * capped at QUARANTINE_MB below). What it reports: per lesson and in all,
 * the input events sent, the frames drawn and their times (median, 99th
 * percentile, worst: paint, upload and present, from TRISTEP_FRAME_TIMES;
 * how fast a frame is belongs to `make bench`), and the resident memory
 * at one minute and at the end.
 *
 *     tristep-soak --build build/sanitize [--minutes 10 | --seconds-per-lesson 4]
 *                  [--seed N] [--keep DIR]
 *
 * Linux only (it reads /proc), like Xvfb; xdotool and Xvfb are test
 * dependencies that `make test` installs.
 */
#define _XOPEN_SOURCE 700

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define FLAT_AFTER_S 60          /* memory is judged after the first minute */
#define FLAT_SLACK_FRACTION 0.10 /* ... growing by at most 10 % */
#define FLAT_SLACK_MB 16.0       /* ... plus 16 MiB */
#define QUARANTINE_MB 64         /* ASan keeps this much freed memory to catch use after free */
#define SCREEN_W 1280
#define SCREEN_H 800
#define MAX_LESSONS 16

static char work[256];           /* the soak's folder: exports, logs */
static pid_t xvfb = -1;

/* --- small things ------------------------------------------------------------------ */

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void sleep_ms(int ms)
{
    struct timespec t = { ms / 1000, (long)(ms % 1000) * 1000000L };
    nanosleep(&t, NULL);
}

static uint64_t rng_state;

static uint64_t rng(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static int rnd(int lo, int hi)              /* lo..hi inclusive */
{
    return lo + (int)(rng() % (uint64_t)(hi - lo + 1));
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0, got;
    char *buf = malloc(cap + 1);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            char *b = realloc(buf, 2 * cap + 1);
            if (!b)
                free(buf);
            buf = b, cap *= 2;
        }
    }
    fclose(f);
    if (buf)
        buf[n] = '\0';
    return buf;
}

/* Start argv with extra "NAME=VALUE" environment, output into files of the
 * work folder (NULL: /dev/null). */
static pid_t start(char *const argv[], const char *const env[], const char *out, const char *err)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        perror("tristep-soak: fork");
        exit(1);
    }
    if (pid == 0) {
        if (chdir(work) != 0)
            _exit(126);
        for (int i = 0; env && env[i]; i++)
            putenv((char *)env[i]);
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

/* Exit status of pid within ms (128 + signal if killed by one), -1 if it is
 * still running (and then it is killed). */
static int finish(pid_t pid, int ms)
{
    int st;
    for (int t = 0; t <= ms; t += 20) {
        if (waitpid(pid, &st, WNOHANG) == pid)
            return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
        sleep_ms(20);
    }
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
    return -1;
}

static char display[16];

static int xdotool(char *const args[], int nargs, const char *out)
{
    char *argv[1024];
    int n = 0;
    argv[n++] = "xdotool";
    for (int i = 0; i < nargs && n < 1022; i++)
        argv[n++] = args[i];
    argv[n] = NULL;
    char denv[32];
    snprintf(denv, sizeof denv, "DISPLAY=%s", display);
    const char *const env[] = { denv, NULL };
    return finish(start(argv, env, out, "xdotool.err"), 60000);
}

static void stop_xvfb(void)
{
    if (xvfb > 0) {
        kill(xvfb, SIGTERM);
        finish(xvfb, 3000);
        xvfb = -1;
    }
}

/* Whether the Xvfb started is still running; if it ended, its status into *st. */
static bool xvfb_alive(int *st)
{
    if (xvfb <= 0)
        return false;
    if (waitpid(xvfb, st, WNOHANG) != xvfb)
        return true;
    xvfb = -1;
    return false;
}

/* Start Xvfb on a display it picks itself and names on a pipe once it
 * accepts connections (-displayfd): two soaks or window tests at once never
 * take the same display, as they could when each looked for a free number
 * first. It ends after `seconds` even if the soak dies. */
static bool start_xvfb(int seconds)
{
    int fds[2];
    if (pipe(fds) != 0) {
        perror("tristep-soak: pipe");
        return false;
    }
    char fd[16], limit[32], screen[32];
    snprintf(fd, sizeof fd, "%d", fds[1]);
    snprintf(limit, sizeof limit, "%d", seconds);
    snprintf(screen, sizeof screen, "%dx%dx24", SCREEN_W, SCREEN_H);
    char *argv[] = { "timeout", limit, "Xvfb", "-displayfd", fd, "-screen", "0", screen,
                     "-nolisten", "tcp", NULL };
    xvfb = start(argv, NULL, NULL, "xvfb.err");
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
        return true;
    }
    int st;
    if (xvfb > 0 && waitpid(xvfb, &st, WNOHANG) == xvfb) {
        xvfb = -1;
        if (WIFEXITED(st) && WEXITSTATUS(st) == 127) {
            fprintf(stderr, "tristep-soak: Xvfb is not installed (make test installs it)\n");
            return false;
        }
    }
    stop_xvfb();
    fprintf(stderr, "tristep-soak: Xvfb did not start within 30 s (its messages: %s/xvfb.err)\n", work);
    return false;
}

/* Resident memory of a process in MiB (VmRSS), -1 when it is gone. */
static double rss_mib(pid_t pid)
{
    char path[64];
    snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
    char *t = read_all(path);
    const char *p = t ? strstr(t, "VmRSS:") : NULL;
    double kb = p ? strtod(p + 6, NULL) : -1024;
    free(t);
    return kb / 1024;
}

/* --- random input ------------------------------------------------------------------ */

static const char *const keys[] = {
    "Right", "Right", "Right", "Left", "Left", "shift+Right", "shift+Left", "ctrl+Right",
    "ctrl+Left", "Home", "End", "Next", "Prior", "v", "v", "shift+v", "0", "1", "2", "3", "n",
    "x", "t", "b", "bracketleft", "bracketright", "p", "f", "h", "space", "plus", "minus",
    "KP_Add", "F1",
};
#define NKEYS (sizeof keys / sizeof keys[0])

struct batch {
    char *arg[1024];
    char store[1024][24];
    int n;
    long events;                /* input events: keys, button presses, moves, resizes */
};

static void add(struct batch *b, const char *fmt, ...)
{
    if (b->n >= 1020)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(b->store[b->n], sizeof b->store[b->n], fmt, ap);
    va_end(ap);
    b->arg[b->n] = b->store[b->n];
    b->n++;
}

/* One random action into the batch; the window is w x h at the origin. */
static void action(struct batch *b, const char *win, int *w, int *h, bool exports)
{
    int canvas_w = *w * 55 / 100, canvas_h = *h * 90 / 100;
    int r = rnd(0, 999);
    if (r < 560) {
        add(b, "key"), add(b, "%s", keys[rnd(0, (int)NKEYS - 1)]);
        b->events++;
    } else if (r < 680) {                       /* a drag: a vertex or the view */
        add(b, "mousemove"), add(b, "%d", rnd(5, canvas_w)), add(b, "%d", rnd(5, canvas_h));
        add(b, "mousedown"), add(b, "1");
        for (int k = 0; k < 3; k++)
            add(b, "mousemove"), add(b, "%d", rnd(0, *w - 1)), add(b, "%d", rnd(0, *h - 1));
        add(b, "mouseup"), add(b, "1");
        b->events += 6;
    } else if (r < 730) {                       /* a click pins a cell */
        add(b, "mousemove"), add(b, "%d", rnd(5, canvas_w)), add(b, "%d", rnd(5, canvas_h));
        add(b, "click"), add(b, "1");
        b->events += 2;
    } else if (r < 860) {                       /* the wheel */
        add(b, "mousemove"), add(b, "%d", rnd(5, canvas_w)), add(b, "%d", rnd(5, canvas_h));
        add(b, "click"), add(b, "%d", rnd(4, 5));
        b->events += 2;
    } else if (r < 960) {                       /* hovering */
        add(b, "mousemove"), add(b, "%d", rnd(0, *w - 1)), add(b, "%d", rnd(0, *h - 1));
        b->events++;
    } else if (r < 995 || !exports) {           /* a new window size */
        *w = rnd(400, SCREEN_W), *h = rnd(300, SCREEN_H);
        add(b, "windowsize"), add(b, "%s", win), add(b, "%d", *w), add(b, "%d", *h);
        b->events++;
    } else {                                    /* export the view (PNG and SVG) */
        add(b, "key"), add(b, "e");
        b->events++;
    }
    add(b, "sleep"), add(b, "0.0%d", rnd(1, 6));
}

/* --- one lesson ------------------------------------------------------------------- */

struct result {
    char program[64];
    bool ok;
    bool not_the_lesson;        /* failed for the display or the leak checker, not for the lesson */
    char why[640];
    char note[640];             /* an X error the program survived (its handler went on) */
    long events;
    double seconds;
    double rss_1min, rss_end, rss_max_after;    /* MiB; rss_1min < 0: ran less than a minute */
    float *frames;
    size_t nframes;
};

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static double quantile(const float *sorted, size_t n, double q)
{
    if (n == 0)
        return 0;
    size_t i = (size_t)ceil(q * (double)n) - 1;
    return sorted[i < n ? i : n - 1];
}

static float *read_frames(const char *path, size_t *n)
{
    char *t = read_all(path);
    *n = 0;
    if (!t)
        return NULL;
    size_t cap = 1024;
    float *f = malloc(cap * sizeof *f);
    for (char *p = t, *end; f && *p; p = end) {
        double v = strtod(p, &end);
        if (end == p)
            break;
        if (*n == cap) {
            float *g = realloc(f, 2 * cap * sizeof *f);
            if (!g)
                break;
            f = g, cap *= 2;
        }
        f[(*n)++] = (float)v;
    }
    free(t);
    return f;
}

/* Xlib's error message, from its first line on, as one line: each of its
 * indented lines ("  Major opcode of failed request: ...", "  Minor
 * opcode ...", "  Serial number ...", "  Current serial number ...")
 * joined to the one before by "; ". What follows them stays apart. */
static void join_lines(char *t)
{
    char *w = t;
    for (const char *r = t; *r;) {
        if (r[0] == '\n' && r[1] == ' ') {
            while (*r == '\n' || *r == ' ')
                r++;
            *w++ = ';', *w++ = ' ';
        } else if (*r == ' ' && r[1] == ' ') {
            r++;                        /* Xlib's two spaces after each colon */
        } else {
            *w++ = *r++;
        }
    }
    *w = '\0';
}

/* A program's end judged from its exit status (128 + signal; -1: it did
 * not end and was killed) and its stderr (the file err): res->ok when all
 * is well, else res->why says what failed, in the program's own words (a
 * sanitizer's report, Xlib's error message whole, else its last line on
 * stderr), and
 * res->not_the_lesson when the display or the leak checker failed under it. */
static void judge(struct result *res, int status, const char *what, const char *err)
{
    char *e = read_all(err);
    const char *report = NULL;
    static const char *const marks[] = { "ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
                                         "runtime error:", "AddressSanitizer:" };
    for (size_t k = 0; e && !report && k < sizeof marks / sizeof marks[0]; k++)
        report = strstr(e, marks[k]);
    /* LeakSanitizer's own failure: its tracer crashed, no leak check ran */
    const char *tracer = e && !report ? strstr(e, "LeakSanitizer has encountered a fatal error") : NULL;
    if (tracer) {
        const char *caught = strstr(e, "Tracer caught signal");
        report = caught && caught < tracer ? caught : tracer;
    }
    /* Xlib's default error handler: five lines or more, then exit(1) */
    char *xerror = e && !report ? strstr(e, "X Error of failed request:") : NULL;
    if (xerror) {
        join_lines(xerror);
        report = xerror;
    }
    if (!report && status != 0 && e && *e) {   /* no sanitizer's: the program's own last words */
        char *table = strstr(e, "-----\nSuppressions used:");  /* LeakSanitizer's, at exit */
        if (table)
            while (table > e && table[-1] == '-')
                *--table = '\0';
        size_t len = strlen(e);
        while (len && e[len - 1] == '\n')
            e[--len] = '\0';
        char *last = strrchr(e, '\n');
        report = last ? last + 1 : e;
    }
    int len = report ? (int)strcspn(report, "\n") : 0;
    int shown = xerror ? len : len < 120 ? len : 120;
    int xst = 0;
    if (status != 0 && !xvfb_alive(&xst)) {
        res->not_the_lesson = true;
        snprintf(res->why, sizeof res->why,
                 "%s (exit status %d) when Xvfb had ended (%s %d): the display went away, not the "
                 "lesson's fault%s%.*s", what, status, WIFSIGNALED(xst) ? "signal" : "exit status",
                 WIFSIGNALED(xst) ? WTERMSIG(xst) : WEXITSTATUS(xst), report ? "; its stderr: " : "",
                 shown, report ? report : "");
    } else if (status != 0 && tracer) {
        res->not_the_lesson = true;
        snprintf(res->why, sizeof res->why,
                 "%s (exit status %d): LeakSanitizer's tracer crashed while it stopped the threads "
                 "to look for leaks (a fault of the sanitizer, not a leak; no leak check ran): %.*s",
                 what, status, len < 120 ? len : 120, report);
    } else if (status != 0) {
        snprintf(res->why, sizeof res->why, "%s (exit status %d)%s%.*s", what, status,
                 report ? ": " : "", shown, report ? report : "");
    } else if (report && report == xerror) {
        res->ok = true;
        snprintf(res->note, sizeof res->note, "an X error, and the window went on: %.*s", len,
                 report);
    } else if (report) {
        snprintf(res->why, sizeof res->why, "a sanitizer report: %.160s", report);
    } else {
        res->ok = true;
    }
    free(e);
}

static void soak_one(const char *path, const char *name, double seconds, bool exports,
                     struct result *res)
{
    memset(res, 0, sizeof *res);
    snprintf(res->program, sizeof res->program, "%s", name);
    res->rss_1min = -1;
    char denv[32], frames[320], out[300], err[300];
    snprintf(denv, sizeof denv, "DISPLAY=%s", display);
    snprintf(frames, sizeof frames, "TRISTEP_FRAME_TIMES=%s/frames-%s.txt", work, name);
    snprintf(out, sizeof out, "%s/%s.out", work, name);
    snprintf(err, sizeof err, "%s/%s.err", work, name);
    static char asan[128];
    snprintf(asan, sizeof asan, "ASAN_OPTIONS=quarantine_size_mb=%d", QUARANTINE_MB);
    const char *const env[] = { denv, "SDL_VIDEODRIVER=x11", "SDL_RENDER_VSYNC=0", frames, asan,
                                NULL };
    char *argv[] = { (char *)path, "--size", "1280x800", NULL };
    pid_t app = start(argv, env, out, err);

    char title[96];
    snprintf(title, sizeof title, "^tristep %s", name);
    char *search[] = { "search", "--sync", "--onlyvisible", "--name", title };
    int st = -1;
    for (int tries = 0; tries < 3 && st != 0; tries++)
        st = xdotool(search, 5, "search.out");
    char idpath[300];
    snprintf(idpath, sizeof idpath, "%s/search.out", work);
    char *ids = read_all(idpath);
    char win[32] = "";
    if (ids)
        snprintf(win, sizeof win, "%.*s", (int)strcspn(ids, "\n"), ids);
    free(ids);
    if (st != 0 || !win[0]) {
        snprintf(res->why, sizeof res->why, "the window did not appear");
        finish(app, 0);
        return;
    }

    int w = SCREEN_W, h = SCREEN_H;
    double start_t = now_s();
    while (now_s() - start_t < seconds) {
        struct batch b = { .n = 0 };
        for (int i = 0; i < 12; i++)
            action(&b, win, &w, &h, exports);
        xdotool(b.arg, b.n, NULL);
        res->events += b.events;
        double rss = rss_mib(app), t = now_s() - start_t;
        int gone;
        if (waitpid(app, &gone, WNOHANG) == app || (rss < 0 && waitpid(app, &gone, 0) == app)) {
            char what[64];
            snprintf(what, sizeof what, "died after %.0f s", t);
            judge(res, WIFSIGNALED(gone) ? 128 + WTERMSIG(gone) : WEXITSTATUS(gone), what, err);
            if (res->ok)        /* exit status 0, nothing on stderr: it quit, and no Q was sent */
                snprintf(res->why, sizeof res->why, "%s (exit status 0), though no Q was sent", what);
            res->ok = false;
            res->seconds = t;
            return;
        }
        if (t >= FLAT_AFTER_S && res->rss_1min < 0)
            res->rss_1min = rss;
        if (res->rss_1min >= 0 && rss > res->rss_max_after)
            res->rss_max_after = rss;
        res->rss_end = rss;
    }
    res->seconds = now_s() - start_t;
    char *quit[] = { "key", "q" };
    xdotool(quit, 2, NULL);
    int status = finish(app, 60000);
    judge(res, status, status < 0 ? "did not quit on Q within 60 s" : "failed", err);
    if (res->ok && res->rss_1min >= 0 && res->seconds >= FLAT_AFTER_S + 30
        && res->rss_max_after > res->rss_1min * (1 + FLAT_SLACK_FRACTION) + FLAT_SLACK_MB) {
        res->ok = false;
        snprintf(res->why, sizeof res->why,
                 "memory grew after the first minute: %.1f MiB at 1 min, up to %.1f MiB",
                 res->rss_1min, res->rss_max_after);
    }
    char fp[320];
    snprintf(fp, sizeof fp, "%s/frames-%s.txt", work, name);
    res->frames = read_frames(fp, &res->nframes);
    if (res->frames)
        qsort(res->frames, res->nframes, sizeof *res->frames, cmp_float);
    if (res->ok && res->nframes == 0) {
        res->ok = false;
        snprintf(res->why, sizeof res->why, "no frame times written (TRISTEP_FRAME_TIMES)");
    }
}

/* --- the run ------------------------------------------------------------------------ */

static void remove_work(const char *keep)
{
    if (keep)
        return;
    DIR *d = opendir(work);
    struct dirent *e;
    char p[600];
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
            snprintf(p, sizeof p, "%s/%s", work, e->d_name), unlink(p);
    if (d)
        closedir(d);
    rmdir(work);
}

static int usage(FILE *f, int status)
{
    fprintf(f, "usage: tristep-soak --build DIR [--minutes M | --seconds-per-lesson S] "
               "[--seed N] [--keep DIR]\n"
               "Every lesson's window under Xvfb, random keys, drags, wheel and resizes.\n");
    return status;
}

int main(int argc, char **argv)
{
    const char *build = NULL, *keep = NULL;
    double minutes = 0, per_lesson = 0;
    rng_state = 0x50a4;
    for (int i = 1; i < argc; i++) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(argv[i], "--help") == 0)
            return usage(stdout, 0);
        else if (v && strcmp(argv[i], "--build") == 0)
            build = v, i++;
        else if (v && strcmp(argv[i], "--minutes") == 0)
            minutes = atof(v), i++;
        else if (v && strcmp(argv[i], "--seconds-per-lesson") == 0)
            per_lesson = atof(v), i++;
        else if (v && strcmp(argv[i], "--seed") == 0)
            rng_state = strtoull(v, NULL, 0), i++;
        else if (v && strcmp(argv[i], "--keep") == 0)
            keep = v, i++;
        else
            return usage(stderr, 2);
    }
    if (!build || (minutes <= 0 && per_lesson <= 0))
        return usage(stderr, 2);

    /* the lesson programs: NN-name executables in the build folder */
    char names[MAX_LESSONS][64];
    int n = 0;
    DIR *d = opendir(build);
    struct dirent *e;
    while (d && (e = readdir(d)) && n < MAX_LESSONS)
        if (e->d_name[0] >= '0' && e->d_name[0] <= '9' && e->d_name[1] >= '0'
            && e->d_name[1] <= '9' && e->d_name[2] == '-' && strlen(e->d_name) < 64)
            snprintf(names[n++], sizeof names[0], "%s", e->d_name);
    if (d)
        closedir(d);
    if (n == 0) {
        fprintf(stderr, "tristep-soak: no lesson programs in %s\n", build);
        return 2;
    }
    qsort(names, (size_t)n, sizeof names[0], (int (*)(const void *, const void *))strcmp);
    if (per_lesson <= 0)
        per_lesson = minutes * 60 / n;

    if (keep) {
        snprintf(work, sizeof work, "%s", keep);
        mkdir(work, 0755);
    } else {
        snprintf(work, sizeof work, "/tmp/tristep-soak-XXXXXX");
        if (!mkdtemp(work)) {
            perror("tristep-soak: mkdtemp");
            return 1;
        }
    }
    if (!start_xvfb((int)(per_lesson * n) + 60 * n + 120))
        return 1;

    printf("tristep soak: %d lessons, %.0f s each, under Xvfb %s (%dx%d), seed 0x%llx\n", n,
           per_lesson, display, SCREEN_W, SCREEN_H, (unsigned long long)rng_state);
    fflush(stdout);
    static struct result res[MAX_LESSONS];
    bool all_ok = true;
    long events = 0;
    size_t nframes = 0;
    for (int i = 0; i < n; i++) {
        char path[1200], cwd[512];
        int len = build[0] == '/' ? snprintf(path, sizeof path, "%s/%s", build, names[i])
                  : getcwd(cwd, sizeof cwd) ? snprintf(path, sizeof path, "%s/%s/%s", cwd, build, names[i])
                  : -1;
        if (len < 0 || len >= (int)sizeof path) {
            fprintf(stderr, "tristep-soak: the path of %s is too long\n", names[i]);
            return 1;
        }
        soak_one(path, names[i], per_lesson, per_lesson >= 30, &res[i]);
        struct result *r = &res[i];
        if (!r->ok && r->not_the_lesson) {      /* not the lesson's failure: once more */
            printf("  %-26s again: the first run %s\n", r->program, r->why);
            fflush(stdout);
            free(r->frames);
            int st;
            if (!xvfb_alive(&st) && !start_xvfb((int)(per_lesson * (n - i)) + 60 * (n - i) + 120))
                return 1;
            soak_one(path, names[i], per_lesson, per_lesson >= 30, r);
        }
        char m1[32] = "-";
        if (r->rss_1min >= 0)
            snprintf(m1, sizeof m1, "%.1f", r->rss_1min);
        printf("  %-26s %s  %.0f s, %ld events, %zu frames: median %.1f ms, p99 %.1f ms, worst %.1f ms;"
               " RSS %s MiB at 1 min, %.1f MiB at the end%s%s\n",
               r->program, r->ok ? "ok  " : "FAIL", r->seconds, r->events, r->nframes,
               quantile(r->frames, r->nframes, 0.5), quantile(r->frames, r->nframes, 0.99),
               quantile(r->frames, r->nframes, 1), m1, r->rss_end,
               r->ok && !r->note[0] ? "" : "\n      ", r->ok ? r->note : r->why);
        fflush(stdout);
        all_ok &= r->ok;
        events += r->events;
        nframes += r->nframes;
    }
    float *all = malloc((nframes ? nframes : 1) * sizeof *all);
    size_t k = 0;
    for (int i = 0; i < n; i++) {
        if (all && res[i].nframes)
            memcpy(all + k, res[i].frames, res[i].nframes * sizeof *all);
        k += res[i].nframes;
        free(res[i].frames);
    }
    if (all)
        qsort(all, nframes, sizeof *all, cmp_float);
    printf("in all: %ld input events, %zu frames: median %.1f ms, p99 %.1f ms, worst %.1f ms "
           "(sanitizer builds are slower; frame speed is measured by make bench)\n",
           events, nframes, all ? quantile(all, nframes, 0.5) : 0, all ? quantile(all, nframes, 0.99) : 0,
           all ? quantile(all, nframes, 1) : 0);
    printf("soak: %s\n", all_ok ? "passed" : "FAILED");
    free(all);
    stop_xvfb();
    remove_work(keep);
    return all_ok ? 0 : 1;
}
