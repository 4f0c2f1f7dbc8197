/* Lesson 01: scanline gradient filling.
 *
 * What it shows: the 1990s way to fill a triangle (the 1994 tutorial, "Triangles -
 * Rendering", 1994). Take the top vertex first, walk the left and the right
 * edge down the screen one scanline at a time, and fill the span between
 * them; colour and depth change by a constant amount from one pixel to the
 * next (Gouraud shading with a z-buffer). Nothing is tested pixel by pixel:
 * every pixel written is known to be inside before it is reached.
 *
 * New here (this is the first lesson): what the 1994 text leaves out and an
 * exact rasterizer needs. The edges are walked in fixed point with an exact
 * error term instead of a float increment, each edge starts with a prestep
 * to the first pixel centre below its top vertex, each span starts with a
 * prestep to the first pixel centre right of its left edge, and a centre
 * exactly on an edge is decided by the top-left rule. With those, every
 * pixel is decided exactly as lesson 02 decides it by testing.
 *
 * The formulas of the 1994 tutorial, numbered here in the order the text prints them
 * (c is any vertex attribute: red, green, blue, z; 1 is the top vertex):
 *
 *        (c2-c1)(y3-y1) - (c3-c1)(y2-y1)
 *   Dc = -------------------------------      (1)  change of c per pixel in x,
 *        (x2-x1)(y3-y1) - (x3-x1)(y2-y1)           the same across the triangle
 *
 *   Dc12 = (c2-c1) / (y2-y1)                  (2)  change of c per pixel in y
 *   Dc13 = (c3-c1) / (y3-y1)                  (3)  along the edges 1-2, 1-3
 *   Dc23 = (c3-c2) / (y3-y2)                  (4)  and 2-3 (x too: c = x)
 *
 *   x_A = x1 + (y2-y1) * Dx13   case [B]      (5)  point A of "Draw X": where
 *   x_A = x1 + (y3-y1) * Dx12   case [A]      (5') the long edge passes the
 *                                                  middle vertex's height
 *                                                  (Dx: formulas (2)-(4) with c = x)
 *
 * The tutorial prints (5) as "A = (1) + (y2-y1) * Dc13", meaning vertex 1 by
 * "(1)", and gives case [B] only.
 *
 * The denominator of (1) is the cross product |12 x 13|: twice the signed
 * area. tri_setup has already ordered the vertices so that it is positive
 * (clockwise on this y-down screen), and a cyclic rotation keeps it so.
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_scaled: the colour every lesson gives a pixel */

static const char *const pseudocode[] = {
    "snap; rotate so 1 is the top vertex, order kept",       /* 0 */
    "case [A] if y2 > y3 (3 on the left), else [B]",         /* 1 */
    "Dc = ((c2-c1)(y3-y1) - (c3-c1)(y2-y1)) / area2",        /* 2 */
    "edges: x and c step by Dx, Dc12, Dc13, Dc23 a row",     /* 3 */
    "for each row whose centre is in [y1, y_bottom):",       /* 4 */
    "  xl, xr = left, right edge x at the row's centre",     /* 5 */
    "  x0 = first centre >= xl; c = c(xl) + Dc (x0 - xl)",   /* 6 */
    "  fill x0 .. last centre < xr: pixel = c; c += Dc",     /* 7 */
    "  step both edges one row (quotient + error term)",     /* 8 */
    NULL,
};

enum { L_SORT, L_CASE, L_GRAD, L_EDGES, L_ROWS, L_ROW, L_PRESTEP, L_FILL, L_STEP };

/* The attributes interpolated: depth, colour, texture coordinates. */
enum { ATTR_Z, ATTR_R, ATTR_G, ATTR_B, ATTR_S, ATTR_T, ATTR_COUNT };

/* A vertex as the walk needs it: snapped position (1/256 px) and attributes,
 * the colour already times 255 and s, t times the checker's N, so that a
 * pixel is written as it is stepped: additions only (shade_scaled). */
struct point {
    int64_t x, y;
    double c[ATTR_COUNT];
};

#define POINT_OF_COST { .mul = 5, .add = 0 }     /* r, g, b times 255; s, t times N */

static struct point point_of(const struct tri_setup *t, const struct raster_params *p, int i)
{
    const struct vertex *v = &t->v[i];
    double n = shade_scale_st(p);
    return (struct point){
        .x = t->x[i], .y = t->y[i],
        .c = { v->z, SHADE_SCALE_RGB * v->r, SHADE_SCALE_RGB * v->g, SHADE_SCALE_RGB * v->b,
               n * v->s, n * v->t },
    };
}

