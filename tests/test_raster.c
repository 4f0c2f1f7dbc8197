/* test_raster.c - unit tests of the exact core: snapping, the top-left rule,
 * edge values, barycentric weights, the bounding box, the render target, and
 * the reference rasterizer itself checked against the rule's definition. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shade/shade.h"
#include "testlib.h"

/* one unit of F is 1/65536 px^2 */
#define PX2 65536

/* --- snapping ---------------------------------------------------------------- */

/* Round v * 2^bits to nearest, ties to even, written out longhand. */
static int64_t round_half_even(double v, int bits)
{
    double s = ldexp(v, bits);          /* exact: a power-of-two scale */
    double f = floor(s), frac = s - f;
    int64_t i = (int64_t)f;
    if (frac > 0.5 || (frac == 0.5 && (i & 1)))
        i++;
    return i * (1 << (SUBPIXEL_BITS - bits));
}

Test(snap, rounds_to_nearest)
{
    cr_expect_eq(snap_coord(0, 8), 0);
    cr_expect_eq(snap_coord(1, 8), 256);
    cr_expect_eq(snap_coord(10.25, 8), 2624);
    cr_expect_eq(snap_coord(0.3 / 256, 8), 0);
    cr_expect_eq(snap_coord(0.7 / 256, 8), 1);
    cr_expect_eq(snap_coord(1.49 / 256, 8), 1);
    cr_expect_eq(snap_coord(1.51 / 256, 8), 2);
}

Test(snap, ties_go_to_even)
{
    cr_expect_eq(snap_coord(0.5 / 256, 8), 0);
    cr_expect_eq(snap_coord(1.5 / 256, 8), 2);
    cr_expect_eq(snap_coord(2.5 / 256, 8), 2);
    cr_expect_eq(snap_coord(3.5 / 256, 8), 4);
    /* every 1/512 tie between -8 and 8 pixels */
    for (int k = -8 * 256; k < 8 * 256; k++) {
        double v = (k + 0.5) / 256;
        int32_t even = (k & 1) ? k + 1 : k;
        cr_assert_eq(snap_coord(v, 8), even, "snap(%.17g) = %d, expected %d", v, snap_coord(v, 8), even);
    }
}

Test(snap, negative_values_mirror_positive_ones)
{
    cr_expect_eq(snap_coord(-10.25, 8), -2624);
    cr_expect_eq(snap_coord(-0.5 / 256, 8), 0);
    cr_expect_eq(snap_coord(-1.5 / 256, 8), -2);
    cr_expect_eq(snap_coord(-2.5 / 256, 8), -2);
    cr_expect_eq(snap_coord(-0.7 / 256, 8), -1);
    struct rng r = rng_for(1);
    for (int i = 0; i < 20000; i++) {
        double v = rng_range(&r, 0, 300);
        if (i & 1)
            v = (floor(v * 256) + 0.5) / 256;   /* a tie */
        cr_assert_eq(snap_coord(-v, 8), -snap_coord(v, 8), "v = %.17g", v);
        cr_assert_eq(snap_coord(v, 8), round_half_even(v, 8), "v = %.17g", v);
        cr_assert_eq(snap_coord(-v, 8), round_half_even(-v, 8), "v = %.17g", -v);
    }
}

Test(snap, coordinate_limits)
{
    cr_expect_eq(snap_coord(-16384, 8), -16384 * 256);
    cr_expect_eq(snap_coord(16384 - 1.0 / 256, 8), 16384 * 256 - 1);
    cr_expect_eq(snap_coord(-16384 + 1.0 / 512, 8), -16384 * 256);     /* a tie, to even */
    cr_expect_eq(snap_coord(16384 - 3.0 / 512, 8), 16384 * 256 - 2);   /* a tie, to even */
    /* the largest representable coordinate below the limit still fits */
    cr_expect_eq(snap_coord(nextafter(16384, 0), 8), 16384 * 256);
}

