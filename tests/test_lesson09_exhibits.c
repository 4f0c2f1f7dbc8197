/* test_lesson09_exhibits.c - lesson 09's exhibits, counted: what each
 * filter, each way of taking derivatives and each size of triangle does to
 * a picture, measured against the ideal one.
 *
 * The ideal colour of a pixel is the mean of the texture over the pixel's
 * square: the box filter that every filter of the lesson approximates. The
 * independent reference (texref.h, written from lessons/CONVENTIONS.md alone)
 * computes it by brute force: 16 x 16 samples per pixel, each with its own
 * perspective-correct (s, t) and the level-0 texel under it (the image as a
 * mosaic of texels). The numbers the lesson's text and answer key quote,
 * marked <!--=l09.KEY--> (testlib.h), are recomputed here. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "explore/replay.h"
#include "front/front.h"
#include "testlib.h"
#include "texref.h"
#include "../lessons/09-textures/textures.h"

extern const struct lesson lesson_09;

#define README "lessons/09-textures/README.md"
#define ANSWERS "lessons/09-textures/ANSWERS.md"

/* The count `got` is the number the text quotes before marker `key`,
 * wherever it quotes it, to the precision of each quote
 * (TRISTEP_PRINT_NUMBERS=1 prints it, for writing the text). */
static void expect_quoted(const char *path, const char *key, double got)
{
    if (getenv("TRISTEP_PRINT_NUMBERS"))
        fprintf(stderr, "%-32s %.17g\n", key, got);
    double tol;
    double quoted = text_number(path, key, &tol);      /* fails when there is none */
    cr_expect(fabs(quoted - got) <= tol, "%s quotes %g for %s, the lesson computes %.17g", path,
              quoted, key, got);
    char marker[128];
    snprintf(marker, sizeof marker, "<!--=%s-->", key);
    const char *text = test_read_text(path);
    for (const char *at = strstr(strstr(text, marker) + 1, marker); at; at = strstr(at + 1, marker)) {
        quoted = number_before(text, at, &tol);
        cr_expect(fabs(quoted - got) <= tol, "%s quotes %g for %s again, the lesson computes %.17g",
                  path, quoted, key, got);
    }
}

/* --- the ideal picture (texref.h) ------------------------------------------------- */

#define IDEAL_N 16          /* samples per pixel along each axis: 16 x 16 */

static struct texref_ideal ideal_scene(const struct scene *s)
{
    struct texref_ideal id;
    cr_assert(texref_ideal_scene(&id, s, IDEAL_N));
    return id;
}

/* The ideal is right where it can be told by hand: a 256 x 256 texture on
 * a 64 x 64 square facing the eye puts 4 x 4 texels in every pixel, 16 x 16
 * samples give each texel 16 of them, and the mean is that of level 2 of
 * the pyramid (which rounds twice: within a level). */
Test(lesson09_exhibits, the_ideal_of_a_pixel_over_4_x_4_texels_is_their_mean)
{
    static const char text[] = "size 64 64\ntexture builtin:checker-numbers\n"
        "tri  0 0 1 1 1 1 0 0   64 0 1 1 1 1 1 0   64 64 1 1 1 1 1 1\n"
        "tri  0 0 1 1 1 1 0 0   64 64 1 1 1 1 1 1   0 64 1 1 1 1 0 1\n";
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "square", text, sizeof text - 1, err, sizeof err), "%s", err);
    const struct texture *tx = scene_texture(&s, 1);
    struct texref r;
    cr_assert(texref_init(&r, tx->level[0].w, tx->level[0].h, tx->level[0].texel, TEXREF_REPEAT));
    cr_assert_eq(r.w[2], 64);
    struct texref_ideal id = ideal_scene(&s);
    long far = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            double want[3];
            texref_texel(&r, 2, x, y, want);
            for (int c = 0; c < 3; c++)
                far += fabs(id.rgb[3 * (y * 64 + x) + c] - want[c]) > 1;
            cr_assert(id.textured[y * 64 + x], "pixel (%d, %d) not on the square", x, y);
        }
    cr_expect_eq(far, 0, "%ld channels differ from level 2 by more than a level", far);
    texref_free(&r);
    texref_ideal_free(&id);
    scene_free(&s);
}

