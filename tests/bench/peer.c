/* peer.c - Mesa's llvmpipe, through OSMesa, as the bench's real peer and its
 * second oracle.
 *
 * Same scenes, same state as the lessons: Gouraud colour, depth test LESS
 * with depth write, RGBA8 colour. Three things make llvmpipe decide exactly
 * the pixels our top-left rule decides:
 *
 *  - glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE): llvmpipe applies
 *    the top-left rule with y growing down its surface's rows;
 *  - those rows are stored top-down while GL numbers window rows from the
 *    bottom: scene row y is GL window row y_w = H - y, and glReadPixels'
 *    rows come back reversed (a pixel centre y + 0.5 lands on y_w + 0.5,
 *    and a horizontal edge's "top" stays the top);
 *  - every transform step is exact for positions on the 1/256 grid: the
 *    viewport is S = 8192 pixels square (a power of two) placed at
 *    (-3072, -3072), vertices go in already divided (w = 1, identity
 *    matrices), and
 *
 *        x_d = (x - 1024) / 4096            x_w = 4096 x_d + 1024 = x
 *        y_d = (y - (H - 1024)) / 4096      y_w = 1024 - 4096 y_d = H - y
 *
 *    are exact in float (|x| < 2^13 with 8 fractional bits is 21 bits).
 *    Vertices inside [-3072, 5120) (and y inside (H - 5120, H + 3072])
 *    never reach the clipper.
 *
 * Without the clip control, or with y_w = y, horizontal edges through pixel
 * centres go the other way (the bottom-left rule): the bench's scenes put a
 * quarter of their vertices on the half-pixel grid to catch exactly that.
 *
 * With samples = 4 (lesson 08's rows), llvmpipe draws into a framebuffer
 * object of 4 samples (colour RGBA8, depth 24 and stencil 8), resolved into
 * OSMesa's buffer by a blit, draw and blit timed together, as an application
 * does MSAA. Its samples are the standard 4x pattern in GL's window space,
 * y up (GL_SAMPLE_POSITION says so); through the flip above they sit in the
 * scene at (x, 256 - y), the pattern of lessons/CONVENTIONS.md upside down, and
 * they are reported (peer_sample_pos) for the bench to check them against
 * the exact rule at those points. Coverage: each sample alone
 * (glSampleMaski), every triangle adding 4 levels of red there without a
 * depth test; the blit's mean of the one sample written and three left at 0
 * is that sample's count (up to 63); the per-pixel sum over the samples is
 * what lesson 08's --dump-coverage counts.
 *
 * A scene with image textures (the bench's textured scenes) is drawn as
 * lessons/CONVENTIONS.md "Textures" says, in GL's words: each texture's level 0 as
 * its image rows come (row 0, t = 0, first: GL's t runs along the rows as
 * they are given, so no flip), its levels made by glGenerateMipmap,
 * GL_LINEAR_MIPMAP_LINEAR and GL_LINEAR, GL_REPEAT or GL_CLAMP_TO_EDGE as
 * the scene says; a shader multiplies the texel by the vertex colour
 * (modulate). Vertices still go in divided (w = 1, the exact positions
 * above), so the shader makes perspective correct itself: it receives
 * (r, g, b, s, t) / z and 1 / z, interpolated linearly in the screen, and
 * divides per pixel, as the lessons do; the texture's derivatives are
 * those of the divided (s, t), by differences on llvmpipe's 2 x 2 quads.
 * Depth is 1/z mapped to [-1, 1] (linear in the screen, as the lessons'
 * 1/z), depth clamping on. The sampler's faster approximations are off
 * (PEER_EXACT_OPTIONS, set before OSMesa makes its screen): GALLIVM_PERF
 * without `brilinear` (a bilinear tap instead of trilinear near integer
 * levels) and `rho_approx` (the level of detail from an approximate
 * length), with `no_quad_lod` (the level of detail computed for each pixel,
 * not once a quad) and `no_aos_sampling` (filtering in floats, not in 8-bit
 * fixed point); LP_PERF (switches that turn features off) unset.
 *
 * llvmpipe reads LP_NUM_THREADS once, when OSMesa makes its screen, so each
 * thread setting runs in a child process; results come back through shared
 * memory.
 */
#define _DEFAULT_SOURCE  /* MAP_ANONYMOUS */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

