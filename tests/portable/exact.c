/* exact.c - the exactness tests without Criterion, for CPUs and systems
 * where Criterion is not at hand: built for aarch64 and run under qemu by
 * `make aarch64`, and natively through SIMDe's portable code by
 * `make simde-test` (both from `make test`).
 *
 * Every non-exhibit variant of every lesson, narrated and fast, against the
 * reference rasterizer:
 *   - seeded random triangles of every category of testlib.h (both windings,
 *     slivers, centres on edges, off-screen, degenerate), at full precision
 *     and at lesson 03's fewer sub-pixel bits, lesson 05 at every block size;
 *   - jittered grid meshes whose triangles share edges: every pixel centre
 *     inside the mesh's rectangle covered exactly once, nothing outside;
 *   - lines (src/raster/line.c): the walk against the rule decided pixel by
 *     pixel, on random segments with ends on the 1/256 grid, often on pixel
 *     centres and boundaries.
 * Colours are not compared (SIMD reciprocals differ between CPUs by design);
 * coverage is integer arithmetic and must agree everywhere.
 *
 *     exact        prints each failure, then "N passed, M failed"; exits 0
 *                  when nothing failed (TRISTEP_SEED=N replays another seed)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../testlib.h"
#include "raster/line.h"

#define W 48
#define H 40
#define TRIS_PER_CATEGORY 200
#define MESHES 12
#define MESH_MAX 6           /* cells per side; the mesh is at least 20 pixels wide */

static long passed, failed;

static void verdict(bool ok, const char *fmt, const char *label, int a, int b)
{
    if (ok) {
        passed++;
        return;
    }
    failed++;
    fprintf(stderr, "FAIL: ");
    fprintf(stderr, fmt, label, a, b);
    fputc('\n', stderr);
}

/* The parameter sets a variant runs with: lesson 05 at every block size. */
static int param_sets(const struct test_variant *tv, struct raster_params out[3])
{
    static const int blocks[] = { 4, 8, 16 };
    int n = lesson_param(tv->lesson, "block-size", NULL) ? 3 : 1;
    for (int i = 0; i < n; i++) {
        out[i] = default_params();
        if (n == 3)
            lesson_param_set(tv->lesson, &out[i], "block-size", blocks[i]);
    }
    return n;
}

/* Draw triangles [0, ntris) of v with one variant; coverage counts in fb. */
static void draw(const struct test_variant *tv, const struct raster_params *p,
                 const struct vertex *v, int ntris, int bits, struct target *fb)
{
    target_clear(fb);
    for (int i = 0; i < ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, v + 3 * i, fb->w, fb->h, bits);
        struct trace tr = { .limit = TRACE_UNLIMITED };
        rasterize_one(tv->variant, p, &t, fb, tv->narrated ? &tr : NULL);
    }
}

static void random_triangles(const struct test_variant *tv, int nv, struct target *fb,
                             uint8_t *ref)
{
    for (int cat = 0; cat < CAT_COUNT; cat++) {
        struct rng r = rng_for(0x51de0000u + (uint64_t)cat);
        for (int i = 0; i < TRIS_PER_CATEGORY; i++) {
            struct vertex v[3];
            random_tri(&r, (enum tri_category)cat, W, H, v);
            int bits = i % 4 == 3 ? i % SUBPIXEL_BITS : SUBPIXEL_BITS;
            struct tri_setup t;
            tri_setup_bits(&t, v, W, H, bits);
            memset(ref, 0, (size_t)W * H);
            reference_mask(&t, ref);
            for (int k = 0; k < nv; k++) {
                struct raster_params ps[3];
                for (int j = 0, n = param_sets(&tv[k], ps); j < n; j++) {
                    ps[j].subpixel_bits = bits;
                    draw(&tv[k], &ps[j], v, 1, bits, fb);
                    char label[160];
                    variant_label(&tv[k], label, sizeof label);
                    struct case_info info = { label, test_seed(), (uint64_t)i, v, 3 };
                    bool ok = memcmp(fb->count, ref, (size_t)W * H) == 0
                              || coverage_equal(ref, fb->count, W, H, &info);
                    verdict(ok, "%s: %s triangle %d differs from the reference", label,
                            cat, i);
                }
            }
        }
    }
}

/* A grid of (nx + 1) x (ny + 1) vertices over [x0, x1) x [y0, y1): the
 * outline's vertices stay on the outline, the inner ones move by at most a
 * fifth of a cell (so every cell stays convex and either diagonal splits
 * it), to a random place or the nearest pixel centre; each cell is split
 * along a random diagonal, each triangle in a random winding. Returns the
 * number of triangles. */
