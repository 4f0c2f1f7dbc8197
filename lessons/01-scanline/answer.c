/* Answer to exercise 01: the skeleton exercise.c with its TODO written as
 * README.md explains it; `make check LESSON=01
 * FILE=lessons/01-scanline/answer.c` passes every check.
 *
 * The one source of both: `make skeletons` writes exercise.c from this
 * file (the tests hold the committed one to it). Your parts are marked:
 * the lines between `#if SKELETON` and `#else` are the skeleton's, those
 * between `#else` and `#endif` (or under `#if !SKELETON`) the answer's.
 *
 * Exercise 01: write lesson 01's span walk yourself.
 *
 * Everything around the span is here, as scanline.c has it: the vertices
 * rotated so that 1 is on top, cases [A] and [B], the gradient Dc of
 * formula (1), and the two edges walked down the rows exactly (the prestep
 * down and the integer error term of README section 3). What is left is the
 * span itself: on each row, which pixels lie between the two edges, and
 * their colour and depth. As given, the file compiles, walks every row and
 * fills nothing.
 *
 *     make exercise LESSON=01        the explorer on this file: every row the
 *                                    walk narrates, every pixel you write,
 *                                    and the diff against the exact rule
 *     make check LESSON=01           the checks, simplest first
 *
 * The edge walker gives you, on each row, for the left and the right edge:
 *   e->x     X, the first pixel column whose centre is at or right of the
 *            edge's crossing of the row's centre line;
 *   e->err, e->den
 *            that centre lies err / den pixels right of the crossing
 *            (0 <= err < den): the prestep across;
 *   e->c[]   the attributes (ATTR_Z, ATTR_R, ATTR_G, ATTR_B, ATTR_S, ATTR_T)
 *            at the crossing.
 * and g->dc[] is Dc of formula (1): the change of each attribute per pixel
 * to the right. */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

/* Lines of lesson 01's pseudo-code, which the explorer lights (scanline.c). */
enum { L_SORT, L_CASE, L_GRAD, L_EDGES, L_ROWS, L_ROW, L_PRESTEP, L_FILL, L_STEP };

enum { ATTR_Z, ATTR_R, ATTR_G, ATTR_B, ATTR_S, ATTR_T, ATTR_COUNT };

struct point {
    int64_t x, y;               /* 1/256 px */
    double c[ATTR_COUNT];
};

struct edge {
    int64_t x, err, den;        /* see above */
    int64_t q, r;               /* one row down: x += q, err -= r, carry */
    double c[ATTR_COUNT];
    double dc[ATTR_COUNT];      /* per row: Dc12, Dc13 or Dc23 */
};

struct gradient {
    double dc[ATTR_COUNT];      /* Dc, formula (1), per pixel to the right */
};

/* TODO, README section 3 ("The fill rule on the span") and section 4: fill
 * row y between the two edges.
 *   - The span is the columns left->x .. right->x - 1: centres at or right
 *     of the left edge, strictly left of the right edge. A centre exactly on
 *     the right edge belongs to the triangle on the other side of it; draw
 *     it here too and it is drawn twice.
 *   - Keep to the target: columns t->minx .. t->maxx. A triangle may reach
 *     past the screen's sides; a write outside it is an error.
 *   - The prestep across: the first pixel you fill, x0, lies
 *     left->err / left->den + (x0 - left->x) pixels right of the left
 *     crossing, so its attribute i is left->c[i] + g->dc[i] * that distance
 *     (divide in double). Start at left->c[i] itself and every pixel is
 *     shifted by up to a pixel's worth of colour.
 *   - Then, pixel by pixel: write it and add g->dc[i] to every attribute:
 *         target_write(fb, x, y, (float)c[ATTR_Z],
 *                      shade_pixel(p, tr, c[ATTR_R], c[ATTR_G], c[ATTR_B], c[ATTR_S], c[ATTR_T]));
 */
static void span(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                 struct trace *tr, int y, const struct edge *left, const struct edge *right, const struct gradient *g)
{
#if SKELETON
    (void)t, (void)p, (void)fb, (void)tr, (void)y, (void)left, (void)right, (void)g;
#else
    int64_t x0 = left->x > t->minx ? left->x : t->minx;
    int64_t x1 = right->x - 1 < t->maxx ? right->x - 1 : t->maxx;
    double across = (double)left->err / (double)left->den + (double)(x0 - left->x);
    double c[ATTR_COUNT];
    for (int i = 0; i < ATTR_COUNT; i++)
        c[i] = left->c[i] + g->dc[i] * across;
    for (int64_t x = x0; x <= x1; x++) {
        target_write(fb, (int)x, y, (float)c[ATTR_Z],
                     shade_pixel(p, tr, c[ATTR_R], c[ATTR_G], c[ATTR_B], c[ATTR_S], c[ATTR_T]));
        for (int i = 0; i < ATTR_COUNT; i++)
            c[i] += g->dc[i];
    }
#endif
}