char peer_renderer[160];
int peer_sample_pos[SAMPLES_MAX][2];

#ifndef TRISTEP_OSMESA

bool peer_run(const struct bench_scene *sc, int nscenes, int threads, int samples, int warmup,
              int runs, struct bench_timing *out, uint8_t *const coverage[], uint32_t *const colour[],
              char *why, size_t whylen)
{
    (void)sc, (void)nscenes, (void)threads, (void)samples, (void)warmup, (void)runs, (void)out;
    (void)coverage, (void)colour;
    snprintf(why, whylen, "OSMesa was not found when the bench was built "
             "(Debian: apt-get install libosmesa6-dev, then make bench)");
    return false;
}

#else

#define GL_GLEXT_PROTOTYPES
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#define VIEW_SIZE   8192        /* viewport side: a power of two */
#define VIEW_ORIGIN (-3072)     /* its corner, so [-3072, 5120) is unclipped */
#define VIEW_HALF   (VIEW_SIZE / 2)
#define VIEW_CENTRE (VIEW_ORIGIN + VIEW_HALF)
#define Z_NEAR 1.5              /* the scenes' depth range, mapped to [-1, 1] */
#define Z_FAR  99.5
#define TEX_MAX 8               /* image textures in a scene llvmpipe draws */

struct gl_vertex {
    float pos[4];
    uint8_t rgba[4];
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint8_t unorm8(double c)
{
    return (uint8_t)(c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0 + 0.5);
}

/* The exact transform of the header: pixels (snapped to 1/256) to NDC. */
static void to_gl(struct gl_vertex *g, const struct vertex *v, int h)
{
    double x = (double)snap_coord(v->x, SUBPIXEL_BITS) / SUBPIXEL_ONE;
    double y = (double)snap_coord(v->y, SUBPIXEL_BITS) / SUBPIXEL_ONE;
    g->pos[0] = (float)((x - VIEW_CENTRE) / VIEW_HALF);
    g->pos[1] = (float)((y - (h - VIEW_CENTRE)) / VIEW_HALF);
    g->pos[2] = (float)((2 * v->z - Z_NEAR - Z_FAR) / (Z_FAR - Z_NEAR));
    g->pos[3] = 1.0f;
    g->rgba[0] = unorm8(v->r);
    g->rgba[1] = unorm8(v->g);
    g->rgba[2] = unorm8(v->b);
    g->rgba[3] = 255;
}

struct shared {
    char why[256];
    char renderer[160];
    int ok;
    int pos[SAMPLES_MAX][2];    /* with samples: where they are, 1/256 pixel, y down */
    struct bench_timing t[8];
};

/* Everything the child does; returns false with shared->why on failure. */
/* The multisampled framebuffer object of the scene's size, bound for drawing
 * (0 when samples <= 1: OSMesa's own buffer); false with sh->why on failure. */
static bool msaa_target(int samples, int w, int h, GLuint fbo_rb[3], struct shared *sh)
{
    fbo_rb[0] = 0;
    if (samples <= 1)
        return true;
    GLint max = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max);
    if (max < samples) {
        snprintf(sh->why, sizeof sh->why, "%s offers %d samples, not %d", sh->renderer, max, samples);
        return false;
    }
    glGenFramebuffers(1, &fbo_rb[0]);
    glGenRenderbuffers(2, &fbo_rb[1]);
    glBindRenderbuffer(GL_RENDERBUFFER, fbo_rb[1]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, fbo_rb[2]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_rb[0]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, fbo_rb[1]);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, fbo_rb[2]);
    GLint got = 0;
    glGetIntegerv(GL_SAMPLES, &got);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE || got != samples) {
        snprintf(sh->why, sizeof sh->why, "%s: no complete %d-sample framebuffer (%d samples)",
                 sh->renderer, samples, got);
        return false;
    }
    /* where its samples are: GL gives them from the pixel's lower-left
     * corner, y up; the scene's y runs down (y_w = H - y) */
    for (int i = 0; i < samples && i < SAMPLES_MAX; i++) {
        GLfloat v[2];
        glGetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)i, v);
        sh->pos[i][0] = (int)lround(v[0] * SUBPIXEL_ONE);
        sh->pos[i][1] = (int)lround((1 - v[1]) * SUBPIXEL_ONE);
    }
    return true;
}

