/* search.c - the search of make check (scenes.h): after a check's fixed
 * scenes, seeded scenes aimed at what the lessons decide, drawn until one
 * fails or the check's time is spent. Each scene is made from its own seed
 * alone, so that the seed printed with a counterexample makes it again.
 *
 *   coverage  ties on random edges of every direction and winding, the
 *             pixel centre exactly on the edge (F = 0) or the least an
 *             edge can miss it (F = +-1); coordinates at the +-16384
 *             limits; slivers; triangles mostly off-screen; hundreds of
 *             layers of one triangle (counts past 255); full-HD screens of
 *             many tiles;
 *   colour    the checker texture under random s and t; a triangle drawn
 *             twice (an exact tie: the first keeps the pixel); surfaces
 *             crossing at nearly equal depths; depths far apart;
 *   textures  (lesson 09) textures of every shape the format allows, 1 x 1
 *             to 4096 wide, repeat and clamp, s and t up to +-10^6, levels
 *             of detail from magnified to beyond the last level;
 *   world     (lesson 06) 3-D triangles through near and far under the
 *             checker, so that a new vertex must carry s and t. */
#include "scenes.h"
#include "gen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int64_t irange(struct rng *r, int64_t lo, int64_t hi)     /* lo .. hi */
{
    return lo + (int64_t)(rng_next(r) % (uint64_t)(hi - lo + 1));
}

static bool pick(struct rng *r, double p)
{
    return rng_unit(r) < p;
}

static int64_t gcd(int64_t a, int64_t b)
{
    a = llabs(a), b = llabs(b);
    while (b) {
        int64_t t = a % b;
        a = b, b = t;
    }
    return a;
}

static double px(int64_t v)            /* 1/256 px units to pixels */
{
    return (double)v / SUBPIXEL_ONE;
}

/* Two triangles sharing an edge A B that passes the pixel centre C at F =
 * f exactly: on it (f = 0), or the least an edge can miss it (f = +-1,
 * 1/65536 of a pixel squared: B - A has coprime coordinates in 1/256 px
 * and C - A is the vector the extended Euclid gives for them). The ends a
 * few pixels or thousands away, in every direction (every edge class), the
 * third vertices either side, windings at random. */
static void tie_pair(struct rng *r, struct scene *s, int f, bool far)
{
    int64_t lim = far ? 8000 * SUBPIXEL_ONE : (int64_t)rng_range(r, 1, 14) * SUBPIXEL_ONE, dx, dy;
    do {
        dx = irange(r, -lim, lim), dy = irange(r, -lim, lim);
        if (pick(r, 0.15)) {                /* horizontal or vertical: the top and left classes themselves */
            if (pick(r, 0.5))
                dy = 0, dx = dx ? dx : 1;
            else
                dx = 0, dy = dy ? dy : 1;
            if (f != 0)                     /* F = +-1 wants coprime coordinates: a step of 1/256 */
                dx = dx ? (dx < 0 ? -1 : 1) : 0, dy = dy ? (dy < 0 ? -1 : 1) : 0;
        }
    } while ((dx == 0 && dy == 0) || gcd(dx, dy) != 1);
    int64_t X = (int64_t)irange(r, 1, s->w - 2) * SUBPIXEL_ONE + SUBPIXEL_HALF;
    int64_t Y = (int64_t)irange(r, 1, s->h - 2) * SUBPIXEL_ONE + SUBPIXEL_HALF;
    int64_t wx = 0, wy = 0, j;      /* C - A = w + j D */
    if (f != 0) {
        /* w with dx wy - dy wx = f (extended Euclid on dx and -dy) */
        int64_t r0 = dx, r1 = -dy, s0 = 1, s1 = 0, t0 = 0, t1 = 1;
        while (r1 != 0) {
            int64_t q = r0 / r1, rr = r0 - q * r1, ss = s0 - q * s1, tt = t0 - q * t1;
            r0 = r1, r1 = rr, s0 = s1, s1 = ss, t0 = t1, t1 = tt;
        }
        wx = t0 * r0 * f, wy = s0 * r0 * f;
        j = (double)wx * (double)dx + (double)wy * (double)dy < 0;      /* C between A and B */
    } else {
        /* on the line: D a whole number n of the steps d, C k steps from A */
        j = 0;
        int64_t big = llabs(dx) > llabs(dy) ? llabs(dx) : llabs(dy), most = lim / big;
        int64_t nsteps = irange(r, 2, most > 2 ? most : 2), k = irange(r, 1, nsteps - 1);
        wx = k * dx, wy = k * dy;
        dx *= nsteps, dy *= nsteps;
    }
    int64_t ax = X - wx - j * dx, ay = Y - wy - j * dy, bx = ax + dx, by = ay + dy;
    struct vertex A = gen_rvtx(r, px(ax), px(ay), 1, 4), B = gen_rvtx(r, px(bx), px(by), 1, 4);
    /* the third vertices along the normal (-dy, dx), a few pixels to thousands away */
    double nl = sqrt((double)dx * (double)dx + (double)dy * (double)dy);
    double u = far && pick(r, 0.5) ? rng_range(r, 50, 9000) : rng_range(r, 1.5, 20);
    double along = rng_range(r, 0, 1);
    double mx = px(ax) + along * (px(bx) - px(ax)), my = px(ay) + along * (px(by) - px(ay));
    struct vertex P = gen_rvtx(r, gen_grid(r, mx - u * (double)dy / nl), gen_grid(r, my + u * (double)dx / nl), 1, 4);
    struct vertex Q = gen_rvtx(r, gen_grid(r, mx + u * (double)dy / nl), gen_grid(r, my - u * (double)dx / nl), 1, 4);
    gen_add_flipped(s, A, B, P, pick(r, 0.5));
    gen_add_flipped(s, B, A, Q, pick(r, 0.5));
}

