/* report.c - what make check says about a failure: expected beside got
 * around the first wrong pixel, why the exact rule decides that pixel as it
 * does, what the code's narration said about it, the step that shows it in
 * the explorer, and the counterexample file. */
#define _POSIX_C_SOURCE 200809L   /* mkdir */

#include "checker.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "exercise/wire.h"
#include "explore/replay.h"
#include "front/front.h"      /* the view depths of a world triangle */
#include "util/file.h"


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
    if (C->p.samples > 1)
        fprintf(out, "      (covered samples per pixel: # one, 2 two, ..., . none; x from %d to %d)\n", x0, x1);
    else
        fprintf(out, "      (# covered once, 2 twice, . not covered; x from %d to %d)\n", x0, x1);
}

static void say_pixels(const struct checker *C, FILE *out, const struct verdict *v);

/* A world triangle: its vertices in the world and their view depths. */
static void say_world_tri(FILE *out, const struct scene *s, int w)
{
    struct frustum fr;
    frustum_init(&fr, &s->world.cam, s->w, s->h);
    const struct world_tri *t = &s->world.tris[w];
    fprintf(out, "      world triangle %d:", w + 1);
    for (int k = 0; k < 3; k++)
        fprintf(out, " (%g, %g, %g)", t->p[k][0], t->p[k][1], t->p[k][2]);
    fprintf(out, "\n      view depths d = ");
    for (int k = 0; k < 3; k++)
        fprintf(out, "%.6g%s", view_vertex(&fr, t->p[k], t->rgb[k]).pos[2], k < 2 ? ", " : "");
    fprintf(out, " (near %g, far %g)\n", fr.near, fr.far);
}

static void say_clip(FILE *out, const struct clip_fault *f)
{
    const char *plane = f->plane == PLANE_FAR ? "d <= far" : "d >= near";
    switch (f->what) {
    case CLIP_OUTSIDE:
        fprintf(out, "      your clipper against %s (%g) kept vertex %d at d = %.17g: %s the plane\n"
                "      (a kept vertex lies inside; a new one gets d = %g exactly)\n", plane, f->at,
                f->vertex + 1, f->d, f->plane == PLANE_FAR ? "beyond" : "behind", f->at);
        break;
    case CLIP_NOT_FINITE:
        fprintf(out, "      your clipper against %s made vertex %d with a coordinate or colour that is not finite\n",
                plane, f->vertex + 1);
        break;
    case CLIP_TOO_MANY:
        fprintf(out, "      your clipper against %s returned %d vertices for a polygon of %d: one plane cuts\n"
                "      a convex polygon into one of at most %d\n", plane, f->n, f->n_in, f->n_in + 1);
        break;
    case CLIP_ORDER: {
        const char *made = f->reversed ? "the other way" : "this way", *not = f->reversed ? "this way" : "the other way";
        fprintf(out, "      your clipper against %s made the new vertex\n"
                "      (%.17g, %.17g, %.17g) walking the polygon %s,\n"
                "      and walking it %s (as the triangle across a shared edge walks it) did not\n"
                "      make it to the last bit: the new vertex depends on the walk, and two triangles\n"
                "      sharing the edge would make two (take the edge's ends in the canonical order)\n",
                plane, f->made[0], f->made[1], f->made[2], made, not);
        break;
    }
    case CLIP_OK:
        break;
    }
}

void say_verdict(const struct checker *C, FILE *out, const struct verdict *v,
                        const struct scene *s)
{
    if (v->world) {
        say_world_tri(out, s, v->tri);
        if (v->what != WRONG_CLIP && v->what != WRONG_NONE)
            fprintf(out, "      made %d screen triangle%s (the lesson's front end: %d)\n", v->got_tris,
                    v->got_tris == 1 ? "" : "s", v->want_tris);
    } else {
        const struct vertex *tv = s->tris[v->tri].v;
        fprintf(out, "      triangle %d: (%g, %g) (%g, %g) (%g, %g)\n", v->tri + 1, tv[0].x, tv[0].y,
                tv[1].x, tv[1].y, tv[2].x, tv[2].y);
    }
    say_pixels(C, out, v);
}