/* The first pixel row whose centre y + 0.5 is at or below y (1/256 px).
 * Rows [row_at(y_top), row_at(y_bottom)) are the triangle's rows: a centre
 * exactly on the top vertex's height is in, on the bottom one's out. */
static int64_t row_at(int64_t y)
{
    return ceil_div(y - SUBPIXEL_HALF, SUBPIXEL_ONE);
}

/* --- walking one edge ---------------------------------------------------------
 *
 * An edge from p (top) to q (bottom), dy = qy - py > 0, dx = qx - px. On the
 * centre line of row r, yc = 256 r + 128, it lies at
 *
 *     x(yc) = px + dx (yc - py) / dy                      (1/256 px)
 *
 * and the first pixel column whose centre 256 X + 128 is at or right of it is
 *
 *     X = ceil( (x(yc) - 128) / 256 ) = ceil( num / den ),
 *     num = (px - 128) dy + dx (yc - py),   den = 256 dy.
 *
 * That one number serves both sides of a span: the span is X_left .. X_right-1,
 * so a centre exactly on the left edge is in and one exactly on the right
 * edge is out -- the top-left rule for the two slanted edges of a row.
 *
 *        row r    . . . | . o o o o o o | . .      o: centres in the span
 *                       |\             /|          |: edge crossings at yc
 *                   xl -' `- X_left    `- xr = X_right lies at or right of xr
 *
 * One row down, num grows by 256 dx = q den + r with 0 <= r < den, so X grows
 * by q or q + 1: Bresenham's error term, exact, no division per row. We keep
 * err = X den - num (0 <= err < den): the first centre lies err/den pixels
 * right of the edge, which is the span's prestep. */
struct edge {
    int64_t x;                  /* X: first column at or right of the edge, this row */
    int64_t err;                /* X den - num, 0 <= err < den */
    int64_t den;                /* 256 dy */
    int64_t q, r;               /* one row down: X += q, err -= r (carry: X += 1) */
    double c[ATTR_COUNT];       /* the attributes where the edge crosses the centre line */
    double dc[ATTR_COUNT];      /* their change per row: Dc12, Dc13 or Dc23, (2)-(4) */
};

/* Start walking the edge p -> q on row `row` (whose centre is on the edge's
 * height): the prestep from p down to the row's centre, exactly. Costs: the
 * position (num, den, X, err, q, r) and each attribute's Dc and value. */
#define EDGE_START_COST { .mul = 6, .add = 6 }
#define EDGE_START_ATTR_COST { .mul = 2, .add = 2 }

static void edge_start(struct edge *e, const struct point *p, const struct point *q, int64_t row)
{
    int64_t dx = q->x - p->x, dy = q->y - p->y;
    int64_t yc = pixel_centre((int)row);
    int64_t num = (p->x - SUBPIXEL_HALF) * dy + dx * (yc - p->y);
    e->den = SUBPIXEL_ONE * dy;
    e->x = ceil_div(num, e->den);
    e->err = e->x * e->den - num;
    e->q = floor_div(dx, dy);
    e->r = SUBPIXEL_ONE * (dx - e->q * dy);

    double height = (double)dy / SUBPIXEL_ONE;               /* y2 - y1 in pixels */
    double prestep = (double)(yc - p->y) / SUBPIXEL_ONE;     /* p down to the centre */
    for (int i = 0; i < ATTR_COUNT; i++) {
        e->dc[i] = (q->c[i] - p->c[i]) / height;             /* (2), (3) or (4) */
        e->c[i] = p->c[i] + e->dc[i] * prestep;
    }
}

/* One row down the edge. Cost: X, err and the carry, then each attribute
 * (PLANE_STEP_COST). */
#define EDGE_WALK_STEP_COST { .mul = 0, .add = 3 }

static void edge_step(struct edge *e)
{
    e->x += e->q;
    e->err -= e->r;
    if (e->err < 0) {           /* the error ran past a whole column: carry */
        e->x += 1;
        e->err += e->den;
    }
    for (int i = 0; i < ATTR_COUNT; i++)
        e->c[i] += e->dc[i];
}

