/* front.c - the 3-D front end timed (lesson 06): a closed torus of 100,000
 * triangles (500 x 100 quads) seen from inside its tube, looking down the
 * tunnel, at 1920 x 1080. The near plane cuts the walls beside the eye, the
 * far plane the tunnel's far part, and the walls close to the eye reach past
 * the guard band: every stage has work. Timed: front_scene, that is look-at,
 * near/far clipping, projection, guard band, fan and cull for every world
 * triangle, the screen triangles stored; no rasterizing. Reported in world
 * triangles per second. */
#define _POSIX_C_SOURCE 200809L   /* clock_gettime */

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "front/front.h"

#define TORUS_SEG 500           /* around the ring */
#define TORUS_RINGS 100         /* around the tube */
#define TORUS_R 10.0
#define TORUS_TUBE 2.0

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void torus_point(int i, int j, double p[3])
{
    const double tau = 6.283185307179586;
    double u = tau * i / TORUS_SEG, v = tau * j / TORUS_RINGS;
    p[0] = (TORUS_R + TORUS_TUBE * cos(v)) * cos(u);
    p[1] = TORUS_TUBE * sin(v);
    p[2] = (TORUS_R + TORUS_TUBE * cos(v)) * sin(u);
}

static bool make_torus(struct scene *s)
{
    *s = (struct scene){ .w = 1920, .h = 1080 };
    s->world.camera_line = 1;
    /* in the tube at u = 0, a little off its centre line, looking along it */
    s->world.cam = (struct camera){ .eye = { TORUS_R + 0.7, 0.4, 0 }, .target = { TORUS_R + 0.7, 0.4, 1 },
                                    .up = { 0.1, 1, 0 }, .fovy = 70, .near = 0.05, .far = 12 };
    for (int j = 0; j < TORUS_RINGS; j++)
        for (int i = 0; i < TORUS_SEG; i++) {
            double q[4][3];
            torus_point(i, j, q[0]);
            torus_point((i + 1) % TORUS_SEG, j, q[1]);
            torus_point((i + 1) % TORUS_SEG, (j + 1) % TORUS_RINGS, q[2]);
            torus_point(i, (j + 1) % TORUS_RINGS, q[3]);
            static const int split[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
            for (int k = 0; k < 2; k++) {
                struct world_tri t = { .texture = 0 };
                for (int c = 0; c < 3; c++) {
                    memcpy(t.p[c], q[split[k][c]], sizeof t.p[c]);
                    t.rgb[c][0] = (double)i / TORUS_SEG;
                    t.rgb[c][1] = (double)j / TORUS_RINGS;
                    t.rgb[c][2] = 0.5;
                }
                if (!world_add(&s->world, &t))
                    return false;
            }
        }
    return true;
}

/* What the stages did, untimed: triangles cut by near or far, and reaching
 * past the guard band. */
static void count_clipping(const struct scene *s, struct bench_front *bf)
{
    struct frustum fr;
    frustum_init(&fr, &s->world.cam, s->w, s->h);
    struct plane pn = depth_plane(&fr, PLANE_NEAR), pf = depth_plane(&fr, PLANE_FAR);
    for (int i = 0; i < s->world.ntris; i++) {
        struct poly a = { .n = 3 }, b, c;
        for (int k = 0; k < 3; k++)
            a.v[k] = view_vertex(&fr, s->world.tris[i].p[k], s->world.tris[i].rgb[k]);
        clip_polygon(&b, &a, &pn, NULL);
        clip_polygon(&c, &b, &pf, NULL);
        bool cut = c.n != 3 || memcmp(a.v, c.v, sizeof a.v[0] * 3) != 0;   /* the vertices, not the padding */
        bf->depth_clipped += cut && c.n > 0;
        bf->culled_whole += c.n == 0;
        project(&fr, &c);
        bf->guard_clipped += c.n > 0 && !in_guard_band(&c);
    }
}

bool bench_front_run(struct bench_front *bf, int runs)
{
    memset(bf, 0, sizeof *bf);
    struct scene s;
    if (!make_torus(&s)) {
        scene_free(&s);
        return false;
    }
    bf->in = s.world.ntris;
    count_clipping(&s, bf);
    bool ok = front_scene(&s);                   /* warm-up */
    bf->t.runs = runs;
    for (int r = 0; r < runs && ok; r++) {
        double t0 = seconds();
        ok = front_scene(&s);
        bf->t.t[r] = seconds() - t0;
    }
    bf->out = s.ntris;
    bench_timing_stats(&bf->t);
    scene_free(&s);
    return ok;
}
