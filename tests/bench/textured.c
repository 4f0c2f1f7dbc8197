/* textured.c - `make bench`'s textured scenes: every lesson that maps image
 * textures beside llvmpipe, both on one thread.
 *
 * What is timed: the lesson's fast build at its defaults (trilinear, the
 * default filter), tri_setup + rasterize of every triangle of the scene
 * with its image texture, the texel modulated by the vertex colour, into an
 * RGBA8 target with a float depth buffer; llvmpipe with LP_NUM_THREADS=0
 * drawing the same (peer.c says how). Interleaved round after round, one
 * warm-up each, medians.
 *
 * What is checked, untimed: coverage against the exact reference and
 * llvmpipe's (0 differing pixels for every exact variant); colour against
 * llvmpipe's, as agreement: of the pixels the reference covers, the share
 * within 2 and within 8 levels in every channel. Real samplers differ from
 * lessons/CONVENTIONS.md's rule by design (llvmpipe's quads take the derivatives at
 * GL's bottom-left pixel, its mip-maps round their own way, its log2 is
 * approximate), so agreement is reported, never asserted.
 */
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "lesson.h"

extern const struct lesson *const all_lessons_fast[];

#define NTEX 3
#define MAX_TEX_ROWS 24

struct tex_row {
    const char *program, *variant;
    char name[40];              /* the variant as the tables show it */
    bool peer, exhibit;
    int threads;                /* 1: one thread; 0: its default (llvmpipe's, or one per core) */
    const struct lesson *lesson;
    const struct lesson_variant *var;
    struct bench_timing t[NTEX];
    struct bench_agree agree[NTEX];     /* against llvmpipe; pixels 0: not compared */
};

static struct bench_scene sc[NTEX];
static bool made;
static struct tex_row rows[MAX_TEX_ROWS];
static int nrows;
static const char *peer_why;            /* why llvmpipe has no row, or NULL */
static char why_buf[256];

/* One timed (r >= 0) or warm-up run of a lesson row on scene i, the target
 * cleared outside the clock, coverage not counted. */
static struct raster_params row_params(const struct tex_row *row)
{
    struct raster_params p = lesson_params_default(row->lesson);
    int k;
    if (row->threads > 0 && lesson_param(row->lesson, "threads", &k))
        *lesson_param_slot(row->lesson, k, &p) = row->threads;
    return p;
}

static void time_once(struct tex_row *row, int i, struct target *fb, int r)
{
    struct raster_params p = row_params(row);
    target_clear(fb);
    struct target timed = *fb;
    timed.count = NULL;
    uint64_t c0 = bench_cycles();
    double t0 = bench_now();
    bench_draw(row->lesson, row->var, &sc[i].s, &p, &timed);
    double t1 = bench_now();
    uint64_t c1 = bench_cycles();
    if (r >= 0)
        row->t[i].t[r] = t1 - t0, row->t[i].cycles[r] = (double)(c1 - c0);
}

/* Does variant v of l run on threads (a scene-level twin with --threads)? */
static bool threaded(const struct lesson *l, const struct lesson_variant *v)
{
    int k;
    return lesson_scene_fn(l, v) && lesson_param(l, "threads", &k);
}

static void add_lesson_rows(const struct bench_tex_options *o)
{
    for (const struct lesson *const *l = all_lessons_fast; *l; l++) {
        if (!(*l)->texturing || (o->only && strncmp((*l)->id, o->only, strlen(o->only)) != 0))
            continue;
        for (int v = 0; v < (*l)->nvariants && nrows < MAX_TEX_ROWS; v++) {
            const struct lesson_variant *var = &(*l)->variants[v];
            if ((variant_against_exact(var) && !o->exhibits)
                || (o->only_variant && strcmp(var->name, o->only_variant) != 0))
                continue;
            /* a threaded variant twice: on one thread, and one worker per core */
            for (int one = threaded(*l, var); one >= 0 && nrows < MAX_TEX_ROWS; one--) {
                struct tex_row *row = &rows[nrows++];
                *row = (struct tex_row){ .program = (*l)->id, .variant = row->name,
                                         .exhibit = variant_against_exact(var), .threads = one,
                                         .lesson = *l, .var = var };
                snprintf(row->name, sizeof row->name, "%s%s", var->name, one ? " 1 thread" : "");
            }
        }
    }
}

