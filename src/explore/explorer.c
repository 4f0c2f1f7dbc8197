/* explorer.c - the explorer's state: replaying the narration to a step,
 * the cells of the current triangle, variants, dragging (stepping by a
 * unit is in stepping.c; the frame's layout, names and zoom in layout.c). */
#include "explorer.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "front/front.h"

/* --- replaying a step ------------------------------------------------------- */

static struct cell *explorer_cell_mut(struct explorer *ex, int x, int y)
{
    if (x < ex->cell_x0 || y < ex->cell_y0 || x >= ex->cell_x0 + ex->cell_w
        || y >= ex->cell_y0 + ex->cell_h)
        return NULL;
    return &ex->cells[(size_t)(y - ex->cell_y0) * (size_t)ex->cell_w + (size_t)(x - ex->cell_x0)];
}

const struct cell *explorer_cell(const struct explorer *ex, int x, int y)
{
    return explorer_cell_mut((struct explorer *)ex, x, y);
}

/* Mark the cells of a rectangle (inclusive corners), clipped to the region. */
static void mark_rect(struct explorer *ex, int x0, int y0, int x1, int y1, uint8_t flags,
                      int klass)
{
    if (x0 < ex->cell_x0) x0 = ex->cell_x0;
    if (y0 < ex->cell_y0) y0 = ex->cell_y0;
    if (x1 >= ex->cell_x0 + ex->cell_w) x1 = ex->cell_x0 + ex->cell_w - 1;
    if (y1 >= ex->cell_y0 + ex->cell_h) y1 = ex->cell_y0 + ex->cell_h - 1;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            struct cell *c = explorer_cell_mut(ex, x, y);
            c->flags |= flags;
            if (klass >= 0)
                c->klass = (uint8_t)klass;
        }
}

/* The sink: every event of the current triangle up to the step, in order. */
static void take_event(void *ctx, const struct trace_event *ev)
{
    struct explorer *ex = ctx;
    ex->last = *ev;
    ex->has_last = true;
    ex->told[ev->line] = *ev;
    struct cell *c;
    switch ((enum trace_kind)ev->kind) {
    case TRACE_ROW:
        mark_rect(ex, ev->x, ev->y, ev->x1, ev->y, CELL_ROW, -1);
        break;
    case TRACE_SPAN:
        mark_rect(ex, ev->x, ev->y, ev->x1, ev->y, CELL_SPAN | CELL_INSIDE, -1);
        break;
    case TRACE_BLOCK:
        /* a step on a rectangle that classifies nothing (lesson 07's
         * binning, take, store) marks no cell: its blocks are not yet
         * classified */
        if (ev->klass < BLOCK_CLASS_COUNT)
            mark_rect(ex, ev->x, ev->y, ev->x1, ev->y1,
                      CELL_BLOCK | (ev->klass == BLOCK_FULL ? CELL_INSIDE : 0), ev->klass);
        break;
    case TRACE_PIXEL_TEST:
        if ((c = explorer_cell_mut(ex, ev->x, ev->y))) {
            c->flags = (uint8_t)((c->flags & ~CELL_INSIDE) | CELL_TESTED
                                 | ((ev->flags & TRACE_INSIDE) ? CELL_INSIDE : 0));
            memcpy(c->e, ev->e, sizeof c->e);
            /* the weights follow from the edge values: u, v, w = F_bc, F_ca, F_ab / area2 */
            if (ex->tri.area2 > 0) {
                double b[3];
                barycentric(&ex->tri, ev->e, b);
                for (int k = 0; k < 3; k++)
                    c->bary[k] = (float)b[k];
            }
            memcpy(c->aux, ev->aux, sizeof c->aux);
            c->line = ev->line;
        }
        break;
    case TRACE_PIXEL_WRITE:
        if ((c = explorer_cell_mut(ex, ev->x, ev->y))) {
            c->flags |= CELL_WRITTEN | CELL_INSIDE
                        | ((ev->flags & TRACE_DEPTH_PASS) ? CELL_DEPTH_PASS : 0);
            c->z = ev->z;
            c->rgba = ev->rgba;
        }
        break;
    case TRACE_STEP:            /* about a pixel when the lesson says so (its cell_lines) */
        for (const int *l = ex->side ? ex->side->cell_lines : NULL; l && *l >= 0; l++)
            if (*l == ev->line && (c = explorer_cell_mut(ex, ev->x, ev->y))) {
                memcpy(c->aux, ev->aux, sizeof c->aux);
                c->line = ev->line;
            }
        break;
    case TRACE_SETUP:
    case TRACE_FRONT:           /* a step of the 3-D front end: no pixel of the grid */
    case TRACE_KIND_COUNT:
        break;
    }
}