static int jittered_mesh(struct rng *r, double x0, double y0, double x1, double y1, int nx,
                         int ny, struct vertex *out)
{
    struct vertex g[MESH_MAX + 1][MESH_MAX + 1];
    double cw = (x1 - x0) / nx, ch = (y1 - y0) / ny;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double x = x0 + cw * i, y = y0 + ch * j;
            bool centre = rng_chance(r, 0.3);   /* pixel centres: at most half a pixel away */
            if (i > 0 && i < nx)
                x = centre ? floor(x) + 0.5 : x + rng_range(r, -0.2, 0.2) * cw;
            if (j > 0 && j < ny)
                y = centre ? floor(y) + 0.5 : y + rng_range(r, -0.2, 0.2) * ch;
            g[j][i] = test_vertex(x, y);
        }
    int n = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            struct vertex a = g[j][i], b = g[j][i + 1], c = g[j + 1][i + 1], d = g[j + 1][i];
            struct vertex t[2][3] = { { a, b, c }, { a, c, d } };
            if (rng_chance(r, 0.5)) {
                struct vertex u[2][3] = { { a, b, d }, { b, c, d } };
                memcpy(t, u, sizeof t);
            }
            for (int k = 0; k < 2; k++) {
                bool flip = rng_chance(r, 0.5);
                out[3 * n + 0] = t[k][0];
                out[3 * n + 1] = t[k][flip ? 2 : 1];
                out[3 * n + 2] = t[k][flip ? 1 : 2];
                n++;
            }
        }
    return n;
}

static void meshes(const struct test_variant *tv, int nv, struct target *fb, uint8_t *expected)
{
    struct rng r = rng_for(0x3e54u);
    static struct vertex v[3 * 2 * MESH_MAX * MESH_MAX];
    for (int m = 0; m < MESHES; m++) {
        /* the outline: corners on pixel centres, whole pixels or the 1/256 grid */
        double x0 = floor(rng_range(&r, -6, 10)) + (m % 3) * 0.5, y0 = floor(rng_range(&r, -6, 8)) + (m % 2) * 0.5;
        double x1 = floor(rng_range(&r, 30, 56)) + (m % 3 == 1 ? 0.25 : 0.5), y1 = floor(rng_range(&r, 26, 48)) + 0.5;
        int n = jittered_mesh(&r, x0, y0, x1, y1, 2 + m % (MESH_MAX - 1),
                              2 + (m * 3) % (MESH_MAX - 1), v);
        /* inside: centre in [x0, x1) x [y0, y1), the top-left rule on a rectangle */
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double cx = x + 0.5, cy = y + 0.5;
                expected[y * W + x] = cx >= x0 && cx < x1 && cy >= y0 && cy < y1;
            }
        for (int k = 0; k < nv; k++) {
            struct raster_params ps[3];
            for (int j = 0, np = param_sets(&tv[k], ps); j < np; j++) {
                draw(&tv[k], &ps[j], v, n, SUBPIXEL_BITS, fb);
                char label[160];
                variant_label(&tv[k], label, sizeof label);
                struct case_info info = { label, test_seed(), (uint64_t)m, v, 3 * n };
                bool ok = memcmp(fb->count, expected, (size_t)W * H) == 0
                          || coverage_equal(expected, fb->count, W, H, &info);
                verdict(ok, "%s: mesh %d of %d triangles not covered exactly once", label, m, n);
            }
        }
    }
}

static void count_line_pixel(void *ctx, int x, int y)
{
    ((uint8_t *)ctx)[y * W + x]++;
}

static void lines(uint8_t *walked, uint8_t *decided)
{
    struct rng r = rng_for(3420);
    for (int i = 0; i < 2000; i++) {
        struct vertex v[2];
        for (int k = 0; k < 2; k++) {
            double x = rng_int(&r, -4 * 256, (W + 4) * 256) / 256.0, y = rng_int(&r, -4 * 256, (H + 4) * 256) / 256.0;
            if (rng_chance(&r, 0.4))
                x = floor(x) + 0.5 * rng_int(&r, 0, 1), y = floor(y) + 0.5 * rng_int(&r, 0, 1);
            v[k] = test_vertex(x, y);
        }
        struct line_setup l;
        line_setup(&l, v, W, H);
        memset(walked, 0, (size_t)W * H);
        memset(decided, 0, (size_t)W * H);
        line_walk(&l, count_line_pixel, walked);
        line_reference(&l, count_line_pixel, decided);
        verdict(memcmp(walked, decided, (size_t)W * H) == 0, "%s: segment %d of %d walks other pixels\n",
                "lines", i, 2000);
    }
}

int main(int argc, char **argv)
{
    if (argc != 1) {
        fprintf(stderr, "usage: %s   (TRISTEP_SEED=N for another seed)\n", argv[0]);
        return 2;
    }
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    struct target fb;
    uint8_t *buf = malloc((size_t)W * H);
    if (!buf || nv > MAX_TEST_VARIANTS || !target_init(&fb, W, H, 0)) {
        fprintf(stderr, "exact: out of memory\n");
        return 1;
    }
    printf("exact: %d exact variants (narrated and fast), seed %#llx\n", nv,
           (unsigned long long)test_seed());
    random_triangles(tv, nv, &fb, buf);
    meshes(tv, nv, &fb, buf);
    uint8_t *buf2 = malloc((size_t)W * H);
    if (!buf2) {
        fprintf(stderr, "exact: out of memory\n");
        return 1;
    }
    lines(buf, buf2);
    free(buf2);
    target_free(&fb);
    free(buf);
    printf("%ld passed, %ld failed\n", passed, failed);
    return failed ? 1 : 0;
}