static const char *const edge_names[3] = { "AB", "BC", "CA" };

/* What is wrong at the pixel (or in the clipper), with its neighbourhood. */
static void say_pixels(const struct checker *C, FILE *out, const struct verdict *v)
{
    if (v->samples > 1 && v->what != WRONG_NONE)
        fprintf(out, "      at %d samples per pixel (SAMPLES=%d; the explorer's samples view shows them)\n",
                v->samples, v->samples);
    switch (v->what) {
    case WRONG_COUNT:
        if (v->samples > 1)
            fprintf(out, "      pixel (%d, %d): expected %d covered samples in all, got %d: %s\n", v->x, v->y,
                    v->want_n, v->got_n, v->got_n > v->want_n ? "a sample too many" : "a sample missing");
        else
            fprintf(out, "      pixel (%d, %d), centre (%g, %g): expected %s, got %s: %s\n", v->x, v->y,
                    v->x + 0.5, v->y + 0.5, times(v->want_n), times(v->got_n),
                    v->got_n > v->want_n ? (v->want_n ? "written twice" : "an extra pixel") : "a missing pixel");
        neighbourhood(C, out, v->x, v->y);
        break;
    case WRONG_MASK:
        fprintf(out, "      pixel (%d, %d): the samples holding a triangle are mask %#x, expected %#x\n"
                "      (bit s = sample s of sample_pattern(%d): the right count, the wrong samples)\n",
                v->x, v->y, v->got_mask, v->want_mask, v->samples);
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
    case WRONG_ORDER:
        fprintf(out, "      pixel (%d, %d) came after pixel (%d, %d): expected the box walked from its\n"
                "      bottom-right pixel, rows from the bottom up, each row from right to left\n",
                v->x, v->y, v->before_x, v->before_y);
        break;
    case WRONG_BLOCK_CLASS: {
        static const char *const klass[] = { "EMPTY", "FULL", "PARTIAL" };
        const char *got = v->got_class >= 0 && v->got_class < 3 ? klass[v->got_class] : "no class";
        fprintf(out, "      block (%d, %d)-(%d, %d) narrated %s; its corner pixel centres make it %s\n",
                v->bx, v->by, v->bx1, v->by1, got, klass[v->want_class]);
        if (v->want_class == BLOCK_FULL)
            fprintf(out, "      (block (%d, %d)-(%d, %d) is covered in full, but was not narrated FULL)\n", v->bx, v->by, v->bx1, v->by1);
        else if (v->got_class == BLOCK_FULL)
            fprintf(out, "      (narrated FULL, but pixel (%d, %d) in it is not covered)\n", v->x, v->y);
        else if (v->want_class == BLOCK_EMPTY)
            fprintf(out, "      (all four corners lie outside edge %s: trivially rejected, never tested pixel by pixel)\n",
                    edge_names[v->edge]);
        else if (v->got_class == BLOCK_EMPTY)
            fprintf(out, "      (no edge has all four corners outside it: the corner test cannot reject it)\n");
        break;
    }
    case WRONG_CLIP:
        say_clip(out, &v->clip);
        break;
    case WRONG_LOD: {
        const double *d = v->deriv;
        fprintf(out, "      quad (%d, %d)-(%d, %d): its derivatives in level-0 texels per pixel are\n"
                "      du/dx = %.6g, dv/dx = %.6g, du/dy = %.6g, dv/dy = %.6g, so\n"
                "      rho = max(|(du/dx, dv/dx)|, |(du/dy, dv/dy)|) = %.6g and lambda = log2(rho) = %.6g;\n"
                "      your level of detail gave lambda = %.6g\n", v->x, v->y, v->x + 1, v->y + 1, d[0], d[1],
                d[2], d[3], exp2(v->want_lambda), v->want_lambda, v->got_lambda);
        break;
    }
    case WRONG_TEXEL: {
        const struct texel_fault *t = &v->texel;
        if (t->w == 0)
            fprintf(out, "      your sampler read level %d of a texture of %d levels (0 to %d):\n"
                    "      a level it does not have (lambda clamped to [0, last level]?)\n", t->level,
                    t->nlevels, t->nlevels - 1);
        else
            fprintf(out, "      your sampler read texel (%lld, %lld) of level %d, outside its %d x %d texels:\n"
                    "      i and j wrapped first (repeat: the mathematical mod, never negative; clamp: to 0 .. size - 1)\n",
                    t->i, t->j, t->level, t->w, t->h);
        fprintf(out, "      (read as black; pixel (%d, %d): expected #%06x, got #%06x)\n", v->x, v->y,
                v->want_c & 0xffffffu, v->got_c & 0xffffffu);
        break;
    }
    case WRONG_TILES:
        fprintf(out, "      your code visited tile (%d, %d)-(%d, %d), outside the triangle's box\n"
                "      (%d, %d)-(%d, %d): only the %d tile%s of the box can hold a pixel of it (the picture is\n"
                "      right, the time is the screen's, not the triangle's)\n", v->bx, v->by, v->bx1, v->by1,
                v->box[0], v->box[1], v->box[2], v->box[3], v->want_n, v->want_n == 1 ? "" : "s");
        break;
    case WRONG_READS:
        fprintf(out, "      your sampler read %d texel%s from %d level%s (mask %#x) for pixel (%d, %d);\n"
                "      the trilinear filter reads two bilinear taps of 4 texels, at two adjacent levels\n"
                "      (or one level twice): %d at most (counted inside exercise_texel(); the picture may be right)\n",
                v->got_n, v->got_n == 1 ? "" : "s", v->got_class, v->got_class == 1 ? "" : "s", v->got_mask,
                v->x, v->y, v->want_n);
        break;
    case WRONG_UNBLOCKED:
        if (!v->edge)
            fprintf(out, "      your code wrote pixel (%d, %d) before it classified any block: no block of the\n"
                    "      triangle's box was narrated (NARRATE .kind = TRACE_BLOCK); the lesson's rasterizer\n"
                    "      classifies each q x q block by its corners and writes a pixel only inside one\n", v->x, v->y);
        else
            fprintf(out, "      your code wrote pixel (%d, %d) outside the block it classified last,\n"
                    "      (%d, %d)-(%d, %d): a pixel is written inside the block it belongs to, after that\n"
                    "      block's class (NARRATE .kind = TRACE_BLOCK)\n", v->x, v->y, v->bx, v->by, v->bx1, v->by1);
        break;
    case WRONG_RUNNER:
        fprintf(out, "      %s\n      (what it printed is in its log)\n", v->runner.why);
        break;
    case WRONG_NONE:
        break;
    }
}