/* The cells cover the triangle's box widened by a pixel (lesson 08's samples
 * reach beyond the box of centres) and to 16-pixel alignment, so the blocks
 * of a block lesson (q <= 16) fit too. */
static bool prepare_cells(struct explorer *ex, const struct tri_setup *t)
{
    ex->cell_w = ex->cell_h = 0;
    ex->cell_x0 = ex->cell_y0 = 0;
    if (t->minx > t->maxx || t->miny > t->maxy)
        return true;
    int x0 = (t->minx > 0 ? t->minx - 1 : 0) & ~15, y0 = (t->miny > 0 ? t->miny - 1 : 0) & ~15;
    int x1 = (t->maxx + 1) | 15, y1 = (t->maxy + 1) | 15;
    if (x1 >= ex->scene.w) x1 = ex->scene.w - 1;
    if (y1 >= ex->scene.h) y1 = ex->scene.h - 1;
    size_t n = (size_t)(x1 - x0 + 1) * (size_t)(y1 - y0 + 1);
    if (n > ex->cell_cap) {
        struct cell *c = realloc(ex->cells, n * sizeof *c);
        if (!c)
            return false;
        ex->cells = c;
        ex->cell_cap = n;
    }
    memset(ex->cells, 0, n * sizeof *ex->cells);
    ex->cell_x0 = x0, ex->cell_y0 = y0;
    ex->cell_w = x1 - x0 + 1, ex->cell_h = y1 - y0 + 1;
    return true;
}

int explorer_finished(const struct explorer *ex)
{
    if (ex->cur < 0)
        return 0;
    uint64_t events = ex->replay.start[ex->cur + 1] - ex->replay.start[ex->cur];
    return ex->local + 1 >= events ? ex->cur + 1 : ex->cur;
}

void explorer_counters(const struct explorer *ex, struct trace_counters *c)
{
    const struct trace_counters *before = &ex->replay.sums[ex->cur >= 0 ? ex->cur : 0];
    trace_counters_add(c, before, &ex->tri_c);
    /* the arithmetic: what the last event carries, done before it in its
     * triangle (the trace went on counting until the next event froze it) */
    c->mul = before->mul + (ex->has_last ? ex->last.mul : 0);
    c->add = before->add + (ex->has_last ? ex->last.add : 0);
}

/* Draw triangles [0, upto) with variants[0] into the exact target. */
static bool advance_exact(struct explorer *ex, int upto)
{
    if (!ex->exact.color || ex->exact_upto < 0 || upto < ex->exact_upto) {
        target_free(&ex->exact);
        if (!target_init(&ex->exact, ex->scene.w, ex->scene.h, scene_background(&ex->scene)))
            return false;
        ex->exact_upto = 0;
    }
    const struct lesson_variant *exact = &ex->lesson->variants[0];
    for (; ex->exact_upto < upto; ex->exact_upto++) {
        struct tri_setup t;
        replay_setup(&ex->replay, ex->exact_upto, &t);
        struct run_place at;
        struct raster_params p = replay_params(&ex->replay, ex->exact_upto, &at);
        exact->rasterize(&t, &p, &ex->exact, NULL);
    }
    return true;
}