/* --- the triangle ---------------------------------------------------------------
 *
 * The 1994 tutorial's two cases, after rotating the vertices so that 1 is on top
 * (tri_setup made the order clockwise on screen, so 1 -> 2 runs down the
 * right side and 3 -> 1 up the left side):
 *
 *        [A]  y2 > y3                  [B]  y3 >= y2
 *
 *             1                              1
 *            / \                            / \
 *           /   \  upper half              /   \
 *          3 ... A  - - - - - -           A ... 2
 *            `.   \  lower half          /   .'
 *               `. \                    / .'
 *                 `.\                  /.'
 *                    2                3
 *
 *     (the long edge runs straight from 1 to the bottom vertex; A is the
 *     point on it at the middle vertex's height)
 *
 *     left: 1-3 then 3-2 (short)     left: 1-3 (long)
 *     right: 1-2 (long)              right: 1-2 then 2-3 (short)
 *
 * The long edge is walked once from top to bottom; the short side changes
 * edge at the middle vertex's height. A flat top or flat bottom simply gives
 * one half no rows. */
struct corners {
    struct point p1, p2, p3;            /* 1 on top, then in setup's (clockwise) order */
    bool case_a;                        /* [A]: 3 is the middle vertex, on the left */
    const struct point *mid, *bottom;   /* the long edge runs from p1 to bottom */
};

/* "1 is the top point (reordination cycling included)": the start of both
 * readings of the 1994 tutorial, the exact walk and the exhibit. */
static void corners_of(struct corners *k, const struct tri_setup *t,
                       const struct raster_params *p)
{
    int top = 0;
    if (t->y[1] < t->y[top])
        top = 1;
    if (t->y[2] < t->y[top])
        top = 2;
    k->p1 = point_of(t, p, top);
    k->p2 = point_of(t, p, (top + 1) % 3);
    k->p3 = point_of(t, p, (top + 2) % 3);
    k->case_a = k->p2.y > k->p3.y;
    k->mid = k->case_a ? &k->p3 : &k->p2;
    k->bottom = k->case_a ? &k->p2 : &k->p3;
}

struct gradient {
    double dc[ATTR_COUNT];      /* Dc, formula (1), per pixel in x */
};

/* Cost of formula (1) for one attribute: two products, the scale to pixels
 * and the division by area2. */
#define GRADIENT_COST { .mul = 4, .add = 3 }

static struct gradient gradient_of(const struct tri_setup *t, const struct point *p1,
                                   const struct point *p2, const struct point *p3)
{
    /* (1): both products are in 1/256 px; area2 is in 1/65536 px^2 */
    struct gradient g;
    double y21 = (double)(p2->y - p1->y), y31 = (double)(p3->y - p1->y);
    for (int i = 0; i < ATTR_COUNT; i++) {
        double num = (p2->c[i] - p1->c[i]) * y31 - (p3->c[i] - p1->c[i]) * y21;
        g.dc[i] = num * SUBPIXEL_ONE / (double)t->area2;
    }
    return g;
}

/* fill(left, right): one span, the pixels whose centres lie in [xl, xr).
 * Costs of the prestep across: the distance from the edge, then each
 * attribute's value there. */
#define PRESTEP_COST { .mul = 1, .add = 2 }
#define PRESTEP_ATTR_COST { .mul = 1, .add = 1 }

static void fill(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
                 struct trace *tr, int64_t row, const struct edge *left,
                 const struct edge *right, const struct gradient *g)
{
    int y = (int)row;
    int64_t x0 = left->x > t->minx ? left->x : t->minx;           /* clipped to the target */
    int64_t x1 = right->x - 1 < t->maxx ? right->x - 1 : t->maxx;

    /* prestep across: from the left edge to the centre of column x0 */
    double across = (double)left->err / (double)left->den + (double)(x0 - left->x);
    double c[ATTR_COUNT];
    for (int i = 0; i < ATTR_COUNT; i++)
        c[i] = left->c[i] + g->dc[i] * across;
    COUNT(tr, 1, PRESTEP_COST);
    COUNT(tr, ATTR_COUNT, PRESTEP_ATTR_COST);

    NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .span = L_ROW - L_ROWS, .x = (int32_t)x0, .y = y,
            .x1 = (int32_t)x1, .y1 = y);
    if (x0 > x1)
        return;
    NARRATE(tr, .kind = TRACE_SPAN, .line = L_PRESTEP, .x = (int32_t)x0, .y = y, .x1 = (int32_t)x1, .y1 = y);

    for (int x = (int)x0; x <= (int)x1; x++) {
        uint32_t color = shade_scaled(p, tr, c[ATTR_R], c[ATTR_G], c[ATTR_B], c[ATTR_S], c[ATTR_T]);
        PLOT(fb, tr, L_FILL, x, y, (float)c[ATTR_Z], color);
        for (int i = 0; i < ATTR_COUNT; i++)
            c[i] += g->dc[i];
        COUNT(tr, ATTR_COUNT, PLANE_STEP_COST);
    }
}