/* What the code's own narration says about the first wrong pixel: its
 * first write there, its last test of it, and the block or span that holds
 * it (the smallest, where a tile holds blocks). From these, the step at which the explorer shows it: the write (or
 * the block or span), or the end of the triangle when the code never wrote
 * the pixel (a missing one). */
static void follow(void *ctx, const struct trace_event *ev)
{
    struct trail *f = ctx;
    bool here = ev->x == f->x && ev->y == f->y;
    if (f->lod_line > 0) {  /* the quad's level of detail, the first time it is narrated */
        if (ev->kind == TRACE_STEP && ev->line == f->lod_line && here && !f->held)
            f->held = true, f->hold = *ev;
        return;
    }
    if (f->by_rect) {       /* the misclassified block itself, the first time it is narrated */
        if (ev->kind == TRACE_BLOCK && !f->held && ev->x == f->rect[0] && ev->y == f->rect[1]
            && ev->x1 == f->rect[2] && ev->y1 == f->rect[3])
            f->held = true, f->hold = *ev;
        return;
    }
    if (ev->kind == TRACE_PIXEL_WRITE && here && !f->written)
        f->written = true, f->write = *ev;
    else if (ev->kind == TRACE_PIXEL_TEST && here)
        f->tested = true, f->test = *ev;
    else if ((ev->kind == TRACE_BLOCK || ev->kind == TRACE_SPAN) && f->x >= ev->x
             && f->x <= ev->x1 && f->y >= ev->y && f->y <= ev->y1
             && (!f->held || (ev->x >= f->hold.x && ev->x1 <= f->hold.x1 && ev->y >= f->hold.y
                              && ev->y1 <= f->hold.y1)))
        f->held = true, f->hold = *ev;      /* the innermost: lesson 07's block in its tile */
}

