/* evaluate.c - make check draws a scene twice, with the exact rule and with
 * the code given to exercise_use, one triangle at a time, and compares
 * after each triangle (check.c says what each check compares). */
#include "checker.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "exercise/remote.h"
#include "exercise/wire.h"
#include "front/front.h"    /* front_scene: the exact picture's triangles */

static int samples_of(const struct target *fb)
{
    return fb->samples ? fb->samples->n : 1;
}

/* fb cleared for scene s at `samples` per pixel; a picture of another size
 * or count is put aside in spare (the most recent first, the oldest
 * dropped), and one that fits is taken from there. */
static bool prepare(struct target *fb, struct target spare[CHECK_SPARES], const struct scene *s, int samples)
{
    if (!fb->color || fb->w != s->w || fb->h != s->h || samples_of(fb) != samples) {
        int found = CHECK_SPARES - 1;
        for (int k = CHECK_SPARES - 1; k >= 0; k--)
            if (spare[k].color && spare[k].w == s->w && spare[k].h == s->h && samples_of(&spare[k]) == samples)
                found = k;
        struct target taken = spare[found];
        if (!(taken.color && taken.w == s->w && taken.h == s->h && samples_of(&taken) == samples)) {
            target_free(&taken);
            taken = (struct target){ 0 };
        }
        memmove(&spare[1], &spare[0], sizeof spare[0] * (size_t)found);
        spare[0] = *fb;
        *fb = taken;
    }
    if (fb->color && fb->w == s->w && fb->h == s->h) {
        fb->background = scene_background(s);
        target_clear(fb);
    } else {
        target_free(fb);
        if (!target_init(fb, s->w, s->h, scene_background(s)))
            return false;
    }
    if ((fb->samples ? fb->samples->n : 1) == samples)
        return true;
    return target_multisample(fb, samples);
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

/* The class the corner test gives the pixels x0..x1, y0..y1 (lessons 05
 * and 07): EMPTY when the centres of its four corner pixels all lie outside
 * one edge (that edge in *edge), FULL when they all lie inside every edge,
 * PARTIAL otherwise; inside as the fill rule decides it. */
static enum block_class corner_class(const struct tri_setup *t, int x0, int y0, int x1, int y1, int *edge)
{
    bool full = true;
    for (int k = 0; k < 3; k++) {
        int in = 0;
        for (int c = 0; c < 4; c++) {
            int x = c & 1 ? x1 : x0, y = c & 2 ? y1 : y0;
            in += edge_inside(t, k, edge_value(t, k, x, y));
        }
        if (in == 0) {
            *edge = k;
            return BLOCK_EMPTY;
        }
        full = full && in == 4;
    }
    return full ? BLOCK_FULL : BLOCK_PARTIAL;
}

/* A quad's level of detail as narrated on lesson_exercise.lod_line,
 * against lambda = log2(rho) of the derivatives narrated with it: rho the
 * longer of (du/dx, dv/dx) and (du/dy, dv/dy), in level-0 texels. The code
 * may compute it in float: 1/1000 of a level is far beyond its rounding,
 * and far below any mistake (log2 of rho squared doubles lambda, texture
 * coordinates for texels move it by log2 of the size). */
#define LOD_TOLERANCE 1e-3
static void watch_lod(struct checker *C, const struct trace_event *ev, struct verdict *v)
{
    if (!(ev->flags & TRACE_INSIDE))
        return;     /* beyond the horizon: the last level, no derivatives */
    double d[4] = { ev->aux[0], ev->aux[1], ev->aux[2], ev->aux[3] };
    double rho2 = fmax(d[0] * d[0] + d[1] * d[1], d[2] * d[2] + d[3] * d[3]);
    double want = 0.5 * log2(rho2), got = ev->aux[5];
    if (got == want || fabs(got - want) <= LOD_TOLERANCE)
        return;
    *v = (struct verdict){ .what = WRONG_LOD, .x = ev->x, .y = ev->y, .deriv = { d[0], d[1], d[2], d[3] },
                           .want_lambda = want, .got_lambda = got };
    (void)C;
}

/* The box walked from its bottom-right pixel (a graded variant's
 * from_bottom_right): every pixel the code tests or writes comes after the
 * one before it in that order, rows from the bottom up, each row from right
 * to left (the same pixel again is its write after its test). */
static void watch_order(struct checker *C, const struct trace_event *ev, struct verdict *v)
{
    if (ev->kind != TRACE_PIXEL_TEST && ev->kind != TRACE_PIXEL_WRITE)
        return;
    bool same = ev->x == C->order_x && ev->y == C->order_y;
    bool after = ev->y < C->order_y || (ev->y == C->order_y && ev->x < C->order_x);
    if (C->order_any && !same && !after) {
        *v = (struct verdict){ .what = WRONG_ORDER, .x = ev->x, .y = ev->y,
                               .before_x = C->order_x, .before_y = C->order_y };
        return;
    }
    C->order_any = true;
    C->order_x = ev->x;
    C->order_y = ev->y;
}

/* The texels read for one written pixel (lesson 09), counted inside
 * exercise_texel(): the trilinear filter reads two bilinear taps of 4
 * texels, at two adjacent levels (or one level twice). A bilinear tap of
 * more texels, or a mix of more levels, draws the same picture slower. */
#define TRILINEAR_READS 8
static void watch_reads(const struct trace_event *ev, struct verdict *v)
{
    const struct texel_reads *r = exercise_texel_reads();
    int levels = __builtin_popcount(r->levels);
    uint32_t low = r->levels & -r->levels;
    bool adjacent = levels < 2 || r->levels == (low | low << 1);
    if (r->n > TRILINEAR_READS || levels > 2 || !adjacent)
        *v = (struct verdict){ .what = WRONG_READS, .x = ev->x, .y = ev->y,
                               .got_n = (int)(r->n < 1000000 ? r->n : 1000000), .want_n = TRILINEAR_READS,
                               .got_class = levels, .got_mask = r->levels };
    exercise_texel_reads_clear();
}

/* A tile narrated (lesson 07): one of the tiles of the triangle's box.
 * Walking every tile of the screen for every triangle draws the same
 * picture, and takes the time of the screen instead of the triangle's. */
static void watch_tile(struct checker *C, const struct trace_event *ev, struct verdict *v)
{
    const struct tri_setup *t = C->t;
    if (ev->x1 < t->minx || ev->x > t->maxx || ev->y1 < t->miny || ev->y > t->maxy)
        *v = (struct verdict){ .what = WRONG_TILES, .x = ev->x, .y = ev->y, .bx = ev->x, .by = ev->y,
                               .bx1 = ev->x1, .by1 = ev->y1,
                               .want_n = (t->maxx / 64 - t->minx / 64 + 1) * (t->maxy / 64 - t->miny / 64 + 1),
                               .box = { t->minx, t->miny, t->maxx, t->maxy } };
}

/* The narration, watched for the lesson's property. */
static void watch(void *ctx, const struct trace_event *ev)
{
    struct checker *C = ctx;
    struct verdict *v = C->prop;
    if (v->what != WRONG_NONE)
        return;
    if (C->kind == CK_ORDER) {
        watch_order(C, ev, v);
        return;
    }
    if (C->l->exercise.textures && ev->kind == TRACE_PIXEL_WRITE) {
        watch_reads(ev, v);
        return;
    }
    if (C->l->exercise.tiles && ev->kind == TRACE_BLOCK && ev->aux[0] == 64 && ev->aux[1] == 0) {
        watch_tile(C, ev, v);
        if (v->what != WRONG_NONE)
            return;
    }
    if (C->l->exercise.lod_line > 0 && ev->kind == TRACE_STEP && ev->line == C->l->exercise.lod_line) {
        watch_lod(C, ev, v);
        return;
    }
    if (C->l->exercise.full_blocks && ev->kind == TRACE_BLOCK && ev->x <= ev->x1 && ev->y <= ev->y1) {
        C->block_any = true;
        C->block[0] = ev->x, C->block[1] = ev->y, C->block[2] = ev->x1, C->block[3] = ev->y1;
    }
    /* the lesson's idea is the classification of blocks: a pixel is
     * written inside the block classified before it, never by a walk of
     * the box that classifies nothing */
    if (C->l->exercise.full_blocks && ev->kind == TRACE_PIXEL_WRITE
        && (!C->block_any || ev->x < C->block[0] || ev->x > C->block[2] || ev->y < C->block[1] || ev->y > C->block[3])) {
        *v = (struct verdict){ .what = WRONG_UNBLOCKED, .x = ev->x, .y = ev->y, .edge = C->block_any,
                               .bx = C->block[0], .by = C->block[1], .bx1 = C->block[2], .by1 = C->block[3] };
        return;
    }
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
        bool classified = !C->l->exercise.class_lines;
        for (const int *line = C->l->exercise.class_lines; line && *line >= 0 && !classified; line++)
            classified = ev->line == *line;
        if (!classified)
            break;
        int edge = -1;
        enum block_class want = corner_class(C->t, ev->x, ev->y, ev->x1, ev->y1, &edge);
        if (ev->klass != want) {
            *v = (struct verdict){ .what = WRONG_BLOCK_CLASS, .x = ev->x, .y = ev->y,
                                   .bx = ev->x, .by = ev->y, .bx1 = ev->x1, .by1 = ev->y1,
                                   .want_class = want, .got_class = ev->klass, .edge = edge };
            /* the pixel that shows it: one not covered in a block called
             * FULL, one covered in a block called EMPTY */
            bool found = false;
            for (int y = ev->y; y <= ev->y1 && !found; y++)
                for (int x = ev->x; x <= ev->x1 && !found; x++)
                    if (ev->klass == BLOCK_FULL ? !covered(C, x, y) : ev->klass == BLOCK_EMPTY && covered(C, x, y))
                        v->x = x, v->y = y, found = true;
        }
        break;
    }
    default:
        break;
    }
}