static void rasterize(const struct tri_setup *t, const struct raster_params *p,
                      struct target *fb, struct trace *tr)
{
    NARRATE_SETUP(tr, t, L_SORT);
    if (t->empty)
        return;

    struct corners k;
    corners_of(&k, t, p);
    COUNT(tr, 3, POINT_OF_COST);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_CASE, .flags = k.case_a);
    struct gradient g = gradient_of(t, &k.p1, &k.p2, &k.p3);
    COUNT(tr, ATTR_COUNT, GRADIENT_COST);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_GRAD);

    /* rows [first, middle) use the upper short edge, [middle, end) the lower */
    int64_t first = row_at(k.p1.y), middle = row_at(k.mid->y), end = row_at(k.bottom->y);
    if (first < t->miny)
        first = t->miny;                        /* rows above the target are skipped */
    if (end > t->maxy + 1)
        end = t->maxy + 1;
    if (first >= end)
        return;

    struct edge long_edge;
    edge_start(&long_edge, &k.p1, k.bottom, first);
    COUNT(tr, 1, EDGE_START_COST);
    COUNT(tr, ATTR_COUNT, EDGE_START_ATTR_COST);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_EDGES, .x = (int32_t)long_edge.x, .y = (int32_t)first);

    for (int half = 0; half < 2; half++) {
        int64_t from = half == 0 ? first : (middle > first ? middle : first);
        int64_t to = half == 0 ? (middle < end ? middle : end) : end;
        if (from >= to)
            continue;
        struct edge short_edge;
        if (half == 0)
            edge_start(&short_edge, &k.p1, k.mid, from);
        else
            edge_start(&short_edge, k.mid, k.bottom, from);
        COUNT(tr, 1, EDGE_START_COST);
        COUNT(tr, ATTR_COUNT, EDGE_START_ATTR_COST);
        NARRATE(tr, .kind = TRACE_STEP, .line = L_EDGES, .x = (int32_t)short_edge.x, .y = (int32_t)from);
        struct edge *left = k.case_a ? &short_edge : &long_edge;
        struct edge *right = k.case_a ? &long_edge : &short_edge;

        for (int64_t row = from; row < to; row++) {
            fill(t, p, fb, tr, row, left, right, &g);
            edge_step(left);
            edge_step(right);
            COUNT(tr, 2, EDGE_WALK_STEP_COST);
            COUNT(tr, 2 * ATTR_COUNT, PLANE_STEP_COST);
            NARRATE(tr, .kind = TRACE_STEP, .line = L_STEP, .x = (int32_t)left->x, .y = (int32_t)row + 1,
                    .x1 = (int32_t)right->x - 1, .y1 = (int32_t)row + 1);
        }
    }
}

/* --- exhibit: the printed loop, read literally ---------------------------------
 *
 * The 1994 tutorial's triangle() with float coordinates: the same corners and halves
 * as the exact walk above, but each edge starts at its top vertex itself,
 * not at the first pixel centre below it, x moves by a float increment per
 * row, and the row count of a segment is its float height truncated. The
 * text does not print calc_seg_incr() and fill(); they are written here the
 * way its loop uses them:
 *
 *     calc_seg_incr(&sg, &p, &q):  sg.len = (int)(q.Ya - p.Ya);
 *                                  sg.incx = (q.Xa - p.Xa) / (q.Ya - p.Ya);
 *     fill(&g, &d):                for (x = g.Xa; x < d.Xa; x++) pixel((int)x, y);
 *
 * and the rows are counted from the top vertex: y = a.Ya, a.Ya + 1, ...
 * The result has gaps and doubly covered pixels where triangles meet (see
 * README.md for the count on the built-in scene "offgrid-strip"). */
struct seg {
    float Xa;                   /* x on the current row, from the top vertex p on */
    double c[ATTR_COUNT];       /* the attributes there */
    int len;                    /* rows in the segment: the float height, truncated */
    float incx;                 /* x per row */
    double inc[ATTR_COUNT];     /* attributes per row */
};