/* A coordinate at a limit of the format (+-16384, on the 1/256 grid), or
 * anywhere between. */
static double limit(struct rng *r)
{
    double u = rng_unit(r);
    if (u < 0.3)
        return -COORD_LIMIT;
    if (u < 0.6)
        return COORD_LIMIT - 1.0 / SUBPIXEL_ONE;
    return gen_grid(r, rng_range(r, -COORD_LIMIT, COORD_LIMIT));
}

/* A random triangle near (cx, cy), d pixels across at most. */
static void near_tri(struct rng *r, struct scene *s, double cx, double cy, double d, double zmin, double zmax)
{
    struct vertex v[3];
    for (int k = 0; k < 3; k++)
        v[k] = gen_rvtx(r, gen_grid(r, cx + rng_range(r, -d, d)), gen_grid(r, cy + rng_range(r, -d, d)), zmin, zmax);
    gen_add(s, v[0], v[1], v[2]);
}

static bool coverage(struct rng *rp, int kind, struct scene *s, char *what, size_t n)
{
    struct rng r = *rp;
    switch (kind) {
    case 0: case 1: case 2: case 3: case 4: case 5: {
        int f = (int)irange(&r, -1, 1);
        bool far = pick(&r, 0.5);
        check_scene_start(s, (int)irange(&r, 8, 40), (int)irange(&r, 8, 30));
        int pairs = (int)irange(&r, 1, 3);
        for (int i = 0; i < pairs; i++)
            tie_pair(&r, s, i == 0 ? f : (int)irange(&r, -1, 1), far);
        snprintf(what, n, "%d pair%s of triangles sharing an edge that passes a pixel centre at F = %+d%s", pairs,
                 pairs == 1 ? "" : "s", f, far ? ", its ends thousands of pixels away" : "");
        return true;
    }
    case 6: case 7: {
        check_scene_start(s, 64, 48);
        struct vertex v[3];
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, limit(&r), limit(&r), 1, 4);
        if (pick(&r, 0.6))
            v[0] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, 0, 64)), gen_grid(&r, rng_range(&r, 0, 48)), 1, 4);
        gen_add(s, v[0], v[1], v[2]);
        snprintf(what, n, "a triangle with vertices at the coordinate limits (+-16384)");
        return true;
    }
    case 8: case 9: {
        check_scene_start(s, 64, 48);
        for (int i = 0; i < 4; i++) {
            struct vertex a = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -200, 264)), gen_grid(&r, rng_range(&r, -200, 248)), 1, 4);
            struct vertex b = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -200, 264)), gen_grid(&r, rng_range(&r, -200, 248)), 1, 4);
            double t = rng_unit(&r), d = rng_range(&r, -0.6, 0.6);
            struct vertex c = gen_rvtx(&r, gen_grid(&r, a.x + t * (b.x - a.x) + d), gen_grid(&r, a.y + t * (b.y - a.y) - d), 1, 4);
            gen_add(s, a, b, c);
        }
        snprintf(what, n, "4 slivers, long and thin, reaching past the target");
        return true;
    }
    case 10: case 11: {
        /* mostly off-screen: two vertices far outside, the triangle cutting a corner or a side */
        int w = (int)irange(&r, 16, 96), h = (int)irange(&r, 16, 72);
        check_scene_start(s, w, h);
        for (int i = 0; i < 3; i++) {
            double cx = pick(&r, 0.5) ? rng_range(&r, -3, 3) : w + rng_range(&r, -3, 3);
            double cy = pick(&r, 0.5) ? rng_range(&r, -3, 3) : h + rng_range(&r, -3, 3);
            struct vertex v[3];
            v[0] = gen_rvtx(&r, gen_grid(&r, cx), gen_grid(&r, cy), 1, 4);
            for (int k = 1; k < 3; k++)
                v[k] = gen_rvtx(&r, gen_grid(&r, cx + (cx < w / 2 ? -1 : 1) * rng_range(&r, -200, 3000)),
                                gen_grid(&r, cy + (cy < h / 2 ? -1 : 1) * rng_range(&r, -200, 3000)), 1, 4);
            gen_add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "3 triangles mostly off-screen, each over a corner of %d x %d pixels", w, h);
        return true;
    }
    case 12: case 13: {
        /* hundreds of layers of one triangle: counts past 255 */
        check_scene_start(s, 16, 12);
        int layers = (int)irange(&r, 64, 300);
        struct vertex v[3];
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, 0, 16)), gen_grid(&r, rng_range(&r, 0, 12)), 1, 4);
        for (int i = 0; i < layers; i++)
            gen_add(s, v[0], v[1], v[2]);
        snprintf(what, n, "one triangle drawn %d times (a pixel's count saturates at 255)", layers);
        return true;
    }
    case 14: {
        /* a fan around a pixel centre or a vertex off it */
        check_scene_start(s, 32, 24);
        double cx = pick(&r, 0.5) ? floor(rng_range(&r, 4, 28)) + 0.5 : gen_grid(&r, rng_range(&r, 4, 28));
        double cy = pick(&r, 0.5) ? floor(rng_range(&r, 4, 20)) + 0.5 : gen_grid(&r, rng_range(&r, 4, 20));
        int k = (int)irange(&r, 3, 9);
        double a0 = rng_range(&r, 0, 6.283185307179586), rad = rng_range(&r, 2, 40);
        struct vertex c = gen_rvtx(&r, cx, cy, 1, 4), first = c, prev = c;
        for (int i = 0; i <= k; i++) {
            double a = a0 + 6.283185307179586 * i / k;
            struct vertex p = i == k ? first : gen_rvtx(&r, gen_grid(&r, cx + rad * cos(a)), gen_grid(&r, cy + rad * sin(a)), 1, 4);
            if (i == 0)
                first = p;
            else
                gen_add_flipped(s, c, prev, p, pick(&r, 0.5));
            prev = p;
        }
        snprintf(what, n, "a fan of %d triangles around (%g, %g), windings mixed", k, cx, cy);
        return true;
    }
    case 15: default: {
        /* a full-HD screen of many tiles: small triangles anywhere, a few large */
        check_scene_start(s, 1920, 1080);
        int count = (int)irange(&r, 20, 60);
        for (int i = 0; i < count; i++) {
            double size = i % 10 == 0 ? rng_range(&r, 100, 900) : rng_range(&r, 1, 30);
            near_tri(&r, s, rng_range(&r, -20, 1940), rng_range(&r, -20, 1100), size, 1, 8);
        }
        snprintf(what, n, "%d triangles on a 1920 x 1080 screen (30 x 17 tiles), most of them small", count);
        return true;
    }
    }
}

