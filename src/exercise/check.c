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
 *              pixels of a row (lesson 03), every block narrated full
 *              really full and every full block found (lesson 05).
 *
 * A write outside the target fails any check. */
#define _DEFAULT_SOURCE           /* mkdir, fork, MAP_ANONYMOUS, strsignal */

#include "exercise.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "exercise/scenes.h"
#include "explore/replay.h"
#include "util/file.h"

/* Shrinking tries at most this many candidate scenes. */
#define SHRINK_BUDGET 4000
/* A scene that takes longer than this is an endless loop: no scene of the
 * checks needs a hundredth of it. */
#define SCENE_SECONDS 10
/* Shrinking a crash runs each candidate in a process of its own. */
#define CRASH_BUDGET 600

/* Where a guarded check is (exercise_check_guarded): shared with the
 * process that runs it, so a crash still says which scene did it. */
struct guard {
    int check, scene, tri;
    struct check_result result;
};
static struct guard *guard;

enum check_kind { CK_COVERAGE, CK_COLOUR, CK_PROPERTY, CK_ALL };

/* What went wrong, at the first triangle after which the pictures differ. */
enum wrong {
    WRONG_NONE, WRONG_COUNT, WRONG_COLOUR, WRONG_DEPTH, WRONG_OUTSIDE, WRONG_MUL,
    WRONG_BLOCK_NOT_FULL, WRONG_BLOCK_MISSED,
};

struct verdict {
    enum wrong what;
    int tri;                    /* the triangle that went wrong */
    int x, y;                   /* its first wrong pixel */
    int want_n, got_n;          /* coverage counts there */
    uint32_t want_c, got_c;     /* colours */
    float want_z, got_z;
    int bx, by, bx1, by1;       /* a block, for the block properties */
    uint64_t mul;               /* multiplications between two pixels */
};

/* Everything one check run needs. */
struct checker {
    const struct lesson *l;
    const struct check_options *o;
    struct raster_params p;
    enum check_kind kind;
    struct target want, got;
    uint8_t *mask;              /* the exact coverage of the triangle being run */
    /* the property watch, fed by the narration */
    struct verdict *prop;
    bool in_row;
    int last_x, last_y;
    uint64_t pixel_mul;         /* mul counted when the last pixel began */
    uint64_t evaluations;       /* scenes drawn, for the report */
    uint64_t triangles;
};

/* --- drawing and comparing -------------------------------------------------- */

static bool prepare(struct target *fb, const struct scene *s)
{
    if (fb->color && fb->w == s->w && fb->h == s->h) {
        fb->background = scene_background(s);
        target_clear(fb);
        return true;
    }
    target_free(fb);
    return target_init(fb, s->w, s->h, scene_background(s));
}

static void mark(void *ctx, int x, int y)
{
    struct checker *C = ctx;
    C->mask[(size_t)y * (size_t)C->want.w + (size_t)x] = 1;
}

static bool covered(const struct checker *C, int x, int y)
{
    return x >= 0 && y >= 0 && x < C->want.w && y < C->want.h
        && C->mask[(size_t)y * (size_t)C->want.w + (size_t)x];
}