/* A texel read outside its level: the pixel that shows it, the first
 * whose colour differs (the black read there), else the first the exact
 * picture covers. */
static void texel_pixel(const struct checker *C, struct verdict *v)
{
    const struct target *W = &C->want, *G = &C->got;
    size_t n = (size_t)W->w * (size_t)W->h, first = n;
    for (size_t i = 0; i < n; i++) {
        if (W->count[i] && first == n)
            first = i;
        if (W->count[i] && W->color[i] != G->color[i]) {
            first = i;
            break;
        }
    }
    if (first < n) {
        v->x = (int)(first % (size_t)W->w), v->y = (int)(first / (size_t)W->w);
        v->want_c = W->color[first], v->got_c = G->color[first];
    }
}

/* The lesson's clipped polygon, starting at another vertex, fanned from
 * there: the other fan's slivers, their vertices snapped to 1/256 pixel,
 * tilt their planes of depth and colour by as much as a sliver is thin.
 * Where the code's clipper gave the lesson's polygons (as cyclic
 * sequences), its pixel i is right when it is the exact rule's on the
 * code's own triangles (the exact plane of the triangle drawn). */
static bool own_close(const struct checker *C, size_t i)
{
    const struct target *G = &C->got, *O = &C->own;
    return O->color && O->count[i] == C->want.count[i]
        && pixel_close(O->color[i], O->depth[i], G->color[i], G->depth[i]);
}

