/* peer.c - lines beside Mesa's llvmpipe GL_LINES (make bench-lines).
 *
 * The exact diamond-exit rule (src/raster/line.c: the walk, colour and z
 * by t, the depth test) and llvmpipe's GL_LINES through OSMesa draw the
 * same scenes at 1920 x 1080, one thread each (llvmpipe with LP_NUM_THREADS=0):
 *
 *  - 3,000 random segments, ends on the 1/256 grid in and around the screen;
 *  - a tie-heavy scene: ends and paths on pixel centres, pixel corners and
 *    diamonds' corners, axis-parallel lines on pixel boundaries, 45 degrees;
 *  - wireframes: builtin:room and builtin:model through the front end at
 *    1920 x 1080, each shared edge once (scene_wireframe).
 *
 * Positions reach llvmpipe exactly as in tests/bench/peer.c: a viewport of
 * 8192 pixels square (a power of two) at (-3072, -3072), vertices already
 * divided, glClipControl(GL_UPPER_LEFT). Coverage is counted by a saturating
 * stencil increment. It prints, per scene, the pixels where the two differ
 * (an exhibit: llvmpipe decides the diamond in float, and its own FIXME in
 * lp_setup_line.c says so) and the time of each, interleaved run by run
 * (only ratios taken in one run mean anything on a shared machine), median and
 * minimum of the runs. First, CONVENTIONS' examples drawn both ways (where
 * a segment runs along pixel boundaries, llvmpipe takes the row above and
 * the column to the left: the other perturbation).
 */
#define _DEFAULT_SOURCE   /* setenv */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "front/front.h"
#include "raster/line.h"
#include "scene/scene.h"

#define W 1920
#define H 1080
#define RUNS 15

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t rng_state = 0x1e5cafe;