/* --- the lesson's pictures -------------------------------------------------------- */

/* A built-in 3-D scene's screen triangles (lesson 06's front end). */
static struct scene load3(const char *name)
{
    struct scene s;
    char err[256];
    cr_assert(scene_builtin(&s, name, err, sizeof err), "%s", err);
    cr_assert(front_scene(&s));
    return s;
}

static const struct lesson_variant *variant(const char *name)
{
    const struct lesson_variant *v = lesson_variant(&lesson_09, name);
    cr_assert_not_null(v, "lesson 09 has no variant %s", name);
    return v;
}

static struct raster_params params_for(enum tex_filter f)
{
    struct raster_params p = default_params();
    p.knob[P_FILTER] = f;
    return p;
}

/* Variant `name`'s picture of s with filter f. */
static struct target draw(const struct scene *s, const char *name, enum tex_filter f)
{
    struct raster_params p = params_for(f);
    struct target fb;
    cr_assert(render_scene(s, variant(name), &p, &fb));
    return fb;
}

/* What a narrated run says, pixel by pixel: the first level and the
 * (u, v) the visible triangle read at each pixel (level -1: none), and the
 * pixels evaluated in quads, covered and helpers. */
struct narrated {
    int *level;
    float *u, *v;
    long covered, helpers;
};

static struct narrated narrate(const struct scene *s, const char *name, enum tex_filter f)
{
    size_t n = (size_t)s->w * (size_t)s->h;
    struct narrated out = { .level = malloc(n * sizeof(int)), .u = calloc(n, sizeof(float)),
                            .v = calloc(n, sizeof(float)) };
    cr_assert(out.level && out.u && out.v);
    for (size_t i = 0; i < n; i++)
        out.level[i] = -1;
    struct raster_params p = params_for(f);
    struct target fb;
    cr_assert(target_init(&fb, s->w, s->h, scene_background(s)));
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        struct test_events ev = { 0 };
        struct trace tr = { .sink = test_collect, .ctx = &ev };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        struct raster_params pi = lesson_params_tri(&p, s, i);
        variant(name)->rasterize(&t, &pi, &fb, &tr);
        int level = -1;
        float u = 0, v = 0;
        for (size_t k = 0; k < ev.n; k++) {
            const struct trace_event *e = &ev.ev[k];
            if (e->kind == TRACE_STEP && e->line == L_EVAL) {
                bool in = e->flags & TRACE_INSIDE;
                out.covered += in, out.helpers += !in;
            }
            if (e->kind == TRACE_STEP && e->line == L_FILTER)
                level = (int)e->aux[AUX_LEVEL0], u = e->aux[AUX_U], v = e->aux[AUX_V];
            if (e->kind == TRACE_PIXEL_WRITE && (e->flags & TRACE_DEPTH_PASS) && e->x >= 0 && e->y >= 0
                && e->x < s->w && e->y < s->h) {
                size_t at = (size_t)e->y * (size_t)s->w + (size_t)e->x;
                out.level[at] = level, out.u[at] = u, out.v[at] = v;
            }
            if (e->kind == TRACE_PIXEL_WRITE)
                level = -1;
        }
        free(ev.ev);
    }
    target_free(&fb);
    return out;
}

static void narrated_free(struct narrated *n)
{
    free(n->level);
    free(n->u);
    free(n->v);
}

/* A picture's error against the ideal over the textured pixels that both
 * cover: the mean difference per channel in levels of 255, and the pixels
 * off by more than 16 levels in some channel. */
struct error {
    double mean;
    long pixels, off16;
};

