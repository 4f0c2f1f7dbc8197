/* check.c - make check: the lesson's checks on the student's code, simplest
 * first; at the first failure, a smallest counterexample and the command
 * that opens it in the explorer at the first wrong pixel.
 *
 * Every check draws scenes twice, with the exact rule (src/raster's
 * reference coverage and reference_shade) and with the code given to
 * exercise_use, one triangle at a time, and compares after each triangle:
 *
 *   coverage   how many times each pixel was written (target.count): a
 *              pixel written twice by one triangle is as wrong as one
 *              written by a triangle that does not cover it;
 *   colour     colour and depth pixel_close() to the exact ones (raster.h),
 *              on every pixel the exact rule covers;
 *   property   what the lesson is about: no multiplication between two
 *              pixels of a row (lesson 03); every tile and block narrated
 *              with exactly the class its four corner pixel centres give
 *              it, EMPTY, FULL or PARTIAL (lessons 05, 07); every quad's
 *              lambda log2(rho) of its derivatives (lesson 09).
 *
 * Lesson 07 adds a check of its own scenes, over many tiles (gen_tiles),
 * that compares all three at once; lesson 09 textured scenes (scenes9.c),
 * held to the lesson's own picture, whose sampler the student writes.
 *
 * A write outside the target fails any check, and so does a texel read
 * outside its level (lesson 09). */
#define _DEFAULT_SOURCE           /* fork, MAP_ANONYMOUS, strsignal */

#include "checker.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "exercise/gen.h"
#include "exercise/remote.h"
#include "exercise/scenes.h"

struct guard *check_guard;

/* One check: its name in the report, what it compares, its scenes; and
 * for lesson 06's clipper, whether every polygon is clipped walked both
 * ways (the shared edges' promise). */
struct check {
    const char *name;
    enum check_kind kind;
    scene_gen gen;
    bool both_ways;
    search_gen search;          /* its search after the fixed scenes, or NULL */
    const char *trusts;         /* what it takes on trust, said with its verdict, or NULL */
};

/* What the search aims at in lesson l. */
static struct search_for search_for(const struct lesson *l)
{
    return (struct search_for){ .tiles = l->exercise.tiles, .samples = l->exercise.samples != NULL,
                                .perspective = l->perspective };
}

/* The seed of search scene k of the check called name: the run's seed,
 * the check and k, mixed (the same scene on every run with that seed). */
