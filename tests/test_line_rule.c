/* test_line_rule.c - lines (lessons/CONVENTIONS.md, "Lines"): the diamond-exit
 * rule with the perturbation delta = (e, e^2), held three ways.
 *
 * - An oracle written from CONVENTIONS alone, by another method than the
 *   code's: the moved segment A + delta + t (B - A), t in [0, 1], clipped
 *   against the diamond's four open half-planes (Liang-Barsky), each bound
 *   on t a rational whose numerator is a polynomial in e, compared by cross
 *   multiplication and read lexicographically. Its own snapping (lrint),
 *   every pixel of the target (no box).
 * - src/raster/line.c's reference (the separating-axis test on every pixel
 *   of the box) and its walk (Bresenham's midpoint step, the rule at the
 *   ends) against it: 0 pixels apart on seeded random and tie-heavy scenes
 *   (ends and paths on diamonds' corners and edges, axis-parallel lines on
 *   pixel boundaries, 45 degree lines, ends off screen to +-16,000 px,
 *   zero length).
 * - The rule's consequences CONVENTIONS names: the examples, the joint of
 *   a path drawn once, a segment split at an exact point drawing the same
 *   pixels, a reversed segment differing only at its two ends' pixels as
 *   the rule predicts.
 */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "front/front.h"
#include "raster/line.h"
#include "testlib.h"

/* --- the oracle ------------------------------------------------------------------ */

/* a0 + a1 e + a2 e^2 */
struct epoly {
    int64_t a[3];
};

static int poly_sign(struct epoly p)
{
    for (int i = 0; i < 3; i++)
        if (p.a[i] != 0)
            return p.a[i] > 0 ? 1 : -1;
    return 0;
}

/* A bound on t: num / den, den > 0, open (strict) or closed. */
struct bound {
    struct epoly num;
    int64_t den;
    bool open;
};

/* sign(b1 - b2) */
static int bound_cmp(const struct bound *b1, const struct bound *b2)
{
    struct epoly d;
    for (int i = 0; i < 3; i++)
        d.a[i] = b1->num.a[i] * b2->den - b2->num.a[i] * b1->den;
    return poly_sign(d);
}

struct oracle_line {
    int64_t ax, ay, bx, by;     /* snapped by the oracle itself */
};

static struct oracle_line oracle_snap(const struct vertex v[2])
{
    return (struct oracle_line){ lrint(v[0].x * 256.0), lrint(v[0].y * 256.0),
                                 lrint(v[1].x * 256.0), lrint(v[1].y * 256.0) };
}

/* Does A + delta + t (B - A), t in [0, 1], meet the open diamond of (px, py)? */
static bool oracle_meets(const struct oracle_line *o, int px, int py)
{
    int64_t cx = 256 * (int64_t)px + 128, cy = 256 * (int64_t)py + 128;
    int64_t dx = o->bx - o->ax, dy = o->by - o->ay;
    struct bound lower[6], upper[6];
    int nl = 0, nu = 0;
    lower[nl++] = (struct bound){ { { 0, 0, 0 } }, 1, false };     /* t >= 0 */
    upper[nu++] = (struct bound){ { { 1, 0, 0 } }, 1, false };     /* t <= 1 */
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2) {
            /* sx (x - cx) + sy (y - cy) < 128 at x = ax + e + t dx, y = ay + e^2 + t dy:
             * alpha + beta t < 128 */
            struct epoly alpha = { { sx * (o->ax - cx) + sy * (o->ay - cy), sx, sy } };
            int64_t beta = sx * dx + sy * dy;
            struct epoly rest = { { 128 - alpha.a[0], -alpha.a[1], -alpha.a[2] } };  /* 128 - alpha */
            if (beta == 0) {
                if (poly_sign(rest) <= 0)
                    return false;           /* alpha >= 128 for every t */
            } else if (beta > 0) {
                upper[nu++] = (struct bound){ rest, beta, true };   /* t < rest / beta */
            } else {
                struct epoly neg = { { -rest.a[0], -rest.a[1], -rest.a[2] } };
                lower[nl++] = (struct bound){ neg, -beta, true };   /* t > rest / beta */
            }
        }
    for (int i = 0; i < nl; i++)
        for (int j = 0; j < nu; j++) {
            int c = bound_cmp(&lower[i], &upper[j]);
            if (c > 0 || (c == 0 && (lower[i].open || upper[j].open)))
                return false;
        }
    return true;
}

/* Is the moved point (x + e, y + e^2) inside the open diamond of (px, py)? */
static bool oracle_in(int64_t x, int64_t y, int px, int py)
{
    int64_t cx = 256 * (int64_t)px + 128, cy = 256 * (int64_t)py + 128;
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2) {
            struct epoly g = { { sx * (x - cx) + sy * (y - cy) - 128, sx, sy } };
            if (poly_sign(g) >= 0)
                return false;
        }
    return true;
}

/* Add the oracle's pixels of the line to mask (w x h), every pixel tested. */
static void oracle_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct oracle_line o = oracle_snap(v);
    if (o.ax == o.bx && o.ay == o.by)
        return;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            if (oracle_meets(&o, x, y) && !oracle_in(o.bx, o.by, x, y))
                mask[(size_t)y * w + x]++;
}

/* --- the code under test --------------------------------------------------------- */

struct mask_ctx {
    uint8_t *mask;
    int w;
};

static void add_pixel(void *ctx, int x, int y)
{
    struct mask_ctx *m = ctx;
    m->mask[(size_t)y * m->w + x]++;
}