static struct error error_of(const struct texref_ideal *id, const struct target *fb)
{
    struct error e = { 0 };
    double sum = 0;
    for (int p = 0; p < id->w * id->h; p++) {
        if (!id->textured[p] || !fb->count[p])
            continue;
        double worst = 0;
        for (int c = 0; c < 3; c++) {
            double d = fabs((double)(fb->color[p] >> (16 - 8 * c) & 255) - id->rgb[3 * p + c]);
            sum += d / 3;
            worst = d > worst ? d : worst;
        }
        e.pixels++;
        e.off16 += worst > 16;
    }
    e.mean = e.pixels ? sum / (double)e.pixels : NAN;
    return e;
}

/* Pixels where two pictures differ by more than `levels` in some channel. */
static long differ(const struct target *a, const struct target *b, int levels)
{
    long n = 0;
    for (int p = 0; p < a->w * a->h; p++) {
        bool far = false;
        for (int shift = 0; shift < 24; shift += 8) {
            int d = (int)(a->color[p] >> shift & 255) - (int)(b->color[p] >> shift & 255);
            far |= d > levels || d < -levels;
        }
        n += far;
    }
    return n;
}

/* --- the exhibits ------------------------------------------------------------------ */

/* Without the pyramid, every pixel reads level 0 and the far floor aliases:
 * trilinear comes much closer to the ideal. */
Test(lesson09_exhibits, minification_without_mipmaps_aliases, .timeout = 60)
{
    struct scene s = load3("texture-floor");
    struct texref_ideal id = ideal_scene(&s);
    struct target nomip = draw(&s, "no-mipmaps", FILTER_TRILINEAR), tri = draw(&s, "quads", FILTER_TRILINEAR);
    struct error en = error_of(&id, &nomip), et = error_of(&id, &tri);
    cr_log_info("floor: no mip-maps %.2f levels (%ld off by > 16), trilinear %.2f (%ld), %ld pixels", en.mean,
                en.off16, et.mean, et.off16, et.pixels);
    cr_expect_eq(en.pixels, et.pixels, "the same pixels covered");
    cr_expect_gt(en.mean, 1.5 * et.mean, "no mip-maps: %.2f levels off, trilinear %.2f", en.mean, et.mean);
    cr_expect_gt(en.off16, et.off16);
    expect_quoted(README, "l09.floor.pixels", (double)et.pixels);
    expect_quoted(README, "l09.nomip.error", en.mean);
    expect_quoted(README, "l09.nomip.off16", (double)en.off16);
    expect_quoted(README, "l09.floor.trilinear.error", et.mean);
    expect_quoted(README, "l09.floor.trilinear.off16", (double)et.off16);
    target_free(&nomip);
    target_free(&tri);
    texref_ideal_free(&id);
    scene_free(&s);
}

/* Lesson 04's swim on an image: (s, t) linear in the screen. What it
 * costs grows with the triangles: the pixels of a scene that differ from
 * the perspective-correct picture by more than 2 levels, and how far
 * (u, v) lands from the right texel at worst. */
struct swim {
    long differ, pixels;
    double worst;
};

static struct swim swim_of(const char *name)
{
    struct scene s = load3(name);
    struct target aff = draw(&s, "affine", FILTER_TRILINEAR), tri = draw(&s, "quads", FILTER_TRILINEAR);
    struct narrated na = narrate(&s, "affine", FILTER_TRILINEAR), nt = narrate(&s, "quads", FILTER_TRILINEAR);
    struct swim w = { .differ = differ(&aff, &tri, 2) };
    for (int p = 0; p < s.w * s.h; p++)
        if (nt.level[p] >= 0) {
            w.pixels++;
            w.worst = fmax(w.worst, fmax(fabs(na.u[p] - nt.u[p]), fabs(na.v[p] - nt.v[p])));
        }
    narrated_free(&na);
    narrated_free(&nt);
    target_free(&aff);
    target_free(&tri);
    scene_free(&s);
    return w;
}