static struct seg calc_seg_incr(const struct point *p, const struct point *q)
{
    float pXa = (float)p->x / SUBPIXEL_ONE, pYa = (float)p->y / SUBPIXEL_ONE;
    float qXa = (float)q->x / SUBPIXEL_ONE, qYa = (float)q->y / SUBPIXEL_ONE;
    float h = qYa - pYa;
    struct seg sg = { .Xa = pXa, .len = (int)h, .incx = h > 0 ? (qXa - pXa) / h : 0.0f };
    for (int i = 0; i < ATTR_COUNT; i++) {
        sg.c[i] = p->c[i];
        sg.inc[i] = h > 0 ? (q->c[i] - p->c[i]) / h : 0.0;
    }
    return sg;
}

static void seg_step(struct seg *e)
{
    e->Xa += e->incx;
    for (int i = 0; i < ATTR_COUNT; i++)
        e->c[i] += e->inc[i];
}

static void fill_float(const struct tri_setup *t, const struct raster_params *p,
                       struct target *fb, struct trace *tr, float Ya,
                       const struct seg *g, const struct seg *d, const struct gradient *grad)
{
    int y = (int)floorf(Ya);
    NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .span = L_ROW - L_ROWS, .x = (int32_t)floorf(g->Xa),
            .y = y, .x1 = (int32_t)floorf(d->Xa), .y1 = y);
    if (y < 0 || y >= t->target_h || !(g->Xa < d->Xa))
        return;
    float x = g->Xa;
    if (x < 0)                  /* skip the part left of the target in one jump */
        x += ceilf(-x);
    double c[ATTR_COUNT];
    for (int i = 0; i < ATTR_COUNT; i++)
        c[i] = g->c[i] + grad->dc[i] * (double)(x - g->Xa);
    for (; x < d->Xa && x < (float)t->target_w; x += 1.0f) {
        uint32_t color = shade_scaled(p, tr, c[ATTR_R], c[ATTR_G], c[ATTR_B], c[ATTR_S], c[ATTR_T]);
        PLOT(fb, tr, L_FILL, (int)x, y, (float)c[ATTR_Z], color);
        for (int i = 0; i < ATTR_COUNT; i++)
            c[i] += grad->dc[i];
    }
}

static void rasterize_source(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr)
{
    NARRATE_SETUP(tr, t, L_SORT);
    if (t->empty)
        return;

    struct corners k;
    corners_of(&k, t, p);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_CASE, .flags = k.case_a);
    struct gradient grad = gradient_of(t, &k.p1, &k.p2, &k.p3);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_GRAD);

    float y = (float)k.p1.y / SUBPIXEL_ONE;     /* a.Ya: the top vertex's height */
    struct seg long_edge = calc_seg_incr(&k.p1, k.bottom);
    NARRATE(tr, .kind = TRACE_STEP, .line = L_EDGES);
    for (int half = 0; half < 2; half++) {
        struct seg short_edge = half == 0 ? calc_seg_incr(&k.p1, k.mid)
                                          : calc_seg_incr(k.mid, k.bottom);
        NARRATE(tr, .kind = TRACE_STEP, .line = L_EDGES);
        struct seg *g = k.case_a ? &short_edge : &long_edge;   /* left ("gauche") */
        struct seg *d = k.case_a ? &long_edge : &short_edge;   /* right ("droite") */
        for (int n = 0; n < short_edge.len; n++, y++) {
            fill_float(t, p, fb, tr, y, g, d, &grad);
            seg_step(g);
            seg_step(d);
            NARRATE(tr, .kind = TRACE_STEP, .line = L_STEP);
        }
    }
}

static const struct lesson_variant variants[] = {
    { .name = "exact", .kind = VARIANT_ALGORITHM, .rasterize = rasterize,
      .what = "fixed-point edges, exact presteps, top-left rule: equal to the reference" },
    { .name = "source-float", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_source,
      .what = "exhibit: the 1994 tutorial's float stepping without prestep: gaps and overlaps" },
};

const struct lesson lesson_01 = {
    .id = "01-scanline",
    .title = "Scanline gradient filling",
    .pseudocode = pseudocode,
    .builtin_scene = "cases-a-b",
    .exhibit_scene = "offgrid-strip",
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, PACK_SCALED_COST), COST_TERM(ATTR_COUNT, PLANE_STEP_COST), { 0 } },
    .exercise = { .write_line = L_FILL },
};