/* The first pixel, in reading order, where the pictures differ. */
static bool compare(const struct checker *C, int tri, struct verdict *v)
{
    const struct target *W = &C->want, *G = &C->got;
    size_t n = (size_t)W->w * (size_t)W->h;
    bool colour = C->kind == CK_COLOUR || C->kind == CK_ALL;
    int ns = W->samples && G->samples ? W->samples->n : 1;
    for (size_t i = 0; i < n; i++) {
        enum wrong what = WRONG_NONE;
        /* at n samples: which samples hold a triangle (a depth) */
        unsigned want_mask = 0, got_mask = 0;
        for (int k = 0; k < ns && ns > 1; k++) {
            want_mask |= (unsigned)(W->samples->depth[i * (size_t)ns + (size_t)k] < INFINITY) << k;
            got_mask |= (unsigned)(G->samples->depth[i * (size_t)ns + (size_t)k] < INFINITY) << k;
        }
        if (W->count[i] != G->count[i])
            what = WRONG_COUNT;
        else if (want_mask != got_mask)
            what = WRONG_MASK;
        else if (colour && W->count[i] && !C->tie[i] && !pixel_close(W->color[i], W->depth[i], G->color[i], G->depth[i])
                 && !(C->use_own && own_close(C, i)))
            what = pixel_close(W->color[i], W->depth[i], G->color[i], W->depth[i]) ? WRONG_DEPTH : WRONG_COLOUR;
        if (what != WRONG_NONE) {
            *v = (struct verdict){
                .what = what, .tri = tri, .x = (int)(i % (size_t)W->w), .y = (int)(i / (size_t)W->w),
                .want_n = W->count[i], .got_n = G->count[i], .want_c = W->color[i], .got_c = G->color[i],
                .want_z = W->depth[i], .got_z = G->depth[i], .samples = ns,
                .want_mask = want_mask, .got_mask = got_mask,
            };
            return false;
        }
    }
    return true;
}