/* The narration, watched for the lesson's property. */
static void watch(void *ctx, const struct trace_event *ev)
{
    struct checker *C = ctx;
    struct verdict *v = C->prop;
    if (v->what != WRONG_NONE)
        return;
    switch (ev->kind) {
    case TRACE_ROW:
    case TRACE_SETUP:
    case TRACE_SPAN:
        C->in_row = false;
        break;
    case TRACE_PIXEL_TEST:
    case TRACE_PIXEL_WRITE:
        if (!C->l->exercise.no_pixel_mul)
            break;
        if (C->in_row && ev->y == C->last_y && ev->x == C->last_x)
            break;          /* the same pixel: its write after its test */
        if (C->in_row && ev->y == C->last_y && ev->mul > C->pixel_mul) {
            *v = (struct verdict){ .what = WRONG_MUL, .x = ev->x, .y = ev->y,
                                   .mul = ev->mul - C->pixel_mul, .bx = C->last_x };
            break;
        }
        C->in_row = true;
        C->last_x = ev->x;
        C->last_y = ev->y;
        C->pixel_mul = ev->mul;
        break;
    case TRACE_BLOCK: {
        C->in_row = false;
        if (!C->l->exercise.full_blocks || ev->x > ev->x1 || ev->y > ev->y1)
            break;
        int missing_x = -1, missing_y = -1;
        for (int y = ev->y; y <= ev->y1 && missing_x < 0; y++)
            for (int x = ev->x; x <= ev->x1; x++)
                if (!covered(C, x, y)) {
                    missing_x = x, missing_y = y;
                    break;
                }
        if (ev->klass == BLOCK_FULL && missing_x >= 0)
            *v = (struct verdict){ .what = WRONG_BLOCK_NOT_FULL, .x = missing_x, .y = missing_y,
                                   .bx = ev->x, .by = ev->y, .bx1 = ev->x1, .by1 = ev->y1 };
        else if (ev->klass != BLOCK_FULL && missing_x < 0)
            *v = (struct verdict){ .what = WRONG_BLOCK_MISSED, .x = ev->x, .y = ev->y,
                                   .bx = ev->x, .by = ev->y, .bx1 = ev->x1, .by1 = ev->y1 };
        break;
    }
    default:
        break;
    }
}

/* The first pixel, in reading order, where the pictures differ. */
static bool compare(const struct checker *C, int tri, struct verdict *v)
{
    const struct target *W = &C->want, *G = &C->got;
    size_t n = (size_t)W->w * (size_t)W->h;
    bool colour = C->kind == CK_COLOUR || C->kind == CK_ALL;
    for (size_t i = 0; i < n; i++) {
        enum wrong what = WRONG_NONE;
        if (W->count[i] != G->count[i])
            what = WRONG_COUNT;
        else if (colour && W->count[i] && !pixel_close(W->color[i], W->depth[i], G->color[i], G->depth[i]))
            what = pixel_close(W->color[i], W->depth[i], G->color[i], W->depth[i]) ? WRONG_DEPTH : WRONG_COLOUR;
        if (what != WRONG_NONE) {
            *v = (struct verdict){
                .what = what, .tri = tri, .x = (int)(i % (size_t)W->w), .y = (int)(i / (size_t)W->w),
                .want_n = W->count[i], .got_n = G->count[i], .want_c = W->color[i], .got_c = G->color[i],
                .want_z = W->depth[i], .got_z = G->depth[i],
            };
            return false;
        }
    }
    return true;
}

/* Draw scene s both ways, triangle by triangle; false (and v) at the first
 * triangle after which they differ in what this check compares. */
static bool evaluate(struct checker *C, const struct scene *s, struct verdict *v)
{
    *v = (struct verdict){ .what = WRONG_NONE };
    if (!prepare(&C->want, s) || !prepare(&C->got, s))
        return true;    /* out of memory: said by the caller */
    uint8_t *mask = realloc(C->mask, (size_t)s->w * (size_t)s->h);
    if (!mask)
        return true;
    C->mask = mask;
    C->evaluations++;
    const struct lesson_variant *exact = exercise_exact(C->l->perspective);
    bool property = C->kind == CK_PROPERTY || C->kind == CK_ALL;
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, C->p.subpixel_bits);
        exact->rasterize(&t, &C->p, &C->want, NULL);
        if (property) {
            memset(C->mask, 0, (size_t)s->w * (size_t)s->h);
            reference_coverage(&t, mark, C);
        }
        struct verdict prop = { .what = WRONG_NONE };
        struct trace tr = { .sink = property ? watch : NULL, .ctx = C };
        C->prop = &prop;
        C->in_row = false;
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        exercise_fault_clear();
        if (guard)
            guard->tri = i;
        exercise_variant.rasterize(&t, &C->p, &C->got, &tr);
        C->triangles++;
        const struct exercise_fault *f = exercise_fault();
        if (f->any) {
            *v = (struct verdict){ .what = WRONG_OUTSIDE, .tri = i, .x = f->x, .y = f->y };
            return false;
        }
        if (prop.what != WRONG_NONE) {
            *v = prop;
            v->tri = i;
            return false;
        }
        if (!compare(C, i, v))
            return false;
    }
    return true;
}

