/* check.c - make check: the lesson's checks on the student's code, simplest
 * first; at the first failure, a smallest counterexample and the command
 * that opens it in the explorer at the first wrong pixel.
 *
 * Every check draws scenes twice, with the exact rule (src/raster's
 * reference coverage and reference_shade) and with the code given to
 * exercise_use, one triangle at a time, and compares after each triangle:
 *
 *   coverage   how many times each pixel was written (target.count): a
 *              pixel written twice by one triangle is as wrong as one
 *              written by a triangle that does not cover it;
 *   colour     colour and depth pixel_close() to the exact ones (raster.h),
 *              on every pixel the exact rule covers;
 *   property   what the lesson is about: no multiplication between two
 *              pixels of a row (lesson 03), every block narrated full
 *              really full and every full block found (lesson 05).
 *
 * A write outside the target fails any check. */
#define _DEFAULT_SOURCE           /* mkdir, fork, MAP_ANONYMOUS, strsignal */

#include "exercise.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "explore/replay.h"
#include "util/file.h"

/* Shrinking tries at most this many candidate scenes. */
#define SHRINK_BUDGET 4000
/* A scene that takes longer than this is an endless loop: no scene of the
 * checks needs a hundredth of it. */
#define SCENE_SECONDS 10
/* Shrinking a crash runs each candidate in a process of its own. */
#define CRASH_BUDGET 600

/* Where a guarded check is (exercise_check_guarded): shared with the
 * process that runs it, so a crash still says which scene did it. */
struct guard {
    int check, scene, tri;
    struct check_result result;
};
static struct guard *guard;

enum check_kind { CK_COVERAGE, CK_COLOUR, CK_PROPERTY, CK_ALL };

/* What went wrong, at the first triangle after which the pictures differ. */
enum wrong {
    WRONG_NONE, WRONG_COUNT, WRONG_COLOUR, WRONG_DEPTH, WRONG_OUTSIDE, WRONG_MUL,
    WRONG_BLOCK_NOT_FULL, WRONG_BLOCK_MISSED,
};

struct verdict {
    enum wrong what;
    int tri;                    /* the triangle that went wrong */
    int x, y;                   /* its first wrong pixel */
    int want_n, got_n;          /* coverage counts there */
    uint32_t want_c, got_c;     /* colours */
    float want_z, got_z;
    int bx, by, bx1, by1;       /* a block, for the block properties */
    uint64_t mul;               /* multiplications between two pixels */
};

/* Everything one check run needs. */
struct checker {
    const struct lesson *l;
    const struct check_options *o;
    struct raster_params p;
    enum check_kind kind;
    struct target want, got;
    uint8_t *mask;              /* the exact coverage of the triangle being run */
    /* the property watch, fed by the narration */
    const struct tri_setup *t;
    struct verdict *prop;
    bool in_row;
    int last_x, last_y;
    uint64_t pixel_mul;         /* mul counted when the last pixel began */
    uint64_t evaluations;       /* scenes drawn, for the report */
    uint64_t triangles;
};

/* --- scenes ---------------------------------------------------------------------- */

/* splitmix64: the checks draw the same scenes on every run */
struct rng {
    uint64_t s;
};