/* The picture the code is held to: the shared exact rule, or for a lesson
 * whose student writes a part of its shading (lesson 09's sampler) the
 * lesson's own. */
const struct lesson_variant *check_exact(const struct lesson *l)
{
    return l->exercise.textures ? &l->variants[0] : exercise_exact(l->perspective);
}

/* The parameters triangle i of s is drawn with: its texture, and the
 * scene's checker (texture checker N), which every lesson shades. */
static struct raster_params tri_params(const struct raster_params *p, const struct scene *s, int i)
{
    struct raster_params out = lesson_params_tri(p, s, i);
    out.checker = s->checker;
    return out;
}

/* Two surfaces whose exact depths at a pixel centre differ by less than
 * this (relative) tie for it: code that computes depth in float (lesson
 * 04's lanes keep 1/z to about 1e-5) may give it to either, and both
 * colours are right. Exactly equal depths (a triangle drawn twice) are no
 * tie: the first one drawn keeps the pixel. */
#define DEPTH_TIE 4e-5
/* A pixel centre this near a border of the checker's squares (in squares,
 * relative to s N and t N) lies on it: float texture coordinates may put
 * it in either square. */
#define CHECKER_TIE 2e-4

struct tie_run {
    struct checker *C;
    const struct tri_setup *t;
    int checker;
    bool perspective;
};

static bool on_border(double v)
{
    return fabs(v - round(v)) <= CHECKER_TIE * fmax(1, fabs(v));
}

/* Before triangle t is drawn: the pixels it ties for with the surface
 * drawn there, and those it takes whose checker square is a toss-up. */
static void tie_pixel(void *ctx, int x, int y)
{
    struct tie_run *r = ctx;
    struct checker *C = r->C;
    size_t i = (size_t)y * (size_t)C->want.w + (size_t)x;
    double z, rgb[3], st[2];
    reference_shade(r->t, x, y, r->perspective, &z, rgb, st);
    bool border = r->checker > 0 && (on_border(st[0] * r->checker) || on_border(st[1] * r->checker));
    if (!C->want.count[i]) {
        C->tie[i] = border;
        C->zexact[i] = z;
        return;
    }
    double old = C->zexact[i], d = z - old;
    if (z != old && fabs(d) <= DEPTH_TIE * fabs(old))
        C->tie[i] = 1;
    else if (d < 0)
        C->tie[i] = border;     /* nearer than both: its own */
    if (d < 0)
        C->zexact[i] = z;
}

/* No ties yet on a picture of s's size; false when out of memory. */
static bool tie_start(struct checker *C, const struct scene *s)
{
    size_t n = (size_t)s->w * (size_t)s->h;
    uint8_t *tie = realloc(C->tie, n);
    if (tie)
        C->tie = tie;
    double *zexact = realloc(C->zexact, sizeof *zexact * n);
    if (zexact)
        C->zexact = zexact;
    if (!tie || !zexact)
        return false;
    memset(C->tie, 0, n);
    return true;
}

/* The picture of the code's own screen triangles, cleared. */
static bool own_start(struct checker *C, const struct scene *s)
{
    struct target *O = &C->own;
    if (O->color && O->w == s->w && O->h == s->h) {
        O->background = scene_background(s);
        target_clear(O);
        return true;
    }
    target_free(O);
    return target_init(O, s->w, s->h, scene_background(s));
}

/* --- the seam: the student's code draws ----------------------------------------- */

/* Where the student's code runs in another process (remote.h), ask it for
 * triangles first .. first + count - 1 of s with params p, traced as
 * `trace` says; each then comes back through the exercise variant's
 * rasterize, in order. In this process: nothing to ask. */
bool student_begin(const struct checker *C, const struct scene *s, const struct raster_params *p,
                   int first, int count, int trace)
{
    if (!remote_active())
        return true;
    return remote_begin(s, p, first, count, trace, C->l->exercise.clip, C->both_ways,
                       C->l->exercise.write_line);
}

void student_end(void)
{
    if (remote_active())
        remote_end();
}

/* The runner crashed, hung or sent garbage drawing triangle tri of s. */
static bool runner_failed(int tri, int samples, bool world, struct verdict *v)
{
    if (exercise_runner_fault()->what == RUNNER_OK)
        return false;
    *v = (struct verdict){ .what = WRONG_RUNNER, .tri = tri, .samples = samples, .world = world,
                           .runner = *exercise_runner_fault() };
    return true;
}