uint64_t step_of(const struct checker *C, const struct scene *s, const struct verdict *v,
                        struct trail *f)
{
    *f = (struct trail){ .x = v->x, .y = v->y, .by_rect = v->what == WRONG_BLOCK_CLASS,
                         .rect = { v->bx, v->by, v->bx1, v->by1 },
                         .lod_line = v->what == WRONG_LOD ? C->l->exercise.lod_line : 0 };
    struct replay r;
    if (v->world) {
        /* other triangles than the exact picture's: the explorer compares
         * the whole picture, at the end of the run */
        struct scene got;
        if (!exercise_projected(C, &got, s)) {
            student_end();
            return 0;
        }
        struct raster_params p = C->p;
        p.at = &(struct run_place){ .scene = &got };
        uint64_t total = replay_init(&r, &got, &exercise_variant, &p) ? r.total : 0;
        student_end();
        replay_free(&r);
        scene_free(&got);
        return total;
    }
    struct raster_params all = C->p;
    all.checker = s->checker;
    bool counted = student_begin(C, s, &all, 0, s->ntris, WIRE_TRACE_COUNT)
                   && replay_init(&r, s, &exercise_variant, &all);
    student_end();
    if (!counted || exercise_runner_fault()->what != RUNNER_OK)
        return 0;
    uint64_t step = r.start[v->tri + 1];
    struct target fb;
    if (target_init(&fb, s->w, s->h, scene_background(s))) {
        struct tri_setup t;
        replay_setup(&r, v->tri, &t);
        struct trace tr = { .sink = follow, .ctx = f };
        trace_begin(&tr, (uint32_t)v->tri, TRACE_UNLIMITED);
        struct raster_params p = lesson_params_tri(&C->p, s, v->tri);
        p.checker = s->checker;
        struct raster_params asked = C->p;
        asked.checker = s->checker;
        if (student_begin(C, s, &asked, v->tri, 1, WIRE_TRACE_EVENTS))
            exercise_variant.rasterize(&t, &p, &fb, &tr);
        student_end();
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


/* Why the exact rule decides the pixel as it does, when its centre lies
 * exactly on an edge; and what the code's narration said about it. */
void explain(const struct checker *C, FILE *out, const struct verdict *v,
                    const struct scene *s, const struct trail *f)
{
    if (v->world)
        return;     /* the verdict said what there is to say of a world triangle */
    if (v->what == WRONG_COUNT || v->what == WRONG_COLOUR || v->what == WRONG_DEPTH) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[v->tri].v, s->w, s->h, C->p.subpixel_bits);
        for (int k = 0; k < 3 && t.area2 > 0; k++) {
            if (edge_value(&t, k, v->x, v->y) != 0)
                continue;
            bool top = t.I[k] == 0 && t.J[k] > 0, left = t.I[k] > 0;
            enum fill_convention rule = exercise_rule();
            fprintf(out, "      its centre lies exactly on edge %s (F = 0), a %s edge: the %s rule %s\n",
                    edge_names[k], top ? "top" : left ? "left" : t.I[k] == 0 ? "bottom" : "right",
                    rule == FILL_BOTTOM_RIGHT ? "bottom-right" : "top-left",
                    reference_edge_owns(rule, t.I[k], t.J[k]) ? "covers it" : "leaves it to the triangle on the other side");
        }
    }
    const struct lesson *l = C->l;
    if (v->what == WRONG_MUL || v->what == WRONG_ORDER || v->what == WRONG_BLOCK_CLASS || v->what == WRONG_OUTSIDE
        || v->what == WRONG_LOD || v->what == WRONG_TEXEL)
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

bool write_counterexample(const char *path, const struct scene *s, const char *check,
                          const struct lesson *l, const char *file, const struct verdict *v,
                          char *err, size_t errlen)
{
    struct scene_out so = { s, check, l->id, file, v };
    return write_file_atomic(path, write_scene, &so, err, errlen);
}

bool make_dirs(const char *dir)
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