static double unit(void)        /* splitmix64, [0, 1) */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return (double)((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
}

static int pick(int lo, int hi)
{
    return lo + (int)(unit() * (hi - lo + 1));
}

static struct vertex end(double x, double y)
{
    return (struct vertex){ .x = x, .y = y, .z = 2 + 90 * unit(), .r = unit(), .g = unit(), .b = unit() };
}

/* A coordinate where ties live: a centre, a boundary, a diamond's corner. */
static double tie(int n)
{
    int p = pick(0, n - 1);
    switch (pick(0, 3)) {
    case 0: return p + 0.5;
    case 1: return p;
    case 2: return p + 0.5 + (pick(0, 1) ? 0.5 : -0.5);
    default: return p + pick(0, 256) / 256.0;
    }
}

struct lines {
    const char *name;
    int n;
    struct vertex *v;           /* 2 n ends */
};

static struct lines random_lines(void)
{
    struct lines l = { "3,000 random segments", 3000, malloc(6000 * sizeof(struct vertex)) };
    for (int i = 0; i < 2 * l.n; i++)
        l.v[i] = end(pick(-100 * 256, (W + 100) * 256) / 256.0, pick(-100 * 256, (H + 100) * 256) / 256.0);
    return l;
}

static struct lines tie_lines(void)
{
    struct lines l = { "3,000 tie-heavy segments", 3000, malloc(6000 * sizeof(struct vertex)) };
    for (int i = 0; i < l.n; i++) {
        double x0 = tie(W), y0 = tie(H), x1 = tie(W), y1 = tie(H);
        int k = pick(0, 3);
        if (k == 0)
            y1 = y0;                    /* horizontal */
        else if (k == 1)
            x1 = x0;                    /* vertical */
        else if (k == 2)
            y1 = y0 + (x1 - x0) * (pick(0, 1) ? 1 : -1);     /* 45 degrees */
        l.v[2 * i] = end(x0, y0);
        l.v[2 * i + 1] = end(x1, fmax(-1000, fmin(H + 1000, y1)));
    }
    return l;
}

static struct lines wireframe(const char *builtin, const char *name)
{
    struct scene s;
    char err[256];
    struct lines l = { name, 0, NULL };
    if (!scene_builtin(&s, builtin, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    s.w = W, s.h = H;
    if (!front_scene(&s) || !(l.v = scene_wireframe(&s, &l.n))) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    scene_free(&s);
    return l;
}

static void draw_exact(const struct lines *l, struct target *fb)
{
    for (int i = 0; i < l->n; i++) {
        struct line_setup ls;
        if (line_setup(&ls, l->v + 2 * i, W, H))
            line_draw(&ls, fb);
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#ifndef TRISTEP_OSMESA
int main(void)
{
    fprintf(stderr, "lines-peer: OSMesa was not found when it was built "
            "(Debian: apt-get install libosmesa6-dev, then make bench-lines)\n");
    return 1;
}
#else

#define GL_GLEXT_PROTOTYPES
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#define VIEW_SIZE   8192
#define VIEW_ORIGIN (-3072)
#define VIEW_HALF   (VIEW_SIZE / 2)
#define VIEW_CENTRE (VIEW_ORIGIN + VIEW_HALF)
#define Z_NEAR 1.5
#define Z_FAR  99.5

struct gl_vertex {
    float pos[4];
    uint8_t rgba[4];
};

static uint8_t unorm8(double c)
{
    return (uint8_t)(c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0 + 0.5);
}

/* tests/bench/peer.c's exact transform: pixels (snapped) to NDC. */
static void to_gl(struct gl_vertex *g, const struct vertex *v)
{
    double x = (double)snap_coord(v->x, SUBPIXEL_BITS) / SUBPIXEL_ONE;
    double y = (double)snap_coord(v->y, SUBPIXEL_BITS) / SUBPIXEL_ONE;
    g->pos[0] = (float)((x - VIEW_CENTRE) / VIEW_HALF);
    g->pos[1] = (float)((y - (H - VIEW_CENTRE)) / VIEW_HALF);
    g->pos[2] = (float)((2 * v->z - Z_NEAR - Z_FAR) / (Z_FAR - Z_NEAR));
    g->pos[3] = 1.0f;
    g->rgba[0] = unorm8(v->r), g->rgba[1] = unorm8(v->g), g->rgba[2] = unorm8(v->b), g->rgba[3] = 255;
}

/* llvmpipe's pixels of one segment, y down, into mask (W x H). */
static void gl_line(const struct vertex v[2], uint8_t *stencil, uint8_t *mask)
{
    struct gl_vertex gv[2];
    to_gl(&gv[0], &v[0]);
    to_gl(&gv[1], &v[1]);
    glVertexPointer(4, GL_FLOAT, sizeof *gv, &gv[0].pos);
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof *gv, &gv[0].rgba);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    glDrawArrays(GL_LINES, 0, 2);
    glReadPixels(0, 0, W, H, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);
    glDisable(GL_STENCIL_TEST);
    for (int y = 0; y < H; y++)
        memcpy(mask + (size_t)y * W, stencil + (size_t)(H - 1 - y) * W, W);
}

static void mask_pixel(void *ctx, int x, int y)
{
    ((uint8_t *)ctx)[(size_t)y * W + x]++;
}

/* CONVENTIONS' examples, both ways: the pixels of the first rows and
 * columns, '#' drawn, as the exact rule and llvmpipe draw them. */
static void probe_examples(uint8_t *stencil)
{
    static const struct { const char *what; double x0, y0, x1, y1; } ex[] = {
        { "centre of pixel 0 to centre of pixel 5, row 1", 0.5, 1.5, 5.5, 1.5 },
        { "horizontal on y = 2", 0.25, 2, 5.25, 2 },
        { "vertical on x = 2", 2, 0.25, 2, 4.25 },
        { "45 degrees through diamonds' corners", 1, 1, 5, 5 },
        { "45 degrees up through diamonds' corners", 1, 5, 5, 1 },
    };
    uint8_t *gl = malloc((size_t)W * H), *exact = malloc((size_t)W * H);
    printf("CONVENTIONS' examples (exact rule | llvmpipe), rows 0..5, columns 0..7:\n\n");
    for (size_t k = 0; k < sizeof ex / sizeof ex[0]; k++) {
        struct vertex v[2] = { end(ex[k].x0, ex[k].y0), end(ex[k].x1, ex[k].y1) };
        gl_line(v, stencil, gl);
        memset(exact, 0, (size_t)W * H);
        struct line_setup l;
        line_setup(&l, v, W, H);
        line_walk(&l, mask_pixel, exact);
        printf("    %s, (%g, %g) to (%g, %g):\n", ex[k].what, ex[k].x0, ex[k].y0, ex[k].x1, ex[k].y1);
        for (int y = 0; y < 6; y++) {
            printf("        ");
            for (int x = 0; x < 8; x++)
                putchar(exact[(size_t)y * W + x] ? '#' : '.');
            printf("  |  ");
            for (int x = 0; x < 8; x++)
                putchar(gl[(size_t)y * W + x] ? '#' : '.');
            putchar('\n');
        }
    }
    putchar('\n');
    free(gl);
    free(exact);
}

int main(void)
{
    setenv("GALLIUM_DRIVER", "llvmpipe", 1);
    setenv("LP_NUM_THREADS", "0", 1);       /* one thread, before the screen is made */
    const int attribs[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                            OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0 };
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, NULL);
    uint8_t *pixels = malloc((size_t)W * H * 4), *stencil = malloc((size_t)W * H);
    if (!ctx || !pixels || !stencil || !OSMesaMakeCurrent(ctx, pixels, GL_UNSIGNED_BYTE, W, H)) {
        fprintf(stderr, "lines-peer: no OSMesa context\n");
        return 1;
    }
    PFNGLCLIPCONTROLPROC clip_control = (PFNGLCLIPCONTROLPROC)OSMesaGetProcAddress("glClipControl");
    if (!clip_control) {
        fprintf(stderr, "lines-peer: no glClipControl\n");
        return 1;
    }
    clip_control(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glViewport(VIEW_ORIGIN, VIEW_ORIGIN, VIEW_SIZE, VIEW_SIZE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glShadeModel(GL_SMOOTH);
    glLineWidth(1);
    glDisable(GL_LINE_SMOOTH);
    printf("%s, %s; %d x %d, one thread each, %d runs interleaved\n\n",
           (const char *)glGetString(GL_VERSION), (const char *)glGetString(GL_RENDERER), W, H, RUNS);

    probe_examples(stencil);
    rng_state = 0x1e5cafe;          /* the same scenes whatever the probe drew */
    printf("| scene | segments | pixels (exact) | llvmpipe differs | exact ms (median, min) | "
           "llvmpipe ms (median, min) | ratio |\n| --- | --- | --- | --- | --- | --- | --- |\n");

    struct lines scenes[] = { random_lines(), tie_lines(), wireframe("room", "builtin:room's wireframe"),
                              wireframe("model", "builtin:model's wireframe") };
    struct target fb;
    if (!target_init(&fb, W, H, 0xff000000u))
        return 1;
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        const struct lines *l = &scenes[k];
        struct gl_vertex *gv = malloc((size_t)(2 * l->n + 1) * sizeof *gv);
        for (int i = 0; i < 2 * l->n; i++)
            to_gl(&gv[i], &l->v[i]);
        glVertexPointer(4, GL_FLOAT, sizeof *gv, &gv[0].pos);
        glColorPointer(4, GL_UNSIGNED_BYTE, sizeof *gv, &gv[0].rgba);

        /* coverage: the exact rule's counts, llvmpipe's by the stencil */
        target_clear(&fb);
        draw_exact(l, &fb);
        glDisable(GL_DEPTH_TEST);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, 0, 0xff);
        glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
        glClearStencil(0);
        glClear(GL_STENCIL_BUFFER_BIT);
        glDrawArrays(GL_LINES, 0, 2 * l->n);
        glReadPixels(0, 0, W, H, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);
        glDisable(GL_STENCIL_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        long differ = 0, lit = 0;
        for (int y = 0; y < H; y++)        /* window row H - 1 - y is scene row y */
            for (int x = 0; x < W; x++) {
                uint8_t a = fb.count[(size_t)y * W + x], b = stencil[(size_t)(H - 1 - y) * W + x];
                differ += a != b;
                lit += a;
            }

        /* time: the whole scene with colour and depth, interleaved */
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        double te[RUNS], tg[RUNS];
        uint8_t *count = fb.count;
        fb.count = NULL;                    /* the timed runs do not count (as the bench's) */
        for (int r = -2; r < RUNS; r++) {
            fb.count = count;
            target_clear(&fb);
            fb.count = NULL;
            double t0 = now();
            draw_exact(l, &fb);
            double t1 = now();
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glFinish();
            double t2 = now();
            glDrawArrays(GL_LINES, 0, 2 * l->n);
            glFinish();
            double t3 = now();
            if (r >= 0)
                te[r] = 1e3 * (t1 - t0), tg[r] = 1e3 * (t3 - t2);
        }
        fb.count = count;
        qsort(te, RUNS, sizeof *te, cmp_double);
        qsort(tg, RUNS, sizeof *tg, cmp_double);
        printf("| %s | %d | %ld | %ld | %.3f, %.3f | %.3f, %.3f | %.2fx |\n", l->name, l->n, lit, differ,
               te[RUNS / 2], te[0], tg[RUNS / 2], tg[0], tg[RUNS / 2] / te[RUNS / 2]);
        free(gv);
    }
    if (glGetError() != GL_NO_ERROR)
        fprintf(stderr, "lines-peer: a GL error\n");
    target_free(&fb);
    OSMesaDestroyContext(ctx);
    return 0;
}
#endif
