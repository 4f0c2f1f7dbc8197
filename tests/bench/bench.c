/* bench.c - `make bench`: every lesson's fast build timed on the same work,
 * beside Mesa's llvmpipe and the memory-bandwidth limit of this machine.
 *
 * What is timed, per lesson variant (variants[0] and every exact twin) and
 * per scene: tri_setup + rasterize for every triangle of the scene, into a
 * 1920 x 1080 RGBA8 target with a float depth buffer (test LESS, with
 * write), Gouraud colour. The target is cleared between runs, outside the
 * clock. One warm-up run, then the median of N runs with their spread.
 *
 * What is checked, untimed, on every scene it times: the coverage count of
 * every pixel equals the exact reference's, and llvmpipe's (0 differing
 * pixels, or the exit status is 1). llvmpipe also draws at 4 samples (a
 * multisampled framebuffer resolved by a blit, beside lesson 08's rows),
 * checked against the exact rule at the samples where it says they are.
 * Then three textured scenes (textured.c): the lessons that map image
 * textures beside llvmpipe on one thread, trilinear, their colours held to
 * llvmpipe's by agreement.
 *
 * Output: a table on stdout, BUILD/bench.csv, BUILD/bench.svg and .png, and
 * the same table as markdown (BUILD/bench.md, or --markdown FILE): `make
 * bench` writes it to BENCH.md, the one place the course's texts take a
 * speed from (tests/test_texts.c holds them to it).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <signal.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "draw/paint.h"
#include "lesson.h"

extern const struct lesson *const all_lessons_fast[];
extern const struct lesson *const all_lessons[];   /* narrated: for the explorer frame */

#define NSCENES 3
#define MAX_ROWS 128   /* programs x variants x sample counts; more is a usage error */
#define PEER_SAMPLES 4          /* llvmpipe's multisampled rows, beside lesson 08's */
#define SCENE_LARGE 0
#define SCENE_SMALL 1
#define SCENE_MIXED 2

/* Targets, medians of the same run. Lesson 07 against llvmpipe: */
#define TARGET_L07_LARGE_X 2.5  /* lesson 07 vs llvmpipe, both on every core, Mpix/s on large */
#define TARGET_L07_SMALL_X 2.5  /* ... Mtri/s on small */
#define TARGET_L07_MIXED_X 2.5  /* ... Mtri/s on mixed */
#define TARGET_L07_ONE_X 2.0    /* lesson 07 --threads 1 vs LP_NUM_THREADS=0, every scene */
#define TARGET_L07_SCALE_X 1.8  /* lesson 07 from 1 to 2 threads, large and mixed */
#define TARGET_L07_SCALE_SMALL_X 1.6    /* ... on small */
#define TARGET_L07_LOADED_X 0.9 /* with one core kept busy: every core vs 1 thread, every scene */
#define TARGET_L07_MEMORY_X 1.0 /* lesson 07 on large, times the memory limit */
#define TARGET_L08_MSAA_X 1.2   /* lesson 08's tiles vs llvmpipe, 4 samples, 1 thread and all cores */
/* Lesson 05 against lesson 02, the paper's figures (Mileff, Nehez and Dudra
 * 2015: their best speed-up of block classification over the bounding box is
 * 9.72x on large triangles; on tiny ones blocks lose, 0.85x). */
#define PAPER_L05_LARGE_X 9.72
#define PAPER_L05_TINY_X 0.85
#define TARGET_FRAME_MS 16.0    /* explorer frame at 1280 x 800 */
#define TARGET_BIG_FIRST_S 5.0  /* 2,000,000 triangles: first frame */
#define TARGET_BIG_RSS_MIB 2048 /* ... within 2 GiB */
#define TARGET_BIG_STEP_MS 100  /* ... every step interactive */
#define TARGET_L09_LP_X 1.5     /* lesson 09 vs llvmpipe, textured (trilinear): 1 thread each, all cores each */
#define BIG_TRIS 2000000
#define BIG_TRIS_QUICK 20000
#define MAX_BIG 16

struct options {
    bool quick, exhibits, peer, no_big;
    int runs;
    uint64_t seed;
    const char *out;            /* directory for bench.csv/svg/png */
    const char *markdown;       /* the markdown table, NULL: OUT/bench.md */
    const char *only;           /* run only lessons whose id starts with this */
    const char *only_variant;   /* ... and only this variant */
    const char *figures_cmd;    /* command that runs `make figures`, timed */
};

/* One line of the table: a lesson variant or a peer, on every scene. */
struct row {
    const char *program;        /* "02-barycentric", "llvmpipe" */
    const char *variant;        /* "top-left", "1 thread" */
    bool exhibit, peer;
    struct bench_timing t[NSCENES];
    const struct lesson *lesson;        /* NULL for a peer */
    const struct lesson_variant *var;
    int samples;                /* lesson 08's samples per pixel (0, 1: the centre) */
    int threads;                /* the lesson's --threads (0: its default, one per core) */
};

static struct row rows[MAX_ROWS];
static int nrows;
static double frame_ms = -1;     /* explorer frame, < 0 not measured */
static struct big_result big[MAX_BIG];
static int nbig;
static double figures_s = -1;    /* make figures, < 0 not measured */
static struct bench_front front;  /* the 3-D front end; front.t.runs == 0: not measured */
/* The memory limits on two cores, each passing over its half (0: not
 * measured): the same buffers as the scenes, and 8 times larger ones. */
static double limit2, limit2_gbs, dram1, dram2;
static char cycles_what[200];     /* what bench_cycles() counts, "" when nothing */
/* The same machine with one core kept busy by a spinning child process:
 * lesson 07 on every core and on 1 thread, llvmpipe on its default threads
 * and on 1 thread (LOADED_*), interleaved; runs == 0: not measured. */
enum { LOADED_L07, LOADED_L07_1, LOADED_LP, LOADED_LP_1, LOADED_ROWS };
static struct bench_timing loaded[LOADED_ROWS][NSCENES];

/* The targets as printed, kept for bench.csv. */
struct target_line {
    char id[64], what[96], unit[8];
    double got, goal;
    bool under, met, measured;
};
static struct target_line targets[40];
static int ntargets;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double bench_now(void)
{
    return now();
}