static void reference_line_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct line_setup l;
    line_setup(&l, v, w, h);
    line_reference(&l, add_pixel, &(struct mask_ctx){ mask, w });
}

static void walk_line_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct line_setup l;
    line_setup(&l, v, w, h);
    line_walk(&l, add_pixel, &(struct mask_ctx){ mask, w });
}

/* --- scenes: random and tie-heavy ---------------------------------------------- */

#define TW 40
#define TH 32

/* A coordinate on the 1/256 grid where ties live: a pixel centre, a pixel
 * boundary, a diamond's corner (centre +- 1/2 on one axis), or anywhere. */
static double tie_coord(struct rng *r, int n)
{
    int p = rng_int(r, -2, n + 1);
    switch (rng_int(r, 0, 5)) {
    case 0: return p + 0.5;
    case 1: return p;
    case 2: return p + 0.5 + (rng_chance(r, 0.5) ? 0.5 : -0.5) * rng_int(r, 0, 1);
    case 3: return p + rng_int(r, 0, 256) / 256.0;
    case 4: return p + 0.5 + rng_int(r, -128, 128) / 256.0;     /* on a diamond's edge with the other */
    default: return rng_range(r, -3, n + 3);
    }
}

enum line_kind { LK_RANDOM, LK_TIES, LK_DIAMOND_EDGE, LK_AXIS, LK_DIAGONAL, LK_FAR, LK_ZERO, LK_SHORT,
                 LK_COUNT };
static const char *const kind_names[] = { "random", "ties", "diamond-edge", "axis", "diagonal",
                                          "far", "zero", "short" };

static struct vertex line_end(double x, double y, struct rng *r)
{
    struct vertex v = test_vertex(x, y);
    v.z = rng_range(r, 0.5, 4);
    v.r = rng_unit(r), v.g = rng_unit(r), v.b = rng_unit(r);
    return v;
}

static void random_line(struct rng *r, enum line_kind k, struct vertex v[2])
{
    double x0, y0, x1, y1;
    switch (k) {
    case LK_RANDOM:
        x0 = rng_range(r, -4, TW + 4), y0 = rng_range(r, -4, TH + 4);
        x1 = rng_range(r, -4, TW + 4), y1 = rng_range(r, -4, TH + 4);
        break;
    case LK_TIES:
        x0 = tie_coord(r, TW), y0 = tie_coord(r, TH), x1 = tie_coord(r, TW), y1 = tie_coord(r, TH);
        break;
    case LK_DIAMOND_EDGE: {
        /* ends exactly on a diamond's edge or corner: |X| + |Y| = 1/2 */
        double c[4];
        for (int i = 0; i < 2; i++) {
            int a = rng_int(r, 0, 128);
            c[2 * i] = rng_int(r, 0, TW - 1) + 0.5 + (rng_chance(r, 0.5) ? a : -a) / 256.0;
            c[2 * i + 1] = rng_int(r, 0, TH - 1) + 0.5 + (rng_chance(r, 0.5) ? 128 - a : a - 128) / 256.0;
        }
        x0 = c[0], y0 = c[1], x1 = c[2], y1 = c[3];
        break;
    }
    case LK_AXIS:
        x0 = tie_coord(r, TW), y0 = tie_coord(r, TH), x1 = tie_coord(r, TW), y1 = tie_coord(r, TH);
        if (rng_chance(r, 0.5))
            y1 = y0;
        else
            x1 = x0;
        break;
    case LK_DIAGONAL: {
        x0 = tie_coord(r, TW), y0 = tie_coord(r, TH);
        double d = rng_int(r, -20 * 256, 20 * 256) / 256.0;
        x1 = x0 + d, y1 = y0 + (rng_chance(r, 0.5) ? d : -d);
        break;
    }
    case LK_FAR: {
        /* through the target, ends up to 16,000 px away */
        double cx = tie_coord(r, TW), cy = tie_coord(r, TH);
        double a = rng_range(r, 0, 6.283185307179586);
        if (rng_chance(r, 0.3))
            a = rng_int(r, 0, 7) * 0.7853981633974483;     /* axis-parallel or 45 degrees */
        double d0 = rng_range(r, 1, 16000), d1 = rng_range(r, 1, 16000);
        x0 = cx - d0 * cos(a), y0 = cy - d0 * sin(a), x1 = cx + d1 * cos(a), y1 = cy + d1 * sin(a);
        x0 = fmax(-16000, fmin(16000, x0)), y0 = fmax(-16000, fmin(16000, y0));
        x1 = fmax(-16000, fmin(16000, x1)), y1 = fmax(-16000, fmin(16000, y1));
        break;
    }
    case LK_ZERO:
        x0 = x1 = tie_coord(r, TW), y0 = y1 = tie_coord(r, TH);
        if (rng_chance(r, 0.5))
            x1 += 1 / 1024.0;       /* snaps to the same point */
        break;
    default:    /* LK_SHORT: within a pixel or two, ends on the grid */
        x0 = tie_coord(r, TW), y0 = tie_coord(r, TH);
        x1 = x0 + rng_int(r, -384, 384) / 256.0, y1 = y0 + rng_int(r, -384, 384) / 256.0;
        break;
    }
    v[0] = line_end(x0, y0, r);
    v[1] = line_end(x1, y1, r);
}

static void print_line(const char *what, const struct vertex v[2])
{
    fprintf(stderr, "%s: line %.17g %.17g 1 1 1 1  %.17g %.17g 1 1 1 1 (target %d x %d)\n", what,
            v[0].x, v[0].y, v[1].x, v[1].y, TW, TH);
}