static uint64_t rng_next(struct rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static double rng_unit(struct rng *r)
{
    return (double)(rng_next(r) >> 11) * 0x1p-53;
}

static double rng_range(struct rng *r, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(r);
}

/* A coordinate as scenes give them: on the 1/256 grid, or on a pixel centre,
 * or an integer, chosen at random. */
static double grid(struct rng *r, double v)
{
    double u = rng_unit(r);
    if (u < 0.2)
        return floor(v) + 0.5;
    if (u < 0.3)
        return floor(v);
    return floor(v * SUBPIXEL_ONE) / SUBPIXEL_ONE;
}

static struct vertex vtx(double x, double y, double z, double r, double g, double b)
{
    return (struct vertex){ .x = x, .y = y, .z = z, .r = r, .g = g, .b = b };
}

/* A vertex with a random colour and a depth in [zmin, zmax]. */
static struct vertex rvtx(struct rng *r, double x, double y, double zmin, double zmax)
{
    return vtx(x, y, rng_range(r, zmin, zmax), rng_unit(r), rng_unit(r), rng_unit(r));
}

static bool add(struct scene *s, struct vertex a, struct vertex b, struct vertex c)
{
    double lim = COORD_LIMIT - 1.0 / SUBPIXEL_ONE;
    struct vertex v[3] = { a, b, c };
    for (int i = 0; i < 3; i++) {
        v[i].x = fmin(fmax(v[i].x, -COORD_LIMIT), lim);
        v[i].y = fmin(fmax(v[i].y, -COORD_LIMIT), lim);
    }
    return scene_add(s, v);
}

/* The same triangle walked the other way round. */
static bool add_flipped(struct scene *s, struct vertex a, struct vertex b, struct vertex c,
                        bool flip)
{
    return flip ? add(s, a, c, b) : add(s, a, b, c);
}

static void scene_start(struct scene *s, int w, int h)
{
    memset(s, 0, sizeof *s);
    s->w = w;
    s->h = h;
}

/* One generator per check: scene number i (0, 1, ...) into s with a line
 * saying what it is; false when there are no more. */
typedef bool (*scene_gen)(int i, struct scene *s, char *what, size_t n);

static bool gen_single(int i, struct scene *s, char *what, size_t n)
{
    /* nothing on a pixel centre: no edge passes exactly through one */
    static const double tris[][6] = {
        { 4.3, 3.2, 35.7, 8.9, 13.1, 26.6 },
        { 20.1, 2.2, 27.9, 27.3, 14.6, 18.35 },
        { 7.7, 5.1, 11.2, 9.9, 3.3, 12.4 },
        { 5.1, 4.2, 30.3, 4.2, 17.9, 25.7 },
        { 36.2, 2.9, 37.1, 26.3, 2.7, 14.1 },
    };
    if (i >= (int)(sizeof tris / sizeof tris[0]))
        return false;
    const double *c = tris[i];
    scene_start(s, 40, 30);
    add(s, vtx(c[0], c[1], 1, 1, 0, 0), vtx(c[2], c[3], 2, 0, 1, 0), vtx(c[4], c[5], 3, 0, 0, 1));
    snprintf(what, n, "one triangle (%g, %g) (%g, %g) (%g, %g)", c[0], c[1], c[2], c[3], c[4], c[5]);
    return true;
}

static bool gen_ties(int i, struct scene *s, char *what, size_t n)
{
    scene_start(s, 20, 16);
    bool f1 = i & 1, f2 = (i >> 1) & 1;     /* the windings of the two triangles */
    const char *w1 = f1 ? "counter-clockwise" : "clockwise", *w2 = f2 ? "counter-clockwise" : "clockwise";
    struct vertex P = vtx(0, 0, 1, 0.9, 0.5, 0.1);
    switch (i >> 2) {
    case 0:     /* a vertical edge x = 10.5 through pixel centres */
        add_flipped(s, vtx(10.5, 2.5, 1, 1, 0, 0), vtx(10.5, 14.5, 1, 0, 1, 0), vtx(3.2, 8.1, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(10.5, 2.5, 2, 1, 1, 0), vtx(17.7, 9.3, 2, 0, 1, 1), vtx(10.5, 14.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the vertical edge x = 10.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 1:     /* a horizontal edge y = 8.5 */
        add_flipped(s, vtx(2.5, 8.5, 1, 1, 0, 0), vtx(17.5, 8.5, 1, 0, 1, 0), vtx(9.2, 1.3, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(2.5, 8.5, 2, 1, 1, 0), vtx(11.7, 15.6, 2, 0, 1, 1), vtx(17.5, 8.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the horizontal edge y = 8.5 through pixel centres (%s, %s)", w1, w2);
        return true;
    case 2:     /* a diagonal through a centre every 3 pixels */
        add_flipped(s, vtx(2.5, 2.5, 1, 1, 0, 0), vtx(17.5, 12.5, 1, 0, 1, 0), vtx(4.1, 13.7, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(2.5, 2.5, 2, 1, 1, 0), vtx(16.2, 3.1, 2, 0, 1, 1), vtx(17.5, 12.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "two triangles sharing the edge (2.5, 2.5)-(17.5, 12.5) through pixel centres (%s, %s)", w1, w2);
        return true;
    case 3:     /* a square of two triangles, every vertex on a pixel centre */
        add_flipped(s, vtx(3.5, 2.5, 1, 1, 0, 0), vtx(15.5, 2.5, 1, 0, 1, 0), vtx(3.5, 13.5, 1, 0, 0, 1), f1);
        add_flipped(s, vtx(15.5, 2.5, 2, 1, 1, 0), vtx(15.5, 13.5, 2, 0, 1, 1), vtx(3.5, 13.5, 2, 1, 0, 1), f2);
        snprintf(what, n, "a square of two triangles, vertices on pixel centres (%s, %s)", w1, w2);
        return true;
    case 4: {   /* a fan of eight around a centre, every vertex on a pixel centre */
        static const double ring[8][2] = { { 10.5, 1.5 }, { 16.5, 3.5 }, { 18.5, 8.5 }, { 15.5, 13.5 },
                                           { 10.5, 14.5 }, { 4.5, 12.5 }, { 1.5, 7.5 }, { 5.5, 2.5 } };
        for (int k = 0; k < 8; k++) {
            const double *a = ring[k], *b = ring[(k + 1) % 8];
            P.x = 10.5, P.y = 8.5;
            add_flipped(s, P, vtx(a[0], a[1], 1, k & 1, 0.5, 1), vtx(b[0], b[1], 1, 1, k & 1, 0.3),
                        (k & 1) ? f1 : f2);
        }
        snprintf(what, n, "a fan of eight triangles around the pixel centre (10.5, 8.5), windings mixed");
        return true;
    }
    case 5:     /* degenerate: they cover nothing */
        if (f2)
            return false;
        if (!f1) {
            add(s, vtx(2.5, 2.5, 1, 1, 1, 1), vtx(8.5, 6.5, 1, 1, 1, 1), vtx(14.5, 10.5, 1, 1, 1, 1));
            add(s, vtx(3.5, 12.5, 1, 1, 1, 1), vtx(15.5, 12.5, 1, 1, 1, 1), vtx(9.5, 12.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: three vertices in line through pixel centres (cover nothing)");
        } else {
            add(s, vtx(4.5, 3.5, 1, 1, 1, 1), vtx(12.3, 9.7, 1, 1, 1, 1), vtx(4.5, 3.5, 1, 1, 1, 1));
            add(s, vtx(7.5, 7.5, 1, 1, 1, 1), vtx(7.5, 7.5, 1, 1, 1, 1), vtx(7.5, 7.5, 1, 1, 1, 1));
            snprintf(what, n, "degenerate: a repeated vertex, a triangle that is a point (cover nothing)");
        }
        return true;
    }
    return false;
}

/* A jittered grid of nx x ny cells over [x0, x1] x [y0, y1], each cell cut
 * along a random diagonal into two triangles of random winding. */
static void grid_mesh(struct scene *s, struct rng *r, int nx, int ny, double x0, double y0,
                      double x1, double y1, double jitter)
{
    struct vertex *v = malloc(sizeof *v * (size_t)(nx + 1) * (size_t)(ny + 1));
    if (!v)
        return;
    double cw = (x1 - x0) / nx, ch = (y1 - y0) / ny;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double x = x0 + i * cw, y = y0 + j * ch;
            if (i > 0 && i < nx)
                x = grid(r, x + rng_range(r, -jitter, jitter) * cw);
            if (j > 0 && j < ny)
                y = grid(r, y + rng_range(r, -jitter, jitter) * ch);
            v[j * (nx + 1) + i] = rvtx(r, x, y, 1, 4);
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            struct vertex a = v[j * (nx + 1) + i], b = v[j * (nx + 1) + i + 1];
            struct vertex c = v[(j + 1) * (nx + 1) + i + 1], d = v[(j + 1) * (nx + 1) + i];
            if (rng_unit(r) < 0.5) {
                add_flipped(s, a, b, c, rng_unit(r) < 0.5);
                add_flipped(s, a, c, d, rng_unit(r) < 0.5);
            } else {
                add_flipped(s, a, b, d, rng_unit(r) < 0.5);
                add_flipped(s, b, c, d, rng_unit(r) < 0.5);
            }
        }
    free(v);
}

static bool gen_meshes(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0x3e5a11u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 6, 4, 2.5, 2.5, 45.5, 33.5, 0.3);
        snprintf(what, n, "a jittered 6 x 4 grid of 48 triangles, corners on pixel centres");
        return true;
    case 1:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 16, 12, 1.3, 1.7, 46.2, 34.1, 0.35);
        snprintf(what, n, "a jittered 16 x 12 grid of 384 small triangles");
        return true;
    case 2:
        scene_start(s, 40, 30);
        grid_mesh(s, &r, 7, 5, -20.25, -15.75, 61.5, 47.25, 0.3);
        snprintf(what, n, "a jittered 7 x 5 grid reaching past every side of the target");
        return true;
    case 3:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 2, 24, 1.5, 0.5, 46.5, 35.5, 0.45);
        snprintf(what, n, "a 2 x 24 grid of long thin triangles");
        return true;
    case 4:
        scene_start(s, 48, 36);
        grid_mesh(s, &r, 12, 9, 0, 0, 48, 36, 0);
        snprintf(what, n, "a regular 12 x 9 grid on whole pixels: every edge through pixel corners");
        return true;
    }
    return false;
}

/* Random triangles by kind, one per scene. */
#define RANDOM_SCENES 1600
static bool gen_random(int i, struct scene *s, char *what, size_t n)
{
    if (i >= RANDOM_SCENES)
        return false;
    struct rng r = { 0x7a11d0u * 31 + (uint64_t)i };
    int w = 64, h = 48;
    double cx = rng_range(&r, 0, w), cy = rng_range(&r, 0, h);
    struct vertex v[3];
    const char *kind;
    switch (i % 8) {
    case 0:
        kind = "generic";
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 1, 24);
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -d, d)), grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 1:
        kind = "sliver";
        v[0] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), grid(&r, rng_range(&r, 0, h)), 1, 4);
        v[1] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), grid(&r, rng_range(&r, 0, h)), 1, 4);
        {
            double t = rng_unit(&r), d = rng_range(&r, -0.7, 0.7);
            v[2] = rvtx(&r, grid(&r, v[0].x + t * (v[1].x - v[0].x) + d),
                        grid(&r, v[0].y + t * (v[1].y - v[0].y) - d), 1, 4);
        }
        break;
    case 2:
        kind = "smaller than a pixel";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -0.7, 0.7)), grid(&r, cy + rng_range(&r, -0.7, 0.7)), 1, 4);
        break;
    case 3:
        kind = "larger than the target";
        w = 256, h = 192;
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, rng_range(&r, -2.0 * w, 3.0 * w)), grid(&r, rng_range(&r, -2.0 * h, 3.0 * h)), 1, 4);
        break;
    case 4:
        kind = "partly off-screen";
        if (rng_unit(&r) < 0.5)
            cx = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : w + rng_range(&r, -4, 4);
        else
            cy = rng_unit(&r) < 0.5 ? rng_range(&r, -4, 4) : h + rng_range(&r, -4, 4);
        for (int k = 0; k < 3; k++) {
            double d = rng_range(&r, 2, 40);
            v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -d, d)), grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
        }
        break;
    case 5:
        kind = "vertices on pixel centres";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, floor(cx + rng_range(&r, -16, 16)) + 0.5, floor(cy + rng_range(&r, -16, 16)) + 0.5, 1, 4);
        break;
    case 6:
        kind = "a horizontal or vertical edge";
        {
            double a = grid(&r, rng_range(&r, 0, w)), b = grid(&r, rng_range(&r, 0, w));
            double c = grid(&r, rng_range(&r, 0, h)), d = grid(&r, rng_range(&r, 0, h));
            v[0] = rvtx(&r, a, c, 1, 4);
            if (rng_unit(&r) < 0.5)
                v[1] = rvtx(&r, b, c, 1, 4), v[2] = rvtx(&r, grid(&r, rng_range(&r, 0, w)), d, 1, 4);
            else
                v[1] = rvtx(&r, a, d, 1, 4), v[2] = rvtx(&r, b, grid(&r, rng_range(&r, 0, h)), 1, 4);
        }
        break;
    default:
        kind = "with far vertices (up to 16384 px away)";
        for (int k = 0; k < 3; k++)
            v[k] = rvtx(&r, grid(&r, rng_range(&r, -16000, 16000)), grid(&r, rng_range(&r, -16000, 16000)), 1, 4);
        if (rng_unit(&r) < 0.7)
            v[0] = rvtx(&r, grid(&r, cx), grid(&r, cy), 1, 4);
        break;
    }
    scene_start(s, w, h);
    add(s, v[0], v[1], v[2]);
    snprintf(what, n, "random triangle %d of %d: %s", i + 1, RANDOM_SCENES, kind);
    return true;
}