/* Processor time of all the program's threads (the lesson's workers too). */
static double process_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void bench_timing_stats(struct bench_timing *bt)
{
    double s[BENCH_MAX_RUNS];
    memcpy(s, bt->t, (size_t)bt->runs * sizeof *s);
    qsort(s, (size_t)bt->runs, sizeof *s, cmp_double);
    int n = bt->runs;
    bt->median = n % 2 ? s[n / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
    bt->lo = s[0];
    bt->hi = s[n - 1];
    memcpy(s, bt->cycles, (size_t)bt->runs * sizeof *s);
    qsort(s, (size_t)bt->runs, sizeof *s, cmp_double);
    bt->cycles_median = n % 2 ? s[n / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
    memcpy(s, bt->cpu, (size_t)bt->runs * sizeof *s);
    qsort(s, (size_t)bt->runs, sizeof *s, cmp_double);
    bt->cpu_median = n % 2 ? s[n / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}

/* Pixels whose counts differ (agree.c). */
static int64_t count_diff(const uint8_t *a, const uint8_t *b, size_t n)
{
    return bench_count_diff(a, b, n);
}


/* --- the lessons ------------------------------------------------------------ */

/* The whole scene: through the lesson's scene-level twin when it has one
 * (lesson 07 bins every triangle, then draws tile by tile on every core),
 * else tri_setup + rasterize triangle after triangle. */
/* The params of a row: its samples, and its threads when it sets them. */
static struct raster_params row_params(const struct row *row)
{
    struct raster_params p = { .subpixel_bits = SUBPIXEL_BITS, .samples = row->samples };
    int k;
    if (row->threads > 0 && lesson_param(row->lesson, "threads", &k))
        *lesson_param_slot(row->lesson, k, &p) = row->threads;
    return p;
}

static void draw_scene(const struct row *row, const struct scene *s,
                       const struct raster_params *p, struct target *fb)
{
    rasterize_scene_fn whole = lesson_scene_fn(row->lesson, row->var);
    if (whole) {
        if (!whole(s, p, fb)) {
            fprintf(stderr, "tristep-bench: %s %s: out of memory\n", row->program, row->variant);
            exit(1);
        }
        return;
    }
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        const struct raster_params each = lesson_params_tri(p, s, i);   /* its image texture */
        row->var->rasterize(&t, &each, fb, NULL);
    }
}

void bench_draw(const struct lesson *l, const struct lesson_variant *v, const struct scene *s,
                const struct raster_params *p, struct target *fb)
{
    const struct row row = { .program = l->id, .variant = v->name, .lesson = l, .var = v };
    draw_scene(&row, s, p, fb);
}

/* Lesson 08's exact answer at n samples: for every pixel, the samples the
 * scene's triangles cover (saturating at 255), each sample decided by the
 * reference (raster.h: reference_point_covered) over a generous box. Made
 * once per scene and sample count, untimed. The samples at pos[] (1/256
 * pixel from the pixel's corner; llvmpipe's), or NULL: sample_pattern(n). */
static uint8_t *sample_reference(const struct scene *s, int n, const int (*pos)[2])
{
    const struct sample_pattern *sp = sample_pattern(n);
    uint8_t *cov = calloc((size_t)s->w * (size_t)s->h, 1);
    if (!cov || !sp) {
        fprintf(stderr, "tristep-bench: out of memory\n");
        exit(1);
    }
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        int64_t lo[2] = { t.x[0], t.y[0] }, hi[2] = { t.x[0], t.y[0] };
        for (int k = 1; k < 3; k++) {
            lo[0] = t.x[k] < lo[0] ? t.x[k] : lo[0], hi[0] = t.x[k] > hi[0] ? t.x[k] : hi[0];
            lo[1] = t.y[k] < lo[1] ? t.y[k] : lo[1], hi[1] = t.y[k] > hi[1] ? t.y[k] : hi[1];
        }
        int64_t x0 = floor_div(lo[0], SUBPIXEL_ONE) - 1, x1 = floor_div(hi[0], SUBPIXEL_ONE) + 1;
        int64_t y0 = floor_div(lo[1], SUBPIXEL_ONE) - 1, y1 = floor_div(hi[1], SUBPIXEL_ONE) + 1;
        x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
        x1 = x1 >= s->w ? s->w - 1 : x1, y1 = y1 >= s->h ? s->h - 1 : y1;
        for (int64_t y = y0; y <= y1; y++)
            for (int64_t x = x0; x <= x1; x++)
                for (int k = 0; k < n; k++)
                    if (reference_point_covered(&t, x * SUBPIXEL_ONE + (pos ? pos[k][0] : sp->x[k]),
                                                y * SUBPIXEL_ONE + (pos ? pos[k][1] : sp->y[k]))) {
                        uint8_t *c = &cov[y * s->w + x];
                        *c += *c < 255;
                    }
    }
    return cov;
}

/* One timed run of a row on scene i (r < 0: the warm-up, not kept). The
 * target (multisample for a row of lesson 08's samples) is cleared outside
 * the clock and does not count coverage. */
static void time_once(struct row *row, int i, const struct scene *s, struct target *fb, int r)
{
    const struct raster_params p = row_params(row);
    target_clear(fb);
    struct target timed = *fb;
    timed.count = NULL;
    uint64_t c0 = bench_cycles();
    double p0 = process_seconds(), t0 = now();
    draw_scene(row, s, &p, &timed);
    double t1 = now(), p1 = process_seconds();
    uint64_t c1 = bench_cycles();
    if (r >= 0)
        row->t[i].t[r] = t1 - t0, row->t[i].cycles[r] = (double)(c1 - c0),
        row->t[i].cpu[r] = p1 - p0;
}

/* A row's target on one scene, among that scene's targets by sample count. */
static struct target *row_target(struct target fbs[], const struct row *row)
{
    return &fbs[row->samples > 1 ? row->samples : 0];
}

/* sample_reference() at the standard pattern, once per scene and count. */
static const uint8_t *sample_reference_of(int i, const struct scene *s, int n)
{
    static uint8_t *ref[NSCENES][SAMPLES_MAX + 1];
    if (!ref[i][n])
        ref[i][n] = sample_reference(s, n, NULL);
    return ref[i][n];
}

/* Does llvmpipe's multisampled framebuffer sample where lesson 08 does? */
static bool peer_samples_standard(void)
{
    const struct sample_pattern *sp = sample_pattern(PEER_SAMPLES);
    for (int k = 0; k < PEER_SAMPLES; k++)
        if (peer_sample_pos[k][0] != sp->x[k] || peer_sample_pos[k][1] != sp->y[k])
            return false;
    return true;
}

/* Untimed: the same code once more, counting coverage, against the
 * reference and llvmpipe; a row of samples > 1 against sample_reference()
 * and, at 4 samples, llvmpipe's multisampled framebuffer (peer_cov4) if it
 * samples at the same points (else there is nothing to compare). */
static void check_coverage(struct row *row, int i, const struct bench_scene *sc,
                           uint8_t *const peer_cov[], uint8_t *const peer_cov4[], struct target *fb)
{
    const struct raster_params p = row_params(row);
    target_clear(fb);
    draw_scene(row, &sc->s, &p, fb);
    size_t n = (size_t)sc->s.w * (size_t)sc->s.h;
    if (row->samples > 1) {
        row->t[i].diff_ref = count_diff(fb->count, sample_reference_of(i, &sc->s, row->samples), n);
        row->t[i].diff_peer = row->samples == PEER_SAMPLES && peer_cov4 && peer_samples_standard()
                            ? count_diff(fb->count, peer_cov4[i], n) : -1;
        return;
    }
    row->t[i].diff_ref = count_diff(fb->count, sc->coverage, n);
    row->t[i].diff_peer = peer_cov ? count_diff(fb->count, peer_cov[i], n) : -1;
}

/* --- the explorer's frame ------------------------------------------------- */

/* Milliseconds to paint one explorer frame of 1280 x 800 showing a 64 x 48
 * pixel grid with numbers in the cells (the depth view: one number a cell),
 * lesson 02 halfway through a large triangle: the painter the window and the
 * figures share. */
static double explorer_frame(int frames)
{
    static const char text[] =
        "size 64 48\n"
        "tri  3.3 2.6 1  0.95 0.2 0.15   61.7 17.2 1  0.2 0.85 0.3   21.5 45.4 1  0.2 0.35 0.95\n";
    struct scene s;
    char err[256];
    if (!scene_parse(&s, "frame", text, sizeof text - 1, err, sizeof err))
        return -1;
    if (!explorer_fonts(err, sizeof err)) {
        fprintf(stderr, "explorer frame: %s\n", err);
        scene_free(&s);
        return -1;
    }
    struct explorer ex;
    struct explorer_desc d = { .lesson = all_lessons[0], .scene = &s, .scene_name = "frame" };
    for (int i = 0; all_lessons[i]; i++)
        if (strncmp(all_lessons[i]->id, "02", 2) == 0)
            d.lesson = all_lessons[i];
    double ms = -1;
    if (!explorer_init(&ex, &d, err, sizeof err))
        fprintf(stderr, "%s\n", err);
    else {
        explorer_set_step(&ex, ex.replay.total / 2);
        ex.numbers = NUMBERS_ALWAYS;   /* one number a cell: at 12 px cells, three would not fit */
        explorer_set_view_name(&ex, "depth");
        ms = explorer_frame_ms(&ex, 1280, 800, frames);
        explorer_free(&ex);
    }
    scene_free(&s);
    return ms;
}

/* --- make figures --------------------------------------------------------- */

/* Seconds `cmd` took, 0 when make has nothing to do for it (no recipe yet),
 * -1 when it failed. */
static double time_command(const char *cmd, char *note, size_t notelen)
{
    char dry[512];
    snprintf(dry, sizeof dry, "%s -n 2>&1", cmd);
    FILE *p = popen(dry, "r");
    int lines = 0;
    char line[512];
    while (p && fgets(line, sizeof line, p))
        lines += strstr(line, "Nothing to be done") == NULL && strstr(line, "make") != line;
    if (p)
        pclose(p);
    if (lines == 0) {
        snprintf(note, notelen, "no recipe for it yet");
        return 0;
    }
    fflush(NULL);
    double t0 = now();
    int status = system(cmd);
    double t = now() - t0;
    if (status != 0) {
        snprintf(note, notelen, "failed (status %d)", status);
        return -1;
    }
    snprintf(note, notelen, "%s", cmd);
    return t;
}

/* --- reporting ------------------------------------------------------------ */

static void cpu_model(char *out, size_t len)
{
    snprintf(out, len, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[256];
    while (f && fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) == 0) {
            char *v = strchr(line, ':');
            if (v) {
                v += strspn(v, ": \t");
                v[strcspn(v, "\n")] = 0;
                snprintf(out, len, "%s", v);
            }
            break;
        }
    }
    if (f)
        fclose(f);
}

static double mtri(const struct bench_scene *sc, const struct bench_timing *t)
{
    return sc->s.ntris / t->median * 1e-6;
}

static double mpix(const struct bench_scene *sc, const struct bench_timing *t)
{
    return (double)sc->pixels / t->median * 1e-6;
}

static const struct row *find_row(const char *prefix, const char *variant)
{
    for (int i = 0; i < nrows; i++)
        if (strncmp(rows[i].program, prefix, strlen(prefix)) == 0
            && (!variant || strcmp(rows[i].variant, variant) == 0))
            return &rows[i];
    return NULL;
}

