/* Lesson 04: SIMD vectors of (1/z, w, u, v), perspective-correct.
 *
 * What it shows: the edge-function notes, section 4. Screen-space barycentrics are not
 * what a perspective camera needs: along a floor that recedes from the eye,
 * equal steps on the screen are ever larger steps on the floor. What IS
 * linear in screen space is 1/z (and a/z for any attribute a), so the lesson
 * steps 1/z next to the three edge values, recovers z = 1 / (1/z) at each
 * covered pixel and weights every attribute by 1/z (formula 23).
 *
 * The source packs the four linear quantities of one pixel into one SSE
 * register, (F00, F01, F02, F03) / Area2 = (1/z, w, u, v), and walks the
 * bounding box with one vector add per pixel (Cx += I) and one per row
 * (Cy += J). The walk is written once; each operation on the register is
 * written twice, side by side: with SSE intrinsics and as its scalar twin
 * on four floats (the tests hold the two equal). A second layout closes the
 * lesson: four PIXELS per register instead of four quantities of one pixel.
 *
 * New since lesson 03: the fourth lane (1/z, formulas 16 to 22), the
 * perspective-correct attributes (23), the depth test written the right way
 * round, and SIMD. What stays: lesson 03's exact integer edge stepping
 * decides coverage; the float lanes only interpolate.
 *
 *                  (1/z)  (w)   (u)   (v)
 *     Cx       = [ F00 | F01 | F02 | F03 ] / Area2     one pixel, one register
 *     I        = [ I00 | I01 | I02 | I03 ] / Area2     added once per pixel
 *     J        = [ J00 | J01 | J02 | J03 ] / Area2     added once per row
 *
 * Lanes as the text names them: w = F01 / Area2 is the weight of C (edge AB
 * is opposite C), u = F02 / Area2 the weight of A, v = F03 / Area2 that of B.
 */
#include "lesson.h"
#include "shade/shade.h"     /* shade_pixel: the colour every lesson gives a pixel */

static const char *const pseudocode[] = {
    "bounding box; I0k, J0k, K0k of the 3 edges",        /* 0 */
    "I00 = I02/ZA + I03/ZB + I01/ZC; J00, K00 alike",    /* 1: (19)-(21) */
    "F = (I X + J Y + K) / Area2, X, Y: 1st centre",     /* 2: (1/z, w, u, v) */
    "I = I / Area2;  J = J / Area2;  Cy = F",            /* 3 */
    "loop y = minY to maxY:  Cx = Cy",                   /* 4 */
    "  loop x = minX to maxX, Cx += I after each:",      /* 5 */
    "    if F01, F02, F03 inside (exact):",              /* 6: top-left rule */
    "      Depth = 1 / Cx[0]",                           /* 7 */
    "      if Depth < DepthBuffer(x, y):",               /* 8: the nearer wins */
    "        P = (u PA/ZA+v PB/ZB+w PC/ZC)*Depth",       /* 9: (23) */
    "        write Depth, colour of P",                  /* 10 */
    "  Cy += J",                                         /* 11 */
    NULL,
};

enum { L_BOX, L_DEPTH_EDGE, L_F, L_DIVIDE, L_ROW, L_PIXEL, L_TEST, L_DEPTH, L_ZTEST, L_ATTR,
       L_WRITE, L_STEP_Y };

/* The lanes, in the source's order. */
enum { LANE_INV_Z, LANE_W, LANE_U, LANE_V };

/* Attributes interpolated by (23): r, g, b, s, t, padded to two registers. */
enum { ATTR_R, ATTR_G, ATTR_B, ATTR_S, ATTR_T, ATTR_COUNT = 8 };

static const char *const aux_names[] = { "1/z", "w", "u", "v", "s", "t", NULL };

enum { P_AFFINE };  /* the lesson's parameter rows: p->knob[P_AFFINE] is --affine */