/* --- shrinking ---------------------------------------------------------------- */

struct shrinker {
    struct checker *C;
    int budget;
};

static bool still_fails(struct shrinker *S, const struct scene *s)
{
    if (S->budget <= 0)
        return false;
    S->budget--;
    struct verdict v;
    return !evaluate(S->C, s, &v);
}

/* Keep candidate c in place of s when it still fails. */
static bool try_candidate(struct shrinker *S, struct scene *s, struct scene *c)
{
    if (still_fails(S, c)) {
        scene_free(s);
        *s = *c;
        return true;
    }
    scene_free(c);
    return false;
}

/* Fewest triangles: drop one at a time while the check still fails. */
static void drop_triangles(struct shrinker *S, struct scene *s)
{
    bool progress = true;
    while (progress && s->ntris > 1) {
        progress = false;
        for (int i = s->ntris - 1; i >= 0 && s->ntris > 1; i--) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            memmove(&c.tris[i], &c.tris[i + 1], sizeof c.tris[0] * (size_t)(c.ntris - i - 1));
            c.ntris--;
            progress |= try_candidate(S, s, &c);
        }
    }
}

/* Every coordinate of the scene, in order: x, y of each vertex. */
static double *coord(struct scene *s, int k)
{
    struct vertex *v = &s->tris[k / 6].v[(k / 2) % 3];
    return k % 2 ? &v->y : &v->x;
}

/* Smallest coordinates: halve the scene while it fails, move it to the
 * origin by whole pixels, make the target no larger than it needs, then
 * round each coordinate to the coarsest grid (whole pixels, centres,
 * halves, ...) that still fails. */
static void round_coordinates(struct shrinker *S, struct scene *s)
{
    for (int pass = 0; pass < 3; pass++) {
        bool progress = false;
        /* half the size about the origin, on the 1/256 grid, while it fails */
        for (int k = 0; k < 8; k++) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            for (int j = 0; j < 6 * c.ntris; j++)
                *coord(&c, j) = round(*coord(&c, j) * SUBPIXEL_HALF) / SUBPIXEL_ONE;
            if (!try_candidate(S, s, &c))
                break;
            progress = true;
        }
        /* to the origin, by whole pixels: every tie stays a tie */
        double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *coord(s, k);
            if (k % 2)
                miny = fmin(miny, v), maxy = fmax(maxy, v);
            else
                minx = fmin(minx, v), maxx = fmax(maxx, v);
        }
        double dx = floor(minx) > 0 ? floor(minx) : 0, dy = floor(miny) > 0 ? floor(miny) : 0;
        for (int axis = 0; axis < 2; axis++) {
            double d = axis ? dy : dx;
            if (d <= 0)
                continue;
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            for (int k = axis; k < 6 * c.ntris; k += 2)
                *coord(&c, k) -= d;
            progress |= try_candidate(S, s, &c);
        }
        /* the target no larger than the triangles */
        int w = (int)fmin(s->w, fmax(1, ceil(maxx - dx) + 1)), h = (int)fmin(s->h, fmax(1, ceil(maxy - dy) + 1));
        if (w < s->w || h < s->h) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            c.w = w, c.h = h;
            progress |= try_candidate(S, s, &c);
        }
        /* each coordinate to a coarser grid */
        static const double steps[] = { 1, 0.5, 0.25, 0.125, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128 };
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *coord(s, k);
            for (size_t g = 0; g < sizeof steps / sizeof steps[0]; g++) {
                double candidates[2] = { round(v / steps[g]) * steps[g],
                                         g == 0 ? floor(v) + 0.5 : NAN };
                bool done = false;
                for (int m = 0; m < 2 && !done; m++) {
                    double u = candidates[m];
                    if (isnan(u) || u == v || fabs(u) > fabs(v) + 1)
                        continue;
                    struct scene c;
                    if (!scene_copy(&c, s))
                        return;
                    *coord(&c, k) = u;
                    done = try_candidate(S, s, &c);
                }
                if (done) {
                    progress = true;
                    break;
                }
            }
        }
        if (!progress)
            break;
    }
}