static void print_diff(char *buf, size_t len, int64_t d)
{
    if (d < 0)
        snprintf(buf, len, "-");
    else
        snprintf(buf, len, "%lld", (long long)d);
}

/* The measured cells of one row of the table on scene i, formatted once for
 * the terminal and the markdown table alike. */
struct cells {
    char median[24], spread[16], mtri[16], mpix[16], ratio[16], mem[16], dref[24], dpeer[24];
};

static void row_cells(const struct bench_scene *sc, int i, const struct row *r, double limit,
                      struct cells *c)
{
    const struct row *base = find_row("02-", NULL);
    const struct bench_timing *t = &r->t[i];
    snprintf(c->median, sizeof c->median, "%.2f", t->median * 1e3);
    snprintf(c->spread, sizeof c->spread, "%.1f%%", 100 * (t->hi - t->lo) / t->median);
    snprintf(c->mtri, sizeof c->mtri, "%.3g", mtri(&sc[i], t));
    snprintf(c->mpix, sizeof c->mpix, "%.1f", mpix(&sc[i], t));
    snprintf(c->ratio, sizeof c->ratio, "-");
    if (base)
        snprintf(c->ratio, sizeof c->ratio, "%.2f", base->t[i].median / t->median);
    snprintf(c->mem, sizeof c->mem, "%.1f%%", limit > 0 ? 100 * mpix(&sc[i], t) / limit : 0.0);
    print_diff(c->dref, sizeof c->dref, t->diff_ref);
    print_diff(c->dpeer, sizeof c->dpeer, t->diff_peer);
}

static void print_table(const struct bench_scene *sc, double limit)
{
    for (int i = 0; i < NSCENES; i++) {
        const struct scene *s = &sc[i].s;
        printf("\nscene %s: %d x %d, %d triangles, %llu covered pixels (%.1f x the screen); %s\n",
               sc[i].name, s->w, s->h, s->ntris, (unsigned long long)sc[i].pixels,
               (double)sc[i].pixels / ((double)s->w * s->h), sc[i].what);
        printf("  %-26s %-15s %10s %7s %9s %9s %7s %6s %9s %9s\n", "program", "variant",
               "median ms", "spread", "Mtri/s", "Mpix/s", "x L02", "% mem", "diff ref", "diff llvm");
        for (int k = 0; k < nrows; k++) {
            const struct row *r = &rows[k];
            struct cells c;
            row_cells(sc, i, r, limit, &c);
            printf("  %-26s %-15s %10s %7s %9s %9s %7s %6s %9s %9s%s\n", r->program, r->variant,
                   c.median, c.spread, c.mtri, c.mpix, c.ratio, c.mem, c.dref, c.dpeer,
                   r->exhibit ? "  (exhibit)" : "");
        }
    }
    printf("\n(spread = (slowest - fastest) / median; Mpix/s counts covered pixels, overdraw "
           "included; diff = pixels whose coverage count differs)\n");
}

static bool write_csv(const char *path, const struct bench_scene *sc, double limit,
                      const char *cpu, const char *date)
{
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return false;
    const struct row *base = find_row("02-", NULL);
    fprintf(f, "# tristep bench, %s, %s\n", cpu, date);
    fprintf(f, "scene,width,height,triangles,pixels,program,variant,exhibit,runs,median_s,min_s,"
               "max_s,mtri_s,mpix_s,ratio_l02,pct_memory_limit,diff_ref,diff_llvmpipe,"
               "pct_within2_llvmpipe,pct_within8_llvmpipe\n");
    for (int i = 0; i < NSCENES; i++)
        for (int k = 0; k < nrows; k++) {
            const struct row *r = &rows[k];
            const struct bench_timing *t = &r->t[i];
            fprintf(f, "%s,%d,%d,%d,%llu,%s,%s,%d,%d,%.6f,%.6f,%.6f,%.4f,%.2f,%.4f,%.2f,%lld,%lld,-1,-1\n",
                    sc[i].name, sc[i].s.w, sc[i].s.h, sc[i].s.ntris,
                    (unsigned long long)sc[i].pixels, r->program, r->variant, r->exhibit, t->runs,
                    t->median, t->lo, t->hi, mtri(&sc[i], t), mpix(&sc[i], t),
                    base ? base->t[i].median / t->median : 0.0,
                    limit > 0 ? 100 * mpix(&sc[i], t) / limit : 0.0, (long long)t->diff_ref,
                    (long long)t->diff_peer);
        }
    bench_textured_csv(f);
    for (int i = 0; i < NSCENES; i++)
        fprintf(f, "%s,%d,%d,0,%llu,memory-limit,read-modify-write,0,0,0,0,0,0,%.2f,0,100,-1,-1,-1,-1\n",
                sc[i].name, sc[i].s.w, sc[i].s.h, (unsigned long long)sc[i].pixels, limit);
    /* not scenes: the explorer's frame and make figures, in seconds */
    if (frame_ms > 0)
        fprintf(f, "none,1280,800,0,0,explorer,frame,0,0,%.6f,0,0,0,0,0,0,-1,-1,-1,-1\n", frame_ms / 1e3);
    if (figures_s > 0)
        fprintf(f, "none,0,0,0,0,make-figures,all,0,1,%.3f,0,0,0,0,0,0,-1,-1,-1,-1\n", figures_s);
    /* the large scene in the explorer: seconds, and peak-rss-mib in MiB */
    for (int i = 0; i < nbig; i++) {
        const struct big_result *b = &big[i];
        if (!b->ok)
            continue;
        const struct { const char *what; double v; } m[] = {
            { "load", b->load_s }, { "first-frame", b->first_frame_s },
            { "first-frame-cpu", b->first_frame_cpu_s }, { "all-counted", b->counted_s },
            { "step-median", b->step_median_s }, { "step-worst", b->step_worst_s },
            { "step-end", b->end_s }, { "step-back-worst", b->back_worst_s },
            { "step-worst-cpu", b->step_worst_cpu_s },
            { "peak-rss-mib", b->peak_rss_mib },
        };
        for (size_t k = 0; k < sizeof m / sizeof m[0]; k++)
            fprintf(f, "big,1920,1080,%d,0,%s,%s,0,1,%.6f,0,0,0,0,0,0,-1,-1,-1,-1\n", b->ntris,
                    b->program, m[k].what, m[k].v);
    }
    /* the 3-D front end: world triangles per second, no pixels */
    if (front.t.runs > 0)
        fprintf(f, "torus-3d,1920,1080,%d,0,front-end,clip+project,0,%d,%.6f,%.6f,%.6f,%.4f,0,0,0,-1,-1,-1,-1\n",
                front.in, front.t.runs, front.t.median, front.t.lo, front.t.hi,
                front.in / front.t.median * 1e-6);
    /* the targets: program target-met or target-missed, variant = its id,
     * median_s = the value measured, min_s = the goal */
    for (int k = 0; k < ntargets; k++)
        if (targets[k].measured)
            fprintf(f, "none,0,0,0,0,%s,%s,0,0,%.4f,%.4f,0,0,0,0,0,-1,-1,-1,-1\n",
                    targets[k].met ? "target-met" : "target-missed", targets[k].id,
                    targets[k].got, targets[k].goal);
    bool ok = fclose(f) == 0 && rename(tmp, path) == 0;
    if (!ok)
        remove(tmp);
    return ok;
}

/* What bounds lesson 07 on one thread, in words (markdown: list items),
 * into buf: the memory limit on two cores beside one's, and the cycles a
 * covered pixel of the large scene costs against the memory traffic of
 * its tiles. False when nothing of it was measured. */
