/* big.c - the bench's large scene: 2,000,000 small triangles at 1920 x 1080
 * (tests/bench/bigscene.c writes the 330 MB file; it is removed afterwards)
 * opened in the explorer as the window opens it, in a child process per
 * lesson so that each one's peak memory is its own:
 *
 *   load         scene_load: reading and parsing the file
 *   first frame  from the start to the first frame painted (1280 x 800):
 *                load, explorer_init (the scene handed over, steps counted
 *                later), one paint
 *   counted      from the start until every step of the lesson and of the
 *                lessons it is compared with is counted (the window does
 *                this between events)
 *   steps        explorer_set_step to random steps (median and worst), End,
 *                and back one triangle at a time (worst), each with its
 *                picture and cells; what a key press costs before painting
 *   peak RSS     getrusage's ru_maxrss of the child at the end
 *
 * Times are wall-clock; the CPU time of the first frame and of the slowest
 * step are reported beside them because a machine may be shared: a busy
 * machine stretches the wall-clock times.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "bigscene.h"
#include "draw/paint.h"

extern const struct lesson *const all_lessons[];

#define RANDOM_STEPS 20
#define BACK_STEPS 20

static double wall(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* In the child: everything measured, or ok = false and why. */
static void measure(const char *path, const struct lesson *l, struct big_result *r)
{
    double t0 = wall(), c0 = cpu();
    struct scene s;
    char err[512];
    if (!scene_load(&s, path, err, sizeof err)) {
        snprintf(r->why, sizeof r->why, "%s", err);
        return;
    }
    r->load_s = wall() - t0;
    r->ntris = s.ntris;
    if (!explorer_fonts(err, sizeof err)) {
        snprintf(r->why, sizeof r->why, "%s", err);
        return;
    }
    struct explorer ex;
    struct explorer_desc d = { .lesson = l, .give_scene = &s, .scene_name = "big",
                               .count_later = true };
    if (!explorer_init(&ex, &d, err, sizeof err)) {
        snprintf(r->why, sizeof r->why, "%s", err);
        return;
    }
    if (explorer_frame_ms(&ex, 1280, 800, 1) < 0) {
        snprintf(r->why, sizeof r->why, "painting failed");
        explorer_free(&ex);
        return;
    }
    /* explorer_frame_ms paints twice (a warm-up): the first frame is the first of them */
    r->first_frame_s = wall() - t0;
    r->first_frame_cpu_s = cpu() - c0;
    while (explorer_counting(&ex))
        if (!explorer_count(&ex, 50)) {
            snprintf(r->why, sizeof r->why, "out of memory counting");
            explorer_free(&ex);
            return;
        }
    r->counted_s = wall() - t0;
    r->steps = ex.replay.total;
    r->checkpoints = ex.replay.nchecks;

    uint64_t state = 0x5eed;
    double t[RANDOM_STEPS];
    for (int i = 0; i < RANDOM_STEPS; i++) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        uint64_t step = (state >> 11) % (ex.replay.total + 1);
        double a = wall(), c = cpu();
        explorer_set_step(&ex, step);
        t[i] = wall() - a;
        r->step_worst_cpu_s = fmax(r->step_worst_cpu_s, cpu() - c);
    }
    qsort(t, RANDOM_STEPS, sizeof t[0], cmp_double);
    r->step_median_s = (t[RANDOM_STEPS / 2 - 1] + t[RANDOM_STEPS / 2]) / 2;
    r->step_worst_s = t[RANDOM_STEPS - 1];
    double a = wall(), c = cpu();
    explorer_set_step(&ex, ex.replay.total);
    r->end_s = wall() - a;
    r->step_worst_cpu_s = fmax(r->step_worst_cpu_s, cpu() - c);
    for (int i = 0; i < BACK_STEPS; i++) {
        a = wall(), c = cpu();
        explorer_move(&ex, STEP_TRIANGLE, -1);
        r->back_worst_s = fmax(r->back_worst_s, wall() - a);
        r->step_worst_cpu_s = fmax(r->step_worst_cpu_s, cpu() - c);
    }
    explorer_free(&ex);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    r->peak_rss_mib = (double)ru.ru_maxrss / 1024;
    r->ok = true;
}

bool bench_big_scene(const char *path, long ntris, const char *only, struct big_result *out,
                     int max, int *n)
{
    *n = 0;
    double g0 = wall();
    if (!big_scene_file(path, ntris, 2026)) {
        fprintf(stderr, "tristep-bench: cannot write %s\n", path);
        return false;
    }
    FILE *f = fopen(path, "rb");
    long bytes = 0;
    if (f && fseek(f, 0, SEEK_END) == 0)
        bytes = ftell(f);
    if (f)
        fclose(f);
    printf("\nlarge scene: %ld triangles at %d x %d, %.0f MB of scene text (written in %.1f s, "
           "removed after)\n", ntris, BIG_SCENE_W, BIG_SCENE_H, (double)bytes * 1e-6, wall() - g0);
    for (int i = 0; all_lessons[i] && *n < max; i++) {
        const struct lesson *l = all_lessons[i];
        if (only && strncmp(l->id, only, strlen(only)) != 0)
            continue;
        fprintf(stderr, "large scene in the explorer of %s...\n", l->id);
        int fd[2];
        if (pipe(fd) != 0)
            break;
        fflush(NULL);
        pid_t pid = fork();
        if (pid == 0) {
            close(fd[0]);
            struct big_result r = { .ok = false };
            measure(path, l, &r);
            ssize_t w = write(fd[1], &r, sizeof r);
            _exit(w == (ssize_t)sizeof r ? 0 : 1);
        }
        close(fd[1]);
        struct big_result *r = &out[*n];
        memset(r, 0, sizeof *r);
        ssize_t got = pid > 0 ? read(fd[0], r, sizeof *r) : -1;
        close(fd[0]);
        int st = 0;
        if (pid > 0)
            waitpid(pid, &st, 0);
        if (got != (ssize_t)sizeof *r) {
            memset(r, 0, sizeof *r);
            snprintf(r->why, sizeof r->why, "the child died (status %d)", st);
        }
        r->program = l->id;
        (*n)++;
    }
    remove(path);
    return true;
}