/* Everything the pixel loops need, computed once per triangle. */
struct persp_setup {
    /* (1/z, w, u, v) at the centre of (minX, minY), per pixel to the right,
     * per row down: the source's F, I and J after the division by Area2. */
    double F[4], I[4], J[4];
    /* Per vertex A, B, C: (r, g, b, s, t) / Z for formula (23), or the bare
     * attributes when the run interpolates affinely (the exhibit). */
    float Q[3][ATTR_COUNT];
    /* Exact edge values F01, F02, F03 at (minX, minY) and their integer
     * steps: these, not the float lanes, decide coverage. */
    int64_t e[3], ex[3], ey[3];
};

/* Formulas (18) to (22): the depth function is built from the edge
 * functions exactly as each barycentric weight is,
 *
 *     D(x, y) = F02 / ZA + F03 / ZB + F01 / ZC = Area2 / Zp          (18)
 *
 * and since every F0k = I0k x + J0k y + K0k is linear, so is D:
 *
 *     I00 = I02/ZA + I03/ZB + I01/ZC                                   (19)
 *     J00 = J02/ZA + J03/ZB + J01/ZC                                   (20)
 *     K00 = K02/ZA + K03/ZB + K01/ZC                                   (21)
 *     F00 = I00 x + J00 y + K00                                        (22)
 *
 * tristep's edge coefficients are in 1/256 pixel units (raster.h): x and y
 * below are the fixed-point pixel centre, and one pixel to the right adds
 * 256 * I. Lanes 1 to 3 start from the exact integer edge values; lane 0 is
 * (22) in double precision, whose rounding (about |K| * 2^-53, under 2^-6
 * of one edge unit for vertices inside +-16384 px) is far below what the
 * float lanes keep. */
static void persp_setup(const struct tri_setup *t, const struct raster_params *p,
                        struct persp_setup *s, struct trace *tr)
{
    const struct vertex *a = &t->v[0], *b = &t->v[1], *c = &t->v[2];
    double ZA = a->z, ZB = b->z, ZC = c->z;
    double X = (double)pixel_centre(t->minx), Y = (double)pixel_centre(t->miny);

    double I00 = t->I[EDGE_BC] / ZA + t->I[EDGE_CA] / ZB + t->I[EDGE_AB] / ZC;  /* (19) */
    double J00 = t->J[EDGE_BC] / ZA + t->J[EDGE_CA] / ZB + t->J[EDGE_AB] / ZC;  /* (20) */
    double K00 = t->K[EDGE_BC] / ZA + t->K[EDGE_CA] / ZB + t->K[EDGE_AB] / ZC;  /* (21) */
    NARRATE(tr, .kind = TRACE_STEP, .line = L_DEPTH_EDGE);

    for (int k = 0; k < 3; k++) {
        s->e[k] = edge_value(t, k, t->minx, t->miny);
        s->ex[k] = t->I[k] * SUBPIXEL_ONE;
        s->ey[k] = t->J[k] * SUBPIXEL_ONE;
    }

    /* the vectors I, J and F = I * minX + J * minY + K, divided by Area2 */
    double A = (double)t->area2;
    double F[4] = { I00 * X + J00 * Y + K00,                           /* (22) */
                    (double)s->e[EDGE_AB], (double)s->e[EDGE_BC], (double)s->e[EDGE_CA] };
    double I[4] = { I00, (double)t->I[EDGE_AB], (double)t->I[EDGE_BC], (double)t->I[EDGE_CA] };
    double J[4] = { J00, (double)t->J[EDGE_AB], (double)t->J[EDGE_BC], (double)t->J[EDGE_CA] };
    for (int lane = 0; lane < 4; lane++) {
        s->F[lane] = F[lane] / A;
        s->I[lane] = I[lane] * SUBPIXEL_ONE / A;
        s->J[lane] = J[lane] * SUBPIXEL_ONE / A;
    }
    NARRATE(tr, .kind = TRACE_STEP, .line = L_DIVIDE, .span = L_DIVIDE - L_F, .x = t->minx, .y = t->miny,
            .aux = { (float)s->F[0], (float)s->F[1], (float)s->F[2], (float)s->F[3] });