static bool masks_equal(const uint8_t *want, const uint8_t *got, const char *what,
                        const struct vertex v[2], uint64_t seed, int index)
{
    if (memcmp(want, got, TW * TH) == 0)
        return true;
    print_line(what, v);
    struct case_info info = { what, seed, (uint64_t)index, v, 0 };
    coverage_equal(want, got, TW, TH, &info);
    return false;
}

/* --- 0 pixels apart ------------------------------------------------------------- */

Test(line_rule, reference_and_walk_equal_the_oracle_on_random_and_tie_heavy_lines)
{
    struct rng r = rng_for(3400);
    int lit = 0, lines = 0;
    for (int k = 0; k < LK_COUNT; k++)
        for (int i = 0; i < 400; i++) {
            struct vertex v[2];
            random_line(&r, (enum line_kind)k, v);
            uint8_t want[TW * TH] = { 0 }, ref[TW * TH] = { 0 }, walk[TW * TH] = { 0 };
            oracle_mask(v, TW, TH, want);
            reference_line_mask(v, TW, TH, ref);
            walk_line_mask(v, TW, TH, walk);
            char what[96];
            snprintf(what, sizeof what, "%s line %d, the reference", kind_names[k], i);
            cr_assert(masks_equal(want, ref, what, v, test_seed(), i));
            snprintf(what, sizeof what, "%s line %d, the walk", kind_names[k], i);
            cr_assert(masks_equal(want, walk, what, v, test_seed(), i));
            for (int p = 0; p < TW * TH; p++) {
                cr_assert_leq(want[p], 1, "a line draws a pixel at most once");
                lit += want[p];
            }
            lines++;
        }
    /* the scenes drew something (the oracle is not vacuously empty) */
    cr_assert_gt(lit, lines * 3, "%d pixels for %d lines", lit, lines);
}

/* Whole lines across a large target, with ends far off it: the walk and
 * the reference (the oracle is slow for every pixel of 512 x 256). */
Test(line_rule, walk_equals_the_reference_on_a_large_target)
{
    enum { W = 512, H = 256 };
    uint8_t *ref = calloc(W * H, 1), *walk = calloc(W * H, 1);
    cr_assert(ref && walk);
    struct rng r = rng_for(3401);
    for (int i = 0; i < 200; i++) {
        struct vertex v[2];
        for (int k = 0; k < 2; k++)
            v[k] = line_end(rng_chance(&r, 0.3) ? rng_range(&r, -16000, 16000) : rng_int(&r, -40, W + 40) + rng_int(&r, 0, 4) / 4.0,
                            rng_chance(&r, 0.3) ? rng_range(&r, -16000, 16000) : rng_int(&r, -40, H + 40) + rng_int(&r, 0, 4) / 4.0, &r);
        struct line_setup l;
        line_setup(&l, v, W, H);
        line_reference(&l, add_pixel, &(struct mask_ctx){ ref, W });
        line_walk(&l, add_pixel, &(struct mask_ctx){ walk, W });
    }
    size_t first = 0;
    while (first < (size_t)W * H && ref[first] == walk[first])
        first++;
    cr_assert_eq(first, (size_t)W * H, "pixel (%zu, %zu): reference %d, walk %d", first % W, first / W,
                 ref[first], walk[first]);
    free(ref);
    free(walk);
}

/* --- what CONVENTIONS says follows ------------------------------------------------ */

static void expect_pixels(const char *what, double x0, double y0, double x1, double y1,
                          const char *want_rows[])
{
    struct vertex v[2] = { test_vertex(x0, y0), test_vertex(x1, y1) };
    uint8_t want[TW * TH] = { 0 }, got[TW * TH] = { 0 }, walk[TW * TH] = { 0 };
    for (int y = 0; want_rows[y]; y++)
        for (int x = 0; want_rows[y][x]; x++)
            want[y * TW + x] = want_rows[y][x] == '#';
    oracle_mask(v, TW, TH, got);
    cr_assert(masks_equal(want, got, what, v, 0, 0), "%s: the oracle", what);
    memset(got, 0, sizeof got);
    reference_line_mask(v, TW, TH, got);
    cr_assert(masks_equal(want, got, what, v, 0, 0), "%s: the reference", what);
    walk_line_mask(v, TW, TH, walk);
    cr_assert(masks_equal(want, walk, what, v, 0, 0), "%s: the walk", what);
}

Test(line_rule, the_examples_of_the_conventions)
{
    expect_pixels("centre of pixel 0 to centre of pixel 5 draws pixels 0..4", 0.5, 1.5, 5.5, 1.5,
                  (const char *[]){ "......", "#####.", NULL });
    expect_pixels("... and back draws 1..5", 5.5, 1.5, 0.5, 1.5,
                  (const char *[]){ "......", ".#####", NULL });
    expect_pixels("horizontal on y = 2 draws the row below it", 0.25, 2, 4.25, 2,
                  (const char *[]){ "....", "....", "####", "....", NULL });
    expect_pixels("... from a diamond's top corner, not that diamond", 0.5, 2, 4.25, 2,
                  (const char *[]){ "....", "....", ".###", "....", NULL });
    expect_pixels("vertical on x = 2 draws the column to its right", 2, 0.5, 2, 3.75,
                  (const char *[]){ "..#.", "..#.", "..#.", "..#.", "....", NULL });
    expect_pixels("a diagonal through the diamonds' corners", 1, 1, 4, 4,
                  (const char *[]){ "....", ".#..", "..#.", "...#", "....", NULL });
    expect_pixels("zero length draws nothing", 2.5, 2.5, 2.5, 2.5, (const char *[]){ NULL });
    expect_pixels("inside one diamond, start to end: nothing", 2.5, 2.5, 2.625, 2.5,
                  (const char *[]){ NULL });
    expect_pixels("out of a diamond: the start's pixel", 2.5, 2.5, 2.5, 3,
                  (const char *[]){ "...", "...", "..#", NULL });
}