Test(lesson09_exhibits, affine_coordinates_swim_more_on_larger_triangles, .timeout = 60)
{
    struct swim model = swim_of("texture-model"), floor = swim_of("texture-floor");
    cr_log_info("affine: torus %ld of %ld pixels differ, (u, v) up to %.1f texels off; floor %ld of %ld, %.1f",
                model.differ, model.pixels, model.worst, floor.differ, floor.pixels, floor.worst);
    cr_expect_gt(model.differ, 0, "the torus's triangles are not flat on the screen: some pixels move");
    cr_expect_gt(floor.differ, floor.pixels / 2, "the floor's two triangles: most pixels move");
    cr_expect_gt((double)floor.differ / (double)floor.pixels, 4.0 * (double)model.differ / (double)model.pixels);
    cr_expect_gt(floor.worst, 100 * model.worst);
    expect_quoted(README, "l09.affine.model.differ", (double)model.differ);
    expect_quoted(README, "l09.affine.model.pixels", (double)model.pixels);
    expect_quoted(README, "l09.affine.model.worst", model.worst);
    expect_quoted(README, "l09.affine.floor.differ", (double)floor.differ);
    expect_quoted(README, "l09.affine.floor.worst", floor.worst);
}

/* One level of detail per quad, against each pixel's own exact one. */
Test(lesson09_exhibits, per_quad_against_per_pixel_level_of_detail, .timeout = 60)
{
    struct scene s = load3("texture-floor");
    struct texref_ideal id = ideal_scene(&s);
    struct narrated nq = narrate(&s, "quads", FILTER_TRILINEAR), na = narrate(&s, "analytic-lod", FILTER_TRILINEAR),
                    nf = narrate(&s, "fine-lod", FILTER_TRILINEAR);
    long moved = 0, moved_fine = 0, written = 0;
    for (int p = 0; p < s.w * s.h; p++) {
        if (nq.level[p] < 0)
            continue;
        written++;
        moved += na.level[p] != nq.level[p];
        moved_fine += nf.level[p] != nq.level[p];
    }
    struct target q = draw(&s, "quads", FILTER_TRILINEAR), a = draw(&s, "analytic-lod", FILTER_TRILINEAR);
    struct error eq = error_of(&id, &q), ea = error_of(&id, &a);
    cr_log_info("floor: %ld of %ld pixels read another level per pixel (fine: %ld); error %.2f -> %.2f", moved,
                written, moved_fine, eq.mean, ea.mean);
    cr_expect_gt(moved, 0, "per-pixel derivatives move some pixel to another level");
    cr_expect_lt(moved, written / 4, "most pixels keep their quad's level");
    cr_expect_lt(moved_fine, moved, "fine differences stay closer to the quad's than exact derivatives");
    cr_expect_lt(fabs(ea.mean - eq.mean), 0.1 * eq.mean, "the quad's shared derivatives cost little");
    expect_quoted(README, "l09.perpixel.level", (double)moved);
    expect_quoted(README, "l09.perpixel.error", ea.mean);
    expect_quoted(README, "l09.fine.level", (double)moved_fine);
    narrated_free(&nq);
    narrated_free(&na);
    narrated_free(&nf);
    target_free(&q);
    target_free(&a);
    texref_ideal_free(&id);
    scene_free(&s);
}

/* At a grazing angle trilinear blurs across the wall; aniso follows the
 * footprint and comes closer to the ideal. */