    /* (23) divides each vertex's attribute by its Z once, here; the affine
     * exhibit keeps the bare attribute and, below, skips the "* Depth". */
    for (int i = 0; i < 3; i++) {
        const struct vertex *v = &t->v[i];
        double q = p->knob[P_AFFINE] ? 1.0 : 1.0 / v->z;
        float *Q = s->Q[i];
        Q[ATTR_R] = (float)(v->r * q);
        Q[ATTR_G] = (float)(v->g * q);
        Q[ATTR_B] = (float)(v->b * q);
        Q[ATTR_S] = (float)(v->s * q);
        Q[ATTR_T] = (float)(v->t * q);
        Q[5] = Q[6] = Q[7] = 0;
    }
}

/* Cost of formula (23) for one attribute, the weights given:
 * (u a_A/Z_A + v a_B/Z_B + w a_C/Z_C) * Depth. */
#define PERSPECTIVE_COST { .mul = 4, .add = 2 }

/* The last line a pixel's test does: the inside test alone, then the depth
 * and its test, then (23) for a fragment that shows. */
static int pixel_line(bool in, bool shows)
{
    return !in ? L_TEST : !shows ? L_ZTEST : L_ATTR;
}

static bool covered(const struct tri_setup *t, const int64_t e[3])
{
    return edge_inside(t, EDGE_AB, e[0]) && edge_inside(t, EDGE_BC, e[1])
        && edge_inside(t, EDGE_CA, e[2]);
}

/* --- the source's layout: one pixel's (1/z, w, u, v) in one register ----------------
 *
 *     Cx  [ 1/z |  w  |  u  |  v  ]
 *            |     |     |     |
 *     +  I [ I00 | I01 | I02 | I03 ] / Area2      one vector add per pixel
 *
 * The walk over the box is written once (walk_box, below); what it does to
 * the register is written twice, side by side: as four plain floats, every
 * step written out (the scalar twin, the reference), and as SSE intrinsics
 * (the same operations in the same order, so the same rounding; the tests
 * hold the two equal). SSE2 is the baseline of every x86-64 compiler; on
 * other CPUs (ARM64) simd.h translates the same intrinsics (SIMDe), so
 * every CPU runs both twins. */
#include "simd.h"   /* SSE2 intrinsics: __m128, _mm_add_ps, _mm_shuffle_ps, ... */

enum twin { SCALAR, SSE };

/* One register: the SSE twin holds it as an __m128, the scalar twin as four
 * floats. */
union reg {
    __m128 sse;
    float lane[4];
};

/* The lanes of one register, broadcast: lane i copied into all four. */
#define BROADCAST(r, i) _mm_shuffle_ps((r), (r), _MM_SHUFFLE(i, i, i, i))

/* (a[0], a[1], a[2], a[3]), each rounded to float. */
static inline union reg reg_set(const double a[4], enum twin tw)
{
    union reg r;
    if (tw == SSE) {   /* _mm_set_ps lists lanes from the highest down: lane 0 last */
        r.sse = _mm_set_ps((float)a[3], (float)a[2], (float)a[1], (float)a[0]);
    } else {
        for (int i = 0; i < 4; i++)
            r.lane[i] = (float)a[i];
    }
    return r;
}

/* Four floats from memory, and back. */
static inline union reg reg_load(const float a[4], enum twin tw)
{
    union reg r;
    if (tw == SSE) {
        r.sse = _mm_loadu_ps(a);
    } else {
        for (int i = 0; i < 4; i++)
            r.lane[i] = a[i];
    }
    return r;
}

static inline void reg_store(float out[4], union reg r, enum twin tw)
{
    if (tw == SSE) {
        _mm_storeu_ps(out, r.sse);
    } else {
        for (int i = 0; i < 4; i++)
            out[i] = r.lane[i];
    }
}