/* The multisampled target resolved into OSMesa's buffer (a blit), or nothing. */
static void resolve(GLuint fbo, int w, int h)
{
    if (!fbo)
        return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
}

/* Untimed, at n samples: how many triangles cover each sample (up to 255 / n),
 * summed per pixel (window rows as they come), by one pass per sample. */
static void sample_counts(int n, GLuint fbo, int w, int h, GLsizei nv, uint8_t *rgba, uint8_t *sum)
{
    memset(sum, 0, (size_t)w * (size_t)h);
    glDisable(GL_DEPTH_TEST);
    glDisableClientState(GL_COLOR_ARRAY);
    glColor4ub((GLubyte)n, 0, 0, 0);        /* n levels a triangle: the mean of n samples, 1 */
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_SAMPLE_MASK);
    glClearColor(0, 0, 0, 0);
    for (int s = 0; s < n; s++) {
        glSampleMaski(0, 1u << s);
        glClear(GL_COLOR_BUFFER_BIT);
        glDrawArrays(GL_TRIANGLES, 0, nv);
        resolve(fbo, w, h);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            unsigned c = sum[i] + (unsigned)rgba[4 * i];
            sum[i] = (uint8_t)(c > 255 ? 255 : c);
        }
    }
    glDisable(GL_SAMPLE_MASK);
    glDisable(GL_BLEND);
    glEnableClientState(GL_COLOR_ARRAY);
}

/* --- textured scenes ------------------------------------------------------- */

struct tex_vertex {
    float pos[4];
    float rgbw[4];      /* r/z, g/z, b/z, 1/z */
    float st[2];        /* s/z, t/z */
};

static const char vertex_src[] =
    "#version 130\n"
    "in vec4 pos;\n in vec4 rgbw;\n in vec2 st;\n"
    "out vec4 c;\n out vec2 q;\n"
    "void main() { gl_Position = pos; c = rgbw; q = st; }\n";
/* perspective-correct (s, t) and colour, then modulate */
static const char fragment_src[] =
    "#version 130\n"
    "uniform sampler2D tex;\n"
    "in vec4 c;\n in vec2 q;\n out vec4 frag;\n"
    "void main() { float z = 1.0 / c.w;\n"
    "  frag = texture(tex, q * z) * vec4(c.rgb * z, 1.0); }\n";

static GLuint shader(GLenum kind, const char *src, struct shared *sh)
{
    GLuint id = glCreateShader(kind);
    glShaderSource(id, 1, &src, NULL);
    glCompileShader(id);
    GLint ok = 0;
    glGetShaderiv(id, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[200] = "";
        glGetShaderInfoLog(id, sizeof log, NULL, log);
        snprintf(sh->why, sizeof sh->why, "%s: shader: %s", sh->renderer, log);
        return 0;
    }
    return id;
}

/* The program of the textured scenes, bound, its attributes 0, 1, 2. */
static GLuint tex_program(struct shared *sh)
{
    GLuint vs = shader(GL_VERTEX_SHADER, vertex_src, sh), fs = vs ? shader(GL_FRAGMENT_SHADER, fragment_src, sh) : 0;
    if (!fs)
        return 0;
    GLuint prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glBindAttribLocation(prog, 0, "pos");
    glBindAttribLocation(prog, 1, "rgbw");
    glBindAttribLocation(prog, 2, "st");
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        snprintf(sh->why, sizeof sh->why, "%s: the textured program does not link", sh->renderer);
        return 0;
    }
    glUseProgram(prog);
    glUniform1i(glGetUniformLocation(prog, "tex"), 0);
    return prog;
}

/* GL textures for the scene's image textures 1..n, and tex[0] a white
 * texel for triangles under none (modulate by white: the vertex colour). */
static void tex_upload(const struct scene *s, GLuint *tex, int n)
{
    static const uint32_t white = 0xffffffffu;
    glGenTextures(n + 1, tex);
    for (int k = 0; k <= n; k++) {
        const struct texture *t = k ? scene_texture(s, k) : NULL;
        glBindTexture(GL_TEXTURE_2D, tex[k]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t ? t->level[0].w : 1, t ? t->level[0].h : 1, 0,
                     GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, t ? t->level[0].texel : &white);
        glGenerateMipmap(GL_TEXTURE_2D);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        GLint wrap = t && t->wrap == TEXTURE_CLAMP ? GL_CLAMP_TO_EDGE : GL_REPEAT;
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    }
}