bool search_ties(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n)
{
    (void)l;
    struct rng r = { seed };
    return coverage(&r, pick(&r, 0.85) ? 0 : 14, s, what, n);
}

bool search_coverage(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n)
{
    struct rng r = { seed };
    /* full HD is slow to compare: one scene in 10 for a lesson of tiles, one in 40 otherwise
     * (none where each scene is drawn at several samples per pixel) */
    static const int kinds[] = { 6, 8, 10, 12, 6, 8, 10, 12, 10, 15 };
    int kind = kinds[irange(&r, 0, 9)];
    if (kind == 15 && (l->samples || (!l->tiles && !pick(&r, 0.25))))
        kind = 10;      /* and never at 4 or 8 samples a pixel */
    return coverage(&r, kind, s, what, n);
}

/* The attribute interpolated over the screen: z (linear) or 1/z. */
static double depth_q(double z, bool perspective)
{
    return perspective ? 1 / z : z;
}

bool search_colour(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n)
{
    struct rng r = { seed };
    int kind = (int)irange(&r, 0, 11);
    if (l->samples && kind >= 6 && kind <= 9)
        kind = 4;       /* near-equal depths per sample: the samples' own ties */
    int w = (int)irange(&r, 16, 64), h = (int)irange(&r, 12, 48);
    check_scene_start(s, w, h);
    switch (kind) {
    case 0: case 1: case 2: case 3: {
        static const int squares[] = { 1, 2, 3, 4, 5, 8, 16 };
        s->checker = squares[irange(&r, 0, 6)];
        s->has_st = true;
        int count = (int)irange(&r, 1, 4);
        for (int i = 0; i < count; i++) {
            double cx = rng_range(&r, 0, w), cy = rng_range(&r, 0, h), d = rng_range(&r, 4, 40);
            struct vertex v[3];
            for (int k = 0; k < 3; k++) {
                v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -d, d)), gen_grid(&r, cy + rng_range(&r, -d, d)), 1, 4);
                v[k].s = rng_range(&r, -2, 3), v[k].t = rng_range(&r, -2, 3);
            }
            gen_add(s, v[0], v[1], v[2]);
        }
        snprintf(what, n, "%d triangle%s under texture checker %d, s and t from -2 to 3", count, count == 1 ? "" : "s",
                 s->checker);
        return true;
    }
    case 4: case 5: {
        /* a triangle drawn again, in other colours: exactly the same depths, the first keeps its pixels */
        int copies = (int)irange(&r, 2, 4);
        double cx = rng_range(&r, 0, w), cy = rng_range(&r, 0, h), d = rng_range(&r, 3, 30);
        struct vertex v[3];
        for (int k = 0; k < 3; k++)
            v[k] = gen_rvtx(&r, gen_grid(&r, cx + rng_range(&r, -d, d)), gen_grid(&r, cy + rng_range(&r, -d, d)), 1, 10);
        for (int i = 0; i < copies; i++) {
            gen_add(s, v[0], v[1], v[2]);
            for (int k = 0; k < 3; k++)
                v[k].r = rng_unit(&r), v[k].g = 1 - v[k].r, v[k].b = rng_unit(&r);
        }
        snprintf(what, n, "one triangle drawn %d times in other colours: equal depths, the first one drawn keeps "
                 "every pixel", copies);
        return true;
    }
    case 6: case 7: case 8: case 9: {
        /* two surfaces crossing at a shallow angle: depths within 1/1000 of each other */
        struct vertex a[3], b[3];
        double z0 = rng_range(&r, 1, 20), spread = rng_range(&r, 1e-4, 1.5e-3);
        for (int k = 0; k < 3; k++) {
            a[k] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -2.0 * w, 3.0 * w)), gen_grid(&r, rng_range(&r, -2.0 * h, 3.0 * h)),
                            z0, z0 * (1 + rng_range(&r, -0.3, 0.3)));
            b[k] = gen_rvtx(&r, gen_grid(&r, rng_range(&r, -2.0 * w, 3.0 * w)), gen_grid(&r, rng_range(&r, -2.0 * h, 3.0 * h)),
                            1, 2);
        }
        /* b's depths on a's plane (in z, or in 1/z where depth is perspective-correct), moved by +-spread */
        double det = (a[1].x - a[0].x) * (a[2].y - a[0].y) - (a[2].x - a[0].x) * (a[1].y - a[0].y);
        if (fabs(det) < 1)
            det = det < 0 ? -1 : 1;
        for (int k = 0; k < 3; k++) {
            double u = ((b[k].x - a[0].x) * (a[2].y - a[0].y) - (a[2].x - a[0].x) * (b[k].y - a[0].y)) / det;
            double v = ((a[1].x - a[0].x) * (b[k].y - a[0].y) - (b[k].x - a[0].x) * (a[1].y - a[0].y)) / det;
            double q0 = depth_q(a[0].z, l->perspective), q = q0 + u * (depth_q(a[1].z, l->perspective) - q0)
                                                          + v * (depth_q(a[2].z, l->perspective) - q0);
            double z = depth_q(q, l->perspective);
            b[k].z = z > 0.05 && isfinite(z) ? z * (1 + rng_range(&r, -spread, spread)) : z0;
        }
        bool first = pick(&r, 0.5);
        gen_add(s, first ? a[0] : b[0], first ? a[1] : b[1], first ? a[2] : b[2]);
        gen_add(s, first ? b[0] : a[0], first ? b[1] : a[1], first ? b[2] : a[2]);
        snprintf(what, n, "two large triangles crossing at a shallow angle: depths within %.2g of each other", spread);
        return true;
    }
    default: {
        /* near, to 1000, or far away (the scene format allows depths to
         * 10^6): there a depth kept to a fixed bound instead of relative to
         * itself is lost, and the colour with it */
        int count = (int)irange(&r, 2, 6), range = (int)irange(&r, 0, 2);
        double zmin = range == 2 ? 1e4 : 1, zmax = range == 0 ? 3 : range == 1 ? 1000 : 1e6;
        for (int i = 0; i < count; i++)
            near_tri(&r, s, rng_range(&r, 0, w), rng_range(&r, 0, h), rng_range(&r, 3, 50), zmin, zmax);
        snprintf(what, n, "%d random coloured triangles, depths %g to %g", count, zmin, zmax);
        return true;
    }
    }
}