/* Cx += I, Cy += J */
static inline union reg reg_add(union reg a, union reg b, enum twin tw)
{
    if (tw == SSE)
        return (union reg){ .sse = _mm_add_ps(a.sse, b.sse) };
    for (int i = 0; i < 4; i++)
        a.lane[i] += b.lane[i];
    return a;
}

/* Depth = 1 / Cx[0] */
static inline float reg_depth(union reg Cx, enum twin tw)
{
    if (tw == SSE)
        return _mm_cvtss_f32(_mm_div_ss(_mm_set1_ps(1.0f), Cx.sse));
    return 1.0f / Cx.lane[LANE_INV_Z];
}

/* (23) on four attributes: (u QA + v QB + w QC) * m, with the weights u, v,
 * w read from the lanes of Cx (SSE: broadcast into whole registers). */
static inline union reg reg_perspective(union reg Cx, union reg QA, union reg QB, union reg QC,
                                        float m, enum twin tw)
{
    if (tw == SSE) {
        __m128 u = BROADCAST(Cx.sse, LANE_U), v = BROADCAST(Cx.sse, LANE_V);
        __m128 w = BROADCAST(Cx.sse, LANE_W);
        __m128 P = _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, QA.sse), _mm_mul_ps(v, QB.sse)),
                              _mm_mul_ps(w, QC.sse));
        return (union reg){ .sse = _mm_mul_ps(P, _mm_set1_ps(m)) };
    }
    float u = Cx.lane[LANE_U], v = Cx.lane[LANE_V], w = Cx.lane[LANE_W];
    union reg P;
    for (int i = 0; i < 4; i++)
        P.lane[i] = (u * QA.lane[i] + v * QB.lane[i] + w * QC.lane[i]) * m;
    return P;
}

/* The source's loop over the box, one pixel per step. Compiled once per
 * twin (always_inline, tw a constant): each keeps only its own register. */
static inline __attribute__((always_inline)) void
walk_box(const struct tri_setup *t, const struct raster_params *p, struct target *fb,
         struct trace *tr, enum twin tw)
{
    struct persp_setup s;
    NARRATE_SETUP(tr, t, L_BOX);
    if (t->empty)
        return;
    persp_setup(t, p, &s, tr);
    union reg I = reg_set(s.I, tw), J = reg_set(s.J, tw), Cy = reg_set(s.F, tw);
    /* each vertex's (r, g, b, s) / Z and (t, 0, 0, 0) / Z: two registers */
    union reg QA[2] = { reg_load(s.Q[0], tw), reg_load(s.Q[0] + 4, tw) };
    union reg QB[2] = { reg_load(s.Q[1], tw), reg_load(s.Q[1] + 4, tw) };
    union reg QC[2] = { reg_load(s.Q[2], tw), reg_load(s.Q[2] + 4, tw) };
    int64_t ey[3] = { s.e[0], s.e[1], s.e[2] };