/* The pixels of a path v[0] -> v[1] -> ... -> v[n - 1]. */
static void path_mask(const struct vertex *v, int n, uint8_t *mask)
{
    for (int i = 0; i + 1 < n; i++)
        reference_line_mask(v + i, TW, TH, mask);
}

static int pixel_of(int32_t c)
{
    return (int)floor_div(c, SUBPIXEL_ONE);
}

/* The pixel whose diamond holds the moved point (x, y), or false. */
static bool diamond_of(int32_t x, int32_t y, int *px, int *py)
{
    for (int j = pixel_of(y) - 1; j <= pixel_of(y) + 1; j++)
        for (int i = pixel_of(x) - 1; i <= pixel_of(x) + 1; i++)
            if (oracle_in(x, y, i, j)) {
                *px = i, *py = j;
                return true;
            }
    return false;
}

Test(line_rule, a_joint_inside_a_diamond_is_drawn_once)
{
    struct rng r = rng_for(3402);
    int joints = 0;
    for (int i = 0; i < 3000; i++) {
        struct vertex v[3];
        random_line(&r, i % 2 ? LK_TIES : LK_RANDOM, v);
        /* the joint: a grid point within a diamond, often on its edges */
        int a = rng_int(&r, -127, 127), b = (128 - abs(a)) - rng_int(&r, 1, 8) * (rng_chance(&r, 0.5) ? 0 : 1);
        if (b < 0)
            b = 0;
        int jx = rng_int(&r, 2, TW - 3), jy = rng_int(&r, 2, TH - 3);
        v[2] = v[1];
        v[1] = line_end(jx + 0.5 + a / 256.0, jy + 0.5 + (rng_chance(&r, 0.5) ? b : -b) / 256.0, &r);
        int px, py;
        if (!diamond_of(snap_coord(v[1].x, 8), snap_coord(v[1].y, 8), &px, &py))
            continue;
        uint8_t m[TW * TH] = { 0 };
        path_mask(v, 3, m);
        struct line_setup l0, l1;
        if (!line_setup(&l0, v, TW, TH) || !line_setup(&l1, v + 1, TW, TH))
            continue;
        if (oracle_in(l1.x[1], l1.y[1], px, py))
            continue;       /* the path ends in the joint's diamond: drawn by neither */
        if (m[py * TW + px] != 1)
            print_line("first segment", v), print_line("second segment", v + 1);
        cr_assert_eq(m[py * TW + px], 1, "case %d: the joint's pixel (%d, %d) drawn %d times", i, px,
                     py, m[py * TW + px]);
        joints++;
    }
    cr_assert_gt(joints, 1000, "only %d joints tested", joints);
}

Test(line_rule, splitting_at_an_exact_point_changes_no_pixel)
{
    struct rng r = rng_for(3403);
    for (int i = 0; i < 2000; i++) {
        struct vertex v[2];
        random_line(&r, i % 3 == 0 ? LK_AXIS : i % 3 == 1 ? LK_TIES : LK_DIAGONAL, v);
        int32_t ax = snap_coord(v[0].x, 8), ay = snap_coord(v[0].y, 8);
        int32_t bx = snap_coord(v[1].x, 8), by = snap_coord(v[1].y, 8);
        /* a point exactly on the segment and on the grid: A + j (B - A) / k
         * where k divides both differences */
        int k = rng_int(&r, 2, 8);
        bx = ax + (bx - ax) / k * k, by = ay + (by - ay) / k * k;
        int j = rng_int(&r, 0, k);
        int32_t sx = ax + (bx - ax) / k * j, sy = ay + (by - ay) / k * j;
        struct vertex path[3] = { v[0], v[1], v[1] };
        path[0].x = ax / 256.0, path[0].y = ay / 256.0;
        path[1].x = sx / 256.0, path[1].y = sy / 256.0;
        path[2].x = bx / 256.0, path[2].y = by / 256.0;
        uint8_t whole[TW * TH] = { 0 }, split[TW * TH] = { 0 };
        struct vertex ab[2] = { path[0], path[2] };
        reference_line_mask(ab, TW, TH, whole);
        path_mask(path, 3, split);
        cr_assert(masks_equal(whole, split, "split at an exact point", ab, test_seed(), i),
                  "case %d: split at (%.17g, %.17g)", i, sx / 256.0, sy / 256.0);
    }
}