static bool gen_colour(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0xc0107u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 40, 30);
        add(s, vtx(4.3, 3.2, 1, 1, 0, 0), vtx(35.7, 8.9, 2, 0, 1, 0), vtx(13.1, 26.6, 3, 0, 0, 1));
        snprintf(what, n, "one triangle, red, green and blue corners at depths 1, 2, 3");
        return true;
    case 1:
        scene_start(s, 64, 48);
        add(s, vtx(2.2, 45.1, 1, 1, 1, 0.2), vtx(61.7, 44.3, 1.2, 0.1, 0.9, 1), vtx(30.4, 2.6, 12, 0.9, 0.1, 0.6));
        snprintf(what, n, "a triangle receding from depth 1 to depth 12");
        return true;
    case 2:
        scene_start(s, 48, 36);
        add(s, vtx(3.5, 3.5, 1, 1, 0, 0), vtx(44.5, 5.5, 6, 0, 1, 0), vtx(40.5, 32.5, 2, 0, 0, 1));
        add(s, vtx(3.5, 3.5, 1, 1, 0, 0), vtx(40.5, 32.5, 2, 0, 0, 1), vtx(5.5, 30.5, 9, 1, 1, 1));
        snprintf(what, n, "a quad of two triangles sharing an edge, depths 1 to 9");
        return true;
    case 3:
    case 4: {   /* the nearer triangle must win, whichever is drawn first */
        scene_start(s, 40, 30);
        struct vertex n0 = vtx(3.3, 4.1, 1, 1, 0.2, 0.2), n1 = vtx(30.2, 9.9, 1.5, 1, 0.6, 0.2),
                      n2 = vtx(9.7, 27.4, 1.2, 0.9, 0.1, 0.3);
        struct vertex f0 = vtx(36.1, 2.2, 4, 0.2, 0.3, 1), f1 = vtx(35.3, 28.8, 6, 0.2, 1, 0.6),
                      f2 = vtx(5.2, 15.6, 5, 0.1, 0.6, 1);
        if (i == 3) {
            add(s, n0, n1, n2);
            add(s, f0, f1, f2);
            snprintf(what, n, "depth test: a near triangle, then a far one over it (the near one stays)");
        } else {
            add(s, f0, f1, f2);
            add(s, n0, n1, n2);
            snprintf(what, n, "depth test: a far triangle, then a near one over it");
        }
        return true;
    }
    case 5:
        scene_start(s, 200, 150);
        add(s, vtx(3.1, 2.7, 1, 1, 0.5, 0), vtx(197.2, 40.3, 3, 0, 0.5, 1), vtx(60.6, 148.1, 8, 0.5, 1, 0.5));
        snprintf(what, n, "a large triangle, 200 x 150 pixels, depths 1 to 8");
        return true;
    default:
        if (i >= 6 + 24)
            return false;
        scene_start(s, 48, 36);
        {
            double cx = rng_range(&r, 8, 40), cy = rng_range(&r, 8, 28);
            struct vertex v[3];
            for (int k = 0; k < 3; k++)
                v[k] = rvtx(&r, grid(&r, cx + rng_range(&r, -20, 20)), grid(&r, cy + rng_range(&r, -20, 20)), 1, 10);
            add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "random coloured triangle %d of 24, depths 1 to 10", i - 5);
        return true;
    }
}