static bool evaluate_at_drawn(struct checker *C, const struct scene *s, struct verdict *v);

/* The scene at one sample count, C->p.samples. */
static bool evaluate_at(struct checker *C, const struct scene *s, struct verdict *v)
{
    bool property = C->kind == CK_PROPERTY || C->kind == CK_ALL || C->kind == CK_ORDER;
    struct raster_params p = C->p;
    p.checker = s->checker;     /* the scene's checker, which every lesson shades */
    if (!student_begin(C, s, &p, 0, s->ntris, property ? WIRE_TRACE_EVENTS : WIRE_TRACE_COUNT)) {
        runner_failed(0, C->p.samples > 1 ? C->p.samples : 1, false, v);
        return false;
    }
    bool ok = evaluate_at_drawn(C, s, v);
    student_end();
    return ok;
}

static bool evaluate_at_drawn(struct checker *C, const struct scene *s, struct verdict *v)
{
    int samples = C->p.samples > 1 ? C->p.samples : 1;
    if (!prepare(&C->want, C->spare_want, s, samples) || !prepare(&C->got, C->spare_got, s, samples))
        return true;    /* out of memory: said by the caller */
    uint8_t *mask = realloc(C->mask, (size_t)s->w * (size_t)s->h);
    if (!mask)
        return true;
    C->mask = mask;
    if (!tie_start(C, s))
        return true;
    bool colour = C->kind == CK_COLOUR || C->kind == CK_ALL;
    C->evaluations++;
    const struct lesson_variant *exact = check_exact(C->l);
    bool property = C->kind == CK_PROPERTY || C->kind == CK_ALL || C->kind == CK_ORDER;
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, C->p.subpixel_bits);
        C->p = tri_params(&C->p, s, i);
        if (colour && samples == 1)
            reference_coverage(&t, tie_pixel, &(struct tie_run){ C, &t, s->checker, C->l->perspective });
        exact->rasterize(&t, &C->p, &C->want, NULL);
        if (property) {
            memset(C->mask, 0, (size_t)s->w * (size_t)s->h);
            reference_coverage_rule(&t, exercise_rule(), mark, C);
        }
        struct verdict prop = { .what = WRONG_NONE };
        struct trace tr = { .sink = property ? watch : NULL, .ctx = C };
        C->prop = &prop;
        C->t = &t;
        C->in_row = false;
        C->order_any = false;
        C->block_any = false;
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        exercise_fault_clear();
        if (check_guard)
            check_guard->tri = i;
        exercise_variant.rasterize(&t, &C->p, &C->got, &tr);
        C->triangles++;
        if (runner_failed(i, samples, false, v))
            return false;
        const struct exercise_fault *f = exercise_fault();
        if (f->any) {
            *v = (struct verdict){ .what = WRONG_OUTSIDE, .tri = i, .x = f->x, .y = f->y,
                                   .samples = samples };
            return false;
        }
        if (exercise_texel_fault()->any) {
            *v = (struct verdict){ .what = WRONG_TEXEL, .tri = i, .texel = *exercise_texel_fault(),
                                   .samples = samples };
            texel_pixel(C, v);
            return false;
        }
        if (prop.what != WRONG_NONE) {
            *v = prop;
            v->tri = i;
            v->samples = samples;
            return false;
        }
        if (!compare(C, i, v))
            return false;
    }
    return true;
}

bool exercise_projected(const struct checker *C, struct scene *out, const struct scene *s)
{
    if (remote_active()) {      /* by the runner; its triangles then follow */
        struct raster_params p = C->p;
        p.samples = 0;
        p.checker = s->checker;
        return student_begin(C, s, &p, 0, INT32_MAX, WIRE_TRACE_COUNT) && remote_projected()
               && scene_copy(out, remote_projected());
    }
    if (!scene_copy(out, s))
        return false;
    if (exercise_front(out))
        return true;
    scene_free(out);
    return false;
}

/* compare() after world triangle w: where the code's clipper gave the
 * lesson's polygons, the exact plane of the triangles it drew is right. */
static bool compare_world(struct checker *C, int w, struct verdict *v)
{
    C->use_own = exercise_clip_as_lesson(w);
    bool same = compare(C, w, v);
    C->use_own = false;
    return same;
}