Test(line_rule, reversing_changes_only_the_two_end_pixels_as_the_rule_says)
{
    struct rng r = rng_for(3404);
    int changed = 0;
    for (int i = 0; i < 3000; i++) {
        struct vertex v[2], back[2];
        random_line(&r, (enum line_kind)(i % LK_COUNT), v);
        back[0] = v[1], back[1] = v[0];
        uint8_t fwd[TW * TH] = { 0 }, rev[TW * TH] = { 0 };
        reference_line_mask(v, TW, TH, fwd);
        reference_line_mask(back, TW, TH, rev);
        int32_t ax = snap_coord(v[0].x, 8), ay = snap_coord(v[0].y, 8);
        int32_t bx = snap_coord(v[1].x, 8), by = snap_coord(v[1].y, 8);
        int pa[2] = { -1000, -1000 }, pb[2] = { -1000, -1000 };
        bool in_a = diamond_of(ax, ay, &pa[0], &pa[1]);
        bool in_b = diamond_of(bx, by, &pb[0], &pb[1]);
        bool same = in_a && in_b && pa[0] == pb[0] && pa[1] == pb[1];
        bool zero = ax == bx && ay == by;
        for (int y = 0; y < TH; y++)
            for (int x = 0; x < TW; x++) {
                bool at_a = in_a && x == pa[0] && y == pa[1];
                bool at_b = in_b && x == pb[0] && y == pb[1];
                /* A -> B leaves out B's pixel and draws A's (its start is
                 * in it); B -> A the other way round; one diamond holding
                 * both ends is drawn by neither */
                int want_fwd = rev[y * TW + x], want_rev = fwd[y * TW + x];
                if (!zero && !same && at_a)
                    want_fwd = 1, want_rev = 0;
                else if (!zero && !same && at_b)
                    want_fwd = 0, want_rev = 1;
                if (fwd[y * TW + x] != want_fwd || rev[y * TW + x] != want_rev)
                    print_line("forward", v);
                cr_assert(fwd[y * TW + x] == want_fwd && rev[y * TW + x] == want_rev,
                          "case %d, pixel (%d, %d): forward %d, reversed %d", i, x, y, fwd[y * TW + x],
                          rev[y * TW + x]);
                changed += fwd[y * TW + x] != rev[y * TW + x];
            }
    }
    cr_assert_gt(changed, 1000, "the ends differed on only %d pixels", changed);
}

/* --- colour, depth and counts ------------------------------------------------------- */

static int channel(uint32_t c, int i)
{
    return (int)((c >> (16 - 8 * i)) & 255);
}

Test(line_draw, colour_and_z_by_the_projection_parameter_clamped)
{
    struct rng r = rng_for(3405);
    struct target fb;
    cr_assert(target_init(&fb, TW, TH, 0xff000000u));
    int checked = 0;
    for (int i = 0; i < 600; i++) {
        struct vertex v[2];
        random_line(&r, (enum line_kind)(i % LK_COUNT), v);
        target_clear(&fb);
        struct line_setup l;
        line_setup(&l, v, TW, TH);
        line_draw(&l, &fb);
        uint8_t want[TW * TH] = { 0 };
        oracle_mask(v, TW, TH, want);
        struct oracle_line o = oracle_snap(v);
        double len2 = (double)(o.bx - o.ax) * (o.bx - o.ax) + (double)(o.by - o.ay) * (o.by - o.ay);
        for (int y = 0; y < TH; y++)
            for (int x = 0; x < TW; x++) {
                size_t p = (size_t)y * TW + x;
                cr_assert_eq(fb.count[p], want[p], "case %d (%d, %d): count %d, the rule %d", i, x, y,
                             fb.count[p], want[p]);
                if (!want[p])
                    continue;
                /* t of the pixel centre, from CONVENTIONS */
                double t = ((256.0 * x + 128 - o.ax) * (o.bx - o.ax) + (256.0 * y + 128 - o.ay) * (o.by - o.ay)) / len2;
                t = t < 0 ? 0 : t > 1 ? 1 : t;
                double c[3] = { (1 - t) * v[0].r + t * v[1].r, (1 - t) * v[0].g + t * v[1].g,
                                (1 - t) * v[0].b + t * v[1].b };
                double z = (1 - t) * v[0].z + t * v[1].z;
                for (int k = 0; k < 3; k++) {
                    int got = channel(fb.color[p], k), exact = (int)lround(c[k] * 255);
                    cr_assert(abs(got - exact) <= PIXEL_COLOUR_LEVELS, "case %d (%d, %d) channel %d: %d, "
                              "exact %d", i, x, y, k, got, exact);
                }
                cr_assert(fabs(fb.depth[p] - z) <= 1e-6 * z, "case %d (%d, %d): z %g, exact %g", i, x, y,
                          fb.depth[p], z);
                checked++;
            }
    }
    cr_assert_gt(checked, 2000);
    target_free(&fb);
}

Test(line_draw, the_nearer_line_wins_and_a_tie_keeps_the_earlier)
{
    struct target fb;
    cr_assert(target_init(&fb, 8, 8, 0xff000000u));
    struct vertex red[2] = { test_vertex(0.5, 3.5), test_vertex(7.5, 3.5) };
    struct vertex green[2] = { test_vertex(3.5, 0.5), test_vertex(3.5, 7.5) };
    red[0].r = red[1].r = 1, red[0].g = red[1].g = red[0].b = red[1].b = 0;
    green[0].g = green[1].g = 1, green[0].r = green[1].r = green[0].b = green[1].b = 0;
    struct line_setup a, b;
    for (int c = 0; c < 3; c++) {
        /* red at z 2, green at z 1, 2 or 3 drawn after it */
        double gz = 1 + c;
        red[0].z = red[1].z = 2;
        green[0].z = green[1].z = gz;
        target_clear(&fb);
        line_setup(&a, red, 8, 8);
        line_setup(&b, green, 8, 8);
        line_draw(&a, &fb);
        line_draw(&b, &fb);
        uint32_t crossing = fb.color[3 * 8 + 3];
        cr_assert_eq(fb.count[3 * 8 + 3], 2, "both lines counted at the crossing");
        cr_assert_eq(crossing, gz < 2 ? 0xff00ff00u : 0xffff0000u, "green at z = %g: %08x", gz, crossing);
    }
    target_free(&fb);
}

/* --- the wireframe ---------------------------------------------------------------- */

static struct scene scene_of(const char *text)
{
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "test.scene", text, strlen(text), err, sizeof err), "%s", err);
    return s;
}