Test(lesson09_exhibits, aniso_beats_trilinear_at_a_grazing_angle, .timeout = 60)
{
    struct scene s = load3("texture-wall");
    struct texref_ideal id = ideal_scene(&s);
    struct target tri = draw(&s, "quads", FILTER_TRILINEAR), an = draw(&s, "quads", FILTER_ANISO);
    struct error et = error_of(&id, &tri), ea = error_of(&id, &an);
    cr_log_info("wall: trilinear %.2f levels (%ld off by > 16), aniso %.2f (%ld), %ld pixels", et.mean, et.off16,
                ea.mean, ea.off16, et.pixels);
    cr_expect_lt(ea.mean, et.mean / 2, "aniso %.2f levels off, trilinear %.2f", ea.mean, et.mean);
    cr_expect_lt(ea.off16, et.off16);
    expect_quoted(README, "l09.wall.pixels", (double)et.pixels);
    expect_quoted(README, "l09.wall.trilinear.error", et.mean);
    expect_quoted(README, "l09.wall.aniso.error", ea.mean);
    expect_quoted(README, "l09.wall.trilinear.off16", (double)et.off16);
    expect_quoted(README, "l09.wall.aniso.off16", (double)ea.off16);
    /* and on the floor, the rest of trilinear's error is blur */
    struct scene f = load3("texture-floor");
    struct texref_ideal idf = ideal_scene(&f);
    struct target fa = draw(&f, "quads", FILTER_ANISO);
    struct error efa = error_of(&idf, &fa);
    cr_log_info("floor: aniso %.2f (%ld)", efa.mean, efa.off16);
    expect_quoted(README, "l09.floor.aniso.error", efa.mean);
    target_free(&fa);
    texref_ideal_free(&idf);
    scene_free(&f);
    target_free(&tri);
    target_free(&an);
    texref_ideal_free(&id);
    scene_free(&s);
}

/* A 2-D scene of squares of side `side` pixels from (x0, y0) on, two
 * triangles each (cut from top-left to bottom-right), under builtin:grid. */
static struct scene sheet(double side, double x0, double y0, double x1, double y1)
{
    size_t cap = 8 << 20, len = 0;
    char *text = malloc(cap);
    cr_assert_not_null(text);
    len += (size_t)snprintf(text + len, cap - len, "size 128 96\ntexture builtin:grid\n");
    for (double y = y0; y + side <= y1; y += side)
        for (double x = x0; x + side <= x1; x += side) {
            double X[4] = { x, x + side, x + side, x }, Y[4] = { y, y, y + side, y + side };
            static const int tri[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
            for (int k = 0; k < 2; k++) {
                len += (size_t)snprintf(text + len, cap - len, "tri");
                for (int j = 0; j < 3; j++) {
                    int c = tri[k][j];
                    len += (size_t)snprintf(text + len, cap - len, "  %.4f %.4f 1 1 1 1 %.6f %.6f", X[c], Y[c],
                                            X[c] / 128, Y[c] / 96);
                }
                len += (size_t)snprintf(text + len, cap - len, "\n");
                cr_assert_lt(len, cap - 256);
            }
        }
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "sheet", text, len, err, sizeof err), "%s", err);
    free(text);
    return s;
}

/* The share of shaded pixels that are helpers, in percent. */
static double helper_share(const struct narrated *n)
{
    return 100.0 * (double)n->helpers / (double)(n->helpers + n->covered);
}

/* Quads cost small triangles most: the share of helpers grows as the
 * triangles shrink, on sheets the test makes and on the built-in scenes. */
Test(lesson09_exhibits, helper_share_grows_as_triangles_shrink, .timeout = 60)
{
    static const struct { double side; const char *key; } sizes[] = {
        { 64, "l09.helpers.64" }, { 16, "l09.helpers.16" }, { 8, "l09.helpers.8" },
        { 4, "l09.helpers.4" }, { 2, "l09.helpers.2" },
    };
    double last = 0;
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        /* an offset that aligns the squares with no quad */
        struct scene s = sheet(sizes[i].side, 1.3, 0.55, 128, 96);
        struct narrated n = narrate(&s, "quads", FILTER_TRILINEAR);
        double share = helper_share(&n);
        cr_log_info("squares of %g: %d triangles, %ld covered, %ld helpers, %.1f %%", sizes[i].side, s.ntris,
                    n.covered, n.helpers, share);
        cr_expect_gt(share, last, "squares of %g: %.1f %% helpers, not more than %.1f %% for larger ones",
                     sizes[i].side, share, last);
        last = share;
        expect_quoted(README, sizes[i].key, share);
        narrated_free(&n);
        scene_free(&s);
    }
    static const struct { const char *scene, *key; } scenes[] = {
        { "texture-tiny", "l09.tiny.helpers" }, { "texture-floor", "l09.floor.helpers" },
    };
    double share[2];
    for (int i = 0; i < 2; i++) {
        struct scene s = load3(scenes[i].scene);
        struct narrated n = narrate(&s, "quads", FILTER_TRILINEAR);
        share[i] = helper_share(&n);
        cr_log_info("%s: %ld covered, %ld helpers, %.1f %%", scenes[i].scene, n.covered, n.helpers, share[i]);
        expect_quoted(README, scenes[i].key, share[i]);
        narrated_free(&n);
        scene_free(&s);
    }
    cr_expect_gt(share[0], 4 * share[1], "8-pixel triangles: %.1f %% helpers, two large ones %.1f %%", share[0],
                 share[1]);
}