static bool gen_property(int i, struct scene *s, char *what, size_t n)
{
    struct rng r = { 0x9409e7u + (uint64_t)i };
    switch (i) {
    case 0:
        scene_start(s, 160, 120);
        add(s, vtx(5.3, 4.7, 1, 1, 0, 0), vtx(154.1, 30.2, 2, 0, 1, 0), vtx(40.8, 116.6, 3, 0, 0, 1));
        snprintf(what, n, "a large triangle, 150 pixels across");
        return true;
    case 1:
        scene_start(s, 160, 120);
        add(s, vtx(80.5, 2.5, 1, 1, 1, 0), vtx(157.5, 117.5, 1, 0, 1, 1), vtx(2.5, 117.5, 1, 1, 0, 1));
        add(s, vtx(20.5, 10.5, 2, 1, 1, 0), vtx(60.5, 10.5, 2, 0, 1, 1), vtx(20.5, 50.5, 2, 1, 0, 1));
        snprintf(what, n, "two large triangles, vertices on pixel centres");
        return true;
    case 2:
        scene_start(s, 96, 72);
        grid_mesh(s, &r, 4, 3, -5.5, -3.25, 101.5, 75.5, 0.25);
        snprintf(what, n, "a jittered 4 x 3 grid of large triangles over the target");
        return true;
    case 3:
        scene_start(s, 128, 96);
        add(s, vtx(-300.2, -200.6, 1, 1, 0, 0), vtx(900.3, 40.1, 1, 0, 1, 0), vtx(60.7, 700.9, 1, 0, 0, 1));
        snprintf(what, n, "a triangle larger than the target");
        return true;
    }
    return false;
}

/* --- drawing and comparing -------------------------------------------------- */

static bool prepare(struct target *fb, const struct scene *s)
{
    if (fb->color && fb->w == s->w && fb->h == s->h) {
        fb->background = scene_background(s);
        target_clear(fb);
        return true;
    }
    target_free(fb);
    return target_init(fb, s->w, s->h, scene_background(s));
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

/* The narration, watched for the lesson's property. */
static void watch(void *ctx, const struct trace_event *ev)
{
    struct checker *C = ctx;
    struct verdict *v = C->prop;
    if (v->what != WRONG_NONE)
        return;
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
        int missing_x = -1, missing_y = -1;
        for (int y = ev->y; y <= ev->y1 && missing_x < 0; y++)
            for (int x = ev->x; x <= ev->x1; x++)
                if (!covered(C, x, y)) {
                    missing_x = x, missing_y = y;
                    break;
                }
        if (ev->klass == BLOCK_FULL && missing_x >= 0)
            *v = (struct verdict){ .what = WRONG_BLOCK_NOT_FULL, .x = missing_x, .y = missing_y,
                                   .bx = ev->x, .by = ev->y, .bx1 = ev->x1, .by1 = ev->y1 };
        else if (ev->klass != BLOCK_FULL && missing_x < 0)
            *v = (struct verdict){ .what = WRONG_BLOCK_MISSED, .x = ev->x, .y = ev->y,
                                   .bx = ev->x, .by = ev->y, .bx1 = ev->x1, .by1 = ev->y1 };
        break;
    }
    default:
        break;
    }
}

/* The first pixel, in reading order, where the pictures differ. */
static bool compare(const struct checker *C, int tri, struct verdict *v)
{
    const struct target *W = &C->want, *G = &C->got;
    size_t n = (size_t)W->w * (size_t)W->h;
    bool colour = C->kind == CK_COLOUR || C->kind == CK_ALL;
    for (size_t i = 0; i < n; i++) {
        enum wrong what = WRONG_NONE;
        if (W->count[i] != G->count[i])
            what = WRONG_COUNT;
        else if (colour && W->count[i] && !pixel_close(W->color[i], W->depth[i], G->color[i], G->depth[i]))
            what = pixel_close(W->color[i], W->depth[i], G->color[i], W->depth[i]) ? WRONG_DEPTH : WRONG_COLOUR;
        if (what != WRONG_NONE) {
            *v = (struct verdict){
                .what = what, .tri = tri, .x = (int)(i % (size_t)W->w), .y = (int)(i / (size_t)W->w),
                .want_n = W->count[i], .got_n = G->count[i], .want_c = W->color[i], .got_c = G->color[i],
                .want_z = W->depth[i], .got_z = G->depth[i],
            };
            return false;
        }
    }
    return true;
}