static bool lex_le(const struct vertex *a, const struct vertex *b)
{
    int32_t ax = snap_coord(a->x, 8), bx = snap_coord(b->x, 8);
    return ax < bx || (ax == bx && snap_coord(a->y, 8) <= snap_coord(b->y, 8));
}

Test(line_draw, wireframe_draws_each_shared_edge_once_from_its_smaller_end_in_file_order)
{
    struct scene s = scene_of(
        "size 16 16\n"
        "line 1 1 1  1 0 0   9 1 1  1 0 0\n"
        "tri 2 2 1  1 1 1   10 2 1  1 1 1   2 10 1  1 1 1\n"
        "line 3 3 1  0 1 0   3 3 1  0 1 0\n"
        "tri 10 2 1  0 0 1   2 10.001 1  0 0 1   10 10 1  0 0 1\n"     /* shares 10,2 - 2,10 (snapped) */
        "line 15 15 1  0 0 1   0 0 1  0 0 1\n");
    int n;
    struct vertex *w = scene_wireframe(&s, &n);
    cr_assert_not_null(w);
    cr_assert_eq(n, 3 + 3 + 2, "three lines, three edges, then two (one shared): %d", n);
    cr_assert(w[0].x == 1 && w[1].x == 9, "the first line first, as the file has it");
    cr_assert(w[2].x == 2 && w[2].y == 2 && w[3].x == 10 && w[3].y == 2, "edge AB");
    cr_assert(w[4].x == 2 && w[4].y == 10 && w[5].x == 10 && w[5].y == 2,
              "edge BC from its smaller end (2, 10)");
    cr_assert(w[6].x == 2 && w[6].y == 2 && w[7].x == 2 && w[7].y == 10, "edge CA from (2, 2)");
    cr_assert(w[8].x == 3 && w[9].x == 3, "the second line after the first triangle");
    /* the second triangle: 10,2 -> 2,10 is drawn already; 2,10 -> 10,10 and 10,10 -> 10,2 */
    cr_assert(w[10].x == 2 && w[10].y == 10.001 && w[11].x == 10 && w[11].y == 10);
    cr_assert(w[12].x == 10 && w[12].y == 2 && w[13].x == 10 && w[13].y == 10);
    cr_assert(w[14].x == 15 && w[15].x == 0, "a line keeps its own direction");
    free(w);
    scene_free(&s);
}

Test(line_draw, wireframe_of_meshes_and_a_3d_scene)
{
    const char *names[] = { "mesh", "fan", "offgrid-strip", "room", "model" };
    for (int k = 0; k < 5; k++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, names[k], err, sizeof err), "%s", err);
        if (s.world.camera_line)
            cr_assert(front_scene(&s));
        int n;
        struct vertex *w = scene_wireframe(&s, &n);
        cr_assert_not_null(w);
        /* each edge once: no two segments with the same snapped ends, every
         * one from its smaller end, and as many as the distinct edges */
        for (int i = 0; i < n; i++) {
            cr_assert(lex_le(&w[2 * i], &w[2 * i + 1]), "%s: edge %d from its larger end", names[k], i);
            for (int j = 0; j < i; j++)
                cr_assert(!(snap_coord(w[2 * i].x, 8) == snap_coord(w[2 * j].x, 8) &&
                            snap_coord(w[2 * i].y, 8) == snap_coord(w[2 * j].y, 8) &&
                            snap_coord(w[2 * i + 1].x, 8) == snap_coord(w[2 * j + 1].x, 8) &&
                            snap_coord(w[2 * i + 1].y, 8) == snap_coord(w[2 * j + 1].y, 8)),
                          "%s: edges %d and %d are the same", names[k], j, i);
        }
        cr_assert_lt(n, 3 * s.ntris, "%s: %d triangles share edges, %d segments", names[k], s.ntris, n);
        cr_assert_gt(n, s.ntris, "%s", names[k]);
        free(w);
        scene_free(&s);
    }
}

/* Ends at the limits of the coordinate range on the largest target, long
 * side along either axis: the 64-bit budget of line.h, under the
 * sanitizers too (make test SANITIZE=1). */
Test(line_rule, walk_equals_the_reference_at_the_coordinate_limits)
{
    struct rng r = rng_for(3406);
    for (int axis = 0; axis < 2; axis++) {
        int w = axis ? 3 : TARGET_MAX, h = axis ? TARGET_MAX : 3;
        uint8_t *ref = calloc((size_t)w * h, 1), *walk = calloc((size_t)w * h, 1);
        cr_assert(ref && walk);
        for (int i = 0; i < 24; i++) {
            double lim = COORD_LIMIT - 1.0 / 256, ends[2] = { -COORD_LIMIT, lim };
            double along0 = rng_chance(&r, 0.5) ? ends[rng_int(&r, 0, 1)] : rng_range(&r, -COORD_LIMIT, lim);
            double along1 = rng_chance(&r, 0.5) ? ends[rng_int(&r, 0, 1)] : rng_range(&r, -COORD_LIMIT, lim);
            double across0 = rng_int(&r, -2 * 256, 5 * 256) / 256.0, across1 = rng_int(&r, -2 * 256, 5 * 256) / 256.0;
            if (i % 4 == 0)
                across1 = rng_chance(&r, 0.5) ? ends[rng_int(&r, 0, 1)] : across0;   /* steep, or parallel */
            struct vertex v[2] = { axis ? line_end(across0, along0, &r) : line_end(along0, across0, &r),
                                   axis ? line_end(across1, along1, &r) : line_end(along1, across1, &r) };
            struct line_setup l;
            line_setup(&l, v, w, h);
            line_reference(&l, add_pixel, &(struct mask_ctx){ ref, w });
            line_walk(&l, add_pixel, &(struct mask_ctx){ walk, w });
        }
        size_t first = 0, lit = 0;
        while (first < (size_t)w * h && ref[first] == walk[first])
            lit += ref[first++];
        cr_assert_eq(first, (size_t)w * h, "%d x %d, pixel (%zu, %zu): reference %d, walk %d", w, h,
                     first % w, first / w, ref[first], walk[first]);
        cr_assert_gt(lit, 10000, "%d x %d: only %zu pixels drawn", w, h, lit);
        free(ref);
        free(walk);
    }
}

