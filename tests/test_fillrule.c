/* test_fillrule.c - the fill rule on the cases where it decides, in the style
 * of piglit's triangle-rasterization test: a small triangle moved one
 * sub-pixel step at a time around a pixel centre, edges exactly through
 * pixel centres, horizontal and vertical edges, vertices on centres.
 *
 * The expected pictures are reasoned out here from the rule's statement, not
 * taken from any rasterizer: every triangle is a right triangle with one
 * horizontal and one vertical leg, so which of its edges is top, left or
 * neither can be read off its shape.
 *
 *   sx = +1, sy = +1          sx = -1, sy = +1         (sy = -1: mirrored
 *   A ---------- B            B ---------- A            upside down, the
 *   |         /               \          |              horizontal leg is
 *   |      /                    \        |              then a bottom edge)
 *   |   /                         \      |
 *   C                               \    C
 *
 * With the centre at (a, b) in the triangle's own frame (a = sx (x - Ax),
 * b = sy (y - Ay), in 1/256 px) and legs Lx, Ly:
 *   horizontal leg:  value b,                 a TOP edge when sy = +1
 *                    (the triangle lies below it in y-down space);
 *   vertical leg:    value a,                 a LEFT edge when sx = +1
 *                    (the interior is on its +x side);
 *   hypotenuse:      value Lx Ly - a Ly - b Lx, a LEFT edge when sx = -1
 *                    (the interior, towards A, is on its +x side then).
 * A centre is covered when every value is positive, or zero on a top or
 * left edge.
 */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

struct frame {
    int64_t ax, ay;     /* the right-angle vertex A, 1/256 px */
    int sx, sy;         /* directions of the legs */
    int64_t lx, ly;     /* leg lengths, 1/256 px */
};

static bool covered_in_frame(const struct frame *f, int64_t cx, int64_t cy)
{
    int64_t a = f->sx * (cx - f->ax), b = f->sy * (cy - f->ay);
    int64_t e_h = b, e_v = a, e_hyp = f->lx * f->ly - a * f->ly - b * f->lx;
    bool ok_h = e_h > 0 || (e_h == 0 && f->sy > 0);
    bool ok_v = e_v > 0 || (e_v == 0 && f->sx > 0);
    bool ok_hyp = e_hyp > 0 || (e_hyp == 0 && f->sx < 0);
    return ok_h && ok_v && ok_hyp;
}

static void frame_vertices(const struct frame *f, int order, struct vertex v[3])
{
    static const int p[6][3] = { {0,1,2}, {1,2,0}, {2,0,1}, {0,2,1}, {2,1,0}, {1,0,2} };
    struct vertex abc[3] = {
        test_vertex(f->ax / 256.0, f->ay / 256.0),
        test_vertex((f->ax + f->sx * f->lx) / 256.0, f->ay / 256.0),
        test_vertex(f->ax / 256.0, (f->ay + f->sy * f->ly) / 256.0),
    };
    for (int k = 0; k < 3; k++)
        v[k] = abc[p[order][k]];
}

/* Expected picture of the frame's triangle on a w x h target. */
static void frame_mask(const struct frame *f, int w, int h, uint8_t *mask)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            mask[y * w + x] = covered_in_frame(f, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128);
}

struct runner {
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv;
    struct target fb;
    uint8_t *expected;
    int w, h;
    uint64_t cases, covered;
};