/* Draw scene s both ways, triangle by triangle; false (and v) at the first
 * triangle after which they differ in what this check compares. */
static bool evaluate(struct checker *C, const struct scene *s, struct verdict *v)
{
    *v = (struct verdict){ .what = WRONG_NONE };
    if (!prepare(&C->want, s) || !prepare(&C->got, s))
        return true;    /* out of memory: said by the caller */
    uint8_t *mask = realloc(C->mask, (size_t)s->w * (size_t)s->h);
    if (!mask)
        return true;
    C->mask = mask;
    C->evaluations++;
    const struct lesson_variant *exact = exercise_exact(C->l->perspective);
    bool property = C->kind == CK_PROPERTY || C->kind == CK_ALL;
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, C->p.subpixel_bits);
        exact->rasterize(&t, &C->p, &C->want, NULL);
        if (property) {
            memset(C->mask, 0, (size_t)s->w * (size_t)s->h);
            reference_coverage(&t, mark, C);
        }
        struct verdict prop = { .what = WRONG_NONE };
        struct trace tr = { .sink = property ? watch : NULL, .ctx = C };
        C->prop = &prop;
        C->t = &t;
        C->in_row = false;
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        exercise_fault_clear();
        if (guard)
            guard->tri = i;
        exercise_variant.rasterize(&t, &C->p, &C->got, &tr);
        C->triangles++;
        const struct exercise_fault *f = exercise_fault();
        if (f->any) {
            *v = (struct verdict){ .what = WRONG_OUTSIDE, .tri = i, .x = f->x, .y = f->y };
            return false;
        }
        if (prop.what != WRONG_NONE) {
            *v = prop;
            v->tri = i;
            return false;
        }
        if (!compare(C, i, v))
            return false;
    }
    return true;
}

/* --- shrinking ---------------------------------------------------------------- */

struct shrinker {
    struct checker *C;
    int budget;
};

static bool still_fails(struct shrinker *S, const struct scene *s)
{
    if (S->budget <= 0)
        return false;
    S->budget--;
    struct verdict v;
    return !evaluate(S->C, s, &v);
}

/* Keep candidate c in place of s when it still fails. */
static bool try_candidate(struct shrinker *S, struct scene *s, struct scene *c)
{
    if (still_fails(S, c)) {
        scene_free(s);
        *s = *c;
        return true;
    }
    scene_free(c);
    return false;
}

/* Fewest triangles: drop one at a time while the check still fails. */
static void drop_triangles(struct shrinker *S, struct scene *s)
{
    bool progress = true;
    while (progress && s->ntris > 1) {
        progress = false;
        for (int i = s->ntris - 1; i >= 0 && s->ntris > 1; i--) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            memmove(&c.tris[i], &c.tris[i + 1], sizeof c.tris[0] * (size_t)(c.ntris - i - 1));
            c.ntris--;
            progress |= try_candidate(S, s, &c);
        }
    }
}

/* Every coordinate of the scene, in order: x, y of each vertex. */
static double *coord(struct scene *s, int k)
{
    struct vertex *v = &s->tris[k / 6].v[(k / 2) % 3];
    return k % 2 ? &v->y : &v->x;
}

/* Smallest coordinates: move the scene to the origin by whole pixels, make
 * the target no larger than it needs, then round each coordinate to the
 * coarsest grid (whole pixels, centres, halves, ...) that still fails. */
static void round_coordinates(struct shrinker *S, struct scene *s)
{
    for (int pass = 0; pass < 3; pass++) {
        bool progress = false;
        /* to the origin, by whole pixels: every tie stays a tie */
        double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *coord(s, k);
            if (k % 2)
                miny = fmin(miny, v), maxy = fmax(maxy, v);
            else
                minx = fmin(minx, v), maxx = fmax(maxx, v);
        }
        double dx = floor(minx) > 0 ? floor(minx) : 0, dy = floor(miny) > 0 ? floor(miny) : 0;
        for (int axis = 0; axis < 2; axis++) {
            double d = axis ? dy : dx;
            if (d <= 0)
                continue;
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            for (int k = axis; k < 6 * c.ntris; k += 2)
                *coord(&c, k) -= d;
            progress |= try_candidate(S, s, &c);
        }
        /* the target no larger than the triangles */
        int w = (int)fmin(s->w, fmax(1, ceil(maxx - dx) + 1)), h = (int)fmin(s->h, fmax(1, ceil(maxy - dy) + 1));
        if (w < s->w || h < s->h) {
            struct scene c;
            if (!scene_copy(&c, s))
                return;
            c.w = w, c.h = h;
            progress |= try_candidate(S, s, &c);
        }
        /* each coordinate to a coarser grid */
        static const double steps[] = { 1, 0.5, 0.25, 0.125, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128 };
        for (int k = 0; k < 6 * s->ntris; k++) {
            double v = *coord(s, k);
            for (size_t g = 0; g < sizeof steps / sizeof steps[0]; g++) {
                double candidates[2] = { round(v / steps[g]) * steps[g],
                                         g == 0 ? floor(v) + 0.5 : NAN };
                bool done = false;
                for (int m = 0; m < 2 && !done; m++) {
                    double u = candidates[m];
                    if (isnan(u) || u == v || fabs(u) > fabs(v) + 1)
                        continue;
                    struct scene c;
                    if (!scene_copy(&c, s))
                        return;
                    *coord(&c, k) = u;
                    done = try_candidate(S, s, &c);
                }
                if (done) {
                    progress = true;
                    break;
                }
            }
        }
        if (!progress)
            break;
    }
}

/* Plain colours and depths for a coverage or property counterexample. */
static void plain_attributes(struct shrinker *S, struct scene *s)
{
    static const double rgb[3][3] = { { 1, 0.2, 0.2 }, { 0.2, 1, 0.2 }, { 0.3, 0.5, 1 } };
    struct scene c;
    if (!scene_copy(&c, s))
        return;
    for (int i = 0; i < c.ntris; i++)
        for (int k = 0; k < 3; k++) {
            struct vertex *v = &c.tris[i].v[k];
            v->z = 1 + i;
            v->r = rgb[i % 3][0], v->g = rgb[i % 3][1], v->b = rgb[i % 3][2];
            v->s = v->t = 0;
        }
    c.background[0] = c.background[1] = c.background[2] = 0;
    try_candidate(S, s, &c);
}