/* Plain colours and depths for a coverage or property counterexample. */
static void plain_attributes(struct shrinker *S, struct scene *s)
{
    static const double rgb[3][3] = { { 1, 0.2, 0.2 }, { 0.2, 1, 0.2 }, { 0.3, 0.5, 1 } };
    struct scene c;
    if (!scene_copy(&c, s))
        return;
    for (int i = 0; i < c.ntris; i++)
        for (int k = 0; k < 3; k++) {
            struct vertex *v = &c.tris[i].v[k];
            v->z = 1 + i;
            v->r = rgb[i % 3][0], v->g = rgb[i % 3][1], v->b = rgb[i % 3][2];
            v->s = v->t = 0;
        }
    c.background[0] = c.background[1] = c.background[2] = 0;
    try_candidate(S, s, &c);
}

static void shrink(struct checker *C, struct scene *s)
{
    struct shrinker S = { C, SHRINK_BUDGET };
    drop_triangles(&S, s);
    round_coordinates(&S, s);
    if (C->kind == CK_COVERAGE || C->kind == CK_PROPERTY)
        plain_attributes(&S, s);
}

/* --- the report -------------------------------------------------------------- */

static const char *times(int n)
{
    static const char *const t[] = { "not covered", "covered once", "covered twice" };
    static char buf[32];
    if (n < 3)
        return t[n];
    snprintf(buf, sizeof buf, "covered %d times", n);
    return buf;
}

/* Expected beside got around the wrong pixel: '.' uncovered, '#' once, a
 * digit for more; the wrong pixel in brackets. */
static void neighbourhood(const struct checker *C, FILE *out, int px, int py)
{
    const struct target *W = &C->want, *G = &C->got;
    int x0 = px - 6 < 0 ? 0 : px - 6, x1 = px + 6 >= W->w ? W->w - 1 : px + 6;
    int y0 = py - 4 < 0 ? 0 : py - 4, y1 = py + 4 >= W->h ? W->h - 1 : py + 4;
    int width = (x1 - x0 + 1) * 2 + 1;
    fprintf(out, "      %-*s    %s\n", width + 4, "expected", "got");
    for (int y = y0; y <= y1; y++) {
        fprintf(out, "  %3d ", y);
        for (int pass = 0; pass < 2; pass++) {
            const struct target *T = pass ? G : W;
            for (int x = x0; x <= x1; x++) {
                int n = T->count[(size_t)y * (size_t)T->w + (size_t)x];
                char ch = n == 0 ? '.' : n == 1 ? '#' : n < 10 ? (char)('0' + n) : '*';
                bool here = x == px && y == py;
                fprintf(out, "%c%c", here ? '[' : (x == px + 1 && y == py) ? ']' : ' ', ch);
            }
            fprintf(out, "%c", x1 == px && y == py ? ']' : ' ');
            fputs(pass ? "\n" : "     ", out);
        }
    }
    fprintf(out, "      (# covered once, 2 twice, . not covered; x from %d to %d)\n", x0, x1);
}