/* The scene's triangles as the shader takes them, into a bound buffer:
 * false when out of memory. */
static bool tex_vertices(const struct scene *s)
{
    double zmin = INFINITY, zmax = 0;
    for (int t = 0; t < s->ntris; t++)
        for (int k = 0; k < 3; k++) {
            zmin = fmin(zmin, s->tris[t].v[k].z);
            zmax = fmax(zmax, s->tris[t].v[k].z);
        }
    size_t nv = (size_t)s->ntris * 3;
    struct tex_vertex *gv = malloc(nv * sizeof *gv);
    if (!gv)
        return false;
    for (size_t i = 0; i < nv; i++) {
        const struct vertex *v = &s->tris[i / 3].v[i % 3];
        struct gl_vertex g;
        to_gl(&g, v, s->h);
        double w = 1 / v->z;
        /* 1/z: the nearest -0.999, the farthest 0.999 (zmin < zmax, or one depth) */
        double d = zmax > zmin ? (1 / zmin - w) / (1 / zmin - 1 / zmax) : 0.5;
        gv[i] = (struct tex_vertex){
            { g.pos[0], g.pos[1], (float)(1.998 * d - 0.999), 1.0f },
            { (float)(v->r * w), (float)(v->g * w), (float)(v->b * w), (float)w },
            { (float)(v->s * w), (float)(v->t * w) },
        };
    }
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * sizeof *gv), gv, GL_STATIC_DRAW);
    free(gv);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof *gv, (const void *)offsetof(struct tex_vertex, pos));
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof *gv, (const void *)offsetof(struct tex_vertex, rgbw));
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof *gv, (const void *)offsetof(struct tex_vertex, st));
    return true;
}

/* Every triangle in the scene's order, a draw call for each run of them
 * under the same texture. */
static void tex_draw(const struct scene *s, const GLuint *tex)
{
    for (int first = 0, t = 1; t <= s->ntris; t++)
        if (t == s->ntris || s->tris[t].texture != s->tris[first].texture) {
            int k = s->tris[first].texture;
            glBindTexture(GL_TEXTURE_2D, tex[k >= 0 && k <= scene_texture_count(s) ? k : 0]);
            glDrawArrays(GL_TRIANGLES, 3 * first, 3 * (t - first));
            first = t;
        }
}