static uint64_t scene_seed(uint64_t seed, const char *name, int k)
{
    uint64_t h = 1469598103934665603u;      /* FNV-1a of the name */
    for (const char *c = name; *c; c++)
        h = (h ^ (uint8_t)*c) * 1099511628211u;
    struct rng r = { seed ^ h };
    r.s += (uint64_t)k * 0x632be59bd9b4e019u;
    return rng_next(&r);
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void progress(const struct check_options *o, int n, int i, const char *name, int done, int total)
{
    if (!o->progress)
        return;
    fprintf(o->out, "\r  %d/%d %-31s %3d%%", i + 1, n, name, total ? 100 * done / total : 0);
    fflush(o->out);
}

/* A name of lower-case letters, digits and single dashes: "Fill-rule
 * ties" -> "fill-rule-ties", "../mine/a.c" -> "mine-a". */
static void slugify(char *slug, size_t n, const char *name)
{
    size_t k = 0;
    for (const char *p = name; *p && k + 1 < n; p++) {
        char c = *p >= 'A' && *p <= 'Z' ? (char)(*p - 'A' + 'a') : *p;
        bool keep = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (keep || (k > 0 && slug[k - 1] != '-'))
            slug[k++] = keep ? c : '-';
    }
    while (k > 0 && slug[k - 1] == '-')
        k--;
    slug[k] = '\0';
}

/* Where the counterexamples of the checked file go, created: a folder of
 * its own under out_dir, named after the file (its path without ".c"), so
 * that checking another file never overwrites them. */
static bool counterexample_dir(const struct check_options *o, char *dir, size_t n)
{
    char file[256], slug[200];
    snprintf(file, sizeof file, "%s", o->file ? o->file : "exercise.c");
    size_t len = strlen(file);
    if (len > 2 && strcmp(file + len - 2, ".c") == 0)
        file[len - 2] = '\0';
    slugify(slug, sizeof slug, file);
    snprintf(dir, n, "%s/%s", o->out_dir, slug[0] ? slug : "file");
    return make_dirs(dir);
}

/* A failing scene: shrink it, write it, say everything. */
static bool report_failure(struct checker *C, const char *name, struct scene *s, const char *what,
                           struct check_result *r)
{
    const struct check_options *o = C->o;
    FILE *out = o->out;
    struct verdict v;
    evaluate(C, s, &v);
    fprintf(out, "FAILED\n      on %s\n", what);
    say_verdict(C, out, &v, s);

    /* a scene drawn for too long is shown as it is: each smaller one
     * tried could take as long */
    if (!(v.what == WRONG_RUNNER && v.runner.what == RUNNER_TIMEOUT)) {
        shrink(C, s);
        evaluate(C, s, &v);
    }
    r->x = v.x, r->y = v.y;
    int ntris = s->world.camera_line ? s->world.ntris : s->ntris;
    r->ntris = ntris;
    struct trail f;
    r->step = step_of(C, s, &v, &f);
    if (!r->failed[0])      /* the first failure (every check runs when grading) */
        snprintf(r->failed, sizeof r->failed, "%s", name);

    char slug[64];
    slugify(slug, sizeof slug, name);
    char dir[400];
    if (!counterexample_dir(o, dir, sizeof dir)) {
        fprintf(out, "  cannot create %s: %s\n", dir, strerror(errno));
        return false;
    }
    snprintf(r->counterexample, sizeof r->counterexample, "%s/%.2s-%s.scene", dir, C->l->id, slug);
    char err[600];
    if (!write_counterexample(r->counterexample, s, name, C->l, o->file, &v, err, sizeof err)) {
        fprintf(out, "  %s\n", err);
        r->counterexample[0] = '\0';
        return false;
    }
    fprintf(out, "\n  smallest counterexample: %d %striangle%s, written to %s\n", ntris,
            s->world.camera_line ? "world " : "", ntris == 1 ? "" : "s", r->counterexample);
    say_verdict(C, out, &v, s);
    explain(C, out, &v, s, &f);
    char samples[32] = "";
    if (C->p.samples > 1)
        snprintf(samples, sizeof samples, " SAMPLES=%d", C->p.samples);
    if (r->step == 0)     /* nothing to step through: no STEP= that opens an empty step */
        fprintf(out, "\n  your code %s, so the explorer has no step to show; opened, it marks\n"
                "  the pixels the exact rule covers and your code does not (cyan: missing):\n      %s%s SCENE=%s\n",
                v.world ? "made no screen triangle of it" : "narrated and wrote nothing for it",
                o->open_cmd, samples, r->counterexample);
    else
        fprintf(out, "\n  open it in the explorer at the %s (step %llu):\n      %s%s SCENE=%s STEP=%llu\n",
                v.what == WRONG_CLIP ? "end of the run" : v.world ? "end, where the diff view marks the wrong pixels"
                : v.what == WRONG_LOD ? "quad's level of detail" : "first wrong pixel",
                (unsigned long long)r->step, o->open_cmd, samples, r->counterexample, (unsigned long long)r->step);
    return true;
}

/* Run one check over all of its scenes. */
static bool run_check(struct checker *C, int i, int n, const struct check *ck, struct check_result *r)
{
    FILE *out = C->o->out;
    fprintf(out, "  %d/%d %-31s ", i + 1, n, ck->name);
    fflush(out);
    C->kind = ck->kind;
    C->both_ways = ck->both_ways;
    uint64_t tris0 = C->triangles;
    int total = 0;
    char what[200];
    struct scene s;
    while (ck->gen(total, &s, what, sizeof what)) {
        scene_free(&s);
        total++;
    }
    for (int k = 0; k < total; k++) {
        if (k % 64 == 0)
            progress(C->o, n, i, ck->name, k, total);
        ck->gen(k, &s, what, sizeof what);
        /* many random scenes of one triangle: each at one sample count in
         * turn, not at every one (the hand-made scenes take them all) */
        C->only_count = 0;
        int ncounts = 0;
        for (const int *c = C->l->exercise.samples; c && *c; c++)
            ncounts++;
        if (ck->gen == gen_random && ncounts > 1)
            C->only_count = C->l->exercise.samples[k % ncounts];
        if (check_guard) {
            check_guard->check = i;
            check_guard->scene = k;
            alarm(SCENE_SECONDS);
        }
        struct verdict v;
        bool passed = evaluate(C, &s, &v);
        if (check_guard)
            alarm(0);
        if (!passed) {
            if (C->o->progress)
                fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
            report_failure(C, ck->name, &s, what, r);
            scene_free(&s);
            return false;
        }
        scene_free(&s);
    }
    int searched = 0, ncounts = 0;
    for (const int *c = C->l->exercise.samples; c && *c; c++)
        ncounts++;
    const struct check_options *o = C->o;
    struct search_for aim = search_for(C->l);
    double end = now() + C->search_share;
    /* The first SEARCH_FLOOR scenes whatever the clock says, so that a
     * verdict does not hang on how busy the machine is; then on while the
     * check's share of the time lasts. */
    while (ck->search && (o->search_seconds > 0 || o->search_scenes > 0)
           && (o->search_scenes <= 0 || searched < o->search_scenes)
           && (o->search_seconds <= 0 || searched < SEARCH_FLOOR || now() < end)) {
        uint64_t seed = scene_seed(o->seed, ck->name, searched);
        ck->search(&aim, seed, &s, what, sizeof what);
        size_t len = strlen(what);
        snprintf(what + len, sizeof what - len, " (search scene %d, seed %llu)", searched + 1,
                 (unsigned long long)o->seed);
        /* each at one sample count in turn, as the random scenes */
        C->only_count = ncounts > 1 ? C->l->exercise.samples[searched % ncounts] : 0;
        if (check_guard) {
            check_guard->check = i;
            check_guard->scene = total + searched;
            check_guard->searching = true;
            check_guard->search_seed = seed;
            alarm(SCENE_SECONDS);
        }
        struct verdict v;
        bool passed = evaluate(C, &s, &v);
        if (check_guard) {
            alarm(0);
            check_guard->searching = false;
        }
        searched++;
        r->searched++;
        if (!passed) {
            if (C->o->progress)
                fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
            r->found_by_search = true;
            report_failure(C, ck->name, &s, what, r);
            fprintf(out, "\n  found by the search (scene %d after the check's %d fixed ones, seed %llu): the\n"
                    "  counterexample file shows it again; make check SEED=%llu searches the same scenes\n",
                    searched, total, (unsigned long long)o->seed, (unsigned long long)o->seed);
            scene_free(&s);
            return false;
        }
        scene_free(&s);
    }
    if (C->o->progress)
        fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
    if (searched)
        fprintf(out, "ok (%d scene%s and %d searched, %llu triangles)\n", total, total == 1 ? "" : "s", searched,
                (unsigned long long)(C->triangles - tris0));
    else
        fprintf(out, "ok (%d scene%s, %llu triangles)\n", total, total == 1 ? "" : "s",
                (unsigned long long)(C->triangles - tris0));
    if (ck->trusts)
        fprintf(out, "      (%s)\n", ck->trusts);
    return true;
}

/* The student's own scenes (SCENE=), every comparison at once. */
static const char *const *user_scenes;
static struct scene *user_loaded;
static int user_count;

static bool gen_user(int i, struct scene *s, char *what, size_t n)
{
    if (i >= user_count)
        return false;
    scene_copy(s, &user_loaded[i]);
    snprintf(what, n, "your scene %s", user_scenes[i]);
    return true;
}

/* No fixed scenes: a check that is its search alone. */
static bool gen_none(int i, struct scene *s, char *what, size_t n)
{
    (void)i, (void)s, (void)what, (void)n;
    return false;
}

/* The checks of lesson l, in order; false when a SCENE= file does not load. */
struct plan {
    struct check checks[CHECKS_MAX];
    int n;
};

static void plan_free(void)
{
    for (int i = 0; i < user_count; i++)
        scene_free(&user_loaded[i]);
    free(user_loaded);
    user_loaded = NULL;
    user_count = 0;
}

static bool plan_checks(const struct lesson *l, const struct check_options *o, struct plan *P)
{
    P->n = 0;
    user_scenes = o->scenes;
    user_count = 0;
    int wanted = 0;
    while (o->scenes && o->scenes[wanted])
        wanted++;
    user_loaded = calloc((size_t)wanted + 1, sizeof *user_loaded);
    if (!user_loaded)
        return false;
    for (; user_count < wanted; user_count++) {
        char err[512];
        if (!scene_load(&user_loaded[user_count], o->scenes[user_count], err, sizeof err)) {
            fprintf(o->out, "%s\n", err);
            plan_free();
            return false;
        }
    }
    struct check *c = P->checks;
    if (user_count)
        c[P->n++] = (struct check){ "your scene", CK_ALL, gen_user, true, NULL, NULL };
    c[P->n++] = (struct check){ "single triangle", CK_COVERAGE, gen_single, false, NULL, NULL };
    c[P->n++] = (struct check){ "fill-rule ties", CK_COVERAGE, gen_ties, false, search_ties, NULL };
    c[P->n++] = (struct check){ "watertight meshes", CK_COVERAGE, gen_meshes, false, NULL, NULL };
    c[P->n++] = (struct check){ "random triangles", CK_COVERAGE, gen_random, false, search_coverage, NULL };
    if (l->exercise.tiles)
        c[P->n++] = (struct check){ "tiles and blocks", CK_ALL, gen_tiles, false, NULL, NULL };
    c[P->n++] = (struct check){ l->perspective ? "colour and depth (perspective)" : "colour and depth (linear)",
                                CK_COLOUR, gen_colour, false, search_colour, NULL };
    const struct exercise_variant *variant = exercise_current_variant();
    if (variant && variant->from_bottom_right)
        c[P->n++] = (struct check){ "walked from the bottom-right", CK_ORDER, gen_property, false, NULL, NULL };
    if (l->exercise.no_pixel_mul)
        c[P->n++] = (struct check){ "no multiplication per pixel", CK_PROPERTY, gen_property, false, NULL,
                                    "counted from your COUNTs and your calls of edge_value() and pixel_centre():\n"
                                    "       a product you write by hand in the loop is not seen" };
    if (l->exercise.full_blocks)
        c[P->n++] = (struct check){ "corner classes", CK_PROPERTY, gen_property, false, NULL, NULL };
    if (l->exercise.textures) {     /* textured scenes, simplest first: colour and the sampler's faults */
        c[P->n++] = (struct check){ "texels magnified", CK_ALL, gen_tex_magnify, false, NULL, NULL };
        c[P->n++] = (struct check){ "texels minified", CK_ALL, gen_tex_minify, false, NULL, NULL };
        c[P->n++] = (struct check){ "repeat, clamp, s and t below 0", CK_ALL, gen_tex_wrap, false, NULL, NULL };
        c[P->n++] = (struct check){ "a texture that is not square", CK_ALL, gen_tex_nonsquare, false, NULL, NULL };
        c[P->n++] = (struct check){ "grazing floors and walls", CK_ALL, gen_tex_floor, false, NULL, NULL };
        c[P->n++] = (struct check){ "tiny triangles", CK_ALL, gen_tex_tiny, false, NULL, NULL };
        c[P->n++] = (struct check){ "textured 3-D scenes", CK_ALL, gen_tex_world, false, NULL, NULL };
        c[P->n++] = (struct check){ "textures of every shape", CK_ALL, gen_none, false, search_textures, NULL };
    }
    if (l->exercise.clip) {     /* 3-D scenes through the front end, simplest first */
        c[P->n++] = (struct check){ "no clipping needed", CK_ALL, gen_no_clip, false, NULL, NULL };
        c[P->n++] = (struct check){ "one vertex behind near", CK_ALL, gen_behind_one, false, NULL, NULL };
        c[P->n++] = (struct check){ "two vertices behind near", CK_ALL, gen_behind_two, false, NULL, NULL };
        c[P->n++] = (struct check){ "crossing far", CK_ALL, gen_crossing_far, false, NULL, NULL };
        c[P->n++] = (struct check){ "shared edges, clipped", CK_ALL, gen_shared_edge, true, NULL, NULL };
        c[P->n++] = (struct check){ "closed box from inside", CK_ALL, gen_box_inside, true, NULL, NULL };
        c[P->n++] = (struct check){ "floor past the guard band", CK_ALL, gen_floor, true, NULL, NULL };
        c[P->n++] = (struct check){ "random cameras", CK_ALL, gen_random_cameras, true, search_world, NULL };
    }
    return true;
}

static struct raster_params check_params(const struct check_options *o)
{
    struct raster_params p = o->params;
    if (p.subpixel_bits == 0 && !memcmp(p.knob, (int[LESSON_PARAMS_MAX]){ 0 }, sizeof p.knob))
        p.subpixel_bits = SUBPIXEL_BITS;
    return p;
}

bool exercise_check(const struct lesson *l, const struct check_options *o, struct check_result *r)
{
    memset(r, 0, sizeof *r);
    FILE *out = o->out;
    struct checker C = { .l = l, .o = o, .p = check_params(o) };
    struct plan P;
    if (!plan_checks(l, o, &P))
        return false;
    int n = P.n, searching = 0;
    for (int i = 0; i < n; i++)
        searching += P.checks[i].search != NULL;
    C.search_share = searching ? o->search_seconds / searching : 0;
    const struct exercise_variant *variant = exercise_current_variant();
    if (variant)
        fprintf(out, "make check, lesson %s, variant %s (%s): %s\n", l->id, variant->name, variant->what, o->file);
    else
        fprintf(out, "make check, lesson %s: %s\n", l->id, o->file);
    clock_t t0 = clock();
    r->nchecks = n;
    bool ok = true;
    for (int i = 0; i < n; i++) {
        struct check_outcome *co = &r->check[i];
        snprintf(co->name, sizeof co->name, "%s", P.checks[i].name);
        /* grading: a runner that hung is not given every check's time again */
        bool hung = i > 0 && r->check[i - 1].ran && r->check[i - 1].runner == RUNNER_TIMEOUT;
        if ((!ok && !o->all) || hung || (i > 0 && !r->check[i - 1].ran))
            continue;
        co->from = ftell(out);
        co->ran = true;
        co->passed = run_check(&C, i, n, &P.checks[i], r);
        co->runner = exercise_runner_fault()->what;
        fflush(out);
        co->to = ftell(out);
        r->passed += co->passed;
        ok = ok && co->passed;
    }
    if (ok)
        fprintf(out, "all %d checks pass: %llu scenes, %llu triangles, every pixel as the exact rule "
                "decides it (%.1f s)\n", n, (unsigned long long)C.evaluations,
                (unsigned long long)C.triangles, (double)(clock() - t0) / CLOCKS_PER_SEC);
    else if (o->all)
        fprintf(out, "\n%d of %d checks passed\n", r->passed, n);
    else
        fprintf(out, "\n%d of %d checks passed; fix the first failure and run make check again\n",
                r->passed, n);
    plan_free();
    target_free(&C.want);
    target_free(&C.got);
    target_free(&C.own);
    for (int i = 0; i < CHECK_SPARES; i++) {
        target_free(&C.spare_want[i]);
        target_free(&C.spare_got[i]);
    }
    free(C.mask);
    free(C.tie);
    free(C.zexact);
    return ok;
}

bool exercise_check_plan(const struct lesson *l, const struct check_options *o, struct check_result *r)
{
    memset(r, 0, sizeof *r);
    struct plan P;
    if (!plan_checks(l, o, &P))
        return false;
    r->nchecks = P.n;
    for (int i = 0; i < P.n; i++)
        snprintf(r->check[i].name, sizeof r->check[i].name, "%s", P.checks[i].name);
    plan_free();
    return true;
}

/* --- a crash or an endless loop ------------------------------------------------ */

/* Does drawing s crash? In a process of its own. */
static bool crashes(struct checker *C, const struct scene *s)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return false;
    if (pid == 0) {
        /* quietly: the first crash has been reported (a sanitizer's handler
         * would report every candidate again) */
        signal(SIGSEGV, SIG_DFL);
        signal(SIGBUS, SIG_DFL);
        signal(SIGFPE, SIG_DFL);
        signal(SIGILL, SIG_DFL);
        alarm(2);
        struct verdict v;
        evaluate(C, s, &v);
        _exit(0);
    }
    int status;
    if (waitpid(pid, &status, 0) != pid)
        return false;
    return !(WIFEXITED(status) && WEXITSTATUS(status) == 0) && !(WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM);
}