Test(snap, fewer_bits)
{
    /* 4 bits: 1/16 pixel, still expressed in 1/256 units */
    cr_expect_eq(snap_coord(1.0 / 32, 4), 0);       /* tie 0.5/16 -> 0 */
    cr_expect_eq(snap_coord(3.0 / 32, 4), 32);      /* tie 1.5/16 -> 2/16 */
    cr_expect_eq(snap_coord(0.1, 4), 32);           /* 1.6/16 -> 2/16 */
    cr_expect_eq(snap_coord(-0.1, 4), -32);
    /* 0 bits: whole pixels */
    cr_expect_eq(snap_coord(0.5, 0), 0);
    cr_expect_eq(snap_coord(1.5, 0), 512);
    cr_expect_eq(snap_coord(2.5, 0), 512);
    cr_expect_eq(snap_coord(2.6, 0), 768);
    cr_expect_eq(snap_coord(-1.5, 0), -512);
    struct rng r = rng_for(2);
    for (int i = 0; i < 20000; i++) {
        int bits = rng_int(&r, 0, 8);
        double v = rng_range(&r, -100, 100);
        if (i & 1)
            v = ldexp(floor(ldexp(v, bits)) + 0.5, -bits);  /* a tie at this precision */
        int32_t s = snap_coord(v, bits);
        cr_assert_eq(s, round_half_even(v, bits), "snap(%.17g, %d) = %d", v, bits, s);
        cr_assert_eq(s % (1 << (SUBPIXEL_BITS - bits)), 0);
    }
}

/* --- the top-left rule ----------------------------------------------------------- */

/* The rule's definition, in y-down screen space, for the edge P -> Q of a
 * triangle whose third vertex is R (all snapped, no orientation assumed):
 * a top edge is exactly horizontal with the triangle below it; a left edge is
 * not horizontal and has the triangle's interior on its +x side. */
static bool top_left_by_definition(int64_t px, int64_t py, int64_t qx, int64_t qy,
                                   int64_t rx, int64_t ry)
{
    if (py == qy)
        return ry > py;
    /* signed horizontal distance from the edge to R, times (qy - py) */
    int64_t d = (rx - px) * (qy - py) - (ry - py) * (qx - px);
    return (qy - py > 0) == (d > 0);
}

static void check_biases(const struct vertex v[3], const char *what)
{
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 64, 64), "%s: empty", what);
    cr_assert_gt(t.area2, 0, "%s", what);
    for (int k = 0; k < 3; k++) {
        int a = k, b = (k + 1) % 3, c = (k + 2) % 3;
        bool expect = top_left_by_definition(t.x[a], t.y[a], t.x[b], t.y[b], t.x[c], t.y[c]);
        cr_assert_eq(t.bias[k] == 0, expect, "%s: edge %d (%d,%d)->(%d,%d): bias %lld",
                     what, k, t.x[a], t.y[a], t.x[b], t.y[b], (long long)t.bias[k]);
        cr_assert_eq(is_top_left(t.I[k], t.J[k]), expect, "%s: edge %d", what, k);
    }
}

/* Every order of the three vertices: both windings, each vertex first. */
static void permutations(const struct vertex in[3], struct vertex out[6][3])
{
    static const int p[6][3] = { {0,1,2}, {1,2,0}, {2,0,1}, {0,2,1}, {2,1,0}, {1,0,2} };
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 3; k++)
            out[i][k] = in[p[i][k]];
}

/* Count how many edges of the triangle are top, left, neither: each named
 * class appears, for every vertex order. */
static void edge_classes(const struct vertex tri[3], int *top, int *left, int *other)
{
    struct tri_setup t;
    tri_setup(&t, tri, 64, 64);
    *top = *left = *other = 0;
    for (int k = 0; k < 3; k++) {
        if (t.I[k] == 0 && t.bias[k] == 0)
            ++*top;
        else if (t.bias[k] == 0)
            ++*left;
        else
            ++*other;
    }
}