static bool child(const struct bench_scene *sc, int nscenes, int samples, int warmup, int runs,
                  struct shared *sh, uint8_t *cov, uint32_t *colour)
{
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
        OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0,
    };
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!ctx) {
        snprintf(sh->why, sizeof sh->why, "OSMesaCreateContextAttribs failed");
        return false;
    }
    int maxw = sc[0].s.w, maxh = sc[0].s.h;
    for (int i = 1; i < nscenes; i++) {
        maxw = sc[i].s.w > maxw ? sc[i].s.w : maxw;
        maxh = sc[i].s.h > maxh ? sc[i].s.h : maxh;
    }
    uint8_t *pixels = malloc((size_t)maxw * (size_t)maxh * 4);
    uint8_t *stencil = malloc((size_t)maxw * (size_t)maxh);
    uint8_t *readback = malloc((size_t)maxw * (size_t)maxh * 4);   /* not OSMesa's own buffer */
    if (!pixels || !stencil || !readback || !OSMesaMakeCurrent(ctx, pixels, GL_UNSIGNED_BYTE, maxw, maxh)) {
        snprintf(sh->why, sizeof sh->why, "OSMesaMakeCurrent failed");
        return false;
    }
    snprintf(sh->renderer, sizeof sh->renderer, "%s %s", (const char *)glGetString(GL_VERSION),
             (const char *)glGetString(GL_RENDERER));
    PFNGLCLIPCONTROLPROC clip_control =
        (PFNGLCLIPCONTROLPROC)OSMesaGetProcAddress("glClipControl");
    const char *ext = (const char *)glGetString(GL_EXTENSIONS);
    if (!clip_control || !ext || !strstr(ext, "GL_ARB_clip_control")) {
        snprintf(sh->why, sizeof sh->why, "%s has no glClipControl", sh->renderer);
        return false;
    }
    clip_control(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glShadeModel(GL_SMOOTH);

    for (int i = 0; i < nscenes; i++) {
        const struct scene *s = &sc[i].s;
        /* the framebuffer is the scene's size: OSMesa draws into the first
         * w x h pixels when told the smaller size */
        if (!OSMesaMakeCurrent(ctx, pixels, GL_UNSIGNED_BYTE, s->w, s->h)) {
            snprintf(sh->why, sizeof sh->why, "OSMesaMakeCurrent %dx%d failed", s->w, s->h);
            return false;
        }
        GLuint fbo_rb[3];
        if (!msaa_target(samples, s->w, s->h, fbo_rb, sh))
            return false;
        glViewport(VIEW_ORIGIN, VIEW_ORIGIN, VIEW_SIZE, VIEW_SIZE);
        size_t nv = (size_t)s->ntris * 3;
        int ntex = samples <= 1 ? scene_texture_count(s) : 0;     /* > 0: drawn textured */
        GLuint vbo, prog = 0, tex[TEX_MAX + 1];
        glGenBuffers(1, &vbo);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        if (ntex > TEX_MAX) {
            snprintf(sh->why, sizeof sh->why, "scene %s: more than %d textures", sc[i].name, TEX_MAX);
            return false;
        }
        if (ntex) {
            if (!(prog = tex_program(sh)))
                return false;
            tex_upload(s, tex, ntex);
            glDisableClientState(GL_VERTEX_ARRAY);
            glDisableClientState(GL_COLOR_ARRAY);
            for (GLuint a = 0; a < 3; a++)
                glEnableVertexAttribArray(a);
            glEnable(GL_DEPTH_CLAMP);
            if (!tex_vertices(s)) {
                snprintf(sh->why, sizeof sh->why, "out of memory");
                return false;
            }
        } else {
            struct gl_vertex *gv = malloc(nv * sizeof *gv);
            if (!gv) {
                snprintf(sh->why, sizeof sh->why, "out of memory");
                return false;
            }
            for (int t = 0; t < s->ntris; t++)
                for (int k = 0; k < 3; k++)
                    to_gl(&gv[3 * (size_t)t + (size_t)k], &s->tris[t].v[k], s->h);
            glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * sizeof *gv), gv, GL_STATIC_DRAW);
            free(gv);
            glVertexPointer(4, GL_FLOAT, sizeof *gv, (const void *)offsetof(struct gl_vertex, pos));
            glColorPointer(4, GL_UNSIGNED_BYTE, sizeof *gv, (const void *)offsetof(struct gl_vertex, rgba));
        }

        /* timed: colour and depth cleared (untimed), then the whole scene */
        glClearColor((float)s->background[0], (float)s->background[1], (float)s->background[2], 1);
        glClearDepth(1.0);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        struct bench_timing *bt = &sh->t[i];
        bt->runs = runs;
        for (int r = -warmup; r < runs; r++) {
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glFinish();
            double t0 = now();
            if (ntex)
                tex_draw(s, tex);
            else
                glDrawArrays(GL_TRIANGLES, 0, (GLsizei)nv);
            resolve(fbo_rb[0], s->w, s->h);
            glFinish();
            if (r >= 0)
                bt->t[r] = now() - t0;
        }
        if (colour) {           /* the last run's picture, window rows bottom-up */
            glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
            glReadPixels(0, 0, s->w, s->h, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, readback);
            if (fbo_rb[0])
                glBindFramebuffer(GL_FRAMEBUFFER, fbo_rb[0]);
            for (int y = 0; y < s->h; y++)
                memcpy(colour + (size_t)y * (size_t)s->w,
                       readback + (size_t)(s->h - 1 - y) * (size_t)s->w * 4, (size_t)s->w * 4);
            colour += (size_t)s->w * (size_t)s->h;
        }

        /* untimed: coverage counted by a saturating stencil increment, or
         * with samples sample by sample */
        if (fbo_rb[0]) {
            sample_counts(samples, fbo_rb[0], s->w, s->h, (GLsizei)nv, readback, stencil);
        } else {
            glDisable(GL_DEPTH_TEST);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glEnable(GL_STENCIL_TEST);
            glStencilFunc(GL_ALWAYS, 0, 0xff);
            glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
            glClearStencil(0);
            glClear(GL_STENCIL_BUFFER_BIT);
            glDrawArrays(GL_TRIANGLES, 0, (GLsizei)nv);
            glReadPixels(0, 0, s->w, s->h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);
            glDisable(GL_STENCIL_TEST);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
        for (int y = 0; y < s->h; y++)     /* window row H - 1 - y is scene row y */
            memcpy(cov + (size_t)y * (size_t)s->w,
                   stencil + (size_t)(s->h - 1 - y) * (size_t)s->w, (size_t)s->w);
        cov += (size_t)s->w * (size_t)s->h;
        glDeleteBuffers(1, &vbo);
        if (ntex) {
            glDeleteTextures(ntex + 1, tex);
            glUseProgram(0);
            glDeleteProgram(prog);
            for (GLuint a = 0; a < 3; a++)
                glDisableVertexAttribArray(a);
            glDisable(GL_DEPTH_CLAMP);
            glEnableClientState(GL_VERTEX_ARRAY);
            glEnableClientState(GL_COLOR_ARRAY);
        }
        if (fbo_rb[0]) {
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glDeleteFramebuffers(1, &fbo_rb[0]);
            glDeleteRenderbuffers(2, &fbo_rb[1]);
        }
        GLenum err = glGetError();
        if (err != GL_NO_ERROR) {
            snprintf(sh->why, sizeof sh->why, "GL error 0x%x on scene %s", err, sc[i].name);
            return false;
        }
    }
    OSMesaDestroyContext(ctx);
    free(pixels);
    free(stencil);
    free(readback);
    return true;
}