/* --- the usual ways, against the rule ---------------------------------------------
 *
 * What lesson 00 shows against the exact rule, each counted here: every one
 * differs from it where the rule says it must not (a joint drawn twice or
 * missed, a pixel lost far from the origin), and the rule does not. */

/* The pixels of a path under `draw` (a line drawing into a mask). */
typedef void (*mask_fn)(const struct vertex v[2], int w, int h, uint8_t *mask);

/* Paths A -> B -> C with B on the 1/256 grid, inside a diamond (on its
 * edges often): how many joints a way of drawing draws twice or misses
 * (the rule: once, by B -> C), and how many pixels of the two segments
 * differ from the rule's. */
static void count_paths(mask_fn draw, int *twice, int *missed, int *differ)
{
    struct rng r = rng_for(3410);
    *twice = *missed = *differ = 0;
    for (int i = 0; i < 2000; i++) {
        struct vertex v[3];
        random_line(&r, i % 2 ? LK_TIES : LK_DIAMOND_EDGE, v);
        v[2] = line_end(tie_coord(&r, TW), tie_coord(&r, TH), &r);
        int32_t x[3], y[3];
        for (int k = 0; k < 3; k++)
            x[k] = snap_coord(v[k].x, 8), y[k] = snap_coord(v[k].y, 8);
        int px, py;
        if (!diamond_of(x[1], y[1], &px, &py) || px < 0 || px >= TW || py < 0 || py >= TH ||
            oracle_in(x[0], y[0], px, py) || oracle_in(x[2], y[2], px, py))
            continue;       /* a joint in a diamond on the target, alone in it */
        uint8_t got[TW * TH] = { 0 }, want[TW * TH] = { 0 };
        for (int k = 0; k < 2; k++) {
            draw(v + k, TW, TH, got);
            oracle_mask(v + k, TW, TH, want);
        }
        *twice += got[py * TW + px] > 1;
        *missed += got[py * TW + px] == 0;
        for (int p = 0; p < TW * TH; p++)
            *differ += got[p] != want[p];
    }
}

/* The crossing row of an x-major line at column px (or column of a
 * y-major one at row px), rounded as Bresenham's classic form rounds it:
 * the pixel nearest the line's point at the centre line, in double. */
static int64_t nearest_minor(const struct line_setup *l, int64_t u)
{
    double au = l->x_major ? l->x[0] : l->y[0], av = l->x_major ? l->y[0] : l->x[0];
    double du = (double)(l->x_major ? l->dx : l->dy), dv = (double)(l->x_major ? l->dy : l->dx);
    double v = av + ((double)pixel_centre((int)u) - au) * dv / du;
    return (int64_t)floor(v / SUBPIXEL_ONE);
}

/* Bresenham from the pixel of A to the pixel of B, both included: the
 * textbook's loop, no end rule. */
static void classic_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct line_setup l;
    if (!line_setup(&l, v, w, h))
        return;
    int64_t a = floor_div(l.x_major ? l.x[0] : l.y[0], 256), b = floor_div(l.x_major ? l.x[1] : l.y[1], 256);
    for (int64_t u = a;; u += a < b ? 1 : -1) {
        int64_t m = nearest_minor(&l, u), x = l.x_major ? u : m, y = l.x_major ? m : u;
        if (x >= 0 && x < w && y >= 0 && y < h)
            mask[y * w + x]++;
        if (u == b)
            break;
    }
}

/* The rule without the perturbation, on closed diamonds: drawn iff the
 * segment meets the closed diamond and B is not strictly inside it. */
static void closed_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct oracle_line o = oracle_snap(v);
    if (o.ax == o.bx && o.ay == o.by)
        return;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int64_t cx = 256 * (int64_t)x + 128, cy = 256 * (int64_t)y + 128;
            /* the nearest point of the segment to the centre, in the diamond's
             * metric, is at one of the segment's crossings of the diamond's
             * axes or at an end: test those */
            double best = 1e300;
            double ts[6] = { 0, 1, 0, 1, 0, 1 };
            int nt = 2;
            double dx = (double)(o.bx - o.ax), dy = (double)(o.by - o.ay);
            if (dx != 0)
                ts[nt++] = (cx - o.ax) / dx;
            if (dy != 0)
                ts[nt++] = (cy - o.ay) / dy;
            for (int k = 0; k < nt; k++) {
                double t = ts[k] < 0 ? 0 : ts[k] > 1 ? 1 : ts[k];
                double d = fabs(o.ax + t * dx - cx) + fabs(o.ay + t * dy - cy);
                best = d < best ? d : best;
            }
            bool end_inside = llabs(o.bx - cx) + llabs(o.by - cy) < 128;
            if (best <= 128 && !end_inside)
                mask[y * w + x]++;
        }
}