    for (int y = t->miny; y <= t->maxy; y++) {
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y);
        union reg Cx = Cy;
        int64_t e[3] = { ey[0], ey[1], ey[2] };
        for (int x = t->minx; x <= t->maxx; x++) {
            bool in = covered(t, e);
            COUNT(tr, 3, FILL_RULE_COST);
            float attr[ATTR_COUNT] = { 0 }, lane[4] = { 0 };
            float depth = 0;
            if (in) {
                depth = reg_depth(Cx, tw);
                COUNT(tr, 1, RECIPROCAL_COST);
            }
            bool shows = in && target_depth_pass(fb, x, y, depth);
            if (shows) {                                /* shade only what will show */
                float m = p->knob[P_AFFINE] ? 1.0f : depth;
                union reg P0 = reg_perspective(Cx, QA[0], QB[0], QC[0], m, tw);  /* r, g, b, s */
                union reg P1 = reg_perspective(Cx, QA[1], QB[1], QC[1], m, tw);  /* t */
                reg_store(attr, P0, tw);
                reg_store(attr + 4, P1, tw);
                COUNT(tr, 5, PERSPECTIVE_COST);
            }
            if (NARRATING)
                reg_store(lane, Cx, tw);
            NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = pixel_line(in, shows),
                    .span = pixel_line(in, shows) - L_PIXEL, .x = x, .y = y,
                    .e = { e[0], e[1], e[2] }, .flags = in ? TRACE_INSIDE : 0, .z = depth,
                    .aux = { lane[0], lane[1], lane[2], lane[3], attr[ATTR_S], attr[ATTR_T] });
            /* a hidden fragment is still counted (PLOT), its colour never written */
            if (in)
                PLOT(fb, tr, L_WRITE, x, y, depth,
                     shows ? shade_pixel(p, tr, attr[ATTR_R], attr[ATTR_G], attr[ATTR_B],
                                         attr[ATTR_S], attr[ATTR_T]) : 0);
            Cx = reg_add(Cx, I, tw);                          /* Cx += I */
            for (int k = 0; k < 3; k++)
                e[k] += s.ex[k];
            COUNT(tr, 4, PLANE_STEP_COST);
            COUNT(tr, 3, EDGE_STEP_COST);
        }
        Cy = reg_add(Cy, J, tw);                              /* Cy += J */
        for (int k = 0; k < 3; k++)
            ey[k] += s.ey[k];
        COUNT(tr, 4, PLANE_STEP_COST);
        COUNT(tr, 3, EDGE_STEP_COST);
        NARRATE(tr, .kind = TRACE_STEP, .line = L_STEP_Y, .x = t->minx, .y = y + 1);
    }
}

static void rasterize_sse(const struct tri_setup *t, const struct raster_params *p,
                          struct target *fb, struct trace *tr)
{
    walk_box(t, p, fb, tr, SSE);
}

static void rasterize_scalar(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr)
{
    walk_box(t, p, fb, tr, SCALAR);
}

/* Beyond the source: four PIXELS per register, one register per quantity.
 *
 *                pixel x    x+1     x+2     x+3
 *     D     = [ 1/z    | 1/z    | 1/z    | 1/z    ]    += 4 * I00 / Area2
 *     W     = [ w      | w      | w      | w      ]    += 4 * I01 / Area2
 *     U, V  likewise
 *     edges = exact int64 F01, F02, F03, two pixels per register, six registers
 *
 * Four pixels cost the same four vector adds one pixel costs above, the
 * division 1 / D serves four pixels at once, and (23) needs no broadcasts.
 * The last group of a row may reach past maxX: those lanes are masked off. */
static void rasterize_row4_sse(const struct tri_setup *t, const struct raster_params *p,
                               struct target *fb, struct trace *tr)
{
    struct persp_setup s;
    NARRATE_SETUP(tr, t, L_BOX);
    if (t->empty)
        return;
    persp_setup(t, p, &s, tr);

    /* quantity q at pixels minX .. minX+3 of row minY: F + (0, 1, 2, 3) * I */
    __m128 Cy[4], I4[4], J[4];
    for (int q = 0; q < 4; q++) {
        Cy[q] = _mm_set_ps((float)(s.F[q] + 3 * s.I[q]), (float)(s.F[q] + 2 * s.I[q]),
                           (float)(s.F[q] + s.I[q]), (float)s.F[q]);
        I4[q] = _mm_set1_ps((float)(4 * s.I[q]));
        J[q] = _mm_set1_ps((float)s.J[q]);
    }
    __m128 QA[ATTR_T + 1], QB[ATTR_T + 1], QC[ATTR_T + 1];
    for (int i = 0; i <= ATTR_T; i++) {
        QA[i] = _mm_set1_ps(s.Q[0][i]);
        QB[i] = _mm_set1_ps(s.Q[1][i]);
        QC[i] = _mm_set1_ps(s.Q[2][i]);
    }
    /* exact edge values: register lo holds pixels (x, x+1), hi holds (x+2, x+3);
     * _mm_set_epi64x lists the high lane first */
    __m128i Ey_lo[3], Ey_hi[3], EX4[3], EY[3], bias[3];
    for (int k = 0; k < 3; k++) {
        int64_t e = s.e[k], dx = s.ex[k];
        Ey_lo[k] = _mm_set_epi64x(e + dx, e);
        Ey_hi[k] = _mm_set_epi64x(e + 3 * dx, e + 2 * dx);
        EX4[k] = _mm_set1_epi64x(4 * dx);
        EY[k] = _mm_set1_epi64x(s.ey[k]);
        bias[k] = _mm_set1_epi64x(t->bias[k]);
    }
    const __m128 one = _mm_set1_ps(1.0f);