static bool limits_line(const struct bench_scene *sc, double limit, char *buf, size_t n, bool md)
{
    size_t at = 0;
    buf[0] = '\0';
    const char *item = md ? "- " : "  ";
    if (limit2 > 0 && limit > 0)
        at += (size_t)snprintf(buf + at, n - at, "%smemory limit on two cores, each passing over "
                               "half of the buffers: %.1f Mpix/s (%.1f GB/s), %.2fx one core's; "
                               "beyond the caches (8 times larger buffers) %.1f Mpix/s on two "
                               "cores, %.2fx one core's %.1f\n", item, limit2, limit2_gbs,
                               limit2 / limit, dram2, dram1 > 0 ? dram2 / dram1 : 0, dram1);
    const struct row *one = find_row("07-", "1-thread");
    const struct bench_timing *t = one ? &one->t[SCENE_LARGE] : NULL;
    if (t && t->median > 0 && cycles_what[0] && t->cycles_median > 0 && at < n) {
        double per_pixel = t->cycles_median / (double)sc[SCENE_LARGE].pixels;
        double screen = (double)sc[SCENE_LARGE].s.w * (double)sc[SCENE_LARGE].s.h;
        double mem_ms = limit > 0 ? screen / (limit * 1e6) * 1e3 : 0;
        at += (size_t)snprintf(buf + at, n - at, "%slesson 07 on large, one thread (`1-thread`): "
                               "%.2f cycles per covered pixel, %.1f per register of 8 (%s); its "
                               "memory traffic, each tile loaded and stored once, is one pass "
                               "over the screen: %.2f ms at the one-core memory limit, %.0f%% of "
                               "its %.2f ms. The rest is pixel work in cache: it is bound by "
                               "computing, not by memory\n", item, per_pixel, 8 * per_pixel,
                               cycles_what, mem_ms, 100 * mem_ms / (t->median * 1e3),
                               t->median * 1e3);
    }
    const struct row *all = find_row("07-", "tiles");
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    for (int i = 0; one && all && i < NSCENES && at < n; i++) {
        const struct bench_timing *a = &all->t[i], *b = &one->t[i];
        if (a->cpu_median <= 0 || b->cpu_median <= 0)
            continue;
        at += (size_t)snprintf(buf + at, n - at, "%slesson 07 on %s, %ld threads against 1: "
                               "%.2fx the processor time of all threads (%.2f ms against %.2f: "
                               "the split's cost, waits spent spinning included), a speed-up "
                               "of %.2fx by the clock (the rest of the gap to %ldx is waiting, "
                               "for a core or another worker)\n", item, sc[i].name, cores, a->cpu_median / b->cpu_median,
                               a->cpu_median * 1e3, b->cpu_median * 1e3, b->median / a->median,
                               cores);
    }
    return at > 0;
}

/* The table as markdown: machine, date, one table per scene (medians,
 * spread), the memory limit, the explorer's frame. Written to a temporary
 * file and renamed, so a failed run leaves the old one. */
/* Lesson 07 one idea at a time: each of its variants that takes one idea
 * away, against the whole (ratios of medians: > 1, the idea helps). */
static void write_journey(FILE *f, const struct bench_scene *sc)
{
    static const struct { const char *idea, *without, *with; } step[] = {
        { "binning", "no-bins", "1-thread" },
        { "one corner per edge", "four-corners", "1-thread" },
        { "tile buffers", "in-place", "1-thread" },
        { "4 pixels a register (SSE2) over plain C", "scalar", "sse2" },
        { "8 pixels a register (AVX2) over SSE2", "sse2", "1-thread" },
        { "threads, one per core", "1-thread", "tiles" },
    };
    if (!find_row("07-", "1-thread"))
        return;
    fprintf(f, "\n## Lesson 07, one idea at a time\n\nWhat each idea gains: the median of "
               "the variant without it over the median with it (above 1: it helps).\n\n"
               "| idea | from | to | %s | %s | %s |\n| --- | --- | --- | ---: | ---: | ---: |\n",
            sc[0].name, sc[1].name, sc[2].name);
    for (size_t k = 0; k < sizeof step / sizeof step[0]; k++) {
        const struct row *a = find_row("07-", step[k].without), *b = find_row("07-", step[k].with);
        if (!a || !b)
            continue;
        fprintf(f, "| %s | `%s` | `%s` |", step[k].idea, step[k].without, step[k].with);
        for (int i = 0; i < NSCENES; i++)
            fprintf(f, " %.2fx |", a->t[i].median / b->t[i].median);
        fprintf(f, "\n");
    }
}

static bool write_markdown(const char *path, const struct bench_scene *sc, double limit,
                           const char *cpu, const char *date, const char *system,
                           const struct options *o)
{
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return false;
    fprintf(f, "# tristep bench%s\n\n", o->quick ? " (quick mode: tiny scenes, not a measurement)" : "");
    fprintf(f, "<!-- written by `make bench` (tests/bench/bench.c); do not edit by hand: "
               "run `make bench` again -->\n\n");
    fprintf(f, "- machine: %s, %ld cores online, %s\n", cpu, sysconf(_SC_NPROCESSORS_ONLN),
            system);
    fprintf(f, "- date: %s\n", date);
    fprintf(f, "- work: every lesson's fast build (narration compiled out), `tri_setup` and "
               "rasterize of every triangle into an RGBA8 target (sizes below) with a float "
               "depth buffer (test LESS, write), Gouraud colour; one thread unless said\n");
    fprintf(f, "- timing: median of %d runs after one warm-up (seed %llu); spread = "
               "(slowest - fastest) / median; on a shared machine, differences smaller than "
               "the spread are noise\n", o->runs, (unsigned long long)o->seed);
    fprintf(f, "- peer: %s\n", find_row("llvmpipe", NULL) ? peer_renderer : "llvmpipe not measured");
    fprintf(f, "- llvmpipe's environment: its sampler's faster approximations off, %s (they "
               "matter on the textured scenes)\n", PEER_EXACT_OPTIONS);
    if (find_row("llvmpipe", "1 thread 4 samples")) {
        fprintf(f, "- llvmpipe at 4 samples: a multisampled framebuffer resolved by a blit, both timed; "
                "its samples (GL_SAMPLE_POSITION) in the scene, 1/256 pixel:");
        for (int k = 0; k < PEER_SAMPLES; k++)
            fprintf(f, " (%d, %d)", peer_sample_pos[k][0], peer_sample_pos[k][1]);
        fprintf(f, peer_samples_standard() ? ", lesson 08's\n"
                   : ", not lesson 08's: its diff ref is against the exact rule at its own samples, "
                     "and lesson 08's rows are not compared with it (-)\n");
    }
    for (int i = 0; i < NSCENES; i++) {
        const struct scene *s = &sc[i].s;
        fprintf(f, "\n## %s: %d x %d, %d triangles, %llu covered pixels (%.1f x the screen)\n\n",
                sc[i].name, s->w, s->h, s->ntris, (unsigned long long)sc[i].pixels,
                (double)sc[i].pixels / ((double)s->w * s->h));
        fprintf(f, "%s\n\n", sc[i].what);
        fprintf(f, "| program | variant | median ms | spread | Mtri/s | Mpix/s | x L02 | %% mem "
                   "| diff ref | diff llvmpipe |\n");
        fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (int k = 0; k < nrows; k++) {
            const struct row *r = &rows[k];
            struct cells c;
            row_cells(sc, i, r, limit, &c);
            fprintf(f, "| %s | %s%s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r->program,
                    r->variant, r->exhibit ? " (exhibit)" : "", c.median, c.spread, c.mtri, c.mpix,
                    c.ratio, c.mem, c.dref, c.dpeer);
        }
    }
    write_journey(f, sc);
    bench_textured_markdown(f);
    if (ntargets > 0) {
        fprintf(f, "\n## Targets\n\n| target | measured | goal | |\n| --- | ---: | ---: | --- |\n");
        for (int k = 0; k < ntargets; k++) {
            const struct target_line *t = &targets[k];
            if (!t->measured) {
                fprintf(f, "| %s | not measured | %s%.2f%s | |\n", t->what, t->under ? "under " : "",
                        t->goal, t->unit);
                continue;
            }
            fprintf(f, "| %s | %.2f%s | %s%.2f%s | %s |\n", t->what, t->got, t->unit,
                    t->under ? "under " : "", t->goal, t->unit, t->met ? "met" : "MISSED");
        }
    }
    fprintf(f, "\n## Limits and the explorer\n\n");
    fprintf(f, "- memory limit (one read-modify-write pass over colour + depth, one core): "
               "%.1f Mpix/s; the %% mem column is a share of it\n", limit);
    char line[2400];
    if (limits_line(sc, limit, line, sizeof line, true))
        fprintf(f, "%s", line);
    bench_textured_cycles(f, true, cycles_what);
    if (frame_ms > 0)
        fprintf(f, "- explorer frame (1280 x 800, 64 x 48 grid, numbers shown): %.2f ms\n",
                frame_ms);
    if (front.t.runs > 0)
        fprintf(f, "- 3-D front end (lesson 06: look-at, near and far clipping, projection, guard "
                   "band, fan, cull), a %d-triangle torus seen from inside its tube: %.2f Mtri/s "
                   "(median %.1f ms, spread %.0f%%; %d cut by near or far, %d wholly outside them, "
                   "%d past the guard band; %d screen triangles out)\n", front.in,
                front.in / front.t.median * 1e-6, front.t.median * 1e3,
                100 * (front.t.hi - front.t.lo) / front.t.median, front.depth_clipped,
                front.culled_whole, front.guard_clipped, front.out);
    if (figures_s > 0)
        fprintf(f, "- `make figures`: %.1f s\n", figures_s);
    if (nbig > 0) {
        fprintf(f, "\n## A scene of %d triangles in the explorer\n\n", big[0].ntris);
        fprintf(f, "| program | load | first frame | (CPU) | all steps counted | steps | jump, median "
                   "| jump, worst | End | back, worst | worst step (CPU) | peak RSS |\n"
                   "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for (int i = 0; i < nbig; i++) {
            const struct big_result *b = &big[i];
            if (b->ok)
                fprintf(f, "| %s | %.2f s | %.2f s | %.2f s | %.1f s | %llu | %.0f ms | %.0f ms "
                           "| %.0f ms | %.0f ms | %.0f ms | %.0f MiB |\n", b->program, b->load_s,
                        b->first_frame_s, b->first_frame_cpu_s, b->counted_s,
                        (unsigned long long)b->steps, 1e3 * b->step_median_s,
                        1e3 * b->step_worst_s, 1e3 * b->end_s, 1e3 * b->back_worst_s,
                        1e3 * b->step_worst_cpu_s, b->peak_rss_mib);
        }
        fprintf(f, "\nFirst frame: reading the scene, opening the explorer, one paint; the "
                   "window counts the steps after it, between events. Wall-clock times, with "
                   "CPU times beside them where a shared machine stretches the wall clock.\n");
    }
    fprintf(f, "\nMpix/s counts covered pixels, overdraw included; x L02 is the speed-up over "
               "lesson 02 (a median's ratio); diff = pixels whose coverage count differs from "
               "the exact reference and from llvmpipe (- when not measured).\n");
    bool ok = fclose(f) == 0 && rename(tmp, path) == 0;
    if (!ok)
        remove(tmp);
    return ok;
}