static void say_verdict(const struct checker *C, FILE *out, const struct verdict *v,
                        const struct scene *s)
{
    const struct vertex *tv = s->tris[v->tri].v;
    fprintf(out, "      triangle %d: (%g, %g) (%g, %g) (%g, %g)\n", v->tri + 1, tv[0].x, tv[0].y,
            tv[1].x, tv[1].y, tv[2].x, tv[2].y);
    switch (v->what) {
    case WRONG_COUNT:
        fprintf(out, "      pixel (%d, %d), centre (%g, %g): expected %s, got %s: %s\n", v->x, v->y,
                v->x + 0.5, v->y + 0.5, times(v->want_n), times(v->got_n),
                v->got_n > v->want_n ? (v->want_n ? "written twice" : "an extra pixel") : "a missing pixel");
        neighbourhood(C, out, v->x, v->y);
        break;
    case WRONG_COLOUR:
        fprintf(out, "      pixel (%d, %d): expected colour #%06x, got #%06x (more than %d of 255 off in a channel);\n"
                "      depth expected %.6g, got %.6g\n", v->x, v->y, v->want_c & 0xffffffu,
                v->got_c & 0xffffffu, PIXEL_COLOUR_LEVELS, v->want_z, v->got_z);
        break;
    case WRONG_DEPTH:
        fprintf(out, "      pixel (%d, %d): expected depth %.6g, got %.6g (more than %g%% off)\n",
                v->x, v->y, v->want_z, v->got_z, 100 * PIXEL_DEPTH_RELATIVE);
        break;
    case WRONG_OUTSIDE:
        fprintf(out, "      wrote pixel (%d, %d), outside the %d x %d target (the write was skipped)\n",
                v->x, v->y, C->got.w, C->got.h);
        break;
    case WRONG_MUL:
        fprintf(out, "      %llu multiplication%s between pixel (%d, %d) and pixel (%d, %d) of the same row:\n"
                "      expected none (COUNT_OPS and every edge_value() or pixel_centre() call count)\n",
                (unsigned long long)v->mul, v->mul == 1 ? "" : "s", v->bx, v->y, v->x, v->y);
        break;
    case WRONG_BLOCK_NOT_FULL:
        fprintf(out, "      block (%d, %d)-(%d, %d) narrated FULL, but pixel (%d, %d) in it is not covered\n",
                v->bx, v->by, v->bx1, v->by1, v->x, v->y);
        break;
    case WRONG_BLOCK_MISSED:
        fprintf(out, "      block (%d, %d)-(%d, %d) is covered in full, but was not narrated FULL\n",
                v->bx, v->by, v->bx1, v->by1);
        break;
    case WRONG_NONE:
        break;
    }
}

/* What the code's own narration says about the first wrong pixel: its
 * first write there, its last test of it, and the block or span that holds
 * it. From these, the step at which the explorer shows it: the write (or
 * the block or span), or the end of the triangle when the code never wrote
 * the pixel (a missing one). */
struct trail {
    int x, y;
    bool written, tested, held;
    struct trace_event write, test, hold;
};

static void follow(void *ctx, const struct trace_event *ev)
{
    struct trail *f = ctx;
    bool here = ev->x == f->x && ev->y == f->y;
    if (ev->kind == TRACE_PIXEL_WRITE && here && !f->written)
        f->written = true, f->write = *ev;
    else if (ev->kind == TRACE_PIXEL_TEST && here)
        f->tested = true, f->test = *ev;
    else if ((ev->kind == TRACE_BLOCK || ev->kind == TRACE_SPAN) && !f->held && f->x >= ev->x
             && f->x <= ev->x1 && f->y >= ev->y && f->y <= ev->y1)
        f->held = true, f->hold = *ev;
}