static void shrink(struct checker *C, struct scene *s)
{
    struct shrinker S = { C, SHRINK_BUDGET };
    drop_triangles(&S, s);
    round_coordinates(&S, s);
    if (C->kind == CK_COVERAGE || C->kind == CK_PROPERTY)
        plain_attributes(&S, s);
}

/* --- the report -------------------------------------------------------------- */

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
    fprintf(out, "      (# covered once, 2 twice, . not covered; x from %d to %d)\n", x0, x1);
}

static void say_verdict(const struct checker *C, FILE *out, const struct verdict *v,
                        const struct scene *s)
{
    const struct vertex *tv = s->tris[v->tri].v;
    fprintf(out, "      triangle %d: (%g, %g) (%g, %g) (%g, %g)\n", v->tri + 1, tv[0].x, tv[0].y,
            tv[1].x, tv[1].y, tv[2].x, tv[2].y);
    switch (v->what) {
    case WRONG_COUNT:
        fprintf(out, "      pixel (%d, %d), centre (%g, %g): expected %s, got %s: %s\n", v->x, v->y,
                v->x + 0.5, v->y + 0.5, times(v->want_n), times(v->got_n),
                v->got_n > v->want_n ? (v->want_n ? "written twice" : "an extra pixel") : "a missing pixel");
        neighbourhood(C, out, v->x, v->y);
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
    case WRONG_BLOCK_NOT_FULL:
        fprintf(out, "      block (%d, %d)-(%d, %d) narrated FULL, but pixel (%d, %d) in it is not covered\n",
                v->bx, v->by, v->bx1, v->by1, v->x, v->y);
        break;
    case WRONG_BLOCK_MISSED:
        fprintf(out, "      block (%d, %d)-(%d, %d) is covered in full, but was not narrated FULL\n",
                v->bx, v->by, v->bx1, v->by1);
        break;
    case WRONG_NONE:
        break;
    }
}

/* What the code's own narration says about the first wrong pixel: its
 * first write there, its last test of it, and the block or span that holds
 * it. From these, the step at which the explorer shows it: the write (or
 * the block or span), or the end of the triangle when the code never wrote
 * the pixel (a missing one). */
struct trail {
    int x, y;
    bool written, tested, held;
    struct trace_event write, test, hold;
};

static void follow(void *ctx, const struct trace_event *ev)
{
    struct trail *f = ctx;
    bool here = ev->x == f->x && ev->y == f->y;
    if (ev->kind == TRACE_PIXEL_WRITE && here && !f->written)
        f->written = true, f->write = *ev;
    else if (ev->kind == TRACE_PIXEL_TEST && here)
        f->tested = true, f->test = *ev;
    else if ((ev->kind == TRACE_BLOCK || ev->kind == TRACE_SPAN) && !f->held && f->x >= ev->x
             && f->x <= ev->x1 && f->y >= ev->y && f->y <= ev->y1)
        f->held = true, f->hold = *ev;
}

static uint64_t step_of(const struct checker *C, const struct scene *s, const struct verdict *v,
                        struct trail *f)
{
    *f = (struct trail){ .x = v->x, .y = v->y };
    struct replay r;
    if (!replay_init(&r, s, &exercise_variant, &C->p))
        return 0;
    uint64_t step = r.start[v->tri + 1];
    struct target fb;
    if (target_init(&fb, s->w, s->h, scene_background(s))) {
        struct tri_setup t;
        replay_setup(&r, v->tri, &t);
        struct trace tr = { .sink = follow, .ctx = f };
        trace_begin(&tr, (uint32_t)v->tri, TRACE_UNLIMITED);
        exercise_variant.rasterize(&t, &C->p, &fb, &tr);
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

static const char *const edge_names[3] = { "AB", "BC", "CA" };

/* Why the exact rule decides the pixel as it does, when its centre lies
 * exactly on an edge; and what the code's narration said about it. */
static void explain(const struct checker *C, FILE *out, const struct verdict *v,
                    const struct scene *s, const struct trail *f)
{
    if (v->what == WRONG_COUNT || v->what == WRONG_COLOUR || v->what == WRONG_DEPTH) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[v->tri].v, s->w, s->h, C->p.subpixel_bits);
        for (int k = 0; k < 3 && t.area2 > 0; k++) {
            if (edge_value(&t, k, v->x, v->y) != 0)
                continue;
            bool top = t.I[k] == 0 && t.J[k] > 0, left = t.I[k] > 0;
            fprintf(out, "      its centre lies exactly on edge %s (F = 0), a %s edge: the top-left rule %s\n",
                    edge_names[k], top ? "top" : left ? "left" : t.I[k] == 0 ? "bottom" : "right",
                    top || left ? "covers it" : "leaves it to the triangle on the other side");
        }
    }
    const struct lesson *l = C->l;
    if (v->what == WRONG_MUL || v->what == WRONG_BLOCK_NOT_FULL || v->what == WRONG_BLOCK_MISSED
        || v->what == WRONG_OUTSIDE)
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

static bool make_dirs(const char *dir)
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

/* --- the checks ------------------------------------------------------------------ */

struct check {
    const char *name;
    enum check_kind kind;
    scene_gen gen;
};

static void progress(const struct check_options *o, int n, int i, const char *name, int done, int total)
{
    if (!o->progress)
        return;
    fprintf(o->out, "\r  %d/%d %-31s %3d%%", i + 1, n, name, total ? 100 * done / total : 0);
    fflush(o->out);
}

/* A failing scene: shrink it, write it, say everything. */
static bool report_failure(struct checker *C, const char *name, struct scene *s, const char *what,
                           struct check_result *r)
{
    const struct check_options *o = C->o;
    FILE *out = o->out;
    struct verdict v;
    evaluate(C, s, &v);
    fprintf(out, "FAILED\n      on %s\n", what);
    say_verdict(C, out, &v, s);