bool search_textures(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n)
{
    (void)l;
    struct rng r = { seed };
    /* a shape the format allows: 1 x N, N x 1, 1 x 1, 4096 wide, ... (at most 2^17 texels) */
    int a, b;
    do {
        a = (int)irange(&r, 0, 12), b = (int)irange(&r, 0, 12);
        if (pick(&r, 0.3)) {        /* one side at an end of the range */
            int end = pick(&r, 0.5) ? 0 : 12;
            if (pick(&r, 0.5))
                a = end;
            else
                b = end;
        }
    } while (a + b > 17);
    int tw = 1 << a, th = 1 << b, last = a > b ? a : b;
    bool clamp = pick(&r, 0.35);
    char texture[64];
    snprintf(texture, sizeof texture, "builtin:noise-%dx%d %s", tw, th, clamp ? "clamp" : "repeat");
    /* where in texture space: near 0, far out (to 10^6: u = s W past 2^31 on a texture 4096 wide),
     * or anywhere between */
    double far = rng_range(&r, -3, 3);
    if (pick(&r, 0.5)) {
        far = (pick(&r, 0.5) ? 1 : -1) * (pick(&r, 0.5) ? rng_range(&r, 5e5, 999990) : exp2(rng_range(&r, 10, 19)));
        if (pick(&r, 0.3))
            a = 12, b = b > 5 ? 5 : b, tw = 1 << a, th = 1 << b, last = a > b ? a : b;
    }
    double s0 = far + rng_range(&r, -1, 1), t0 = (pick(&r, 0.5) ? far : 0) + rng_range(&r, -1, 1);
    /* the level of detail across the triangle: magnified to beyond the last level */
    double lambda = rng_range(&r, -3, last + 2.5);
    double ds = exp2(lambda) * 44 / tw * rng_range(&r, 0.3, 1), dt = exp2(lambda) * 30 / th * rng_range(&r, 0.3, 1);
    if (pick(&r, 0.5))
        ds *= rng_range(&r, 0.02, 1);
    else
        dt *= rng_range(&r, 0.02, 1);
    /* every s and t of the scene within the format's +-10^6 */
    ds = fmin(ds, 1e5), dt = fmin(dt, 1e5);
    double room = 999999 - 3 * (ds + dt) - 2;
    s0 = fmax(fmin(s0, room), -room), t0 = fmax(fmin(t0, room), -room);
    struct gen_text x;
    gen_text_start(&x, 48, 36, texture);
    double z1 = pick(&r, 0.5) ? 1 : rng_range(&r, 1, 6);
    struct tv A = { gen_grid(&r, rng_range(&r, -4, 10)), gen_grid(&r, rng_range(&r, -4, 8)), 1, 1, 1, 1, s0, t0 };
    struct tv B = { gen_grid(&r, rng_range(&r, 38, 52)), gen_grid(&r, rng_range(&r, -4, 12)), z1, 1, 1, 1, s0 + ds, t0 };
    struct tv C = { gen_grid(&r, rng_range(&r, -4, 14)), gen_grid(&r, rng_range(&r, 28, 40)), z1, 1, 1, 1, s0, t0 + dt };
    if (pick(&r, 0.5)) {
        B.t += dt * rng_range(&r, -1, 1);
        C.s += ds * rng_range(&r, -1, 1);
    }
    if (pick(&r, 0.3))
        A.g = rng_unit(&r), B.b = rng_unit(&r), C.r = rng_unit(&r);
    gen_tri(&x, A, B, C);
    if (pick(&r, 0.5)) {    /* the quad's other half: an edge shared */
        struct tv D = { gen_grid(&r, rng_range(&r, 38, 52)), gen_grid(&r, rng_range(&r, 28, 40)), z1, 1, 1, 1, s0 + ds, t0 + dt };
        gen_tri(&x, B, D, C);
    }
    snprintf(what, n, "builtin:noise-%dx%d %s, s from %.9g, t from %.9g, lambda up to about %.2g (last level %d)",
             tw, th, clamp ? "clamp" : "repeat", s0, t0, lambda, last);
    return gen_text_end(&x, s);
}