bool bench_textured_run(const struct bench_tex_options *o)
{
    if (!bench_tex_scenes_make(sc, o->seed, o->quick))
        return false;
    made = true;
    int npeers = 0;
    if (o->peer) {
        rows[nrows++] = (struct tex_row){ .program = "llvmpipe", .variant = "1 thread", .peer = true,
                                          .threads = 1 };
        rows[nrows++] = (struct tex_row){ .program = "llvmpipe", .variant = "default threads",
                                          .peer = true };
        npeers = nrows;
    } else {
        peer_why = "not run (--no-llvmpipe)";
    }
    add_lesson_rows(o);

    static struct target fb[NTEX];
    uint8_t *peer_cov[NTEX], *scratch[NTEX];
    uint32_t *peer_col[NTEX];
    for (int i = 0; i < NTEX; i++) {
        size_t n = (size_t)sc[i].s.w * (size_t)sc[i].s.h;
        peer_cov[i] = malloc(n);
        scratch[i] = malloc(n);
        peer_col[i] = malloc(4 * n);
        if (!peer_cov[i] || !scratch[i] || !peer_col[i]
            || !target_init(&fb[i], sc[i].s.w, sc[i].s.h, scene_background(&sc[i].s)))
            return false;
    }
    for (int k = 0; k < nrows; k++)
        for (int i = 0; i < NTEX; i++) {
            rows[k].t[i].runs = o->runs;
            if (!rows[k].peer)
                time_once(&rows[k], i, &fb[i], -1);
        }
    bool peer_ok = o->peer;
    for (int r = 0; r < o->runs; r++) {
        fprintf(stderr, "textured: round %d of %d...\n", r + 1, o->runs);
        for (int c = 0; c < npeers && peer_ok; c++) {    /* LP_NUM_THREADS=0, then unset */
            struct bench_timing one[NTEX];
            bool first = r == 0 && c == 0;
            if (!peer_run(sc, NTEX, rows[c].threads ? 0 : -1, 1, 1, 1, one, first ? peer_cov : scratch,
                          first ? peer_col : NULL, why_buf, sizeof why_buf)) {
                peer_ok = false;
                peer_why = why_buf;
            }
            for (int i = 0; i < NTEX && peer_ok; i++)
                rows[c].t[i].t[r] = one[i].t[0];
        }
        for (int k = 0; k < nrows; k++)
            for (int i = 0; i < NTEX; i++)
                if (!rows[k].peer)
                    time_once(&rows[k], i, &fb[i], r);
    }
    if (o->peer && !peer_ok) {          /* llvmpipe leaves the table */
        memmove(rows, rows + npeers, (size_t)(nrows - npeers) * sizeof *rows);
        nrows -= npeers;
        for (int k = 0; k < nrows; k++)
            if (rows[k].name[0])        /* (its name moved with it) */
                rows[k].variant = rows[k].name;
    }
    for (int k = 0; k < nrows; k++)
        for (int i = 0; i < NTEX; i++) {
            struct tex_row *row = &rows[k];
            size_t n = (size_t)sc[i].s.w * (size_t)sc[i].s.h;
            bench_timing_stats(&row->t[i]);
            if (row->peer) {
                row->t[i].diff_ref = bench_count_diff(peer_cov[i], sc[i].coverage, n);
                row->t[i].diff_peer = 0;
                continue;
            }
            /* untimed: the same code once more, counting coverage */
            struct raster_params p = row_params(row);
            target_clear(&fb[i]);
            bench_draw(row->lesson, row->var, &sc[i].s, &p, &fb[i]);
            row->t[i].diff_ref = bench_count_diff(fb[i].count, sc[i].coverage, n);
            row->t[i].diff_peer = peer_ok ? bench_count_diff(fb[i].count, peer_cov[i], n) : -1;
            if (peer_ok)
                row->agree[i] = bench_agreement(fb[i].color, peer_col[i], sc[i].coverage, n);
        }
    for (int i = 0; i < NTEX; i++) {
        target_free(&fb[i]);
        free(peer_cov[i]);
        free(scratch[i]);
        free(peer_col[i]);
    }
    return true;
}