/* Draw screen triangles [*i, end of world triangle w) of s with fn into fb. */
static void draw_world_tri(struct checker *C, const struct scene *s, int w, int *i,
                           const struct lesson_variant *v, struct target *fb, bool watch_faults, bool ties)
{
    struct raster_params p = C->p;
    p.at = &(struct run_place){ .scene = s };
    for (; *i < s->ntris && s->world.from[*i] == w; ++*i) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[*i].v, s->w, s->h, C->p.subpixel_bits);
        p = tri_params(&p, s, *i);
        struct trace tr = { .sink = NULL };
        trace_begin(&tr, (uint32_t)*i, TRACE_UNLIMITED);
        if (watch_faults && check_guard)
            check_guard->tri = *i;
        if (ties)               /* the exact picture: its ties first */
            reference_coverage(&t, tie_pixel, &(struct tie_run){ C, &t, s->checker, true });
        v->rasterize(&t, &p, fb, watch_faults ? &tr : NULL);
        if (watch_faults)
            C->triangles++;
    }
}

/* A 3-D scene: the exact picture from the lesson's front end, the
 * exercise's from its own (exercise_front), compared after each world
 * triangle; the clipper's faults first. */
static bool evaluate_world(struct checker *C, const struct scene *s, struct verdict *v)
{
    struct scene want, got;
    if (!scene_copy(&want, s))
        return true;    /* out of memory: said by the caller */
    exercise_clip_both_ways(C->both_ways);
    if (!front_scene(&want)) {
        scene_free(&want);
        return true;
    }
    if (!exercise_projected(C, &got, s)) {
        scene_free(&want);
        student_end();
        if (runner_failed(0, 1, true, v))
            return false;
        return true;
    }
    bool ok = prepare(&C->want, C->spare_want, s, 1) && prepare(&C->got, C->spare_got, s, 1);
    ok = ok && tie_start(C, s) && own_start(C, s);
    C->evaluations += ok;
    const struct lesson_variant *exact = C->l->exercise.textures ? check_exact(C->l) : exercise_exact(true);
    const struct clip_fault *cf = exercise_clip_fault();
    int a = 0, b = 0;
    for (int w = 0; ok && w < s->world.ntris; w++) {
        int a0 = a, b0 = b;
        draw_world_tri(C, &want, w, &a, exact, &C->want, false, true);
        struct verdict base = { .world = true, .tri = w, .samples = 1 };
        if (cf->what != CLIP_OK && cf->tri == w) {
            *v = base;
            v->what = WRONG_CLIP;
            v->clip = *cf;
            ok = false;
            break;
        }
        exercise_fault_clear();
        int b0_own = b;
        draw_world_tri(C, &got, w, &b0_own, exact, &C->own, false, false);
        draw_world_tri(C, &got, w, &b, &exercise_variant, &C->got, true, false);
        const struct exercise_fault *f = exercise_fault();
        if (runner_failed(w, 1, true, v)) {
            ok = false;
        } else if (f->any) {
            *v = base;
            v->what = WRONG_OUTSIDE, v->x = f->x, v->y = f->y;
            ok = false;
        } else if (exercise_texel_fault()->any) {
            *v = base;
            v->what = WRONG_TEXEL, v->texel = *exercise_texel_fault();
            texel_pixel(C, v);
            ok = false;
        } else if (!compare_world(C, w, v)) {
            v->world = true;
            ok = false;
        }
        v->want_tris = a - a0, v->got_tris = b - b0;
    }
    student_end();
    scene_free(&want);
    scene_free(&got);
    return ok;
}

/* Every sample count of the lesson in turn (lesson_exercise.samples), or the
 * one C->only_count names, or the pixel centre alone; at a failure
 * C->p.samples stays the count it failed at. */
bool evaluate(struct checker *C, const struct scene *s, struct verdict *v)
{
    *v = (struct verdict){ .what = WRONG_NONE, .samples = 1 };
    if (s->world.camera_line) {
        C->p.samples = 0;
        if (evaluate_world(C, s, v))
            *v = (struct verdict){ .what = WRONG_NONE, .samples = 1 };
        return v->what == WRONG_NONE;
    }
    const int *counts = C->l->exercise.samples;
    if (!counts) {
        C->p.samples = 0;
        return evaluate_at(C, s, v);
    }
    for (; *counts; counts++) {
        if (C->only_count > 0 && *counts != C->only_count)
            continue;
        C->p.samples = *counts;
        if (!evaluate_at(C, s, v))
            return false;
    }
    *v = (struct verdict){ .what = WRONG_NONE, .samples = 1 };
    return true;
}