bool search_world(const struct search_for *l, uint64_t seed, struct scene *s, char *what, size_t n)
{
    (void)l;
    struct rng r = { seed };
    static const int squares[] = { 2, 3, 4, 8, 16 };
    int checker = squares[irange(&r, 0, 4)];
    double near = rng_range(&r, 0.1, 2), far = near + rng_range(&r, 1, 12);
    struct gen_text x;
    gen_text_start(&x, 48, 36, NULL);
    fprintf(x.f, "camera  0 0 0   0 0 -1   0 1 0   %.17g  %.17g %.17g\ntexture checker %d\n",
            rng_range(&r, 40, 100), near, far, checker);
    int count = (int)irange(&r, 1, 4);
    for (int i = 0; i < count; i++) {
        fputs("tri3", x.f);
        for (int k = 0; k < 3; k++) {
            /* view depths from behind the eye to beyond far */
            double d = rng_range(&r, -near, far * 1.6), k2 = d > 0.2 ? d : 0.2;
            fprintf(x.f, "  %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", rng_range(&r, -0.8, 0.8) * k2,
                    rng_range(&r, -0.6, 0.6) * k2, -d, rng_unit(&r), rng_unit(&r), rng_unit(&r),
                    rng_range(&r, -1, 2), rng_range(&r, -1, 2));
        }
        fputc('\n', x.f);
    }
    snprintf(what, n, "%d triangle%s through near (%.3g) and far (%.3g) under texture checker %d", count,
             count == 1 ? "" : "s", near, far, checker);
    return gen_text_end(&x, s);
}