/* An exhibit with a front end of its own (lesson 06) makes other triangles
 * than variants[0]: its exact picture is the whole scene as variants[0]
 * projects and draws it, compared once every triangle is finished. */
static bool own_front(const struct explorer *ex)
{
    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    return ex->scene.world.camera_line
           && lesson_front(ex->lesson, v) != lesson_front(ex->lesson, ex->lesson->variants);
}

/* An exhibit of a scene-level lesson whose units come in an order of their
 * own (lesson 07's `unordered`: a tile's triangles in another order than
 * the scene's) is compared the same way: drawn unit after unit in the
 * exhibit's order, the exact picture would take the exhibit's order too,
 * and the diff would show nothing. -1: out of memory. */
static int own_order(struct explorer *ex)
{
    if (ex->own_order >= 0)
        return ex->own_order;
    if (!ex->replay.units_fn || !ex->replay.units || ex->variant == 0)
        return ex->own_order = 0;
    long n = ex->replay.ntris;
    struct lesson_unit *u = malloc((size_t)(n > 0 ? n : 1) * sizeof *u);
    long m = u ? ex->replay.units_fn(ex->replay.scene, ex->lesson->variants, &ex->replay.params, u, n) : -1;
    bool same = m == n;
    for (long i = 0; same && i < n; i++)
        same = u[i].tri == ex->replay.units[i].tri && u[i].tile == ex->replay.units[i].tile;
    free(u);
    return m < 0 ? -1 : (ex->own_order = !same);
}

static bool exact_whole_scene(struct explorer *ex)
{
    if (ex->exact_upto == INT_MAX)
        return true;
    struct scene s;
    if (!scene_copy(&s, &ex->scene))
        return false;
    const struct lesson_variant *v0 = &ex->lesson->variants[0];
    struct raster_params p = ex->params;
    p.at = &(struct run_place){ .scene = &s };
    target_free(&ex->exact);
    bool ok = lesson_front(ex->lesson, v0)(&s) && render_scene(&s, v0, &p, &ex->exact);
    scene_free(&s);
    ex->exact_upto = ok ? INT_MAX : -1;
    return ok;
}

/* An exhibit: compare the coverage counts of the finished triangles with
 * what variants[0] gives for the same triangles. */
struct exact_mask {
    uint8_t *m;
    int w;
};

static void mark_exact(void *ctx, int x, int y)
{
    struct exact_mask *e = ctx;
    e->m[(size_t)y * (size_t)e->w + (size_t)x] = 1;
}

/* The triangle being drawn, compared as it writes (writes only add): a
 * pixel written more often than the exact rule covers it is extra, one
 * written as often in another colour or depth than the exact rule's is
 * wrong, both at the step that writes them; a missing one shows at the end. */
static bool extra_so_far(struct explorer *ex)
{
    size_t n = (size_t)ex->scene.w * (size_t)ex->scene.h;
    uint8_t *exact = calloc(n, 1);
    if (!exact)
        return false;
    reference_coverage(&ex->tri, mark_exact, &(struct exact_mask){ exact, ex->scene.w });
    struct target with = { 0 };     /* the exact picture with this triangle too */
    struct run_place at;
    struct raster_params p = replay_params(&ex->replay, ex->cur, &at);
    bool shaded = target_copy(&with, &ex->exact);
    if (shaded)
        ex->lesson->variants[0].rasterize(&ex->tri, &p, &with, NULL);
    bool other_depth = ex->lesson->variants[ex->variant].other_depth;
    for (size_t i = 0; i < n; i++) {
        int now = ex->fb.count[i] - ex->replay.base.count[i];
        if (ex->diff[i] == 0 && now > exact[i])     /* an earlier verdict stands */
            ex->diff[i] = EXHIBIT_EXTRA, ex->extra++;
        else if (ex->diff[i] == 0 && shaded && now > 0 && ex->fb.count[i] == with.count[i]
                 && !pixel_close(with.color[i], other_depth ? ex->fb.depth[i] : with.depth[i],
                                 ex->fb.color[i], ex->fb.depth[i]))
            ex->diff[i] = EXHIBIT_COLOUR, ex->wrong_colour++;
    }
    target_free(&with);
    free(exact);
    return true;
}