Test(top_left, every_edge_class_both_windings)
{
    /* name, vertices, and (reasoned by hand) how many top / left / other edges */
    struct { const char *name; double p[6]; int top, left, other; } cases[] = {
        /*  A ---- B      top edge AB (triangle below it), left edge CA,
         *  |    /        right (other) edge BC                         */
        { "flat top, right angle at left",   { 2, 2, 10, 2, 2, 10 }, 1, 1, 1 },
        /*  A ---- B      top edge, left edge CA (goes up from C), BC is right */
        { "flat top, apex below",            { 2, 2, 12, 2, 7, 10 }, 1, 1, 1 },
        /*      A         flat bottom: BC is a bottom edge (other),
         *    /   \       AB... left side goes up: left; right side: other */
        { "flat bottom, apex above",         { 7, 2, 12, 10, 2, 10 }, 0, 1, 2 },
        /*  a vertical right edge and a vertical... */
        { "vertical left edge",              { 2, 2, 2, 12, 9, 7 }, 0, 1, 2 },
        { "vertical right edge",             { 9, 2, 9, 12, 2, 7 }, 0, 2, 1 },
        /* no horizontal edge: two left edges when the middle vertex is left */
        { "middle vertex left",              { 6, 1, 9, 12, 1, 6 }, 0, 2, 1 },
        { "middle vertex right",             { 4, 1, 2, 12, 11, 6 }, 0, 1, 2 },
        { "flat top, off the grid",          { 2.3, 2.7, 10.1, 2.7, 5.9, 9.3 }, 1, 1, 1 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct vertex v[3], perm[6][3];
        for (int k = 0; k < 3; k++)
            v[k] = test_vertex(cases[i].p[2 * k], cases[i].p[2 * k + 1]);
        permutations(v, perm);
        for (int j = 0; j < 6; j++) {
            char what[96];
            snprintf(what, sizeof what, "%s, order %d", cases[i].name, j);
            check_biases(perm[j], what);
            int top, left, other;
            edge_classes(perm[j], &top, &left, &other);
            cr_expect_eq(top, cases[i].top, "%s: %d top edges", what, top);
            cr_expect_eq(left, cases[i].left, "%s: %d left edges", what, left);
            cr_expect_eq(other, cases[i].other, "%s: %d other edges", what, other);
        }
    }
}

Test(top_left, random_triangles_after_normalisation)
{
    struct rng r = rng_for(3);
    for (int i = 0; i < 20000; i++) {
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(i % CAT_COUNT), 64, 64, v);
        if (i % CAT_COUNT == CAT_DEGENERATE)
            continue;
        struct tri_setup t;
        tri_setup(&t, v, 1 << 14, 1 << 14);
        if (t.area2 == 0)
            continue;
        char what[64];
        snprintf(what, sizeof what, "case %d", i);
        /* normalised: the vertex set is the input set, the area positive */
        for (int k = 0; k < 3; k++) {
            int src = t.swapped ? (3 - k) % 3 : k;
            cr_assert_eq(t.x[k], snap_coord(v[src].x, 8), "%s", what);
            cr_assert_eq(t.y[k], snap_coord(v[src].y, 8), "%s", what);
        }
        for (int k = 0; k < 3; k++) {
            int a = k, b = (k + 1) % 3, c = (k + 2) % 3;
            cr_assert_eq(t.bias[k] == 0,
                         top_left_by_definition(t.x[a], t.y[a], t.x[b], t.y[b], t.x[c], t.y[c]),
                         "%s edge %d", what, k);
        }
    }
}

/* --- edge values and barycentrics ------------------------------------------------- */