static void report_crash(const struct lesson *l, const struct check_options *o, const struct guard *g,
                         int status, struct check_result *r)
{
    FILE *out = o->out;
    struct plan P;
    memset(r, 0, sizeof *r);
    if (!plan_checks(l, o, &P))
        return;
    r->nchecks = P.n;
    r->passed = g->check;
    bool endless = WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM;
    const struct check *ck = &P.checks[g->check < P.n ? g->check : P.n - 1];
    snprintf(r->failed, sizeof r->failed, "%s", ck->name);
    struct scene s;
    char what[200];
    struct search_for aim = search_for(l);
    if (g->searching ? !ck->search(&aim, g->search_seed, &s, what, sizeof what)
                     : !ck->gen(g->scene, &s, what, sizeof what)) {
        plan_free();
        return;
    }
    if (endless)
        fprintf(out, "DID NOT FINISH\n      your code drew triangle %d of %s for %d s: an endless loop?\n",
                g->tri + 1, what, SCENE_SECONDS);
    else if (WIFSIGNALED(status))
        fprintf(out, "CRASHED\n      your code crashed (%s) drawing triangle %d of %s\n",
                strsignal(WTERMSIG(status)), g->tri + 1, what);
    else
        fprintf(out, "CRASHED\n      your code stopped the check (exit status %d) drawing triangle %d of %s\n",
                WEXITSTATUS(status), g->tri + 1, what);

    struct checker C = { .l = l, .o = o, .p = check_params(o), .kind = ck->kind, .both_ways = ck->both_ways };
    if (!endless) {
        /* fewest triangles, then each coordinate rounded, while it still crashes */
        int budget = CRASH_BUDGET;
        for (int i = s.world.ntris - 1; i >= 0 && s.world.ntris > 1 && budget > 0; i--, budget--) {
            struct scene c;     /* a 3-D scene: fewest world triangles */
            if (!scene_copy(&c, &s))
                break;
            struct world *w = &c.world;
            memmove(&w->tris[i], &w->tris[i + 1], sizeof w->tris[0] * (size_t)(w->ntris - i - 1));
            w->ntris--;
            if (crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
        for (int i = s.ntris - 1; i >= 0 && s.ntris > 1 && budget > 0; i--, budget--) {
            struct scene c;
            if (!scene_copy(&c, &s))
                break;
            memmove(&c.tris[i], &c.tris[i + 1], sizeof c.tris[0] * (size_t)(c.ntris - i - 1));
            c.ntris--;
            if (crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
        for (int k = 0; k < 6 * s.ntris && budget > 0; k++, budget--) {
            struct scene c;
            if (!scene_copy(&c, &s))
                break;
            *scene_coord(&c, k) = round(*scene_coord(&c, k));
            if (*scene_coord(&c, k) != *scene_coord(&s, k) && crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
    }
    char dir[400];
    if (counterexample_dir(o, dir, sizeof dir)) {
        snprintf(r->counterexample, sizeof r->counterexample, "%s/%.2s-%s.scene", dir, l->id,
                 endless ? "endless" : "crash");
        struct verdict v = { .tri = 0 };
        char err[600];
        if (write_counterexample(r->counterexample, &s, endless ? "did not finish" : "crashed", l, o->file,
                                 &v, err, sizeof err)) {
            r->ntris = s.world.camera_line ? s.world.ntris : s.ntris;
            fprintf(out, "\n  %s: %d %striangle%s, written to %s\n", endless ? "the scene" : "smallest scene that crashes",
                    r->ntris, s.world.camera_line ? "world " : "", r->ntris == 1 ? "" : "s", r->counterexample);
            for (int i = 0; i < s.ntris; i++) {
                const struct vertex *tv = s.tris[i].v;
                fprintf(out, "      triangle %d: (%g, %g) (%g, %g) (%g, %g)\n", i + 1, tv[0].x, tv[0].y,
                        tv[1].x, tv[1].y, tv[2].x, tv[2].y);
            }
            fprintf(out, "\n  the explorer runs your code too, and stops where it does; to see where, run it\n"
                    "  under the debugger:\n      gdb -ex run --args %s --file %s --scene %s --dump-coverage /tmp/coverage.pgm\n",
                    o->program ? o->program : "build/exercise-NN", o->file, r->counterexample);
        } else {
            fprintf(out, "  %s\n", err);
            r->counterexample[0] = '\0';
        }
    }
    fprintf(out, "\n%d of %d checks passed; fix the first failure and run make check again\n",
            r->passed, P.n);
    scene_free(&s);
    plan_free();
}

bool exercise_check_guarded(const struct lesson *l, const struct check_options *o,
                            struct check_result *r)
{
    if (remote_active())        /* the student's code is in the runner: nothing here to guard */
        return exercise_check(l, o, r);
    struct guard *g = mmap(NULL, sizeof *g, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (g == MAP_FAILED)
        return exercise_check(l, o, r);
    memset(g, 0, sizeof *g);
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        munmap(g, sizeof *g);
        return exercise_check(l, o, r);
    }
    if (pid == 0) {
        check_guard = g;
        bool ok = exercise_check(l, o, &g->result);
        fflush(NULL);
        _exit(ok ? 10 : 11);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) {
            status = 0;
            break;
        }
    bool ok = false;
    if (WIFEXITED(status) && (WEXITSTATUS(status) == 10 || WEXITSTATUS(status) == 11)) {
        *r = g->result;
        ok = WEXITSTATUS(status) == 10;
    } else {
        report_crash(l, o, g, status, r);
    }
    munmap(g, sizeof *g);
    return ok;
}