/* --- what it found ---------------------------------------------------------- */

static const struct tex_row *peer_row(void)
{
    return nrows > 0 && rows[0].peer ? &rows[0] : NULL;
}

static const struct tex_row *peer_row_all(void)
{
    return nrows > 1 && rows[1].peer ? &rows[1] : NULL;
}

const char *bench_textured_scene(int i)
{
    return made && i >= 0 && i < NTEX ? sc[i].name : "";
}

/* The last texture-mapping lesson's fastest exact row on scene i, on one
 * thread (all: false) or on one worker per core (all: true, a threaded
 * variant at its default). */
static const struct tex_row *fastest(int i, bool all)
{
    const struct tex_row *best = NULL;
    for (int k = 0; k < nrows; k++) {
        const struct tex_row *r = &rows[k];
        if (r->peer || r->exhibit || (r->threads == 0 && threaded(r->lesson, r->var)) != all)
            continue;
        if (!best || strcmp(r->program, best->program) > 0
            || (strcmp(r->program, best->program) == 0 && r->t[i].median < best->t[i].median))
            best = r;
    }
    return best;
}

double bench_textured_speedup(int i, bool all, const char **lesson, const char **variant)
{
    const struct tex_row *lp = all ? peer_row_all() : peer_row(), *best = fastest(i, all);
    *lesson = best ? best->program : "09-textures";     /* the target names it even when missing */
    *variant = best ? best->variant : "";
    return lp && best ? lp->t[i].median / best->t[i].median : 0;
}

/* Lesson 09's cost per covered pixel, counted: the narrated algorithm's
 * multiplications and additions (its counters: lesson 04's evaluation, the
 * texture unit's taps, the mix, the level of detail, the modulation) over
 * the scene, per covered pixel. Made once per scene. */
static double counted_ops(int i)
{
    static double ops[NTEX];
    extern const struct lesson *const all_lessons[];
    const struct lesson *l = NULL;
    for (const struct lesson *const *a = all_lessons; *a; a++)
        if ((*a)->texturing)
            l = *a;
    if (ops[i] > 0 || !l)
        return ops[i];
    struct target fb;
    if (!target_init(&fb, sc[i].s.w, sc[i].s.h, scene_background(&sc[i].s)))
        return 0;
    struct raster_params p = lesson_params_default(l);
    struct trace tr = { 0 };
    uint64_t total = 0;
    for (int k = 0; k < sc[i].s.ntris; k++) {
        struct tri_setup t;
        tri_setup(&t, sc[i].s.tris[k].v, sc[i].s.w, sc[i].s.h);
        const struct raster_params each = lesson_params_tri(&p, &sc[i].s, k);
        trace_begin(&tr, (uint32_t)k, TRACE_UNLIMITED);
        l->variants[0].rasterize(&t, &each, &fb, &tr);
        total += tr.c.mul + tr.c.add;
    }
    target_free(&fb);
    return ops[i] = (double)total / (double)sc[i].pixels;
}