/* --- the walk, as scanline.c writes it ------------------------------------------ */

static struct point point_of(const struct tri_setup *t, int i)
{
    const struct vertex *v = &t->v[i];
    return (struct point){ t->x[i], t->y[i], { v->z, v->r, v->g, v->b, v->s, v->t } };
}

/* The first row whose centre is at or below y (1/256 px); ceil_div and
 * floor_div are raster.h's, correct for negative numbers. */
static int64_t row_at(int64_t y)
{
    return ceil_div(y - SUBPIXEL_HALF, SUBPIXEL_ONE);
}

/* Start the edge p -> q (p on top) on row `row`: the prestep down. */
static void edge_start(struct edge *e, const struct point *p, const struct point *q, int64_t row)
{
    int64_t dx = q->x - p->x, dy = q->y - p->y;
    int64_t yc = row * SUBPIXEL_ONE + SUBPIXEL_HALF;
    int64_t num = (p->x - SUBPIXEL_HALF) * dy + dx * (yc - p->y);
    e->den = SUBPIXEL_ONE * dy;
    e->x = ceil_div(num, e->den);
    e->err = e->x * e->den - num;
    e->q = floor_div(dx, dy);
    e->r = SUBPIXEL_ONE * (dx - e->q * dy);
    double height = (double)dy / SUBPIXEL_ONE, prestep = (double)(yc - p->y) / SUBPIXEL_ONE;
    for (int i = 0; i < ATTR_COUNT; i++) {
        e->dc[i] = (q->c[i] - p->c[i]) / height;            /* (2), (3) or (4) */
        e->c[i] = p->c[i] + e->dc[i] * prestep;
    }
}

/* One row down the edge: Bresenham's error term. */
static void edge_step(struct edge *e)
{
    e->x += e->q;
    e->err -= e->r;
    if (e->err < 0) {
        e->x += 1;
        e->err += e->den;
    }
    for (int i = 0; i < ATTR_COUNT; i++)
        e->c[i] += e->dc[i];
}

static struct gradient gradient_of(const struct tri_setup *t, const struct point *p1,
                                   const struct point *p2, const struct point *p3)
{
    struct gradient g;
    double y21 = (double)(p2->y - p1->y), y31 = (double)(p3->y - p1->y);
    for (int i = 0; i < ATTR_COUNT; i++) {
        double num = (p2->c[i] - p1->c[i]) * y31 - (p3->c[i] - p1->c[i]) * y21;
        g.dc[i] = num * SUBPIXEL_ONE / (double)t->area2;    /* (1) */
    }
    return g;
}

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr)
{
    NARRATE(tr, .kind = TRACE_SETUP, .line = L_SORT, .x = t->minx, .y = t->miny,
            .x1 = t->maxx, .y1 = t->maxy, .e = { t->area2, 0, 0 });
    if (t->empty)
        return;
    int top = 0;                                /* 1 is the top vertex */
    if (t->y[1] < t->y[top])
        top = 1;
    if (t->y[2] < t->y[top])
        top = 2;
    struct point p1 = point_of(t, top), p2 = point_of(t, (top + 1) % 3), p3 = point_of(t, (top + 2) % 3);
    bool case_a = p2.y > p3.y;                  /* [A]: 3 is the middle vertex, on the left */
    const struct point *mid = case_a ? &p3 : &p2, *bottom = case_a ? &p2 : &p3;
    struct gradient g = gradient_of(t, &p1, &p2, &p3);

    int64_t first = row_at(p1.y), middle = row_at(mid->y), end = row_at(bottom->y);
    if (first < t->miny)
        first = t->miny;
    if (end > t->maxy + 1)
        end = t->maxy + 1;
    if (first >= end)
        return;
    struct edge long_edge;
    edge_start(&long_edge, &p1, bottom, first);
    for (int half = 0; half < 2; half++) {
        int64_t from = half == 0 ? first : (middle > first ? middle : first);
        int64_t to = half == 0 ? (middle < end ? middle : end) : end;
        if (from >= to)
            continue;
        struct edge short_edge;
        edge_start(&short_edge, half == 0 ? &p1 : mid, half == 0 ? mid : bottom, from);
        struct edge *left = case_a ? &short_edge : &long_edge;
        struct edge *right = case_a ? &long_edge : &short_edge;
        for (int64_t row = from; row < to; row++) {
            NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = (int32_t)left->x, .y = (int32_t)row,
                    .x1 = (int32_t)right->x - 1, .y1 = (int32_t)row,
                    .aux = { (float)((double)left->x + 0.5 - (double)left->err / (double)left->den),
                             (float)((double)right->x + 0.5 - (double)right->err / (double)right->den),
                             (float)((double)left->err / (double)left->den) });
            span(t, p, fb, tr, (int)row, left, right, &g);
            edge_step(left);
            edge_step(right);
        }
    }
}