    for (int y = t->miny; y <= t->maxy; y++) {
        NARRATE(tr, .kind = TRACE_ROW, .line = L_ROW, .x = t->minx, .y = y, .x1 = t->maxx, .y1 = y);
        __m128 D = Cy[LANE_INV_Z], W = Cy[LANE_W], U = Cy[LANE_U], V = Cy[LANE_V];
        __m128i E_lo[3] = { Ey_lo[0], Ey_lo[1], Ey_lo[2] };
        __m128i E_hi[3] = { Ey_hi[0], Ey_hi[1], Ey_hi[2] };
        for (int x = t->minx; x <= t->maxx; x += 4) {
            /* A pixel is outside when some F + bias < 0: the sign bit of each
             * 64-bit lane, OR-ed over the three edges, read by movemask. */
            __m128i out_lo = _mm_setzero_si128(), out_hi = _mm_setzero_si128();
            for (int k = 0; k < 3; k++) {
                out_lo = _mm_or_si128(out_lo, _mm_add_epi64(E_lo[k], bias[k]));
                out_hi = _mm_or_si128(out_hi, _mm_add_epi64(E_hi[k], bias[k]));
            }
            int outside = _mm_movemask_pd(_mm_castsi128_pd(out_lo))
                        | _mm_movemask_pd(_mm_castsi128_pd(out_hi)) << 2;
            int valid = t->maxx - x >= 3 ? 4 : t->maxx - x + 1;  /* lanes inside the box */
            int inside = ~outside & ((1 << valid) - 1);
            COUNT(tr, 4 * 3, FILL_RULE_COST);

            float depth[4] = { 0 }, attr[ATTR_T + 1][4] = { { 0 } };
            int shows = 0;                      /* inside and nearer than the buffer */
            if (inside) {
                __m128 Z = _mm_div_ps(one, D);                     /* four depths at once */
                _mm_storeu_ps(depth, Z);
                for (int i = 0; i < valid; i++)
                    if (inside >> i & 1 && target_depth_pass(fb, x + i, y, depth[i]))
                        shows |= 1 << i;
                COUNT(tr, 4, RECIPROCAL_COST);
            }
            if (shows) {
                __m128 M = p->knob[P_AFFINE] ? one : _mm_loadu_ps(depth);
                for (int i = 0; i <= ATTR_T; i++)                  /* (23), four pixels */
                    _mm_storeu_ps(attr[i], _mm_mul_ps(_mm_add_ps(_mm_add_ps(
                        _mm_mul_ps(U, QA[i]), _mm_mul_ps(V, QB[i])), _mm_mul_ps(W, QC[i])), M));
                COUNT(tr, 4 * 5, PERSPECTIVE_COST);     /* four pixels: r, g, b, s, t */
            }
            float lanes[4][4] = { { 0 } };
            int64_t e[3][4] = { { 0 } };
            if (NARRATING) {
                _mm_storeu_ps(lanes[LANE_INV_Z], D);
                _mm_storeu_ps(lanes[LANE_W], W);
                _mm_storeu_ps(lanes[LANE_U], U);
                _mm_storeu_ps(lanes[LANE_V], V);
                for (int k = 0; k < 3; k++) {
                    _mm_storeu_si128((__m128i *)&e[k][0], E_lo[k]);
                    _mm_storeu_si128((__m128i *)&e[k][2], E_hi[k]);
                }
            }
            for (int i = 0; i < valid; i++) {
                bool in = inside >> i & 1;
                NARRATE(tr, .kind = TRACE_PIXEL_TEST, .line = pixel_line(in, shows >> i & 1),
                        .span = pixel_line(in, shows >> i & 1) - L_PIXEL, .x = x + i, .y = y,
                        .e = { e[0][i], e[1][i], e[2][i] }, .flags = in ? TRACE_INSIDE : 0,
                        .z = depth[i],
                        .aux = { lanes[0][i], lanes[1][i], lanes[2][i], lanes[3][i],
                                 attr[ATTR_S][i], attr[ATTR_T][i] });
                if (in)
                    PLOT(fb, tr, L_WRITE, x + i, y, depth[i],
                         shows >> i & 1 ? shade_pixel(p, tr, attr[ATTR_R][i], attr[ATTR_G][i],
                                                      attr[ATTR_B][i], attr[ATTR_S][i],
                                                      attr[ATTR_T][i]) : 0);
            }
            D = _mm_add_ps(D, I4[LANE_INV_Z]);
            W = _mm_add_ps(W, I4[LANE_W]);
            U = _mm_add_ps(U, I4[LANE_U]);
            V = _mm_add_ps(V, I4[LANE_V]);
            for (int k = 0; k < 3; k++) {
                E_lo[k] = _mm_add_epi64(E_lo[k], EX4[k]);
                E_hi[k] = _mm_add_epi64(E_hi[k], EX4[k]);
            }
            COUNT(tr, 4 * 4, PLANE_STEP_COST);
            COUNT(tr, 4 * 3, EDGE_STEP_COST);
        }
        for (int q = 0; q < 4; q++)
            Cy[q] = _mm_add_ps(Cy[q], J[q]);
        for (int k = 0; k < 3; k++) {
            Ey_lo[k] = _mm_add_epi64(Ey_lo[k], EY[k]);
            Ey_hi[k] = _mm_add_epi64(Ey_hi[k], EY[k]);
        }
        COUNT(tr, 4 * 4, PLANE_STEP_COST);
        COUNT(tr, 4 * 3, EDGE_STEP_COST);
        NARRATE(tr, .kind = TRACE_STEP, .line = L_STEP_Y, .x = t->minx, .y = y + 1);
    }
}