static bool write_chart(const char *dir, const struct bench_scene *sc, double limit,
                        const char *title)
{
    static struct chart_panel panels[NSCENES];
    for (int i = 0; i < NSCENES; i++) {
        struct chart_panel *p = &panels[i];
        bool pixels = i == SCENE_LARGE;
        p->title = sc[i].name;
        p->unit = pixels ? "Mpixels/s" : "Mtriangles/s";
        p->nbars = 0;
        p->limit = pixels ? limit : 0;
        p->limit_label = "memory limit";
        for (int k = 0; k < nrows && p->nbars < 48; k++) {
            static char labels[NSCENES][MAX_ROWS][64];
            const struct row *r = &rows[k];
            if (r->exhibit)
                continue;
            snprintf(labels[i][k], sizeof labels[i][k], "%.2s %s", r->program, r->variant);
            if (r->peer)
                snprintf(labels[i][k], sizeof labels[i][k], "llvmpipe %s", r->variant);
            p->bars[p->nbars++] = (struct chart_bar){
                labels[i][k], pixels ? mpix(&sc[i], &r->t[i]) : mtri(&sc[i], &r->t[i]), r->peer,
            };
        }
    }
    char svg[1024], png[1024], err[256];
    snprintf(svg, sizeof svg, "%s/bench.svg", dir);
    snprintf(png, sizeof png, "%s/bench.png", dir);
    if (!chart_write(panels, NSCENES, title, svg, png, err, sizeof err)) {
        fprintf(stderr, "tristep-bench: chart: %s\n", err);
        return false;
    }
    return true;
}

/* One target line: measured value against the goal, met or missed by how
 * much (under: the value must stay under the goal). */
static void print_target(const char *id, const char *what, double got, double goal,
                         const char *unit, bool under)
{
    struct target_line *t = ntargets < 40 ? &targets[ntargets++] : &targets[39];
    snprintf(t->id, sizeof t->id, "%s", id);
    snprintf(t->what, sizeof t->what, "%s", what);
    snprintf(t->unit, sizeof t->unit, "%s", unit);
    t->got = got, t->goal = goal, t->under = under, t->measured = got > 0;
    if (got <= 0) {
        printf("  %-60s not measured\n", what);
        return;
    }
    t->met = under ? got <= goal : got >= goal;
    double by = under ? (t->met ? 1 - got / goal : got / goal - 1)
                      : (t->met ? got / goal - 1 : 1 - got / goal);
    printf("  %-60s %7.2f%s (goal %s%.2f%s)  %s by %.0f%%\n", what, got, unit,
           under ? "under " : "", goal, unit, t->met ? "met" : "MISSED", 100 * by);
}

/* Ratio of medians b / a on scene i (a faster: > 1), 0 when a row is missing. */
static double speedup(const struct row *fast, const struct row *slow, int i)
{
    return fast && slow ? slow->t[i].median / fast->t[i].median : 0;
}

static void print_targets(const struct bench_scene *sc, double limit, double cache_limit)
{
    const struct row *l07 = find_row("07-", "tiles"), *l07_1 = find_row("07-", "1-thread");
    const struct row *lp1 = find_row("llvmpipe", "1 thread");
    const struct row *lpn = find_row("llvmpipe", "default threads");
    const struct row *l05 = find_row("05-", NULL), *l02 = find_row("02-", NULL);
    static const char *const scene_id[NSCENES] = { "large", "small", "mixed" };
    static const char *const unit[NSCENES] = { "Mpix/s", "Mtri/s", "Mtri/s" };
    static const double goal[NSCENES] = { TARGET_L07_LARGE_X, TARGET_L07_SMALL_X, TARGET_L07_MIXED_X };
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    char what[160], id[64];

    printf("\ntargets (medians of the same run; lesson 07 = 07-tiles on %ld threads, one per "
           "core; llvmpipe with its default threads):\n", cores);
    for (int i = 0; i < NSCENES; i++) {
        snprintf(what, sizeof what, "lesson 07 vs llvmpipe on %s (%s)", scene_id[i], unit[i]);
        snprintf(id, sizeof id, "l07-vs-llvmpipe-%s", scene_id[i]);
        print_target(id, what, speedup(l07, lpn, i), goal[i], "x", false);
    }
    for (int i = 0; i < NSCENES; i++) {
        snprintf(what, sizeof what, "lesson 07, 1 thread vs llvmpipe, 1 thread, on %s", scene_id[i]);
        snprintf(id, sizeof id, "l07-1-thread-vs-llvmpipe-1-thread-%s", scene_id[i]);
        print_target(id, what, speedup(l07_1, lp1, i), TARGET_L07_ONE_X, "x", false);
    }
    for (int i = 0; i < NSCENES; i++) {
        snprintf(what, sizeof what, "lesson 07 from 1 to %ld threads on %s", cores, scene_id[i]);
        snprintf(id, sizeof id, "l07-1-to-%ld-threads-%s", cores, scene_id[i]);
        print_target(id, what, speedup(l07, l07_1, i),
                     i == SCENE_SMALL ? TARGET_L07_SCALE_SMALL_X : TARGET_L07_SCALE_X, "x", false);
    }
    for (int i = 0; i < NSCENES; i++) {     /* one core kept busy by another process */
        const struct bench_timing *all = &loaded[LOADED_L07][i], *one = &loaded[LOADED_L07_1][i];
        snprintf(what, sizeof what, "one core busy: lesson 07, %ld threads vs 1, on %s", cores,
                 scene_id[i]);
        snprintf(id, sizeof id, "l07-loaded-%s", scene_id[i]);
        print_target(id, what, all->runs && one->runs ? one->median / all->median : 0,
                     TARGET_L07_LOADED_X, "x", false);
        const struct bench_timing *lp = &loaded[LOADED_LP][i], *lp1 = &loaded[LOADED_LP_1][i];
        if (lp->runs && lp1->runs)
            printf("  %-60s %6.2fx\n", "  ... llvmpipe there, default threads vs 1", lp1->median / lp->median);
    }
    /* lesson 08's tiles against llvmpipe, both at 4 samples */
    const struct row *l08 = find_row("08-", "tiles 4 samples"), *l08_1 = find_row("08-", "tiles 1 thread 4 samples");
    const struct row *lp4 = find_row("llvmpipe", "default 4 samples");
    const struct row *lp4_1 = find_row("llvmpipe", "1 thread 4 samples");
    for (int each = 0; each < 2 && (l08 || l08_1); each++)
        for (int i = 0; i < NSCENES; i++) {
            snprintf(what, sizeof what, "lesson 08 tiled 4x MSAA vs llvmpipe 4x MSAA, %s, on %s",
                     each ? "all cores each" : "one thread each", scene_id[i]);
            snprintf(id, sizeof id, "l08-tiles-vs-llvmpipe-msaa4-%s-%s", each ? "all" : "1-thread",
                     scene_id[i]);
            print_target(id, what, each ? speedup(l08, lp4, i) : speedup(l08_1, lp4_1, i),
                         TARGET_L08_MSAA_X, "x", false);
        }
    double rate = l07 ? mpix(&sc[SCENE_LARGE], &l07->t[SCENE_LARGE]) : 0;
    print_target("l07-large-vs-memory-limit", "lesson 07 on large, times the memory limit",
                 limit > 0 ? rate / limit : 0, TARGET_L07_MEMORY_X, "x", false);
    if (rate > 0 && cache_limit > 0)
        printf("  %-60s %6.0f%%  (%.0f of %.0f Mpix/s)\n",
               "  ... that is of the cache-resident limit (one 64 x 64 tile)",
               100 * rate / cache_limit, rate, cache_limit);

    printf("\nlesson 05 against lesson 02, the paper's figures (Mileff, Nehez, Dudra 2015):\n");
    print_target("l05-vs-l02-large", "lesson 05 vs lesson 02 on large (paper's best: 9.72x)",
                 speedup(l05, l02, SCENE_LARGE), PAPER_L05_LARGE_X, "x", false);
    print_target("l05-vs-l02-tiny", "lesson 05 vs lesson 02 on small, tiny triangles (paper: 0.85x)",
                 speedup(l05, l02, SCENE_SMALL), PAPER_L05_TINY_X, "x", false);
    print_target("explorer-frame-ms", "explorer frame, 1280 x 800, 64 x 48 grid, numbers", frame_ms,
                 TARGET_FRAME_MS, " ms", true);
    double first = 0, rss = 0, step = 0;
    for (int i = 0; i < nbig; i++)
        if (big[i].ok) {
            first = fmax(first, big[i].first_frame_s);
            rss = fmax(rss, big[i].peak_rss_mib);
            step = fmax(step, 1e3 * fmax(big[i].step_worst_s, fmax(big[i].end_s, big[i].back_worst_s)));
        }
    print_target("big-first-frame-s", "large scene: first frame, slowest lesson", first,
                 TARGET_BIG_FIRST_S, " s", true);
    print_target("big-peak-rss-mib", "large scene: peak memory, largest lesson", rss,
                 TARGET_BIG_RSS_MIB, " MiB", true);
    print_target("big-slowest-step-ms", "large scene: slowest step (jump, End, back)", step,
                 TARGET_BIG_STEP_MS, " ms", true);
    printf("\ntexture mapping against llvmpipe, trilinear, one thread each and all cores each:\n");
    for (int all = 0; all < 2; all++)
        for (int i = 0; i < 3; i++) {
            const char *lesson, *variant;
            double x = bench_textured_speedup(i, all, &lesson, &variant);
            snprintf(what, sizeof what, "lesson %.2s vs llvmpipe, %s, textured (trilinear), on %s",
                     lesson, all ? "all cores each" : "1 thread", bench_textured_scene(i));
            snprintf(id, sizeof id, "l%.2s-vs-llvmpipe-%s-textured-%s", lesson, all ? "all" : "1-thread",
                     bench_textured_scene(i));
            print_target(id, what, x, TARGET_L09_LP_X, "x", false);
            if (x > 0)
                printf("  %-60s %s %s\n", "  ... the lesson's fastest exact variant:", lesson, variant);
        }
    bench_textured_cycles(stdout, false, cycles_what);
    /* the fastest exact variant of every lesson on each scene, for the record */
    for (int i = 0; i < NSCENES && lp1; i++) {
        const struct row *best = NULL;
        for (int k = 0; k < nrows; k++)
            if (!rows[k].peer && !rows[k].exhibit
                && (!best || rows[k].t[i].median < best->t[i].median))
                best = &rows[k];
        if (best)
            printf("  fastest on %-6s: %s %-12s %.2fx llvmpipe 1 thread\n", sc[i].name,
                   best->program, best->variant, lp1->t[i].median / best->t[i].median);
    }
}