bool peer_run(const struct bench_scene *sc, int nscenes, int threads, int samples, int warmup,
              int runs, struct bench_timing *out, uint8_t *const coverage[], uint32_t *const colour[],
              char *why, size_t whylen)
{
    size_t covsize = 0;
    for (int i = 0; i < nscenes; i++)
        covsize += (size_t)sc[i].s.w * (size_t)sc[i].s.h;
    if (nscenes > 8 || runs > BENCH_MAX_RUNS) {
        snprintf(why, whylen, "too many scenes or runs");
        return false;
    }
    /* the shared block: results, then the pictures, then the coverage counts */
    size_t colsize = colour ? 4 * covsize : 0;
    size_t size = sizeof(struct shared) + colsize + covsize;
    void *mem = mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (mem == MAP_FAILED) {
        snprintf(why, whylen, "mmap: %s", strerror(errno));
        return false;
    }
    struct shared *sh = mem;
    memset(sh, 0, sizeof *sh);
    uint32_t *col = colour ? (uint32_t *)(sh + 1) : NULL;
    uint8_t *cov = (uint8_t *)(sh + 1) + colsize;

    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(why, whylen, "fork: %s", strerror(errno));
        munmap(mem, size);
        return false;
    }
    if (pid == 0) {
        setenv("GALLIUM_DRIVER", "llvmpipe", 1);
        /* the sampler's exact paths (PEER_EXACT_OPTIONS; the header says why) */
        setenv("GALLIVM_PERF", "no_quad_lod,no_aos_sampling", 1);
        unsetenv("LP_PERF");
        if (threads >= 0) {
            char n[16];
            snprintf(n, sizeof n, "%d", threads);
            setenv("LP_NUM_THREADS", n, 1);
        } else {
            unsetenv("LP_NUM_THREADS");
        }
        sh->ok = child(sc, nscenes, samples, warmup, runs, sh, cov, col);
        _exit(0);
    }
    int status = 0;
    bool ok = waitpid(pid, &status, 0) == pid && WIFEXITED(status) && sh->ok;
    if (ok) {
        snprintf(peer_renderer, sizeof peer_renderer, "%s", sh->renderer);
        if (samples > 1)
            memcpy(peer_sample_pos, sh->pos, sizeof peer_sample_pos);
        for (int i = 0; i < nscenes; i++) {
            out[i] = sh->t[i];
            bench_timing_stats(&out[i]);
            size_t n = (size_t)sc[i].s.w * (size_t)sc[i].s.h;
            memcpy(coverage[i], cov, n);
            cov += n;
            if (colour) {
                memcpy(colour[i], col, 4 * n);
                col += n;
            }
        }
    } else if (sh->why[0]) {
        snprintf(why, whylen, "%s", sh->why);
    } else {
        snprintf(why, whylen, "the llvmpipe process ended abnormally (status 0x%x)", status);
    }
    munmap(mem, size);
    return ok;
}

#endif