static const struct lesson_variant variants[] = {
    { .name = "sse", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_sse,
      .what = "the source's layout: one pixel's (1/z, w, u, v) in one SSE register" },
    { .name = "scalar", .kind = VARIANT_TWIN, .rasterize = rasterize_scalar,
      .what = "the same steps on four plain floats: the SSE code's twin" },
    { .name = "row4", .kind = VARIANT_TWIN, .rasterize = rasterize_row4_sse,
      .what = "four pixels per register, one register per quantity" },
};

const struct lesson lesson_04 = {
    .id = "04-simd-perspective",
    .title = "SIMD vectors of (1/z, w, u, v), perspective-correct",
    .pseudocode = pseudocode,
    .builtin_scene = "floor",
    .exhibit_scene = "floor",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .aux_names = aux_names,
    .params = (const struct lesson_param[]){
        [P_AFFINE] = { .option = "affine", .name = "texturing",
                       .help = "texture affinely, not perspective-correct (lesson 04's exhibit)",
                       .words = (const char *const[]){ "perspective", "affine" },
                       .key = 'p', .min = 0, .max = 1 },
        { 0 } },
    .cost_tested = (const struct cost_term[]){
        COST_TERM(3, FILL_RULE_COST), COST_TERM(4, PLANE_STEP_COST), COST_TERM(3, EDGE_STEP_COST),
        { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, RECIPROCAL_COST), COST_TERM(5, PERSPECTIVE_COST), COST_TERM(1, PACK_RGB_COST),
        { 0 } },
    .exercise = { .write_line = L_WRITE },
};