void bench_textured_cycles(FILE *f, bool md, const char *cycles_what)
{
    for (int i = 0; i < NTEX && made && cycles_what[0]; i++) {
        const struct tex_row *one = fastest(i, false);
        if (!one || one->t[i].cycles_median <= 0)
            continue;
        double per_pixel = one->t[i].cycles_median / (double)sc[i].pixels, ops = counted_ops(i);
        fprintf(f, "%s%s %s on %s, one thread: %.1f cycles per covered pixel (%s); the "
                   "algorithm counts %.1f multiplications and additions per covered pixel "
                   "(helper pixels, texel taps, the mix and the level of detail included), "
                   "%.1f cycles at two 4-lane operations a cycle with nothing else: %.1fx that "
                   "bound\n", md ? "- " : "  ", one->program, one->variant, sc[i].name, per_pixel,
                cycles_what, ops, ops / 8, ops > 0 ? per_pixel / (ops / 8) : 0);
    }
}

int64_t bench_textured_differences(void)
{
    int64_t bad = 0;
    for (int k = 0; k < nrows; k++)
        for (int i = 0; i < NTEX && !rows[k].peer && !rows[k].exhibit; i++)
            bad += rows[k].t[i].diff_ref + (rows[k].t[i].diff_peer > 0 ? rows[k].t[i].diff_peer : 0);
    return bad;
}

/* The cells of row k on scene i, as the terminal and the markdown show them. */
struct tex_cells {
    char median[24], spread[16], mpix[16], ratio[16], dref[24], dpeer[24], w2[16], w8[16];
};

static void cells(int k, int i, struct tex_cells *c)
{
    const struct tex_row *r = &rows[k], *lp = peer_row();
    const struct bench_timing *t = &r->t[i];
    snprintf(c->median, sizeof c->median, "%.2f", t->median * 1e3);
    snprintf(c->spread, sizeof c->spread, "%.1f%%", 100 * (t->hi - t->lo) / t->median);
    snprintf(c->mpix, sizeof c->mpix, "%.1f", (double)sc[i].pixels / t->median * 1e-6);
    snprintf(c->ratio, sizeof c->ratio, "-");
    if (lp)
        snprintf(c->ratio, sizeof c->ratio, "%.2f", lp->t[i].median / t->median);
    snprintf(c->dref, sizeof c->dref, "%lld", (long long)t->diff_ref);
    snprintf(c->dpeer, sizeof c->dpeer, t->diff_peer < 0 ? "-" : "%lld", (long long)t->diff_peer);
    const struct bench_agree *g = &r->agree[i];
    snprintf(c->w2, sizeof c->w2, "-");
    snprintf(c->w8, sizeof c->w8, "-");
    if (g->pixels > 0) {
        snprintf(c->w2, sizeof c->w2, "%.2f%%", 100.0 * (double)g->within2 / (double)g->pixels);
        snprintf(c->w8, sizeof c->w8, "%.2f%%", 100.0 * (double)g->within8 / (double)g->pixels);
    }
}

static void scene_line(FILE *f, int i, const char *prefix)
{
    const struct scene *s = &sc[i].s;
    fprintf(f, "%s%s: %d x %d, %d triangles, %llu covered pixels (%.1f x the screen)", prefix,
            sc[i].name, s->w, s->h, s->ntris, (unsigned long long)sc[i].pixels,
            (double)sc[i].pixels / ((double)s->w * s->h));
}

void bench_textured_print(void)
{
    if (!made)
        return;
    printf("\ntextured scenes (trilinear, modulate), one thread unless said; x llvm: over llvmpipe's "
           "one thread; llvmpipe %s\n",
           peer_why ? peer_why : "with " PEER_EXACT_OPTIONS);
    for (int i = 0; i < NTEX; i++) {
        scene_line(stdout, i, "\nscene ");
        printf("; %s\n  %-22s %-14s %10s %7s %9s %7s %9s %9s %9s %9s\n", sc[i].what, "program",
               "variant", "median ms", "spread", "Mpix/s", "x llvm", "diff ref", "diff llvm",
               "within 2", "within 8");
        for (int k = 0; k < nrows; k++) {
            struct tex_cells c;
            cells(k, i, &c);
            printf("  %-22s %-14s %10s %7s %9s %7s %9s %9s %9s %9s%s\n", rows[k].program,
                   rows[k].variant, c.median, c.spread, c.mpix, c.ratio, c.dref, c.dpeer, c.w2,
                   c.w8, rows[k].exhibit ? "  (exhibit)" : "");
        }
    }
    printf("(within 2, within 8: of the covered pixels, the share whose colour is within that many "
           "levels of llvmpipe's in every channel)\n");
}