Test(edges, values_match_a_hand_computation)
{
    /* A = (1, 1), B = (5, 1), C = (1, 4): a right triangle, 4 x 3 pixels,
     * area2 = 12 px^2. At the centre P = (2.5, 2.5) of pixel (2, 2):
     *   F_AB = |AB| * dist(P, AB) = 4 * 1.5                       = 6   px^2
     *   F_BC = (Cx-Bx)(Py-By) - (Cy-By)(Px-Bx) = -4*1.5 + 3*2.5  = 1.5 px^2
     *   F_CA = (Ax-Cx)(Py-Cy) - (Ay-Cy)(Px-Cx) = 0 + 3*1.5       = 4.5 px^2
     * and the weights u = F_BC/12, v = F_CA/12, w = F_AB/12 reproduce P. */
    struct vertex v[3] = { test_vertex(1, 1), test_vertex(5, 1), test_vertex(1, 4) };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 16, 16));
    cr_expect_eq(t.area2, 12 * PX2);
    cr_expect_eq(edge_value(&t, EDGE_AB, 2, 2), 6 * PX2);
    cr_expect_eq(edge_value(&t, EDGE_BC, 2, 2), 3 * PX2 / 2);
    cr_expect_eq(edge_value(&t, EDGE_CA, 2, 2), 9 * PX2 / 2);
    cr_expect_eq(t.I[EDGE_AB], 0);
    cr_expect_eq(t.J[EDGE_AB], 4 * 256);
    /* one pixel to the right: F changes by I = Ay - By (in 1/256 px) times 256 */
    cr_expect_eq(edge_value(&t, EDGE_BC, 3, 2) - edge_value(&t, EDGE_BC, 2, 2), t.I[EDGE_BC] * 256);
    cr_expect_eq(t.I[EDGE_BC], -3 * 256);

    int64_t f[3] = { edge_value(&t, 0, 2, 2), edge_value(&t, 1, 2, 2), edge_value(&t, 2, 2, 2) };
    double b[3];
    barycentric(&t, f, b);
    cr_expect_eq(b[0], 0.125);
    cr_expect_eq(b[1], 0.375);
    cr_expect_eq(b[2], 0.5);

    /* the other winding gives the same values after normalisation */
    struct vertex w[3] = { v[0], v[2], v[1] };
    struct tri_setup s;
    cr_assert(tri_setup(&s, w, 16, 16));
    cr_expect(s.swapped);
    cr_expect_eq(s.area2, 12 * PX2);
    for (int k = 0; k < 3; k++)
        cr_expect_eq(edge_value(&s, k, 2, 2), edge_value(&t, k, 2, 2), "edge %d", k);
}

/* Each weight is an exact integer times a rounded 1/area2, rounded again:
 * relative error below 2 epsilon; the two additions add one epsilon each,
 * relative to the magnitudes added. So |u + v + w - 1| stays below
 * BARY_SUM_TOLERANCE * (|u| + |v| + |w|): inside the triangle that sum of
 * magnitudes is 1, outside it (a box corner) the weights can be large with
 * opposite signs and the bound grows with them. */
#define BARY_SUM_TOLERANCE (4 * DBL_EPSILON)

Test(edges, barycentric_weights_sum_to_one)
{
    struct rng r = rng_for(4);
    double worst = 0;
    for (int i = 0; i < 5000; i++) {
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(i % 2 ? CAT_GENERIC : CAT_LARGE), 48, 48, v);
        struct tri_setup t;
        if (!tri_setup(&t, v, 48, 48))
            continue;
        for (int y = t.miny; y <= t.maxy; y += 3)
            for (int x = t.minx; x <= t.maxx; x += 3) {
                int64_t f[3] = { edge_value(&t, 0, x, y), edge_value(&t, 1, x, y), edge_value(&t, 2, x, y) };
                cr_assert_eq(f[0] + f[1] + f[2], t.area2, "sum of edge values is the area");
                double b[3];
                barycentric(&t, f, b);
                double mag = fabs(b[0]) + fabs(b[1]) + fabs(b[2]);
                double err = fabs(b[0] + b[1] + b[2] - 1);
                worst = err / mag > worst ? err / mag : worst;
                cr_assert_leq(err, BARY_SUM_TOLERANCE * mag, "case %d pixel (%d, %d): sum - 1 = %g, "
                              "|u| + |v| + |w| = %g", i, x, y, err, mag);
            }
    }
    cr_log_info("largest |u + v + w - 1| / (|u| + |v| + |w|) = %g", worst);
}

/* --- bounding box --------------------------------------------------------------- */