    shrink(C, s);
    evaluate(C, s, &v);
    r->x = v.x, r->y = v.y;
    r->ntris = s->ntris;
    struct trail f;
    r->step = step_of(C, s, &v, &f);
    snprintf(r->failed, sizeof r->failed, "%s", name);

    char slug[64];
    size_t k = 0;
    for (const char *p = name; *p && k + 1 < sizeof slug; p++)
        slug[k++] = (*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9') ? *p : '-';
    while (k > 0 && slug[k - 1] == '-')
        k--;
    slug[k] = '\0';
    for (char *p = slug; (p = strstr(p, "--"));)
        memmove(p, p + 1, strlen(p));
    char nn[3] = { C->l->id[0], C->l->id[1], '\0' };
    if (!make_dirs(o->out_dir)) {
        fprintf(out, "  cannot create %s: %s\n", o->out_dir, strerror(errno));
        return false;
    }
    snprintf(r->counterexample, sizeof r->counterexample, "%s/%s-%s.scene", o->out_dir, nn, slug);
    struct scene_out so = { s, name, C->l->id, o->file, &v };
    char err[600];
    if (!write_file_atomic(r->counterexample, write_scene, &so, err, sizeof err)) {
        fprintf(out, "  %s\n", err);
        r->counterexample[0] = '\0';
        return false;
    }
    fprintf(out, "\n  smallest counterexample: %d triangle%s, written to %s\n", s->ntris,
            s->ntris == 1 ? "" : "s", r->counterexample);
    say_verdict(C, out, &v, s);
    explain(C, out, &v, s, &f);
    fprintf(out, "\n  open it in the explorer at the first wrong pixel (step %llu):\n      %s SCENE=%s STEP=%llu\n",
            (unsigned long long)r->step, o->open_cmd, r->counterexample, (unsigned long long)r->step);
    return true;
}

/* Run one check over all of its scenes. */
static bool run_check(struct checker *C, int i, int n, const struct check *ck, struct check_result *r)
{
    FILE *out = C->o->out;
    fprintf(out, "  %d/%d %-31s ", i + 1, n, ck->name);
    fflush(out);
    C->kind = ck->kind;
    uint64_t tris0 = C->triangles;
    int total = 0;
    char what[200];
    struct scene s;
    while (ck->gen(total, &s, what, sizeof what)) {
        scene_free(&s);
        total++;
    }
    for (int k = 0; k < total; k++) {
        if (k % 64 == 0)
            progress(C->o, n, i, ck->name, k, total);
        ck->gen(k, &s, what, sizeof what);
        if (guard) {
            guard->check = i;
            guard->scene = k;
            alarm(SCENE_SECONDS);
        }
        struct verdict v;
        bool passed = evaluate(C, &s, &v);
        if (guard)
            alarm(0);
        if (!passed) {
            if (C->o->progress)
                fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
            report_failure(C, ck->name, &s, what, r);
            scene_free(&s);
            return false;
        }
        scene_free(&s);
    }
    if (C->o->progress)
        fprintf(out, "\r  %d/%d %-31s ", i + 1, n, ck->name);
    fprintf(out, "ok (%d scene%s, %llu triangles)\n", total, total == 1 ? "" : "s",
            (unsigned long long)(C->triangles - tris0));
    return true;
}

/* The student's own scenes (SCENE=), every comparison at once. */
static const char *const *user_scenes;
static struct scene *user_loaded;
static int user_count;

static bool gen_user(int i, struct scene *s, char *what, size_t n)
{
    if (i >= user_count)
        return false;
    scene_copy(s, &user_loaded[i]);
    snprintf(what, n, "your scene %s", user_scenes[i]);
    return true;
}

/* The checks of lesson l, in order; false when a SCENE= file does not load. */
struct plan {
    struct check checks[8];
    int n;
};

static void plan_free(void)
{
    for (int i = 0; i < user_count; i++)
        scene_free(&user_loaded[i]);
    free(user_loaded);
    user_loaded = NULL;
    user_count = 0;
}

static bool plan_checks(const struct lesson *l, const struct check_options *o, struct plan *P)
{
    P->n = 0;
    user_scenes = o->scenes;
    user_count = 0;
    int wanted = 0;
    while (o->scenes && o->scenes[wanted])
        wanted++;
    user_loaded = calloc((size_t)wanted + 1, sizeof *user_loaded);
    if (!user_loaded)
        return false;
    for (; user_count < wanted; user_count++) {
        char err[512];
        if (!scene_load(&user_loaded[user_count], o->scenes[user_count], err, sizeof err)) {
            fprintf(o->out, "%s\n", err);
            plan_free();
            return false;
        }
    }
    struct check *c = P->checks;
    if (user_count)
        c[P->n++] = (struct check){ "your scene", CK_ALL, gen_user };
    c[P->n++] = (struct check){ "single triangle", CK_COVERAGE, gen_single };
    c[P->n++] = (struct check){ "fill-rule ties", CK_COVERAGE, gen_ties };
    c[P->n++] = (struct check){ "watertight meshes", CK_COVERAGE, gen_meshes };
    c[P->n++] = (struct check){ "random triangles", CK_COVERAGE, gen_random };
    c[P->n++] = (struct check){ l->perspective ? "colour and depth (perspective)" : "colour and depth (linear)",
                                CK_COLOUR, gen_colour };
    if (l->exercise.no_pixel_mul)
        c[P->n++] = (struct check){ "no multiplication per pixel", CK_PROPERTY, gen_property };
    if (l->exercise.full_blocks)
        c[P->n++] = (struct check){ "full blocks really full", CK_PROPERTY, gen_property };
    return true;
}

static struct raster_params check_params(const struct check_options *o)
{
    struct raster_params p = o->params;
    if (p.subpixel_bits == 0 && p.block_size == 0 && !p.affine)
        p.subpixel_bits = SUBPIXEL_BITS;
    return p;
}

bool exercise_check(const struct lesson *l, const struct check_options *o, struct check_result *r)
{
    memset(r, 0, sizeof *r);
    FILE *out = o->out;
    struct checker C = { .l = l, .o = o, .p = check_params(o) };
    struct plan P;
    if (!plan_checks(l, o, &P))
        return false;
    int n = P.n;
    fprintf(out, "make check, lesson %s: %s\n", l->id, o->file);
    clock_t t0 = clock();
    r->nchecks = n;
    bool ok = true;
    for (int i = 0; i < n && ok; i++) {
        ok = run_check(&C, i, n, &P.checks[i], r);
        r->passed += ok;
    }
    if (ok)
        fprintf(out, "all %d checks pass: %llu scenes, %llu triangles, every pixel as the exact rule "
                "decides it (%.1f s)\n", n, (unsigned long long)C.evaluations,
                (unsigned long long)C.triangles, (double)(clock() - t0) / CLOCKS_PER_SEC);
    else
        fprintf(out, "\n%d of %d checks passed; fix the first failure and run make check again\n",
                r->passed, n);
    plan_free();
    target_free(&C.want);
    target_free(&C.got);
    free(C.mask);
    return ok;
}

/* --- a crash or an endless loop ------------------------------------------------ */

/* Does drawing s crash? In a process of its own. */
static bool crashes(struct checker *C, const struct scene *s)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return false;
    if (pid == 0) {
        alarm(2);
        struct verdict v;
        evaluate(C, s, &v);
        _exit(0);
    }
    int status;
    if (waitpid(pid, &status, 0) != pid)
        return false;
    return !(WIFEXITED(status) && WEXITSTATUS(status) == 0) && !(WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM);
}

static void report_crash(const struct lesson *l, const struct check_options *o, const struct guard *g,
                         int status, struct check_result *r)
{
    FILE *out = o->out;
    struct plan P;
    memset(r, 0, sizeof *r);
    if (!plan_checks(l, o, &P))
        return;
    r->nchecks = P.n;
    r->passed = g->check;
    bool endless = WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM;
    const struct check *ck = &P.checks[g->check < P.n ? g->check : P.n - 1];
    snprintf(r->failed, sizeof r->failed, "%s", ck->name);
    struct scene s;
    char what[200];
    if (!ck->gen(g->scene, &s, what, sizeof what)) {
        plan_free();
        return;
    }
    if (endless)
        fprintf(out, "DID NOT FINISH\n      your code drew triangle %d of %s for %d s: an endless loop?\n",
                g->tri + 1, what, SCENE_SECONDS);
    else if (WIFSIGNALED(status))
        fprintf(out, "CRASHED\n      your code crashed (%s) drawing triangle %d of %s\n",
                strsignal(WTERMSIG(status)), g->tri + 1, what);
    else
        fprintf(out, "CRASHED\n      your code stopped the check (exit status %d) drawing triangle %d of %s\n",
                WEXITSTATUS(status), g->tri + 1, what);

    struct checker C = { .l = l, .o = o, .p = check_params(o), .kind = ck->kind };
    if (!endless) {
        /* fewest triangles, then each coordinate rounded, while it still crashes */
        int budget = CRASH_BUDGET;
        for (int i = s.ntris - 1; i >= 0 && s.ntris > 1 && budget > 0; i--, budget--) {
            struct scene c;
            if (!scene_copy(&c, &s))
                break;
            memmove(&c.tris[i], &c.tris[i + 1], sizeof c.tris[0] * (size_t)(c.ntris - i - 1));
            c.ntris--;
            if (crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
        for (int k = 0; k < 6 * s.ntris && budget > 0; k++, budget--) {
            struct scene c;
            if (!scene_copy(&c, &s))
                break;
            *coord(&c, k) = round(*coord(&c, k));
            if (*coord(&c, k) != *coord(&s, k) && crashes(&C, &c)) {
                scene_free(&s);
                s = c;
            } else {
                scene_free(&c);
            }
        }
    }
    if (make_dirs(o->out_dir)) {
        char nn[3] = { l->id[0], l->id[1], '\0' };
        snprintf(r->counterexample, sizeof r->counterexample, "%s/%s-%s.scene", o->out_dir, nn,
                 endless ? "endless" : "crash");
        struct verdict v = { .tri = 0 };
        struct scene_out so = { &s, endless ? "did not finish" : "crashed", l->id, o->file, &v };
        char err[600];
        if (write_file_atomic(r->counterexample, write_scene, &so, err, sizeof err)) {
            r->ntris = s.ntris;
            fprintf(out, "\n  %s: %d triangle%s, written to %s\n", endless ? "the scene" : "smallest scene that crashes",
                    s.ntris, s.ntris == 1 ? "" : "s", r->counterexample);
            for (int i = 0; i < s.ntris; i++) {
                const struct vertex *tv = s.tris[i].v;
                fprintf(out, "      triangle %d: (%g, %g) (%g, %g) (%g, %g)\n", i + 1, tv[0].x, tv[0].y,
                        tv[1].x, tv[1].y, tv[2].x, tv[2].y);
            }
            fprintf(out, "\n  the explorer runs your code too, and stops where it does; to see where, run it\n"
                    "  under the debugger:\n      gdb -ex run --args %s --file %s --scene %s --dump-coverage /tmp/coverage.pgm\n",
                    o->program ? o->program : "build/exercise-NN", o->file, r->counterexample);
        } else {
            fprintf(out, "  %s\n", err);
            r->counterexample[0] = '\0';
        }
    }
    fprintf(out, "\n%d of %d checks passed; fix the first failure and run make check again\n",
            r->passed, P.n);
    scene_free(&s);
    plan_free();
}

bool exercise_check_guarded(const struct lesson *l, const struct check_options *o,
                            struct check_result *r)
{
    struct guard *g = mmap(NULL, sizeof *g, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (g == MAP_FAILED)
        return exercise_check(l, o, r);
    memset(g, 0, sizeof *g);
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        munmap(g, sizeof *g);
        return exercise_check(l, o, r);
    }
    if (pid == 0) {
        guard = g;
        bool ok = exercise_check(l, o, &g->result);
        fflush(NULL);
        _exit(ok ? 10 : 11);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) {
            status = 0;
            break;
        }
    bool ok = false;
    if (WIFEXITED(status) && (WEXITSTATUS(status) == 10 || WEXITSTATUS(status) == 11)) {
        *r = g->result;
        ok = WEXITSTATUS(status) == 10;
    } else {
        report_crash(l, o, g, status, r);
    }
    munmap(g, sizeof *g);
    return ok;
}