/* --- main ------------------------------------------------------------------- */

/* Lesson 07 and llvmpipe on every core and on one, again, while a child
 * process keeps one core busy: a worker that waits for another one the
 * system has put aside loses more than the second core gives. */
static void measure_loaded(const struct bench_scene *sc, struct target *fb[NSCENES], int runs,
                           bool peer, int lp_one, int lp_all)
{
    struct row *all = NULL, *one = NULL;
    for (int k = 0; k < nrows; k++) {
        if (rows[k].peer || strncmp(rows[k].program, "07-", 3) != 0)
            continue;
        all = strcmp(rows[k].variant, "tiles") == 0 ? &rows[k] : all;
        one = strcmp(rows[k].variant, "1-thread") == 0 ? &rows[k] : one;
    }
    if (!all || !one)
        return;
    fflush(stdout);
    pid_t child = fork();
    if (child == 0)
        for (volatile unsigned long spin = 0;; spin++)
            ;
    if (child < 0)
        return;
    struct row *mine[2] = { all, one };
    struct bench_timing scratch[NSCENES];
    for (int r = 0; r < runs; r++) {
        fprintf(stderr, "one core busy: round %d of %d...\n", r + 1, runs);
        for (int m = 0; m < 2; m++)
            for (int i = 0; i < NSCENES; i++) {
                struct bench_timing keep = mine[m]->t[i];
                time_once(mine[m], i, &sc[i].s, fb[i], r);
                loaded[m ? LOADED_L07_1 : LOADED_L07][i].t[r] = mine[m]->t[i].t[r];
                loaded[m ? LOADED_L07_1 : LOADED_L07][i].runs = r + 1;
                mine[m]->t[i] = keep;
            }
        for (int c = 0; peer && c < 2; c++) {
            uint8_t *cov[NSCENES];
            for (int i = 0; i < NSCENES; i++)
                cov[i] = fb[i]->count;
            char why[256];
            if (!peer_run(sc, NSCENES, c ? lp_all : lp_one, 1, 1, 1, scratch, cov, NULL, why, sizeof why))
                continue;
            for (int i = 0; i < NSCENES; i++) {
                loaded[c ? LOADED_LP : LOADED_LP_1][i].t[r] = scratch[i].t[0];
                loaded[c ? LOADED_LP : LOADED_LP_1][i].runs = r + 1;
            }
        }
    }
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    for (int k = 0; k < LOADED_ROWS; k++)
        for (int i = 0; i < NSCENES; i++)
            if (loaded[k][i].runs == runs)
                bench_timing_stats(&loaded[k][i]);
            else
                loaded[k][i].runs = 0;
}

static int usage(FILE *f, int status)
{
    fprintf(f,
        "usage: tristep-bench [--quick] [--runs N] [--seed N] [--out DIR] [--markdown F]\n"
        "                     [--lesson NN [--variant NAME]]\n"
        "                     [--exhibits] [--no-llvmpipe] [--no-large-scene] [--figures-cmd CMD]\n"
        "Times every lesson's fast build on three seeded 1920x1080 scenes beside\n"
        "Mesa's llvmpipe and the memory limit, and the texture-mapping lessons on\n"
        "three textured scenes beside llvmpipe; checks coverage on every scene.\n"
        "  --quick        tiny scenes, 3 runs (what `make test` runs)\n"
        "  --runs N       timed runs after one warm-up (default 7, at least 5)\n"
        "  --out DIR      write DIR/bench.csv, bench.svg, bench.png (default build)\n"
        "  --markdown F   write the table as markdown to F (default DIR/bench.md)\n"
        "  --lesson NN    only lessons whose id starts with NN\n"
        "  --variant NAME only that variant of them\n"
        "  --exhibits     also run the exhibits (their coverage is expected to differ)\n"
        "  --figures-cmd  the command that runs `make figures`, timed\n"
        "  --no-large-scene  skip the 2,000,000-triangle scene in the explorer\n"
        "Exit status: 0 all exact, 1 a coverage difference or a failure, 2 bad usage.\n");
    return status;
}

static bool parse(struct options *o, int argc, char **argv)
{
    *o = (struct options){ .peer = true, .runs = 0, .seed = 2024, .out = "build" };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (strcmp(a, "--quick") == 0) {
            o->quick = true;
        } else if (strcmp(a, "--exhibits") == 0) {
            o->exhibits = true;
        } else if (strcmp(a, "--no-llvmpipe") == 0) {
            o->peer = false;
        } else if (strcmp(a, "--no-large-scene") == 0) {
            o->no_big = true;
        } else if (val && strcmp(a, "--runs") == 0) {
            errno = 0;
            long n = strtol(val, &end, 10);
            if (errno || *end || n < 1 || n > BENCH_MAX_RUNS)
                return false;
            o->runs = (int)n;
            i++;
        } else if (val && strcmp(a, "--seed") == 0) {
            errno = 0;
            o->seed = strtoull(val, &end, 10);
            if (errno || *end || !*val)
                return false;
            i++;
        } else if (val && strcmp(a, "--out") == 0) {
            o->out = argv[++i];
        } else if (val && strcmp(a, "--markdown") == 0) {
            o->markdown = argv[++i];
        } else if (val && strcmp(a, "--lesson") == 0) {
            o->only = argv[++i];
        } else if (val && strcmp(a, "--variant") == 0) {
            o->only_variant = argv[++i];
        } else if (val && strcmp(a, "--figures-cmd") == 0) {
            o->figures_cmd = argv[++i];
        } else {
            return false;
        }
    }
    if (!o->runs)
        o->runs = o->quick ? 3 : 7;
    return true;
}