Test(bbox, clamped_to_the_target_and_holds_every_covered_centre)
{
    struct rng r = rng_for(5);
    const int w = 37, h = 29;
    uint8_t mask[37 * 29];
    for (int i = 0; i < 20000; i++) {
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(i % CAT_COUNT), w, h, v);
        struct tri_setup t;
        bool nonempty = tri_setup(&t, v, w, h);
        cr_assert_eq(nonempty, !t.empty);
        /* candidate pixels: centre (p + 1/2) * 256 within the snapped extent */
        double lo_x = fmin(t.x[0], fmin(t.x[1], t.x[2])), hi_x = fmax(t.x[0], fmax(t.x[1], t.x[2]));
        double lo_y = fmin(t.y[0], fmin(t.y[1], t.y[2])), hi_y = fmax(t.y[0], fmax(t.y[1], t.y[2]));
        double minx = fmax(0, ceil(lo_x / 256 - 0.5)), maxx = fmin(w - 1, floor(hi_x / 256 - 0.5));
        double miny = fmax(0, ceil(lo_y / 256 - 0.5)), maxy = fmin(h - 1, floor(hi_y / 256 - 0.5));
        bool box_empty = minx > maxx || miny > maxy;
        cr_assert_eq(t.empty, t.area2 == 0 || box_empty, "case %d", i);
        if (!t.empty) {
            cr_assert(t.minx == minx && t.maxx == maxx && t.miny == miny && t.maxy == maxy,
                      "case %d: box %d..%d x %d..%d, expected %g..%g x %g..%g", i,
                      t.minx, t.maxx, t.miny, t.maxy, minx, maxx, miny, maxy);
        }
        memset(mask, 0, sizeof mask);
        reference_mask(&t, mask);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                if (mask[y * w + x])
                    cr_assert(!t.empty && x >= t.minx && x <= t.maxx && y >= t.miny && y <= t.maxy,
                              "case %d: covered pixel (%d, %d) outside the box", i, x, y);
    }
}

/* --- the render target ------------------------------------------------------------ */

Test(target, nearest_wins_ties_keep_the_earlier)
{
    struct target fb;
    cr_assert(target_init(&fb, 4, 3, 0xff101010u));
    cr_expect_eq(fb.color[5], 0xff101010u);
    cr_expect(isinf(fb.depth[5]) && fb.depth[5] > 0);
    cr_expect(target_depth_pass(&fb, 1, 1, 1e30f));
    target_write(&fb, 1, 1, 2.0f, 0xffff0000u);
    cr_expect_eq(fb.color[5], 0xffff0000u, "first write into +infinity passes");
    target_write(&fb, 1, 1, 1.0f, 0xff00ff00u);
    cr_expect_eq(fb.color[5], 0xff00ff00u, "smaller z wins");
    cr_expect(!target_depth_pass(&fb, 1, 1, 1.0f));
    target_write(&fb, 1, 1, 1.0f, 0xff0000ffu);
    cr_expect_eq(fb.color[5], 0xff00ff00u, "a tie keeps the earlier");
    target_write(&fb, 1, 1, 3.0f, 0xffffffffu);
    cr_expect_eq(fb.color[5], 0xff00ff00u, "farther loses");
    cr_expect_eq(fb.depth[5], 1.0f);
    cr_expect_eq(fb.count[5], 4, "every write counts, whatever the depth test said");
    for (int i = 0; i < 12; i++)
        if (i != 5)
            cr_expect(fb.count[i] == 0 && fb.color[i] == 0xff101010u, "pixel %d untouched", i);
    target_free(&fb);
}

Test(target, coverage_count_saturates_at_255)
{
    struct target fb;
    cr_assert(target_init(&fb, 2, 2, 0));
    for (int i = 0; i < 300; i++)
        target_write(&fb, 0, 1, (float)(300 - i), 0xff000000u | (uint32_t)i);
    cr_expect_eq(fb.count[2], 255);
    cr_expect_eq(fb.count[0], 0);
    cr_expect_eq(fb.color[2], 0xff000000u | 299u);
    target_free(&fb);

    /* and through every lesson: 300 copies of one triangle */
    struct test_variant tv[MAX_TEST_VARIANTS];
    int n = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    struct vertex v[3] = { test_vertex(1.2, 1.1), test_vertex(9.7, 2.3), test_vertex(3.1, 8.8) };
    struct tri_setup t;
    cr_assert(tri_setup(&t, v, 12, 12));
    uint8_t ref[144] = { 0 };
    reference_mask(&t, ref);
    for (int i = 0; i < 144; i++)
        ref[i] = ref[i] ? 255 : 0;
    for (int k = 0; k < n && k < MAX_TEST_VARIANTS; k++) {
        cr_assert(target_init(&fb, 12, 12, 0));
        for (int i = 0; i < 300; i++)
            rasterize_one(tv[k].variant, NULL, &t, &fb, NULL);
        char label[128];
        struct case_info info = { variant_label(&tv[k], label, sizeof label), test_seed(), 0, v, 3 };
        cr_expect(coverage_equal(ref, fb.count, 12, 12, &info));
        target_free(&fb);
    }
}