static bool compare_exhibit(struct explorer *ex)
{
    ex->extra = ex->missing = ex->wrong_colour = 0;
    ex->diff_done = 0;
    if (!variant_against_exact(&ex->lesson->variants[ex->variant]))
        return true;
    size_t n = (size_t)ex->scene.w * (size_t)ex->scene.h;
    if (!ex->diff && !(ex->diff = malloc(n)))
        return false;
    int done = explorer_finished(ex);
    /* the picture of exactly the finished triangles */
    const struct target *have_fb = ex->cur >= 0 && done > ex->cur ? &ex->fb : &ex->replay.base;
    const uint8_t *count = have_fb->count;
    int order = own_order(ex);
    if (order < 0)
        return false;
    if (own_front(ex) || order) {
        if (done < ex->replay.ntris) {      /* other triangles or another order: only the whole picture compares */
            memset(ex->diff, 0, n);
            return true;
        }
        if (!exact_whole_scene(ex))
            return false;
    } else if (!advance_exact(ex, done)) {
        return false;
    }
    ex->diff_done = done;
    bool other_depth = ex->lesson->variants[ex->variant].other_depth;
    for (size_t i = 0; i < n; i++) {
        int have = count ? count[i] : 0, want = ex->exact.count[i];
        /* a buffer holding another depth than z (lesson 06's storages) is
         * compared by its colours */
        float want_z = other_depth ? have_fb->depth[i] : ex->exact.depth[i];
        bool colour = have == want && want > 0
            && !pixel_close(ex->exact.color[i], want_z, have_fb->color[i], have_fb->depth[i]);
        ex->diff[i] = have > want ? EXHIBIT_EXTRA : have < want ? EXHIBIT_MISSING
                    : colour ? EXHIBIT_COLOUR : 0;
        ex->extra += have > want;
        ex->missing += have < want;
        ex->wrong_colour += colour;
    }
    return ex->cur >= 0 && done == ex->cur ? extra_so_far(ex) : true;
}

bool explorer_set_step(struct explorer *ex, uint64_t step)
{
    if (step > ex->replay.total)
        step = ex->replay.total;
    ex->step = step;
    uint64_t local;
    int cur = replay_locate(&ex->replay, step, &local);
    ex->has_last = false;
    for (size_t i = 0; i < sizeof ex->told / sizeof ex->told[0]; i++)
        ex->told[i].kind = TRACE_KIND_COUNT;
    ex->focus = cur >= 0 ? replay_unit_tri(&ex->replay, cur) : 0;
    memset(&ex->tri, 0, sizeof ex->tri);
    if (ex->scene.ntris > 0 && ex->replay.ntris > 0)
        replay_setup(&ex->replay, cur >= 0 ? cur : 0, &ex->tri);
    if (!prepare_cells(ex, cur >= 0 ? &ex->tri : &(struct tri_setup){ .minx = 1, .maxx = 0 }))
        return false;
    int got = replay_to(&ex->replay, step, &ex->fb, take_event, ex, &ex->tri_c);
    if (got < -1)
        return false;
    ex->cur = got;
    ex->local = local;
    return compare_exhibit(ex);
}

/* --- variants, params, vertices ---------------------------------------------- */

/* Run the lessons named by lesson->compare on the same scene and params. */
static bool compare_init(struct explorer *ex)
{
    for (int i = 0; ex->lesson->compare && ex->lesson->compare[i] && i < LESSON_COMPARE_MAX; i++)
        for (int k = 0; all_lessons[k]; k++)
            if (strcmp(all_lessons[k]->id, ex->lesson->compare[i]) == 0) {
                struct raster_params p = lesson_params_as(all_lessons[k], ex->lesson, &ex->params);
                if (!(ex->count_later ? replay_begin : replay_init)(
                        &ex->compare_replay[ex->ncompare], &ex->scene,
                        &all_lessons[k]->variants[0], &p)) {
                    replay_free(&ex->compare_replay[ex->ncompare]);
                    return false;
                }
                ex->compare[ex->ncompare++] = all_lessons[k];
            }
    return true;
}