int main(int argc, char **argv)
{
    struct options o;
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0)
            return usage(stdout, 0);
    if (!parse(&o, argc, argv))
        return usage(stderr, 2);
    /* the outputs' directory, made if missing: found unwritable only after
     * minutes of timing would throw the run away */
    if (mkdir(o.out, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "tristep-bench: --out %s: %s\n", o.out, strerror(errno));
        return 2;
    }
    if (access(o.out, W_OK) != 0) {
        fprintf(stderr, "tristep-bench: --out %s: %s\n", o.out, strerror(errno));
        return 2;
    }

    double start = now();
    char cpu[160], date[64];
    cpu_model(cpu, sizeof cpu);
    time_t tnow = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%d %H:%M %Z", localtime(&tnow));
    struct utsname un;
    uname(&un);
    printf("tristep bench%s, %s\nCPU: %s, %ld cores online, %s %s\nseed %llu, %d timed runs "
           "after 1 warm-up, single thread unless said\n",
           o.quick ? " (quick mode: tiny scenes, not a measurement)" : "", date, cpu,
           sysconf(_SC_NPROCESSORS_ONLN), un.sysname, un.release, (unsigned long long)o.seed,
           o.runs);

    static struct bench_scene sc[NSCENES];
    if (!bench_scenes_make(sc, o.seed, o.quick)) {
        fprintf(stderr, "tristep-bench: out of memory making the scenes\n");
        return 1;
    }

    /* The rows: llvmpipe on one thread and on its default threads, each at
     * one sample and at 4 (a multisampled framebuffer resolved by a blit,
     * beside lesson 08's 4 samples; only when lesson 08 runs), then every
     * lesson variant. */
    static const struct { int threads, samples; const char *name; } cfg[] = {
        { 0, 1, "1 thread" }, { -1, 1, "default threads" },
        { 0, PEER_SAMPLES, "1 thread 4 samples" }, { -1, PEER_SAMPLES, "default 4 samples" },
    };
    int npeers = 0;
    bool with_samples = !o.only || strncmp("08", o.only, strlen(o.only)) == 0;
    if (o.peer)
        for (int c = 0; c < (with_samples ? 4 : 2); c++)
            rows[nrows++] = (struct row){ .program = "llvmpipe", .variant = cfg[c].name, .peer = true,
                                          .samples = cfg[c].samples };
    else
        printf("llvmpipe: not run (--no-llvmpipe)\n");
    npeers = nrows;
    for (const struct lesson *const *l = all_lessons_fast; *l; l++) {
        if (o.only && strncmp((*l)->id, o.only, strlen(o.only)) != 0)
            continue;
        for (int v = 0; v < (*l)->nvariants && nrows < MAX_ROWS; v++) {
            const struct lesson_variant *var = &(*l)->variants[v];
            if ((variant_against_exact(var) && !o.exhibits) || (o.only_variant && strcmp(var->name, o.only_variant)))
                continue;
            rows[nrows++] = (struct row){ .program = (*l)->id, .variant = var->name,
                                          .exhibit = variant_against_exact(var), .lesson = *l, .var = var };
            /* a lesson with samples: its exact variants at 4 and 8 samples
             * too, each checked against its own reference */
            for (int n = 4; n <= 8 && lesson_param(*l, "samples", NULL) && !variant_against_exact(var)
                            && nrows < MAX_ROWS; n += 4) {
                static char names[MAX_ROWS][48];
                snprintf(names[nrows], sizeof names[nrows], "%s %d samples", var->name, n);
                rows[nrows] = (struct row){ .program = (*l)->id, .variant = names[nrows],
                                            .lesson = *l, .var = var, .samples = n };
                nrows++;
                /* a whole-scene variant with threads (lesson 08's tiles): on one
                 * thread too, beside llvmpipe's one thread at 4 samples */
                if (n == PEER_SAMPLES && lesson_param(*l, "threads", NULL) && lesson_scene_fn(*l, var)
                    && nrows < MAX_ROWS) {
                    snprintf(names[nrows], sizeof names[nrows], "%s 1 thread %d samples", var->name, n);
                    rows[nrows] = (struct row){ .program = (*l)->id, .variant = names[nrows],
                                                .lesson = *l, .var = var, .samples = n, .threads = 1 };
                    nrows++;
                }
            }
        }
    }

    if (nrows == MAX_ROWS) {
        fprintf(stderr, "tristep-bench: more than %d rows (programs, variants, sample counts): "
                "raise MAX_ROWS in tests/bench/bench.c\n", MAX_ROWS);
        return 2;
    }

    /* Interleaved, round after round: every row runs once per scene in each
     * round, so that a slow phase of the shared machine hits every program
     * alike. llvmpipe runs in a child process per round (it reads
     * its thread count once per process), with its own warm-up. */
    uint8_t *peer_cov[NSCENES] = { NULL }, *peer_cov4[NSCENES] = { NULL };
    bool have_peer = false;
    /* one target per scene and sample count that a row uses: fbs[i][0]
     * for one sample, fbs[i][n] for lesson 08's n samples */
    static struct target fbs[NSCENES][SAMPLES_MAX + 1];
    struct target *fb[NSCENES];
    for (int i = 0; i < NSCENES; i++) {
        peer_cov[i] = malloc((size_t)sc[i].s.w * (size_t)sc[i].s.h);
        peer_cov4[i] = malloc((size_t)sc[i].s.w * (size_t)sc[i].s.h);
        fb[i] = &fbs[i][0];
        if (!peer_cov[i] || !peer_cov4[i]
            || !target_init(fb[i], sc[i].s.w, sc[i].s.h, scene_background(&sc[i].s))) {
            fprintf(stderr, "tristep-bench: out of memory\n");
            return 1;
        }
        for (int k = npeers; k < nrows; k++) {
            int n = rows[k].samples > 1 ? rows[k].samples : 0;
            if (!fbs[i][n].color
                && (!target_init(&fbs[i][n], sc[i].s.w, sc[i].s.h, scene_background(&sc[i].s))
                    || !target_multisample(&fbs[i][n], n))) {
                fprintf(stderr, "tristep-bench: out of memory\n");
                return 1;
            }
        }
    }
    for (int k = npeers; k < nrows; k++) {
        rows[k].t[0].runs = rows[k].t[1].runs = rows[k].t[2].runs = o.runs;
        for (int i = 0; i < NSCENES; i++)
            time_once(&rows[k], i, &sc[i].s, row_target(fbs[i], &rows[k]), -1);
    }
    bool peer_ok[4] = { npeers > 0, npeers > 1, npeers > 2, npeers > 3 };
    for (int r = 0; r < o.runs; r++) {
        fprintf(stderr, "round %d of %d...\n", r + 1, o.runs);
        for (int c = 0; c < npeers; c++) {
            if (!peer_ok[c])
                continue;
            char why[256];
            struct bench_timing one[NSCENES];
            uint8_t *cov[NSCENES];
            for (int i = 0; i < NSCENES; i++)       /* fb's count: scratch after the first */
                cov[i] = r == 0 && c == 0 ? peer_cov[i] : r == 0 && c == 2 ? peer_cov4[i] : fb[i]->count;
            if (!peer_run(sc, NSCENES, cfg[c].threads, cfg[c].samples, 1, 1, one, cov, NULL, why, sizeof why)) {
                printf("llvmpipe (%s): not measured: %s\n", cfg[c].name, why);
                peer_ok[c] = false;
                continue;
            }
            for (int i = 0; i < NSCENES; i++) {
                rows[c].t[i].t[r] = one[i].t[0];
                rows[c].t[i].runs = r + 1;
                if (r == 0 && cfg[c].samples > 1) {    /* against the exact rule at its own samples */
                    size_t n = (size_t)sc[i].s.w * (size_t)sc[i].s.h;
                    const int (*at)[2] = (const int (*)[2])peer_sample_pos;
                    uint8_t *ref = sample_reference(&sc[i].s, cfg[c].samples, at);
                    rows[c].t[i].diff_ref = count_diff(cov[i], ref, n);
                    rows[c].t[i].diff_peer = c == 2 ? 0
                                           : peer_ok[2] ? count_diff(cov[i], peer_cov4[i], n) : -1;
                    free(ref);
                } else if (r == 0) {
                    size_t n = (size_t)sc[i].s.w * (size_t)sc[i].s.h;
                    rows[c].t[i].diff_ref = count_diff(cov[i], sc[i].coverage, n);
                    rows[c].t[i].diff_peer = c == 0 ? 0 : count_diff(cov[i], peer_cov[i], n);
                }
            }
        }
        for (int k = npeers; k < nrows; k++)
            for (int i = 0; i < NSCENES; i++)
                time_once(&rows[k], i, &sc[i].s, row_target(fbs[i], &rows[k]), r);
    }
    have_peer = peer_ok[0];
    /* a peer that failed leaves the table */
    int kept = 0;
    for (int k = 0; k < nrows; k++)
        if (!rows[k].peer || peer_ok[k])
            rows[kept++] = rows[k];
    nrows = kept;
    if (have_peer)
        printf("peer: %s\n", peer_renderer);
    if (npeers > 2 && peer_ok[2]) {
        printf("llvmpipe's %d samples (GL_SAMPLE_POSITION, in the scene's y-down 1/256 pixel):",
               PEER_SAMPLES);
        for (int k = 0; k < PEER_SAMPLES; k++)
            printf(" (%d, %d)", peer_sample_pos[k][0], peer_sample_pos[k][1]);
        printf(peer_samples_standard() ? ": lesson 08's, compared pixel by pixel\n"
               : ": not lesson 08's, so each is checked against the exact rule at its own samples\n");
    }
    for (int k = 0; k < nrows; k++) {
        for (int i = 0; i < NSCENES; i++) {
            bench_timing_stats(&rows[k].t[i]);
            if (!rows[k].peer)
                check_coverage(&rows[k], i, &sc[i], have_peer ? peer_cov : NULL,
                               npeers > 2 && peer_ok[2] ? peer_cov4 : NULL, row_target(fbs[i], &rows[k]));
        }
    }
    measure_loaded(sc, fb, o.runs, have_peer, cfg[0].threads, cfg[1].threads);
    for (int i = 0; i < NSCENES; i++)
        for (int n = 0; n <= SAMPLES_MAX; n++)
            target_free(&fbs[i][n]);
    const struct bench_tex_options to = { .runs = o.runs, .seed = o.seed, .quick = o.quick,
                                          .peer = o.peer, .exhibits = o.exhibits, .only = o.only,
                                          .only_variant = o.only_variant };
    if (!bench_textured_run(&to)) {
        fprintf(stderr, "tristep-bench: out of memory in the textured scenes\n");
        return 1;
    }

    double gbs = 0, dram_gbs = 0;
    size_t npix = (size_t)sc[0].s.w * (size_t)sc[0].s.h;
    double limit = bench_memory_limit(npix, 1, o.runs < 5 ? 5 : o.runs, &gbs);
    double dram = bench_memory_limit(o.quick ? npix : 8 * npix, 1, 3, &dram_gbs), dram2_gbs = 0;
    limit2 = bench_memory_limit(npix, 2, o.runs < 5 ? 5 : o.runs, &limit2_gbs);
    dram2 = bench_memory_limit(o.quick ? npix : 8 * npix, 2, 3, &dram2_gbs);
    dram1 = dram;
    if (!bench_cycles_source(cycles_what, sizeof cycles_what))
        cycles_what[0] = '\0';
    double cache_gbs = 0;
    double cache_limit = bench_cache_limit(npix, o.runs < 5 ? 5 : o.runs, &cache_gbs);
    print_table(sc, limit);
    bench_textured_print();
    char l3[32] = "?";
    FILE *cf = fopen("/sys/devices/system/cpu/cpu0/cache/index3/size", "r");
    if (cf && fgets(l3, sizeof l3, cf))
        l3[strcspn(l3, "\n")] = 0;
    if (cf)
        fclose(cf);
    printf("\nmemory limit: one read-modify-write pass over colour + depth, 8 bytes a pixel, "
           "one core:\n  same buffers (%d x %d, %.1f MB; L3 cache %s): %.1f Mpix/s (%.1f GB/s), "
           "the %% mem column\n  8 times larger buffers (beyond the caches): %.1f Mpix/s "
           "(%.1f GB/s)\n  one 64 x 64 tile over and over (cache-resident): %.1f Mpix/s (%.1f GB/s)\n",
           sc[0].s.w, sc[0].s.h, 8e-6 * (double)npix, l3, limit, gbs, dram, dram_gbs,
           cache_limit, cache_gbs);
    char line[2400];
    if (limits_line(sc, limit, line, sizeof line, false))
        printf("%s", line);

    frame_ms = explorer_frame(o.quick ? 5 : 60);
    if (frame_ms > 0)
        printf("\nexplorer frame (1280 x 800, 64 x 48 grid, numbers shown): %.2f ms\n", frame_ms);
    else
        printf("\nexplorer frame: could not be measured (out of memory)\n");
    if (!o.no_big) {
        char path[1100];
        snprintf(path, sizeof path, "%s/bench-large.scene", o.out);
        bench_big_scene(path, o.quick ? BIG_TRIS_QUICK : BIG_TRIS, o.only, big, MAX_BIG, &nbig);
        printf("  %-26s %7s %12s %8s %10s %10s %9s %9s %11s %9s %10s\n", "program", "load s",
               "first frame", "(cpu s)", "counted s", "steps", "jump med", "jump max",
               "End / back", "(cpu max)", "peak RSS");
        for (int i = 0; i < nbig; i++) {
            const struct big_result *b = &big[i];
            if (!b->ok) {
                printf("  %-26s not measured: %s\n", b->program, b->why);
                continue;
            }
            printf("  %-26s %7.2f %10.2f s %8.2f %10.1f %10llu %6.0f ms %6.0f ms %4.0f/%3.0f ms %6.0f ms %6.0f MiB\n",
                   b->program, b->load_s, b->first_frame_s, b->first_frame_cpu_s, b->counted_s,
                   (unsigned long long)b->steps, 1e3 * b->step_median_s, 1e3 * b->step_worst_s,
                   1e3 * b->end_s, 1e3 * b->back_worst_s, 1e3 * b->step_worst_cpu_s, b->peak_rss_mib);
        }
        printf("  (first frame: load, explorer_init and one paint; counted: every step known, "
               "the window counts them between events)\n");
    }
    if (o.figures_cmd) {
        char note[512];
        double t = time_command(o.figures_cmd, note, sizeof note);
        if (t > 0) {
            figures_s = t;
            printf("make figures: %.1f s (%s)\n", t, note);
        } else {
            printf("make figures: %s\n", note);
        }
    }

    if (bench_front_run(&front, o.runs))
        printf("\n3-D front end (lesson 06), a %d-triangle torus seen from inside its tube at "
               "1920 x 1080:\n  %.2f Mtri/s through look-at, near/far clipping, projection, guard "
               "band, fan and cull\n  (median %.1f ms, min %.1f ms; %d cut by near or far, %d "
               "wholly outside them, %d past the guard band; %d screen triangles out)\n",
               front.in, front.in / front.t.median * 1e-6, front.t.median * 1e3, front.t.lo * 1e3,
               front.depth_clipped, front.culled_whole, front.guard_clipped, front.out);
    else
        printf("\n3-D front end: could not be measured (out of memory)\n");

    print_targets(sc, limit, cache_limit);

    /* verdict on exactness: every exact variant, every scene */
    int64_t bad = 0;
    for (int k = 0; k < nrows; k++)
        for (int i = 0; i < NSCENES; i++)
            if (!rows[k].exhibit)
                bad += rows[k].t[i].diff_ref + (rows[k].t[i].diff_peer > 0 ? rows[k].t[i].diff_peer : 0);
    bad += bench_textured_differences();
    printf("\ncoverage check: %s (%d programs x %d scenes and the textured scenes against the "
           "reference%s)\n", bad ? "DIFFERENCES FOUND" : "0 differing pixels", nrows, NSCENES,
           have_peer ? " and llvmpipe" : "; llvmpipe not available");

    char path[1024], title[320];
    snprintf(path, sizeof path, "%s/bench.csv", o.out);
    bool ok = write_csv(path, sc, limit, cpu, date);
    if (!ok)
        fprintf(stderr, "tristep-bench: cannot write %s: %s\n", path, strerror(errno));
    char md[1024], sys[160];
    snprintf(sys, sizeof sys, "%s %s", un.sysname, un.release);
    if (o.markdown)
        snprintf(md, sizeof md, "%s", o.markdown);
    else
        snprintf(md, sizeof md, "%s/bench.md", o.out);
    if (!write_markdown(md, sc, limit, cpu, date, sys, &o)) {
        fprintf(stderr, "tristep-bench: cannot write %s: %s\n", md, strerror(errno));
        ok = false;
    }
    snprintf(title, sizeof title, "tristep bench, %s, %s%s", cpu, date, o.quick ? " (quick)" : "");
    ok = write_chart(o.out, sc, limit, title) && ok;
    if (ok)
        printf("wrote %s/bench.csv, bench.svg, bench.png and %s; %.0f s in all\n", o.out, md,
               now() - start);
    else
        printf("not every output was written (see above); %.0f s in all\n", now() - start);

    for (int i = 0; i < NSCENES; i++) {
        free(peer_cov[i]);
        free(peer_cov4[i]);
    }
    bench_scenes_free(sc);
    return bad || !ok ? 1 : 0;
}