/* --- the reference against the rule's definition ---------------------------------- */

/* Covered, decided from the definition alone: the centre is on the inner
 * side of every edge (the side of the third vertex), or exactly on an edge
 * that is top or left by top_left_by_definition(). No setup, no bias. */
static bool covered_by_definition(const int32_t X[3], const int32_t Y[3], int64_t cx, int64_t cy)
{
    for (int k = 0; k < 3; k++) {
        int a = k, b = (k + 1) % 3, c = (k + 2) % 3;
        int64_t ex = (int64_t)X[b] - X[a], ey = (int64_t)Y[b] - Y[a];
        int64_t side_p = ex * (cy - Y[a]) - ey * (cx - X[a]);
        int64_t side_c = ex * ((int64_t)Y[c] - Y[a]) - ey * ((int64_t)X[c] - X[a]);
        if (side_c == 0)
            return false;                       /* degenerate */
        if (side_p == 0) {
            if (!top_left_by_definition(X[a], Y[a], X[b], Y[b], X[c], Y[c]))
                return false;
        } else if ((side_p > 0) != (side_c > 0)) {
            return false;
        }
    }
    return true;
}

Test(reference, agrees_with_the_rule_as_defined)
{
    struct rng r = rng_for(6);
    const int w = 40, h = 30;
    uint8_t mask[40 * 30];
    for (int i = 0; i < 20000; i++) {
        struct vertex v[3];
        random_tri(&r, (enum tri_category)(i % CAT_COUNT), w, h, v);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        memset(mask, 0, sizeof mask);
        reference_mask(&t, mask);
        int32_t X[3], Y[3];
        for (int k = 0; k < 3; k++) {               /* the input order, not normalised */
            X[k] = snap_coord(v[k].x, 8);
            Y[k] = snap_coord(v[k].y, 8);
        }
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                bool expect = covered_by_definition(X, Y, x * 256 + 128, y * 256 + 128);
                if (mask[y * w + x] != expect) {
                    struct case_info info = { "reference_coverage vs the definition", test_seed(), (uint64_t)i, v, 3 };
                    print_case(&info);
                    cr_assert_fail("pixel (%d, %d): reference %d, definition %d", x, y, mask[y * w + x], expect);
                }
            }
    }
}

/* regression: pack_rgb clamped with "c < 0 ? 0 : c > 1 ? 1 : c", which lets
 * a NaN through to an undefined float-to-int conversion; a NaN channel is 0 */
Test(target, pack_rgb_nan_reached_an_undefined_cast)
{
    cr_expect_eq(pack_rgb(NAN, 1, 0.5), 0xff00ff80u);
    cr_expect_eq(pack_rgb(-INFINITY, INFINITY, -0.0), 0xff00ff00u);
    cr_expect_eq(pack_rgb(1e300, -1e300, 0.2), 0xffff0033u);
}

/* regression: shade_pixel's checker square went through (long)floor(s * n),
 * undefined for a NaN or a huge s; such squares are light (parity 0) now,
 * and ordinary ones keep their parity, negative ones included */
Test(target, checker_parity_of_nan_and_huge_coordinates)
{
    struct raster_params p = { .checker = 4 };
    uint32_t light = pack_rgb(1, 1, 1), dark = pack_rgb(CHECKER_DARK, CHECKER_DARK, CHECKER_DARK);
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, NAN, 0.1), light);
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, 1e300, 0.1), light);
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, 0.1, 0.1), light);      /* square (0, 0) */
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, 0.3, 0.1), dark);       /* square (1, 0) */
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, -0.1, 0.1), dark);      /* square (-1, 0) */
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, -0.3, -0.1), dark);     /* square (-2, -1) */
    cr_expect_eq(shade_pixel(&p, NULL, 1, 1, 1, -0.3, -0.3), light);    /* square (-2, -2) */
}