Test(line_exhibits, without_the_end_rule_a_joint_is_drawn_twice)
{
    int twice, missed, differ;
    count_paths(reference_line_mask, &twice, &missed, &differ);
    cr_assert_eq(twice + missed + differ, 0, "the rule: %d joints twice, %d missed, %d pixels apart "
                 "from the oracle", twice, missed, differ);
    count_paths(classic_mask, &twice, &missed, &differ);
    cr_log_info("Bresenham from A's pixel to B's: %d joints twice, %d missed, %d pixels differ\n",
                twice, missed, differ);
    cr_assert_gt(twice, 300, "joints drawn twice: %d", twice);
}

Test(line_exhibits, closed_diamonds_draw_a_joint_on_a_corner_twice)
{
    int twice, missed, differ;
    count_paths(closed_mask, &twice, &missed, &differ);
    cr_log_info("closed diamonds, no perturbation: %d joints twice, %d missed, %d pixels differ\n",
                twice, missed, differ);
    cr_assert_gt(twice, 20, "joints drawn twice: %d", twice);
}

/* A DDA in single precision: the minor coordinate stepped by its slope in
 * float, the pixel the rounded value falls in; the ends as the rule says
 * (line_draws), so only the stepping differs from the walk. */
static void dda_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    struct line_setup l;
    if (!line_setup(&l, v, w, h))
        return;
    int64_t a = floor_div(l.x_major ? l.x[0] : l.y[0], 256), b = floor_div(l.x_major ? l.x[1] : l.y[1], 256);
    int step = a < b ? 1 : -1;
    float du = (float)(l.x_major ? l.dx : l.dy), dv = (float)(l.x_major ? l.dy : l.dx);
    float slope = dv / du * (float)step;            /* minor pixels per major pixel */
    float m = (float)((l.x_major ? l.y[0] : l.x[0]) / 256.0 +
                      ((double)pixel_centre((int)a) - (l.x_major ? l.x[0] : l.y[0])) / 256.0 * slope * step);
    for (int64_t u = a;; u += step) {
        int64_t mm = (int64_t)floorf(m), x = l.x_major ? u : mm, y = l.x_major ? mm : u;
        if (x >= 0 && x < w && y >= 0 && y < h && ((u != a && u != b) || line_draws(&l, (int)x, (int)y)))
            mask[y * w + x]++;
        if (u == b)
            break;
        m += slope;
    }
}

Test(line_exhibits, float_stepping_loses_pixels_far_from_the_origin)
{
    enum { W = 256, H = 128 };
    uint8_t *want = calloc(W * H, 1), *got = calloc(W * H, 1);
    cr_assert(want && got);
    struct rng r = rng_for(3411);
    int near = 0, far = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < 200; i++) {
            memset(want, 0, W * H);
            memset(got, 0, W * H);
            /* through the target; near: ends on it, far: ends 16,000 px away */
            double cx = rng_range(&r, 0, W), cy = rng_range(&r, 0, H), a = rng_range(&r, 0, 6.283185307179586);
            double d = pass ? 16000 : rng_range(&r, 20, 100);
            struct vertex v[2] = { line_end(cx - d * cos(a), cy - d * sin(a), &r),
                                   line_end(cx + d * cos(a), cy + d * sin(a), &r) };
            reference_line_mask(v, W, H, want);
            dda_mask(v, W, H, got);
            for (int p = 0; p < W * H; p++)
                *(pass ? &far : &near) += want[p] != got[p];
        }
    cr_log_info("float DDA: %d pixels differ near the origin, %d with ends 16,000 px away\n", near, far);
    cr_assert_gt(far, 10 * (near + 10), "far %d, near %d", far, near);
    free(want);
    free(got);
}

/* A line as the rectangle of width 1 around it, two triangles under the
 * top-left rule (how a triangle rasterizer draws a wide line). */
static void quad_mask(const struct vertex v[2], int w, int h, uint8_t *mask)
{
    double dx = v[1].x - v[0].x, dy = v[1].y - v[0].y, len = sqrt(dx * dx + dy * dy);
    if (len == 0)
        return;
    double nx = -dy / len * 0.5, ny = dx / len * 0.5;
    struct vertex q[4] = { v[0], v[1], v[1], v[0] };
    q[0].x += nx, q[0].y += ny, q[1].x += nx, q[1].y += ny;
    q[2].x -= nx, q[2].y -= ny, q[3].x -= nx, q[3].y -= ny;
    struct vertex t0[3] = { q[0], q[1], q[2] }, t1[3] = { q[0], q[2], q[3] };
    struct tri_setup t;
    uint8_t *m = calloc((size_t)w * h, 1);
    cr_assert(m);
    if (tri_setup(&t, t0, w, h))
        reference_mask(&t, m);
    if (tri_setup(&t, t1, w, h))
        reference_mask(&t, m);
    for (int p = 0; p < w * h; p++)
        mask[p] += m[p];
    free(m);
}

Test(line_exhibits, two_thin_triangles_are_not_the_diamond_rule)
{
    struct rng r = rng_for(3412);
    int differ = 0, lit = 0;
    for (int i = 0; i < 1000; i++) {
        struct vertex v[2];
        random_line(&r, LK_RANDOM, v);
        uint8_t want[TW * TH] = { 0 }, got[TW * TH] = { 0 };
        oracle_mask(v, TW, TH, want);
        quad_mask(v, TW, TH, got);
        for (int p = 0; p < TW * TH; p++)
            differ += want[p] != got[p], lit += want[p];
    }
    cr_log_info("two triangles of width 1: %d of %d pixels differ\n", differ, lit);
    cr_assert_gt(differ, lit / 50, "%d of %d differ", differ, lit);
}
