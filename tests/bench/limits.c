/* limits.c - what this machine allows at most, for the bench to measure the
 * lessons against: how many pixels a second one core and two cores can read
 * and write in memory, how many when they stay in cache, and a counter of
 * cycles to say what one covered pixel costs. */
#define _GNU_SOURCE     /* syscall() for perf_event_open */
#include <linux/perf_event.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#define HAVE_TSC 1
#else
#define HAVE_TSC 0
#endif

#include "bench.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* --- the memory limit ------------------------------------------------------ */

/* The least work a fill must do per pixel: read and write colour and depth.
 * `threads` threads each take an equal part of the buffers and pass over it
 * together, started and stopped by a barrier, so that the time is that of
 * the slowest part. The threads begin once all of them are there (start). */
struct pass {
    uint32_t *c;
    float *d;
    size_t n, threads;
    int runs;
    pthread_mutex_t start;
    bool failed;                /* a thread could not be started: nobody passes */
    pthread_barrier_t go;
    struct bench_timing bt;
};

struct part {
    struct pass *p;
    size_t id;
};

static void *pass_part(void *arg)
{
    const struct part *pt = arg;
    struct pass *p = pt->p;
    pthread_mutex_lock(&p->start);
    bool failed = p->failed;
    pthread_mutex_unlock(&p->start);
    if (failed)
        return NULL;
    size_t lo = p->n * pt->id / p->threads, hi = p->n * (pt->id + 1) / p->threads;
    for (int r = -1; r < p->runs; r++) {
        pthread_barrier_wait(&p->go);
        double t0 = now();
        for (size_t i = lo; i < hi; i++) {
            p->c[i] ^= 0x00010101u;
            p->d[i] += 1.0f;
        }
        __asm__ volatile("" ::: "memory");      /* each pass really reads and writes */
        pthread_barrier_wait(&p->go);
        if (pt->id == 0 && r >= 0)
            p->bt.t[r] = now() - t0;
    }
    return NULL;
}

double bench_memory_limit(size_t n, int threads, int runs, double *gbs)
{
    enum { MOST = 8 };
    struct pass p = { .n = n, .threads = (size_t)threads, .runs = runs, .bt = { .runs = runs },
                      .start = PTHREAD_MUTEX_INITIALIZER };
    pthread_t tid[MOST];
    struct part parts[MOST];
    *gbs = 0;
    if (threads < 1 || threads > MOST || runs > BENCH_MAX_RUNS)
        return 0;
    p.c = malloc(n * sizeof *p.c);
    p.d = malloc(n * sizeof *p.d);
    if (!p.c || !p.d || pthread_barrier_init(&p.go, NULL, (unsigned)threads) != 0) {
        free(p.c);
        free(p.d);
        return 0;
    }
    for (size_t i = 0; i < n; i++) {
        p.c[i] = (uint32_t)i;
        p.d[i] = (float)(i & 1023);
    }
    pthread_mutex_lock(&p.start);
    int started = 1;
    for (; started < threads; started++) {
        parts[started] = (struct part){ &p, (size_t)started };
        if (pthread_create(&tid[started], NULL, pass_part, &parts[started]) != 0)
            break;
    }
    p.failed = started < threads;
    pthread_mutex_unlock(&p.start);
    parts[0] = (struct part){ &p, 0 };
    pass_part(&parts[0]);
    for (int k = 1; k < started; k++)
        pthread_join(tid[k], NULL);
    pthread_barrier_destroy(&p.go);
    free(p.c);
    free(p.d);
    if (p.failed)
        return 0;
    bench_timing_stats(&p.bt);
    *gbs = 16.0 * (double)n / p.bt.median * 1e-9;
    return (double)n / p.bt.median * 1e-6;
}

/* The same pass over one 64 x 64 tile's colour and depth (32 KB), again and
 * again until n pixels are done: the rate when every access hits the cache,
 * what a tiled rasterizer's overdraw costs at best. Returns Mpix/s. */
double bench_cache_limit(size_t n, int runs, double *gbs)
{
    enum { TILE_PIX = 64 * 64 };
    static uint32_t c[TILE_PIX];
    static float d[TILE_PIX];
    for (size_t i = 0; i < TILE_PIX; i++) {
        c[i] = (uint32_t)i;
        d[i] = (float)(i & 1023);
    }
    size_t passes = n / TILE_PIX + 1;
    struct bench_timing bt = { .runs = runs };
    for (int r = -1; r < runs; r++) {
        double t0 = now();
        for (size_t p = 0; p < passes; p++) {
            for (size_t i = 0; i < TILE_PIX; i++) {
                c[i] ^= 0x00010101u;
                d[i] += 1.0f;
            }
            __asm__ volatile("" ::: "memory");  /* each pass really reads and writes */
        }
        if (r >= 0)
            bt.t[r] = now() - t0;
    }
    bench_timing_stats(&bt);
    double pix = (double)(passes * TILE_PIX);
    *gbs = 16.0 * pix / bt.median * 1e-9;
    return pix / bt.median * 1e-6;
}

/* --- cycles ------------------------------------------------------------------- */

/* The core's own cycles in user space, for the calling thread, where the
 * system lets a program count them (perf_event_open; a virtual machine
 * often does not); else the thread's processor time (not the clock: time
 * while other programs run is not counted) in cycles of the time-stamp
 * counter, whose rate is the processor's nominal clock. */
static int cycles_fd = -2;      /* -2: not tried yet, -1: no counter of the core's */
static double tsc_hz;

static void cycles_open(void)
{
    if (cycles_fd != -2)
        return;
    struct perf_event_attr a;
    memset(&a, 0, sizeof a);
    a.type = PERF_TYPE_HARDWARE;
    a.size = sizeof a;
    a.config = PERF_COUNT_HW_CPU_CYCLES;
    a.exclude_kernel = 1;
    a.exclude_hv = 1;
    cycles_fd = (int)syscall(SYS_perf_event_open, &a, 0, -1, -1, 0);
    if (cycles_fd >= 0) {
        uint64_t v;
        if (ioctl(cycles_fd, PERF_EVENT_IOC_ENABLE, 0) != 0 || read(cycles_fd, &v, sizeof v) != sizeof v) {
            close(cycles_fd);
            cycles_fd = -1;
        }
    } else {
        cycles_fd = -1;
    }
#if HAVE_TSC
    if (cycles_fd < 0) {        /* its rate, against the clock, over 50 ms */
        double t0 = now();
        uint64_t c0 = __rdtsc();
        while (now() - t0 < 0.05)
            ;
        tsc_hz = (double)(__rdtsc() - c0) / (now() - t0);
    }
#endif
}

const char *bench_cycles_source(char *buf, size_t n)
{
    cycles_open();
    if (cycles_fd >= 0)
        snprintf(buf, n, "the core's own cycles, perf_event_open");
    else if (HAVE_TSC)
        snprintf(buf, n, "the thread's processor time in cycles of the %.2f GHz time-stamp "
                 "counter: the core's own cannot be counted here", tsc_hz * 1e-9);
    else
        return NULL;
    return buf;
}

uint64_t bench_cycles(void)
{
    cycles_open();
    uint64_t v = 0;
    if (cycles_fd >= 0) {
        if (read(cycles_fd, &v, sizeof v) != sizeof v)
            v = 0;
        return v;
    }
#if HAVE_TSC
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    v = (uint64_t)(((double)t.tv_sec + 1e-9 * (double)t.tv_nsec) * tsc_hz);
#endif
    return v;
}