static bool compare_recount(struct explorer *ex)
{
    for (int i = 0; i < ex->ncompare; i++) {
        ex->compare_replay[i].params = lesson_params_as(ex->compare[i], ex->lesson, &ex->params);
        ex->compare_replay[i].scene = &ex->scene;
        if (!(ex->count_later ? replay_restart(&ex->compare_replay[i])
                              : replay_recount(&ex->compare_replay[i])))
            return false;
    }
    return true;
}

/* --- counting a part at a time ------------------------------------------------- */

static double now_ms(void)
{
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* Triangles counted between two looks at the clock. */
#define COUNT_BATCH 256

bool explorer_counting(const struct explorer *ex)
{
    if (!replay_counted(&ex->replay))
        return true;
    for (int i = 0; i < ex->ncompare; i++)
        if (!replay_counted(&ex->compare_replay[i]))
            return true;
    return false;
}

bool explorer_count(struct explorer *ex, double ms)
{
    double until = now_ms() + ms;
    for (int i = -1; i < ex->ncompare; i++) {
        struct replay *r = i < 0 ? &ex->replay : &ex->compare_replay[i];
        while (!replay_counted(r)) {
            if (!replay_count(r, COUNT_BATCH))
                return false;
            if (now_ms() >= until)
                return true;
        }
    }
    return true;
}

/* Count the lesson's own run at least as far as `step` (all of it unless
 * counting later). */
static bool count_to(struct explorer *ex, uint64_t step)
{
    if (!ex->count_later)
        return replay_count(&ex->replay, INT_MAX);
    while (!replay_counted(&ex->replay) && ex->replay.total < step)
        if (!replay_count(&ex->replay, COUNT_BATCH))
            return false;
    return true;
}

/* A 3-D scene's screen triangles as the current variant makes them (an
 * exhibit may make them its own way): made again only when the variant's
 * way differs from the one that made them, so dragged vertices stay. */
static bool project_scene(struct explorer *ex)
{
    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    ex->at = (struct run_place){ .scene = &ex->scene };
    ex->params.at = &ex->at;
    front_fn f = lesson_front(ex->lesson, v);
    if (!ex->scene.world.camera_line || f == ex->projected_by)
        return true;
    ex->projected_by = f;
    ex->focus = 0;
    return ex->projected_by(&ex->scene);
}

/* A variant that draws the whole scene at once (lesson 07's, lesson 08's
 * tiles) steps through that run's own units; the others, triangles. */
static lesson_units_fn units_of(const struct explorer *ex)
{
    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    return lesson_scene_fn(ex->lesson, v) ? ex->lesson->narration_units : NULL;
}

/* The lesson's own run, first counted (at least as far as `step`), keeping
 * pictures along the way for stepping back. */
static bool begin_replay(struct explorer *ex, uint64_t step)
{
    if (!replay_begin_units(&ex->replay, &ex->scene, &ex->lesson->variants[ex->variant],
                            &ex->params, units_of(ex)))
        return false;
    replay_keep_pictures(&ex->replay);
    return count_to(ex, step);
}

/* The scene, variant or params changed: count again, keep the step. */
static bool rerun(struct explorer *ex, uint64_t step)
{
    if (!project_scene(ex))
        return false;
    ex->replay.variant = &ex->lesson->variants[ex->variant];
    ex->replay.units_fn = units_of(ex);
    ex->replay.params = ex->params;
    ex->replay.scene = &ex->scene;
    if (!replay_restart(&ex->replay) || !count_to(ex, step) || !compare_recount(ex))
        return false;
    ex->marks_tri = -1;
    ex->exact_upto = -1;
    ex->own_order = -1;
    return explorer_set_step(ex, step);
}

bool explorer_set_variant(struct explorer *ex, int index)
{
    if (index < 0 || index >= ex->lesson->nvariants)
        return false;
    ex->variant = index;
    return rerun(ex, ex->step);
}

bool explorer_set_theme(struct explorer *ex, enum theme t)
{
    theme_background(ex, t);
    target_free(&ex->scratch);      /* made again, on the new background */
    return rerun(ex, ex->step);
}

bool explorer_set_params(struct explorer *ex, const struct raster_params *p)
{
    ex->params = *p;
    ex->params.checker = ex->scene.checker;
    return rerun(ex, ex->step);
}

/* The next variant after the current one shown against the exact rule (want) or not. */
static int next_variant(const struct explorer *ex, bool want)
{
    for (int i = ex->variant + 1; i < ex->lesson->nvariants; i++)
        if (variant_against_exact(&ex->lesson->variants[i]) == want)
            return i;
    return 0;
}

bool explorer_cycle_exhibit(struct explorer *ex)
{
    int next = next_variant(ex, true);
    if (next == ex->variant)
        return true;
    uint64_t step = ex->step;
    if (next != 0 && ex->scene_is_default && ex->lesson->exhibit_scene) {
        /* the exhibits are made to be seen on the lesson's exhibit scene */
        struct scene s;
        char err[256];
        bool ok = scene_builtin(&s, ex->lesson->exhibit_scene, err, sizeof err);
        if (ok && !front_scene(&s)) {   /* a 3-D scene: its screen triangles */
            scene_free(&s);
            ok = false;
        }
        if (ok) {
            scene_free(&ex->scene);
            ex->scene = s;
            ex->projected_by = front_scene;
            ex->scene_is_default = false;
            snprintf(ex->scene_name, sizeof ex->scene_name, "builtin:%s", ex->lesson->exhibit_scene);
            ex->params.checker = s.checker;
            ex->zoom = 0;
            ex->pinned = false;     /* its pixel may lie outside the new scene */
            ex->hover_vertex = -1;
            target_free(&ex->fb);
            target_free(&ex->scratch);
            free(ex->diff);
            ex->diff = NULL;
            step = UINT64_MAX;      /* show the whole run: the result is the point */
        }
    }
    ex->variant = next;
    if (!rerun(ex, step))
        return false;
    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    snprintf(ex->message, sizeof ex->message, "%s: %s", v->name, v->what);
    return true;
}

bool explorer_cycle_twin(struct explorer *ex)
{
    int next = next_variant(ex, false);
    if (next == ex->variant)
        return true;
    if (!explorer_set_variant(ex, next))
        return false;
    const struct lesson_variant *v = &ex->lesson->variants[ex->variant];
    snprintf(ex->message, sizeof ex->message, "%s: %s", v->name, v->what);
    return true;
}

bool explorer_move_vertex(struct explorer *ex, int k, double x, double y)
{
    if (ex->scene.ntris == 0 || k < 0 || k > 2)
        return true;
    int sk = ex->tri.swapped && k > 0 ? 3 - k : k;     /* setup exchanged B and C */
    struct vertex *v = &ex->scene.tris[ex->focus].v[sk];
    double lim = COORD_LIMIT - 1.0 / SUBPIXEL_ONE;
    x = fmin(fmax(x, -COORD_LIMIT), lim);
    y = fmin(fmax(y, -COORD_LIMIT), lim);
    x = (double)lrint(x * SUBPIXEL_ONE) / SUBPIXEL_ONE;
    y = (double)lrint(y * SUBPIXEL_ONE) / SUBPIXEL_ONE;
    double ox = v->x, oy = v->y;
    if (x == ox && y == oy)
        return true;
    if (ex->scene.world.camera_line) {
        /* a 3-D scene: the model's vertex moves, and the front end runs again */
        if (!front_move_vertex(&ex->scene, ex->focus, ox, oy, x, y)) {
            snprintf(ex->message, sizeof ex->message,
                     "%c is not a vertex of the model (the clipper made it): drag one that is",
                     "ABC"[k]);
            return true;
        }
        ex->projected_by = NULL;
        return rerun(ex, ex->step);
    }
    for (int i = 0; i < ex->scene.ntris; i++)
        for (int j = 0; j < 3; j++) {
            struct vertex *u = &ex->scene.tris[i].v[j];
            if (u->x == ox && u->y == oy)
                u->x = x, u->y = y;
        }
    return rerun(ex, ex->step);
}

/* --- life ------------------------------------------------------------------------ */

bool explorer_init(struct explorer *ex, const struct explorer_desc *d, char *err, size_t errlen)
{
    memset(ex, 0, sizeof *ex);
    ex->lesson = d->lesson;
    ex->scene_is_default = d->scene_is_default;
    snprintf(ex->scene_name, sizeof ex->scene_name, "%s", d->scene_name ? d->scene_name : "scene");
    ex->params = d->params ? *d->params : (struct raster_params){ .subpixel_bits = SUBPIXEL_BITS };
    const char *id = d->lesson ? d->lesson->id : "explorer";
    if (!d->lesson || !(d->scene || d->give_scene)) {
        snprintf(err, errlen, "%s: no %s to explore", id, d->lesson ? "scene" : "lesson");
        return false;
    }
    bool ours = !d->variant;
    for (int i = 0; i < d->lesson->nvariants; i++)
        ours |= d->variant == &d->lesson->variants[i];
    if (!ours) {
        snprintf(err, errlen, "%s: variant '%s' is not one of this lesson's", id, d->variant->name);
        return false;
    }
    ex->side = d->side ? d->side : lesson_explorer_of(d->lesson);
    ex->variant = d->variant ? (int)(d->variant - d->lesson->variants) : 0;
    ex->edge = -1;
    ex->zoom = d->zoom;
    ex->scale = d->scale > 0 ? d->scale : 1;
    ex->theme = d->theme;
    ex->part = d->part;
    ex->speed = 8;              /* 16 events per second */
    ex->marks_tri = -1;
    ex->exact_upto = -1;
    ex->own_order = -1;
    ex->hover_vertex = -1;
    ex->count_later = d->count_later;
    const char *failed = NULL;
    const struct scene *given = d->give_scene ? d->give_scene : d->scene;
    int w = given->w, h = given->h, n = given->ntris;
    if (d->give_scene) {
        ex->scene = *d->give_scene;             /* handed over: no copy of its triangles */
        memset(d->give_scene, 0, sizeof *d->give_scene);
    } else if (!scene_copy(&ex->scene, d->scene)) {
        failed = "copying the scene";
    }
    if (!failed) {
        ex->params.checker = ex->scene.checker;
        memcpy(ex->own_background, ex->scene.background, sizeof ex->own_background);
        theme_background(ex, d->theme);
        ex->centre_x = ex->scene.w / 2.0;
        ex->centre_y = ex->scene.h / 2.0;
        uint64_t step = d->step_end ? UINT64_MAX : d->step;
        if (!project_scene(ex))
            failed = "projecting the 3-D scene";
        else if (!begin_replay(ex, step))
            failed = "counting the scene's events";
        else if (!compare_init(ex))
            failed = "running the lessons compared with this one";
        else if (!explorer_set_step(ex, step))
            failed = "drawing the first step";
    }
    if (!failed)
        return true;
    snprintf(err, errlen, "%s: out of memory %s (%d x %d pixels, %d triangles)", id, failed,
             w, h, n);
    explorer_free(ex);
    return false;
}

void explorer_free(struct explorer *ex)
{
    replay_free(&ex->replay);
    for (int i = 0; i < ex->ncompare; i++)
        replay_free(&ex->compare_replay[i]);
    target_free(&ex->fb);
    target_free(&ex->scratch);
    target_free(&ex->exact);
    free(ex->cells);
    free(ex->marks);
    free(ex->diff);
    scene_free(&ex->scene);
    memset(ex, 0, sizeof *ex);
}