static uint64_t step_of(const struct checker *C, const struct scene *s, const struct verdict *v,
                        struct trail *f)
{
    *f = (struct trail){ .x = v->x, .y = v->y };
    struct replay r;
    if (!replay_init(&r, s, &exercise_variant, &C->p))
        return 0;
    uint64_t step = r.start[v->tri + 1];
    struct target fb;
    if (target_init(&fb, s->w, s->h, scene_background(s))) {
        struct tri_setup t;
        replay_setup(&r, v->tri, &t);
        struct trace tr = { .sink = follow, .ctx = f };
        trace_begin(&tr, (uint32_t)v->tri, TRACE_UNLIMITED);
        exercise_variant.rasterize(&t, &C->p, &fb, &tr);
        bool missing = v->what == WRONG_COUNT && v->got_n < v->want_n;
        if (!missing && f->written)
            step = r.start[v->tri] + f->write.index + 1;
        else if (!missing && f->held)
            step = r.start[v->tri] + f->hold.index + 1;
        target_free(&fb);
    }
    replay_free(&r);
    return step;
}

static const char *line_text(const struct lesson *l, int line)
{
    for (int i = 0; l->pseudocode && l->pseudocode[i]; i++)
        if (i == line)
            return l->pseudocode[i];
    return "?";
}

static const char *const edge_names[3] = { "AB", "BC", "CA" };

/* Why the exact rule decides the pixel as it does, when its centre lies
 * exactly on an edge; and what the code's narration said about it. */
static void explain(const struct checker *C, FILE *out, const struct verdict *v,
                    const struct scene *s, const struct trail *f)
{
    if (v->what == WRONG_COUNT || v->what == WRONG_COLOUR || v->what == WRONG_DEPTH) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[v->tri].v, s->w, s->h, C->p.subpixel_bits);
        for (int k = 0; k < 3 && t.area2 > 0; k++) {
            if (edge_value(&t, k, v->x, v->y) != 0)
                continue;
            bool top = t.I[k] == 0 && t.J[k] > 0, left = t.I[k] > 0;
            fprintf(out, "      its centre lies exactly on edge %s (F = 0), a %s edge: the top-left rule %s\n",
                    edge_names[k], top ? "top" : left ? "left" : t.I[k] == 0 ? "bottom" : "right",
                    top || left ? "covers it" : "leaves it to the triangle on the other side");
        }
    }
    const struct lesson *l = C->l;
    if (v->what == WRONG_MUL || v->what == WRONG_BLOCK_NOT_FULL || v->what == WRONG_BLOCK_MISSED
        || v->what == WRONG_OUTSIDE)
        return;     /* the verdict said it all */
    if (f->held) {
        static const char *const klass[] = { "EMPTY", "FULL", "PARTIAL" };
        if (f->hold.kind == TRACE_BLOCK)
            fprintf(out, "      your code put it in block (%d, %d)-(%d, %d), classified %s (masks %x %x %x)\n",
                    f->hold.x, f->hold.y, f->hold.x1, f->hold.y1,
                    f->hold.klass < 3 ? klass[f->hold.klass] : "?", f->hold.mask[0], f->hold.mask[1],
                    f->hold.mask[2]);
        else
            fprintf(out, "      your code put it in the span %d..%d of row %d\n", f->hold.x, f->hold.x1,
                    f->hold.y);
    }
    if (f->tested) {
        fprintf(out, "      your code tested it and said %s, edge values F_ab, F_bc, F_ca = %lld, %lld, %lld\n",
                f->test.flags & TRACE_INSIDE ? "inside" : "outside", (long long)f->test.e[0],
                (long long)f->test.e[1], (long long)f->test.e[2]);
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[v->tri].v, s->w, s->h, C->p.subpixel_bits);
        int64_t e[3] = { edge_value(&t, 0, v->x, v->y), edge_value(&t, 1, v->x, v->y),
                         edge_value(&t, 2, v->x, v->y) };
        if (e[0] != f->test.e[0] || e[1] != f->test.e[1] || e[2] != f->test.e[2])
            fprintf(out, "      the exact edge values at its centre (%g, %g) are %lld, %lld, %lld\n",
                    v->x + 0.5, v->y + 0.5, (long long)e[0], (long long)e[1], (long long)e[2]);
        double w[3];
        barycentric(&t, e, w);
        if (v->what != WRONG_COUNT)
            fprintf(out, "      the exact weights of A, B, C there: %.4f, %.4f, %.4f (A, B, C in setup's order%s)\n",
                    w[0], w[1], w[2], t.swapped ? ": the file's second and third vertex exchanged" : "");
    }
    if (f->written)
        fprintf(out, "      your code wrote it (\"%s\"): colour #%06x, depth %.6g\n",
                line_text(l, f->write.line), f->write.rgba & 0xffffffu, f->write.z);
    else if (v->what == WRONG_COUNT)
        fprintf(out, "      your code never wrote it\n");
}