static void runner_init(struct runner *r, int w, int h)
{
    r->nv = exact_variants(r->tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    cr_assert(r->nv >= 2 && r->nv <= MAX_TEST_VARIANTS);
    r->w = w;
    r->h = h;
    r->cases = r->covered = 0;
    cr_assert(target_init(&r->fb, w, h, 0));
    r->expected = calloc((size_t)w * (size_t)h, 1);
}

static void runner_free(struct runner *r)
{
    target_free(&r->fb);
    free(r->expected);
}

/* Every vertex order of the frame's triangle, through every exact variant. */
static void run_frame(struct runner *r, const struct frame *f, const char *what)
{
    frame_mask(f, r->w, r->h, r->expected);
    size_t n = (size_t)r->w * (size_t)r->h;
    for (size_t i = 0; i < n; i++)
        r->covered += r->expected[i];
    for (int order = 0; order < 6; order++) {
        struct vertex v[3];
        frame_vertices(f, order, v);
        struct tri_setup t;
        tri_setup(&t, v, r->w, r->h);
        for (int k = 0; k < r->nv; k++) {
            char label[128], msg[320];
            snprintf(msg, sizeof msg, "%s: %s, frame sx %d sy %d, legs %lld x %lld /256, order %d",
                     variant_label(&r->tv[k], label, sizeof label), what, f->sx, f->sy,
                     (long long)f->lx, (long long)f->ly, order);
            struct case_info info = { msg, test_seed(), r->cases, v, 3 };
            memset(r->fb.count, 0, n);
            rasterize_one(r->tv[k].variant, NULL, &t, &r->fb, NULL);
            cr_assert(coverage_equal(r->expected, r->fb.count, r->w, r->h, &info));
        }
        r->cases++;
    }
}

/* A small triangle, each of its three corners and three edge midpoints in
 * turn brought to the centre of pixel (6, 6), then moved by -3..3 steps of
 * 1/256 px in x and y: the centre crosses every edge and every vertex. */
Test(fillrule, small_triangle_moved_by_subpixel_steps_around_a_centre)
{
    struct runner r;
    runner_init(&r, 13, 13);
    const int64_t cx = 6 * 256 + 128, cy = 6 * 256 + 128;
    int centre_in = 0, centre_out = 0;
    const int64_t legs[][2] = { { 4, 4 }, { 16, 6 }, { 256, 256 }, { 3, 384 } };
    for (size_t l = 0; l < sizeof legs / sizeof legs[0]; l++) {
        int64_t lx = legs[l][0], ly = legs[l][1];
        /* points of the triangle, in its own frame (a, b) */
        const int64_t anchors[][2] = { { 0, 0 }, { lx, 0 }, { 0, ly },
                                       { lx / 2, 0 }, { 0, ly / 2 }, { lx / 2, ly / 2 } };
        for (int s = 0; s < 4; s++)
            for (size_t an = 0; an < 6; an++)
                for (int dy = -3; dy <= 3; dy++)
                    for (int dx = -3; dx <= 3; dx++) {
                        struct frame f = { .sx = s & 1 ? -1 : 1, .sy = s & 2 ? -1 : 1, .lx = lx, .ly = ly };
                        /* the centre sits at (a, b) = anchor + (dx, dy) */
                        int64_t a = anchors[an][0] + dx, b = anchors[an][1] + dy;
                        f.ax = cx - f.sx * a;
                        f.ay = cy - f.sy * b;
                        if (covered_in_frame(&f, cx, cy))
                            centre_in++;
                        else
                            centre_out++;
                        char what[96];
                        snprintf(what, sizeof what, "anchor %zu moved by (%d, %d)/256", an, dx, dy);
                        run_frame(&r, &f, what);
                    }
    }
    /* the sweep really did put the centre on both sides of the rule */
    cr_assert(centre_in > 100 && centre_out > 100, "centre covered in %d moves, not in %d",
              centre_in, centre_out);
    runner_free(&r);
}

/* Larger triangles whose vertices sit on pixel centres, pixel corners and
 * quarter pixels: legs run along rows and columns of centres, the
 * hypotenuse through centres whenever the legs allow. */
Test(fillrule, edges_and_vertices_exactly_on_centres)
{
    struct runner r;
    runner_init(&r, 20, 20);
    const int64_t offsets[] = { 128, 0, 64, 192, 1 };   /* centre, corner, quarters, a step */
    for (int s = 0; s < 4; s++)
        for (size_t o = 0; o < sizeof offsets / sizeof offsets[0]; o++)
            for (int lx = 1; lx <= 7; lx += 2)
                for (int ly = 1; ly <= 8; ly += 3) {
                    struct frame f = { .sx = s & 1 ? -1 : 1, .sy = s & 2 ? -1 : 1,
                                       .lx = lx * 256, .ly = ly * 256,
                                       .ax = 10 * 256 + offsets[o], .ay = 10 * 256 + offsets[(o + s) % 5] };
                    run_frame(&r, &f, "legs along centres");
                }
    runner_free(&r);
}

/* Named cases a student can check on squared paper. Two triangles share an
 * edge through pixel centres; every centre on it goes to exactly one of them,
 * the one for which the edge is top or left. */
struct pair_case {
    const char *name;
    double t[2][6];
    int owner;              /* which triangle covers the shared edge's inner centres */
    int x0, y0, dx, dy, n;  /* the inner centres of the shared edge */
};

Test(fillrule, shared_edges_go_to_the_top_or_left_triangle)
{
    const struct pair_case cases[] = {
        /* horizontal edge y = 6.5: the lower triangle has it as a TOP edge */
        { "horizontal", { { 2.5, 6.5, 6.5, 2.5, 10.5, 6.5 }, { 2.5, 6.5, 10.5, 6.5, 6.5, 10.5 } },
          1, 3, 6, 1, 0, 7 },
        /* vertical edge x = 6.5: the right triangle has it as a LEFT edge */
        { "vertical", { { 6.5, 2.5, 6.5, 10.5, 2.5, 6.5 }, { 6.5, 2.5, 10.5, 6.5, 6.5, 10.5 } },
          1, 6, 3, 0, 1, 7 },
        /* diagonal through (k.5, k.5): the upper-right triangle lies on its
         * +x side, so for it the diagonal is a LEFT edge */
        { "diagonal", { { 2.5, 2.5, 10.5, 2.5, 10.5, 10.5 }, { 2.5, 2.5, 10.5, 10.5, 2.5, 10.5 } },
          0, 3, 3, 1, 1, 7 },
        /* anti-diagonal through (2.5, 10.5)..(10.5, 2.5): the lower-right
         * triangle lies on its +x side */
        { "anti-diagonal", { { 2.5, 10.5, 10.5, 2.5, 2.5, 2.5 }, { 2.5, 10.5, 10.5, 10.5, 10.5, 2.5 } },
          1, 3, 9, 1, -1, 7 },
    };
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        for (int k = 0; k < nv; k++)
            for (int wind = 0; wind < 2; wind++) {
                struct target fb[2];
                for (int i = 0; i < 2; i++) {
                    const double *p = cases[c].t[i];
                    struct vertex v[3] = { test_vertex(p[0], p[1]), test_vertex(p[2], p[3]),
                                           test_vertex(p[4], p[5]) };
                    if (wind) {
                        struct vertex tmp = v[1]; v[1] = v[2]; v[2] = tmp;
                    }
                    struct tri_setup t;
                    tri_setup(&t, v, 13, 13);
                    cr_assert(target_init(&fb[i], 13, 13, 0));
                    rasterize_one(tv[k].variant, NULL, &t, &fb[i], NULL);
                }
                char label[128];
                variant_label(&tv[k], label, sizeof label);
                for (int j = 0; j < cases[c].n; j++) {
                    int x = cases[c].x0 + j * cases[c].dx, y = cases[c].y0 + j * cases[c].dy;
                    int own = fb[cases[c].owner].count[y * 13 + x];
                    int other = fb[1 - cases[c].owner].count[y * 13 + x];
                    cr_assert(own == 1 && other == 0,
                              "%s, %s edge, winding %d: centre (%d.5, %d.5) covered %d times by "
                              "triangle %d (expected 1) and %d times by the other (expected 0)",
                              label, cases[c].name, wind, x, y, own, cases[c].owner, other);
                }
                /* and no centre anywhere is covered by both */
                for (int i = 0; i < 13 * 13; i++)
                    cr_assert(fb[0].count[i] + fb[1].count[i] <= 1, "%s, %s: pixel %d covered twice",
                              label, cases[c].name, i);
                target_free(&fb[0]);
                target_free(&fb[1]);
            }
}

/* A triangle whose three vertices are all pixel centres: each vertex's own
 * pixel is covered only when both edges meeting there are top or left. */
Test(fillrule, vertices_on_centres_need_both_edges_top_left)
{
    /* A = (2.5, 2.5), B = (9.5, 2.5), C = (2.5, 9.5):
     *   at A: top edge AB and left edge CA       -> covered
     *   at B: top edge AB but right edge BC      -> not covered
     *   at C: left edge CA but right edge BC     -> not covered
     * and the mirror image (A = (9.5, 2.5), B = (2.5, 2.5), C = (9.5, 9.5)):
     *   at A: top edge, but AC is a right edge   -> not covered
     *   at B: top edge and left edge BC          -> covered
     *   at C: right edge CA, left edge BC        -> not covered */
    const struct { double p[6]; bool at[3]; } cases[] = {
        { { 2.5, 2.5, 9.5, 2.5, 2.5, 9.5 }, { true, false, false } },
        { { 9.5, 2.5, 2.5, 2.5, 9.5, 9.5 }, { false, true, false } },
        /* upside down: A = (2.5, 9.5) with a bottom edge AB: nothing at A, B or C */
        { { 2.5, 9.5, 9.5, 9.5, 2.5, 2.5 }, { false, false, false } },
    };
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        for (int k = 0; k < nv; k++) {
            const double *p = cases[c].p;
            struct vertex v[3] = { test_vertex(p[0], p[1]), test_vertex(p[2], p[3]), test_vertex(p[4], p[5]) };
            struct tri_setup t;
            tri_setup(&t, v, 12, 12);
            struct target fb;
            cr_assert(target_init(&fb, 12, 12, 0));
            rasterize_one(tv[k].variant, NULL, &t, &fb, NULL);
            char label[128];
            for (int i = 0; i < 3; i++) {
                int x = (int)p[2 * i], y = (int)p[2 * i + 1];
                cr_assert_eq(fb.count[y * 12 + x], cases[c].at[i], "%s, case %zu: vertex %c at (%d.5, %d.5)",
                             variant_label(&tv[k], label, sizeof label), c, "ABC"[i], x, y);
            }
            target_free(&fb);
        }
}

/* The bottom-right rule (raster.h: lesson 02's graded variant) is the
 * top-left rule turned half way round: turned 180 degrees about the middle
 * of a W x H target, pixel (x, y) becomes pixel (W-1-x, H-1-y), a top edge
 * a bottom edge and a left edge a right edge, and the snapped coordinates
 * stay exact (W * 256 - x) while they stay inside the coordinate limit.
 * Random triangles of every kind, ties included:
 * the rules must differ on some centres, or the test saw no tie. */
Test(fillrule, the_bottom_right_rule_is_the_top_left_rule_turned_half_way_round)
{
    enum { W = 48, H = 40 };
    struct rng r = rng_for(4100);
    long differ = 0;
    for (int i = 0; i < 3000; i++) {
        struct vertex v[3], turned[3];
        random_tri(&r, (enum tri_category)(i % CAT_COUNT), W, H, v);
        struct tri_setup t, u;
        tri_setup(&t, v, W, H);
        bool in_range = true;       /* turned, still inside the coordinate limit (else snapping clamps it) */
        for (int k = 0; k < 3; k++) {
            turned[k] = test_vertex(W - t.x[k] / (double)SUBPIXEL_ONE, H - t.y[k] / (double)SUBPIXEL_ONE);
            in_range = in_range && turned[k].x < COORD_LIMIT && turned[k].y < COORD_LIMIT;
        }
        if (!in_range)
            continue;
        tri_setup(&u, turned, W, H);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                bool br = reference_point_covered_rule(&t, FILL_BOTTOM_RIGHT, pixel_centre(x), pixel_centre(y));
                bool tl = reference_point_covered(&u, pixel_centre(W - 1 - x), pixel_centre(H - 1 - y));
                if (br != tl) {
                    struct case_info info = { "bottom-right against top-left turned", test_seed(), (uint64_t)i, v, 3 };
                    print_case(&info);
                    cr_assert_fail("pixel (%d, %d): bottom-right %d, top-left turned half way %d", x, y, br, tl);
                }
                differ += br != reference_point_covered(&t, pixel_centre(x), pixel_centre(y));
            }
    }
    cr_assert_gt(differ, 100, "the two rules differ on %ld centres only: too few ties", differ);
}