#if !TRISTEP_NO_ANSWERS
/* The answer key's exercise 5: squares drawn by hand. */
Test(lesson09_exhibits, helpers_of_three_squares, .timeout = 60)
{
    static const struct { double x0, side; const char *shaded, *helpers; } sq[] = {
        { 1, 3, "l09.ans.square3.shaded", "l09.ans.square3.helpers" },
        { 0, 4, "l09.ans.square4.shaded", "l09.ans.square4.helpers" },
        { 1, 4, "l09.ans.square4off.shaded", "l09.ans.square4off.helpers" },
    };
    for (int i = 0; i < 3; i++) {
        struct scene s = sheet(sq[i].side, sq[i].x0, sq[i].x0, sq[i].x0 + sq[i].side, sq[i].x0 + sq[i].side);
        cr_assert_eq(s.ntris, 2);
        struct narrated n = narrate(&s, "quads", FILTER_TRILINEAR);
        cr_log_info("square %g at %g: %ld shaded, %ld helpers", sq[i].side, sq[i].x0, n.covered + n.helpers,
                    n.helpers);
        cr_expect_eq(n.covered, (long)(sq[i].side * sq[i].side), "every pixel of the square covered once");
        expect_quoted(ANSWERS, sq[i].shaded, (double)(n.covered + n.helpers));
        expect_quoted(ANSWERS, sq[i].helpers, (double)n.helpers);
        narrated_free(&n);
        scene_free(&s);
    }
}
#endif

#if !TRISTEP_NO_ANSWERS
/* The answer key's exercise 6: one footprint, 12 texels by 1.5, through the
 * lesson's texture unit. */
Test(lesson09_exhibits, answer_6_one_long_footprint)
{
    struct scene s = load3("texture-floor");         /* for its 256 x 256 texture */
    const struct texture *tex = scene_texture(&s, 1);
    cr_assert(tex && tex->level[0].w == 256 && tex->level[0].h == 256);
    struct tex_deriv d = { .dsdx = 12.0 / 256, .dtdx = 0, .dsdy = 0, .dtdy = 1.5 / 256, .w0 = 256, .h0 = 256 };
    struct tex_used tri, a16, a4;
    tex_filter_texel(tex, FILTER_TRILINEAR, 16, 0.5, 0.5, &d, &tex_stages_lesson, &tri);
    tex_filter_texel(tex, FILTER_ANISO, 16, 0.5, 0.5, &d, &tex_stages_lesson, &a16);
    tex_filter_texel(tex, FILTER_ANISO, 4, 0.5, 0.5, &d, &tex_stages_lesson, &a4);
    cr_expect_eq(tri.taps, 1);
    cr_expect_eq(tri.level0, 3);
    cr_expect_eq(a16.level0, 0);
    cr_expect_eq(a4.level0, 1);
    expect_quoted(ANSWERS, "l09.ans.trilinear.lambda", tri.lambda);
    expect_quoted(ANSWERS, "l09.ans.aniso16.taps", a16.taps);
    expect_quoted(ANSWERS, "l09.ans.aniso16.lambda", a16.lambda);
    expect_quoted(ANSWERS, "l09.ans.aniso4.taps", a4.taps);
    expect_quoted(ANSWERS, "l09.ans.aniso4.lambda", a4.lambda);
    scene_free(&s);
}
#endif