struct scene_out {
    const struct scene *s;
    const char *check, *lesson, *file;
    const struct verdict *v;
};

static bool write_scene(FILE *out, void *ctx)
{
    const struct scene_out *o = ctx;
    fprintf(out, "# the smallest counterexample make check found for lesson %s\n"
            "# check: %s, code: %s\n# first wrong pixel: (%d, %d), triangle %d\n",
            o->lesson, o->check, o->file, o->v->x, o->v->y, o->v->tri + 1);
    return scene_write(o->s, out);
}

static bool make_dirs(const char *dir)
{
    char path[512];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(path, 0777) != 0 && errno != EEXIST)
                return false;
            *p = '/';
        }
    return mkdir(path, 0777) == 0 || errno == EEXIST;
}

/* --- the checks ------------------------------------------------------------------ */

struct check {
    const char *name;
    enum check_kind kind;
    scene_gen gen;
};

static void progress(const struct check_options *o, int n, int i, const char *name, int done, int total)
{
    if (!o->progress)
        return;
    fprintf(o->out, "\r  %d/%d %-31s %3d%%", i + 1, n, name, total ? 100 * done / total : 0);
    fflush(o->out);
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

    shrink(C, s);
    evaluate(C, s, &v);
    r->x = v.x, r->y = v.y;
    r->ntris = s->ntris;
    struct trail f;
    r->step = step_of(C, s, &v, &f);
    snprintf(r->failed, sizeof r->failed, "%s", name);

    char slug[64];
    size_t k = 0;
    for (const char *p = name; *p && k + 1 < sizeof slug; p++)
        slug[k++] = (*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9') ? *p : '-';
    while (k > 0 && slug[k - 1] == '-')
        k--;
    slug[k] = '\0';
    for (char *p = slug; (p = strstr(p, "--"));)
        memmove(p, p + 1, strlen(p));
    char nn[3] = { C->l->id[0], C->l->id[1], '\0' };
    if (!make_dirs(o->out_dir)) {
        fprintf(out, "  cannot create %s: %s\n", o->out_dir, strerror(errno));
        return false;
    }
    snprintf(r->counterexample, sizeof r->counterexample, "%s/%s-%s.scene", o->out_dir, nn, slug);
    struct scene_out so = { s, name, C->l->id, o->file, &v };
    char err[600];
    if (!write_file_atomic(r->counterexample, write_scene, &so, err, sizeof err)) {
        fprintf(out, "  %s\n", err);
        r->counterexample[0] = '\0';
        return false;
    }
    fprintf(out, "\n  smallest counterexample: %d triangle%s, written to %s\n", s->ntris,
            s->ntris == 1 ? "" : "s", r->counterexample);
    say_verdict(C, out, &v, s);
    explain(C, out, &v, s, &f);
    fprintf(out, "\n  open it in the explorer at the first wrong pixel (step %llu):\n      %s SCENE=%s STEP=%llu\n",
            (unsigned long long)r->step, o->open_cmd, r->counterexample, (unsigned long long)r->step);
    return true;
}

/* Run one check over all of its scenes. */
static bool run_check(struct checker *C, int i, int n, const struct check *ck, struct check_result *r)
{
    FILE *out = C->o->out;
    fprintf(out, "  %d/%d %-31s ", i + 1, n, ck->name);
    fflush(out);
    C->kind = ck->kind;
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
        if (guard) {
            guard->check = i;
            guard->scene = k;
            alarm(SCENE_SECONDS);
        }
        struct verdict v;
        bool passed = evaluate(C, &s, &v);
        if (guard)
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
    if (C->o->progress)
        fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
    fprintf(out, "ok (%d scene%s, %llu triangles)\n", total, total == 1 ? "" : "s",
            (unsigned long long)(C->triangles - tris0));
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

/* The checks of lesson l, in order; false when a SCENE= file does not load. */
struct plan {
    struct check checks[8];
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
        c[P->n++] = (struct check){ "your scene", CK_ALL, gen_user };
    c[P->n++] = (struct check){ "single triangle", CK_COVERAGE, gen_single };
    c[P->n++] = (struct check){ "fill-rule ties", CK_COVERAGE, gen_ties };
    c[P->n++] = (struct check){ "watertight meshes", CK_COVERAGE, gen_meshes };
    c[P->n++] = (struct check){ "random triangles", CK_COVERAGE, gen_random };
    c[P->n++] = (struct check){ l->perspective ? "colour and depth (perspective)" : "colour and depth (linear)",
                                CK_COLOUR, gen_colour };
    if (l->exercise.no_pixel_mul)
        c[P->n++] = (struct check){ "no multiplication per pixel", CK_PROPERTY, gen_property };
    if (l->exercise.full_blocks)
        c[P->n++] = (struct check){ "full blocks really full", CK_PROPERTY, gen_property };
    return true;
}

static struct raster_params check_params(const struct check_options *o)
{
    struct raster_params p = o->params;
    if (p.subpixel_bits == 0 && p.block_size == 0 && !p.affine)
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
    int n = P.n;
    fprintf(out, "make check, lesson %s: %s\n", l->id, o->file);
    clock_t t0 = clock();
    r->nchecks = n;
    bool ok = true;
    for (int i = 0; i < n && ok; i++) {
        ok = run_check(&C, i, n, &P.checks[i], r);
        r->passed += ok;
    }
    if (ok)
        fprintf(out, "all %d checks pass: %llu scenes, %llu triangles, every pixel as the exact rule "
                "decides it (%.1f s)\n", n, (unsigned long long)C.evaluations,
                (unsigned long long)C.triangles, (double)(clock() - t0) / CLOCKS_PER_SEC);
    else
        fprintf(out, "\n%d of %d checks passed; fix the first failure and run make check again\n",
                r->passed, n);
    plan_free();
    target_free(&C.want);
    target_free(&C.got);
    free(C.mask);
    return ok;
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
    if (!ck->gen(g->scene, &s, what, sizeof what)) {
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

    struct checker C = { .l = l, .o = o, .p = check_params(o), .kind = ck->kind };
    if (!endless) {
        /* fewest triangles, then each coordinate rounded, while it still crashes */
        int budget = CRASH_BUDGET;
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
            *coord(&c, k) = round(*coord(&c, k));
            if (*coord(&c, k) != *coord(&s, k) && crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
    }
    if (make_dirs(o->out_dir)) {
        char nn[3] = { l->id[0], l->id[1], '\0' };
        snprintf(r->counterexample, sizeof r->counterexample, "%s/%s-%s.scene", o->out_dir, nn,
                 endless ? "endless" : "crash");
        struct verdict v = { .tri = 0 };
        struct scene_out so = { &s, endless ? "did not finish" : "crashed", l->id, o->file, &v };
        char err[600];
        if (write_file_atomic(r->counterexample, write_scene, &so, err, sizeof err)) {
            r->ntris = s.ntris;
            fprintf(out, "\n  %s: %d triangle%s, written to %s\n", endless ? "the scene" : "smallest scene that crashes",
                    s.ntris, s.ntris == 1 ? "" : "s", r->counterexample);
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
        guard = g;
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