void bench_textured_markdown(FILE *f)
{
    if (!made)
        return;
    fprintf(f, "\n## Textured scenes: trilinear, modulate, beside llvmpipe\n\n");
    fprintf(f, "- work: every lesson that maps image textures, its fast build at its defaults "
               "(trilinear), `tri_setup` and rasterize of every triangle under its image texture, "
               "the filtered texel times the vertex colour, perspective-correct, into an RGBA8 "
               "target with a float depth buffer; one thread, and a variant on workers "
               "(lesson 07's tiles) also at its default, one worker per core\n");
    if (peer_why)
        fprintf(f, "- llvmpipe: %s\n", peer_why);
    else
        fprintf(f, "- llvmpipe, one thread (LP_NUM_THREADS=0) and its default threads: the same textures (GL_RGBA8), their "
                   "mip-maps from glGenerateMipmap, GL_LINEAR_MIPMAP_LINEAR and GL_LINEAR, GL_REPEAT "
                   "or GL_CLAMP_TO_EDGE as the scene says, the texel times the vertex colour in a "
                   "fragment shader, (s, t) and colour perspective-correct; its sampler's faster "
                   "approximations off: %s\n", PEER_EXACT_OPTIONS);
    fprintf(f, "- within 2, within 8: of the pixels the exact reference covers, the share whose "
               "colour is within 2 (8) levels of llvmpipe's in every channel; diff: pixels whose "
               "coverage count differs; x llvmpipe: llvmpipe's median on one thread over the row's "
               "(the Targets take the fastest exact variant of the last texture-mapping lesson, "
               "on one thread against llvmpipe's one, on every core against its default threads)\n");
    for (int i = 0; i < NTEX; i++) {
        scene_line(f, i, "\n### ");
        fprintf(f, "\n\n%s\n\n", sc[i].what);
        fprintf(f, "| program | variant | median ms | spread | Mpix/s | x llvmpipe | diff ref "
                   "| diff llvmpipe | within 2 | within 8 |\n");
        fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (int k = 0; k < nrows; k++) {
            struct tex_cells c;
            cells(k, i, &c);
            fprintf(f, "| %s | %s%s | %s | %s | %s | %s | %s | %s | %s | %s |\n", rows[k].program,
                    rows[k].variant, rows[k].exhibit ? " (exhibit)" : "", c.median, c.spread,
                    c.mpix, c.ratio, c.dref, c.dpeer, c.w2, c.w8);
        }
    }
}

void bench_textured_csv(FILE *f)
{
    if (!made)
        return;
    for (int i = 0; i < NTEX; i++)
        for (int k = 0; k < nrows; k++) {
            const struct tex_row *r = &rows[k];
            const struct bench_timing *t = &r->t[i];
            const struct bench_agree *g = &r->agree[i];
            double px = (double)g->pixels;
            fprintf(f, "%s,%d,%d,%d,%llu,%s,%s,%d,%d,%.6f,%.6f,%.6f,%.4f,%.2f,0,0,%lld,%lld,%.4f,%.4f\n",
                    sc[i].name, sc[i].s.w, sc[i].s.h, sc[i].s.ntris,
                    (unsigned long long)sc[i].pixels, r->program, r->variant, r->exhibit, t->runs,
                    t->median, t->lo, t->hi, sc[i].s.ntris / t->median * 1e-6,
                    (double)sc[i].pixels / t->median * 1e-6, (long long)t->diff_ref,
                    (long long)t->diff_peer, px > 0 ? 100 * (double)g->within2 / px : -1.0,
                    px > 0 ? 100 * (double)g->within8 / px : -1.0);
        }
}
