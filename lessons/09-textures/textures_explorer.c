/* Lesson 09, what the explorer adds (compiled only in the narrated build;
 * the algorithm is textures.c, the texture unit sampling.c). Views:
 *   texels  the texture space of the pixel shown, over the canvas: the
 *           pyramid, and the levels the filter reads magnified around the
 *           pixel's (u, v): texels, the footprint (the parallelogram of its
 *           quad's derivatives, centred at (u, v)), the taps with their
 *           weights, aniso's probes along the longer derivative;
 *   lod     each filtered pixel of the triangle in its level's colour (two
 *           levels mixed by their weights), a swatch per level;
 *   quads   covered and helper pixels (evaluated, never written), the quad grid.
 * The watch: each step of a quad, and at a pixel's filter and write u, v,
 * the derivatives, rho, lambda, the levels and their weights. All of it
 * from the events told so far (run_place.told), so it follows the step
 * both ways; the taps follow from the told (u, v), levels and mix by the
 * rules of lessons/CONVENTIONS.md "Textures". */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "front/front.h"     /* clip_polygon, lesson 06's clipper */
#include "lesson_explorer.h"
#include "textures.h"

extern const struct lesson lesson_09;

/* --- the pixel shown, from the events told so far --------------------------------- */

#define PROBES_MAX 16
#define TAPS_MAX (PROBES_MAX * 8)

struct tap {
    int level;
    int64_t i, j;               /* the texel, before wrapping */
    double w;                   /* its share of the filtered colour */
};

/* One textured pixel as the views and the watch show it. */
struct look {
    const struct texture *tex;
    int x, y;                   /* the pixel */
    bool covered;               /* else a helper */
    double u, v;                /* level-0 texels */
    bool has_deriv;             /* its quad's derivatives are told */
    double d[4];                /* du/dx, dv/dx, du/dy, dv/dy (level-0 texels per pixel) */
    double rho, lambda;
    bool beyond;                /* a helper beyond the horizon: the last level */
    bool filtered;              /* the filter has run: what follows is told */
    int filter;                 /* enum tex_filter */
    double used_lambda;         /* the lambda it read the levels at (aniso's: log2(P_max / n)) */
    int nlevels, level[2];      /* the levels read, finer first */
    double level_w[2];          /* their weights */
    int nprobes;                /* 1, or aniso's n along the major axis */
    double probe[PROBES_MAX][2];/* level-0 texels */
    int ntaps;
    struct tap tap[TAPS_MAX];
};

static const struct trace_event *told(const struct raster_params *p, int line)
{
    const struct trace_event *t = p->at ? p->at->told : NULL;
    return t && t[line].kind != TRACE_KIND_COUNT ? &t[line] : NULL;
}

static int level_of(const struct texture *tex, float v)
{
    return v >= 0 && v < tex->nlevels ? (int)v : v >= tex->nlevels ? tex->nlevels - 1 : 0;
}

/* The bilinear taps of level k at (u, v) in level-0 texels, with weight w:
 * u_k - 1/2 = i0 + a, v_k - 1/2 = j0 + b. */
static void bilinear_taps(struct look *lk, int k, double u, double v, double w)
{
    const struct texture_level *l = &lk->tex->level[k];
    double uk = u / lk->tex->level[0].w * l->w - 0.5, vk = v / lk->tex->level[0].h * l->h - 0.5;
    if (!(fabs(uk) < 0x1p52 && fabs(vk) < 0x1p52) || lk->ntaps + 4 > TAPS_MAX)
        return;
    double i0 = floor(uk), j0 = floor(vk), a = uk - i0, b = vk - j0;
    const double share[4] = { (1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b };
    for (int m = 0; m < 4; m++)
        lk->tap[lk->ntaps++] = (struct tap){ k, (int64_t)i0 + (m & 1), (int64_t)j0 + (m >> 1),
                                             w * share[m] };
}

/* The filter's taps from what L_FILTER told: nearest's one texel, or per
 * probe (one, or aniso's n along the longer derivative) a bilinear tap on
 * each level read. */
static void taps(struct look *lk)
{
    if (lk->filter == FILTER_NEAREST) {
        if (fabs(lk->u) < 0x1p52 && fabs(lk->v) < 0x1p52)
            lk->tap[lk->ntaps++] = (struct tap){ 0, (int64_t)floor(lk->u), (int64_t)floor(lk->v), 1 };
        return;
    }
    double ax = 0, ay = 0;      /* the major axis, level-0 texels */
    if (lk->nprobes > 1 && lk->has_deriv) {
        bool along_x = hypot(lk->d[0], lk->d[1]) >= hypot(lk->d[2], lk->d[3]);
        ax = along_x ? lk->d[0] : lk->d[2], ay = along_x ? lk->d[1] : lk->d[3];
    }
    for (int i = 0; i < lk->nprobes; i++) {
        double o = (i + 0.5) / lk->nprobes - 0.5;
        lk->probe[i][0] = lk->u + o * ax, lk->probe[i][1] = lk->v + o * ay;
        for (int m = 0; m < lk->nlevels; m++)
            if (lk->level_w[m] > 0)
                bilinear_taps(lk, lk->level[m], lk->probe[i][0], lk->probe[i][1],
                              lk->level_w[m] / lk->nprobes);
    }
}

/* The pixel last evaluated or filtered in the current triangle, with its
 * quad's derivatives once told and its filter's levels and taps once run.
 * False when there is none (no textured quad evaluated yet). */
static bool look_at(const struct raster_params *p, struct look *lk)
{
    memset(lk, 0, sizeof *lk);
    const struct trace_event *ev = told(p, L_EVAL), *lod = told(p, L_LOD), *fil = told(p, L_FILTER);
    lk->tex = p->texture;
    if (!lk->tex || !ev)
        return false;
    const struct trace_event *px = fil && fil->index > ev->index ? fil : ev;
    lk->x = px->x, lk->y = px->y;
    lk->covered = px == fil || (ev->flags & TRACE_INSIDE);
    lk->u = px->aux[AUX_U], lk->v = px->aux[AUX_V];
    /* its derivatives: told at the pixel (fine, analytic) or at its quad's top-left (coarse) */
    if (lod && ((lod->x == lk->x && lod->y == lk->y) || (lod->x == (lk->x & ~1) && lod->y == (lk->y & ~1)))) {
        lk->has_deriv = true;
        for (int k = 0; k < 4; k++)
            lk->d[k] = lod->aux[AUX_DUDX + k];
        lk->rho = lod->aux[AUX_RHO], lk->lambda = lod->aux[AUX_LAMBDA];
        lk->beyond = !(lod->flags & TRACE_INSIDE);
        if (lk->beyond || !(isfinite(lk->d[0]) && isfinite(lk->d[1]) && isfinite(lk->d[2])
                            && isfinite(lk->d[3])))
            lk->d[0] = lk->d[1] = lk->d[2] = lk->d[3] = 0;
    }
    if (px != fil)
        return true;
    lk->filtered = true;
    lk->filter = fil->mask[2] >= FILTER_NEAREST && fil->mask[2] <= FILTER_ANISO ? fil->mask[2]
                                                                                 : FILTER_TRILINEAR;
    lk->used_lambda = fil->aux[AUX_USED_LAMBDA];
    double mix = fil->aux[AUX_MIX] > 0 ? (fil->aux[AUX_MIX] < 1 ? fil->aux[AUX_MIX] : 1) : 0;
    lk->level[0] = level_of(lk->tex, fil->aux[AUX_LEVEL0]);
    lk->level[1] = level_of(lk->tex, fil->aux[AUX_LEVEL1]);
    lk->nlevels = lk->level[1] != lk->level[0] && mix > 0 ? 2 : 1;
    lk->level_w[0] = lk->nlevels == 2 ? 1 - mix : 1, lk->level_w[1] = mix;
    lk->nprobes = fil->mask[1] >= 1 && fil->mask[1] <= PROBES_MAX ? fil->mask[1] : 1;
    taps(lk);
    return true;
}

/* The colour the taps of the pixel shown add up to, each texel times its
 * weight (0..255 per channel), and that pixel: what the texels view draws,
 * held by the tests to the colour the lesson wrote. False when no pixel
 * has been filtered. */
bool textures_explorer_taps(const struct raster_params *p, int *x, int *y, double rgb[3])
{
    struct look lk;
    if (!look_at(p, &lk) || !lk.filtered)
        return false;
    *x = lk.x, *y = lk.y;
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (int a = 0; a < lk.ntaps; a++) {
        uint32_t c = texture_fetch(lk.tex, lk.tap[a].level, lk.tap[a].i, lk.tap[a].j);
        for (int k = 0; k < 3; k++)
            rgb[k] += lk.tap[a].w * (double)(c >> (16 - 8 * k) & 255);
    }
    return true;
}

static const char *const filter_word[] = { "?", "nearest", "bilinear", "mip-bilinear", "trilinear",
                                           "aniso" };

/* The look in lines: u, v, the derivatives, rho, lambda, the levels read
 * and their weights (what the watch and the texels view write). */
static void describe(const struct look *lk, char *buf, size_t n)
{
    size_t at = (size_t)snprintf(buf, n, "pixel (%d, %d)%s: u %.4g, v %.4g (level-0 texels)\n", lk->x, lk->y,
                                 lk->covered ? "" : ", a helper", lk->u, lk->v);
    if (lk->has_deriv && !lk->beyond && at < n)
        at += (size_t)snprintf(buf + at, n - at, "du/dx %.4g, dv/dx %.4g\ndu/dy %.4g, dv/dy %.4g\n"
                               "rho %.4g, lambda %.4g\n", lk->d[0], lk->d[1], lk->d[2], lk->d[3], lk->rho,
                               lk->lambda);
    else if (at < n)
        at += (size_t)snprintf(buf + at, n - at, "%s\n", lk->beyond ? "its quad reaches beyond the horizon: the last level"
                                                                     : "its quad's derivatives: not taken yet");
    if (at >= n)
        return;
    if (!lk->filtered) {
        snprintf(buf + at, n - at, "not filtered yet\n");
        return;
    }
    if (lk->filter == FILTER_NEAREST) {
        snprintf(buf + at, n - at, "nearest: level 0, texel (%.0f, %.0f)\n", floor(lk->u), floor(lk->v));
        return;
    }
    if (lk->filter == FILTER_BILINEAR || !(lk->used_lambda > 0))
        at += (size_t)snprintf(buf + at, n - at, "%s: bilinear, level 0%s", filter_word[lk->filter],
                               lk->filter == FILTER_BILINEAR ? "" : " (magnified)");
    else
        at += (size_t)snprintf(buf + at, n - at, "%s at lambda %.4g:\nlevel %d x %.4g", filter_word[lk->filter],
                               lk->used_lambda, lk->level[0], lk->level_w[0]);
    if (lk->nlevels == 2 && at < n)
        at += (size_t)snprintf(buf + at, n - at, " + level %d x %.4g", lk->level[1], lk->level_w[1]);
    if (lk->nprobes > 1 && at < n)
        snprintf(buf + at, n - at, ",\nat each of %d probes along the longer derivative\n", lk->nprobes);
    else if (at < n)
        snprintf(buf + at, n - at, "\n");
}

/* --- drawing inside a rectangle of the canvas ----------------------------------- */

struct rect {
    double x0, y0, x1, y1;
};

static void rect_pen(const struct lesson_canvas *c, struct rect r, struct pen pen)
{
    c->polygon(c, (const double[][2]){ { r.x0, r.y0 }, { r.x1, r.y0 }, { r.x1, r.y1 }, { r.x0, r.y1 } },
               4, pen);
}

/* A convex polygon cut to r by the front end's clipper (lesson 06's), in
 * doubles: a footprint stretched far beyond the panel stays exact. */
static void clipped_polygon(const struct lesson_canvas *c, struct rect r, const double (*xy)[2], int n,
                            struct pen pen)
{
    struct poly p = { .n = n };
    for (int k = 0; k < n; k++)
        p.v[k] = (struct pvert){ .pos = { xy[k][0], xy[k][1], 1 } };
    clip_polygon_rect(&p, r.x0, r.y0, r.x1, r.y1);
    double out[POLY_MAX][2];
    for (int k = 0; k < p.n; k++)
        out[k][0] = p.v[k].pos[0], out[k][1] = p.v[k].pos[1];
    if (p.n >= 3)
        c->polygon(c, (const double(*)[2])out, p.n, pen);
}

static bool inside(struct rect r, double x, double y)
{
    return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;
}

/* --- texels: the texture space of the current pixel ------------------------------- */

/* Where texels land on the canvas: texel coordinate (a, b) of level k at
 * (ox + (a - i0) sx, oy + (b - j0) sy). */
struct frame {
    double ox, oy, sx, sy;
    double i0, j0;
    double fx, fy;              /* level-k texels per level-0 texel, across and down */
};

static void at(const struct frame *f, double a, double b, double out[2])
{
    out[0] = f->ox + (a - f->i0) * f->sx;
    out[1] = f->oy + (b - f->j0) * f->sy;
}

/* The footprint: the parallelogram spanned by the derivatives, centred at
 * (cu, cv), in the frame's texels. */
static void footprint(const struct look *lk, const struct frame *f, double cu, double cv,
                      double out[4][2])
{
    double ax = lk->d[0] * f->fx / 2, ay = lk->d[1] * f->fy / 2;
    double bx = lk->d[2] * f->fx / 2, by = lk->d[3] * f->fy / 2;
    const double sign[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    for (int k = 0; k < 4; k++)
        at(f, cu + sign[k][0] * ax + sign[k][1] * bx, cv + sign[k][0] * ay + sign[k][1] * by, out[k]);
}

/* The pyramid in r: level 0, the levels below it in a column beside it,
 * each the whole texture (the square of s, t in [0, 1]) at half the size;
 * on the levels read, the footprint and a ring at (s, t) brought into the
 * image (repeat) or onto its border (clamp). Returns where it ends below. */
static double draw_pyramid(const struct lesson_canvas *c, struct rect r, const struct look *lk, bool shown)
{
    const struct texture *tex = lk->tex;
    double w0 = tex->level[0].w, h0 = tex->level[0].h;
    double scale = fmin((r.x1 - r.x0) / (1.5 * w0), (r.y1 - r.y0) / h0);
    double a = w0 * scale, b = h0 * scale, gap = 3 * c->unit, y = r.y0;
    for (int k = 0; k < tex->nlevels; k++) {
        double f = ldexp(1.0, -k);
        struct rect box = { r.x0, r.y0, r.x0 + a, r.y0 + b };
        if (k > 0) {
            box = (struct rect){ r.x0 + a + gap, y, r.x0 + a + gap + a * f, y + b * f };
            y = box.y1 + gap;
        }
        if (box.x1 - box.x0 < 3 * c->unit || box.y1 - box.y0 < 3 * c->unit || box.y1 > r.y1)
            break;          /* too small to show */
        /* more texels than screen pixels: a coarser level shows them (a 4096 x 4096 image is
         * not copied at every frame, and averaged texels alias less than picked ones) */
        int j = k;
        while (j + 1 < tex->nlevels && tex->level[j].w > 2 * (box.x1 - box.x0) / c->unit)
            j++;
        c->image(c, box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0, tex->level[j].texel,
                 tex->level[j].w, tex->level[j].h);
        bool read = shown && (k == lk->level[0] || (lk->nlevels == 2 && k == lk->level[1]));
        rect_pen(c, box, (struct pen){ .stroke = read ? INK_PROBE : INK_TEXT, .width = read ? 2.5 : 1,
                                       .alpha = read ? 1 : 0.5 });
        if (!read)
            continue;
        double s = lk->u / w0, t = lk->v / h0;
        if (tex->wrap == TEXTURE_REPEAT)
            s -= floor(s), t -= floor(t);
        s = fmin(fmax(s, 0), 1), t = fmin(fmax(t, 0), 1);
        struct frame fr = { .ox = box.x0, .oy = box.y0, .sx = (box.x1 - box.x0) / w0,
                            .sy = (box.y1 - box.y0) / h0, .fx = 1, .fy = 1 };
        double fp[4][2], q[2];
        if (lk->has_deriv) {
            footprint(lk, &fr, s * w0, t * h0, fp);
            clipped_polygon(c, box, (const double(*)[2])fp, 4, (struct pen){ .fill = INK_MARK, .alpha = 0.8 });
        }
        at(&fr, s * w0, t * h0, q);
        c->disc(c, q[0], q[1], 5, (struct pen){ .stroke = INK_PROBE, .width = 2 });
    }
    char text[160];
    snprintf(text, sizeof text, "%s: %d x %d, %d levels, %s", tex->name, tex->level[0].w,
             tex->level[0].h, tex->nlevels, tex->wrap == TEXTURE_REPEAT ? "repeat" : "clamp");
    c->label(c, r.x0, r.y0 - 17 * c->unit, text, 11, INK_TEXT);
    return r.y0 + b;
}

/* Level k magnified around the pixel's (u, v) in r: a window of texels wide
 * enough for the footprint (fetched as the filter fetches them: wrapped or
 * clamped), their grid, the footprint, aniso's probes, the taps as discs
 * (area as the weight) with their weights, (u, v) itself. */
static void draw_level(const struct lesson_canvas *c, struct rect r, const struct look *lk, int k,
                       double weight)
{
    const struct texture *tex = lk->tex;
    const struct texture_level *L = &tex->level[k];
    struct frame fr = { .fx = (double)L->w / tex->level[0].w, .fy = (double)L->h / tex->level[0].h };
    double u = lk->u * fr.fx, v = lk->v * fr.fy;
    double reach = fmax((fabs(lk->d[0]) + fabs(lk->d[2])) * fr.fx, (fabs(lk->d[1]) + fabs(lk->d[3])) * fr.fy);
    int n = 2 * (int)ceil(fmin(reach, 64) / 2) + 4;
    n = n > 32 ? 32 : n;
    double top = 17 * c->unit, side = fmin(r.x1 - r.x0, r.y1 - r.y0 - top);
    if (side <= 4 * c->unit || !(fabs(u) < 0x1p52 && fabs(v) < 0x1p52))
        return;
    int64_t i0 = (int64_t)floor(u + 0.5) - n / 2, j0 = (int64_t)floor(v + 0.5) - n / 2;
    fr.i0 = (double)i0, fr.j0 = (double)j0;
    fr.sx = fr.sy = side / n;
    fr.ox = r.x0, fr.oy = r.y0 + top;
    struct rect box = { fr.ox, fr.oy, fr.ox + side, fr.oy + side };
    uint32_t px[32 * 32];
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            px[j * n + i] = texture_fetch(tex, k, i0 + i, j0 + j);
    c->image(c, box.x0, box.y0, side, side, px, n, n);
    if (fr.sx >= 6 * c->unit)
        for (int i = 1; i < n; i++) {
            struct pen grid = { .stroke = INK_OUTLINE, .width = 1, .alpha = 0.6 };
            c->line(c, box.x0 + i * fr.sx, box.y0, box.x0 + i * fr.sx, box.y1, grid);
            c->line(c, box.x0, box.y0 + i * fr.sy, box.x1, box.y0 + i * fr.sy, grid);
        }
    rect_pen(c, box, (struct pen){ .stroke = INK_PROBE, .width = 2.5 });
    if (lk->has_deriv) {
        double fp[4][2];
        footprint(lk, &fr, u, v, fp);
        clipped_polygon(c, box, (const double(*)[2])fp, 4, (struct pen){ .fill = INK_MARK, .alpha = 0.3 });
        clipped_polygon(c, box, (const double(*)[2])fp, 4, (struct pen){ .stroke = INK_MARK, .width = 2 });
    }
    for (int m = 0; m < lk->nprobes && lk->nprobes > 1; m++) {
        double q[2];
        at(&fr, lk->probe[m][0] * fr.fx, lk->probe[m][1] * fr.fy, q);
        if (inside(box, q[0], q[1]))
            c->disc(c, q[0], q[1], 3, (struct pen){ .fill = INK_MARK, .stroke = INK_OUTLINE });
    }
    /* the taps of this level; a texel several probes read, once, its weights summed */
    bool done[TAPS_MAX] = { false };
    for (int a = 0; a < lk->ntaps; a++) {
        if (done[a] || lk->tap[a].level != k)
            continue;
        double w = 0;
        for (int b = a; b < lk->ntaps; b++)
            if (!done[b] && lk->tap[b].level == k && lk->tap[b].i == lk->tap[a].i && lk->tap[b].j == lk->tap[a].j)
                w += lk->tap[b].w, done[b] = true;
        double q[2], rad = 2.5 + 7 * sqrt(fmax(w, 0));
        at(&fr, (double)lk->tap[a].i + 0.5, (double)lk->tap[a].j + 0.5, q);
        if (!inside(box, q[0], q[1]))
            continue;
        c->disc(c, q[0], q[1], rad, (struct pen){ .fill = INK_PROBE, .stroke = INK_OUTLINE, .width = 1.5 });
        if (fr.sx >= 40 * c->unit) {
            char text[16];
            snprintf(text, sizeof text, "%.3f", w);
            c->label(c, q[0] - 14 * c->unit, q[1] + (rad + 3) * c->unit, text, 10, INK_TEXT);
        }
    }
    double q[2];
    at(&fr, u, v, q);
    c->disc(c, q[0], q[1], 4, (struct pen){ .fill = INK_MARK, .stroke = INK_OUTLINE, .width = 1.5 });
    char text[128];
    if (weight >= 0)
        snprintf(text, sizeof text, "level %d, %d x %d: weight %.3f", k, L->w, L->h, weight);
    else
        snprintf(text, sizeof text, "level %d, %d x %d: not filtered yet", k, L->w, L->h);
    c->label(c, r.x0, r.y0, text, 11, INK_TEXT);
}

static void draw_texels(const struct lesson_canvas *c, const struct raster_params *p, int w, int h)
{
    c->cover(c);
    double u = c->unit, m = 8 * u;
    struct look lk;
    bool shown = look_at(p, &lk);
    if (!lk.tex) {
        c->label(c, m, m, "this triangle has no image texture", 11, INK_TEXT);
        return;
    }
    if (shown && !lk.filtered) {    /* before the filter: the level lambda points at */
        int k = lk.has_deriv ? level_of(lk.tex, (float)fmax(lk.lambda, 0)) : 0;
        lk.nlevels = 1, lk.level[0] = lk.beyond ? lk.tex->nlevels - 1 : k, lk.level_w[0] = -1;
    }
    double y = draw_pyramid(c, (struct rect){ m, m + 19 * u, w * 0.47, h - m }, &lk, shown) + 8 * u;
    if (!shown) {
        c->label(c, w * 0.5, m, "no quad of this triangle evaluated yet", 11, INK_TEXT);
        return;
    }
    char text[512];
    describe(&lk, text, sizeof text);
    int k = 0;
    for (char *line = strtok(text, "\n"); line && y < h; line = strtok(NULL, "\n"), y += 15 * u)
        c->label(c, m, y, line, 11, k++ ? INK_TEXT : INK_PROBE);
    struct rect right = { w * 0.5, m, w - m, h - m };
    if (lk.nlevels == 1) {
        draw_level(c, right, &lk, lk.level[0], lk.level_w[0]);
        return;
    }
    double rw = right.x1 - right.x0, rh = right.y1 - right.y0;
    struct rect a = right, b = right;
    if (fmin(rw, rh / 2) >= fmin(rw / 2, rh))
        a.y1 = right.y0 + rh / 2 - 2 * u, b.y0 = right.y0 + rh / 2 + 2 * u;
    else
        a.x1 = right.x0 + rw / 2 - 2 * u, b.x0 = right.x0 + rw / 2 + 2 * u;
    draw_level(c, a, &lk, lk.level[0], lk.level_w[0]);
    draw_level(c, b, &lk, lk.level[1], lk.level_w[1]);
}
/* --- lod: one colour per level --------------------------------------------------- */

/* The levels' colours, finest first: a hue each, distinct side by side. */
static const double level_rgb[TEXTURE_LEVELS_MAX][3] = {
    { 0.90, 0.16, 0.16 }, { 0.96, 0.55, 0.10 }, { 0.95, 0.88, 0.15 }, { 0.45, 0.85, 0.20 },
    { 0.10, 0.70, 0.45 }, { 0.15, 0.80, 0.90 }, { 0.20, 0.45, 0.95 }, { 0.50, 0.30, 0.90 },
    { 0.85, 0.35, 0.85 }, { 0.95, 0.60, 0.70 }, { 0.70, 0.55, 0.35 }, { 0.75, 0.75, 0.75 },
    { 0.40, 0.40, 0.40 },
};

/* The most levels of the scene's textures (a swatch for each). */
static int scene_levels(const struct raster_params *p)
{
    int most = 0;
    const struct scene *s = drawn_scene(p);
    for (int k = 1; s && k <= scene_texture_count(s); k++) {
        const struct texture *t = scene_texture(s, k);
        most = t && t->nlevels > most ? t->nlevels : most;
    }
    return most;
}


static bool lod_cell(const struct tri_setup *t, const struct trace_event *test,
                     const struct trace_event *write, double rgb[3])
{
    (void)t, (void)write;
    if (!test || test->line != L_FILTER)
        return false;       /* not filtered (yet), or untextured */
    int last = TEXTURE_LEVELS_MAX - 1;
    int k0 = test->aux[AUX_LEVEL0] >= 0 && test->aux[AUX_LEVEL0] <= last ? (int)test->aux[AUX_LEVEL0] : 0;
    int k1 = test->aux[AUX_LEVEL1] >= 0 && test->aux[AUX_LEVEL1] <= last ? (int)test->aux[AUX_LEVEL1] : k0;
    double mix = test->aux[AUX_MIX] > 0 ? (test->aux[AUX_MIX] < 1 ? test->aux[AUX_MIX] : 1) : 0;
    for (int c = 0; c < 3; c++)
        rgb[c] = (1 - mix) * level_rgb[k0][c] + mix * level_rgb[k1][c];
    return true;
}

/* --- quads: covered and helper pixels ----------------------------------------------- */

static const struct lesson_swatch quad_swatch[4] = {
    { { 0.82, 0.84, 0.90 }, "covered: evaluated, filtered, written" },
    { { 0.98, 0.52, 0.10 }, "helper: evaluated, never written" },
    { { 0.42, 0.44, 0.55 }, "covered, quad not evaluated yet" },
    { { 0.20, 0.20, 0.25 }, "outside, quad skipped or not yet evaluated" },
};

static bool quads_cell(const struct tri_setup *t, const struct trace_event *test,
                       const struct trace_event *write, double rgb[3])
{
    (void)t, (void)write;
    if (!test)
        return false;
    bool evaluated = test->line == L_EVAL || test->line == L_FILTER, in = test->flags & TRACE_INSIDE;
    memcpy(rgb, quad_swatch[evaluated ? (in ? 0 : 1) : (in ? 2 : 3)].rgb, 3 * sizeof *rgb);
    return true;
}

/* The quad grid over the triangle's box (the quad of pixel (x, y) has its
 * top-left pixel at (x & ~1, y & ~1)), the quad of the current step outlined. */
static void draw_quads(const struct lesson_canvas *c, const struct tri_setup *t,
                       const struct trace_event *last)
{
    if (t->area2 <= 0 || t->empty || c->unit > 1.0 / 5)
        return;
    int x0 = t->minx & ~1, y0 = t->miny & ~1, x1 = (t->maxx | 1) + 1, y1 = (t->maxy | 1) + 1;
    for (int pass = 0; pass < 2 && c->unit <= 1.0 / 12; pass++) {  /* white on a dark halo: seen on any cell */
        struct pen grid = pass ? (struct pen){ .stroke = INK_MARK, .width = 1.5 }
                               : (struct pen){ .stroke = INK_OUTLINE, .width = 4, .alpha = 0.8 };
        for (int x = x0; x <= x1; x += 2)
            c->line(c, x, y0, x, y1, grid);
        for (int y = y0; y <= y1; y += 2)
            c->line(c, x0, y, x1, y, grid);
    }
    bool quad_step = last && (last->kind == TRACE_PIXEL_TEST || last->kind == TRACE_PIXEL_WRITE
                              || (last->kind == TRACE_STEP && last->line >= L_SKIP && last->line <= L_FILTER));
    if (quad_step) {
        double qx = last->x & ~1, qy = last->y & ~1;
        c->polygon(c, (const double[][2]){ { qx, qy }, { qx + 2, qy }, { qx + 2, qy + 2 }, { qx, qy + 2 } },
                   4, (struct pen){ .stroke = INK_PROBE, .width = 3 });
    }
}

static int swatches(const char *view, const struct raster_params *p, struct lesson_swatch *out, int max)
{
    int n = 0;
    if (strcmp(view, "quads") == 0)
        for (; n < 4 && n < max; n++)
            out[n] = quad_swatch[n];
    if (strcmp(view, "lod") == 0)
        for (int most = scene_levels(p); n < most && n < max; n++) {
            out[n] = (struct lesson_swatch){ .rgb = { level_rgb[n][0], level_rgb[n][1], level_rgb[n][2] } };
            snprintf(out[n].label, sizeof out[n].label, n == 0 ? "level 0 (and magnified)" : "level %d", n);
        }
    return n;
}

/* (texels draws a picture of its own over the canvas: its cells lie under it) */
static const struct lesson_view views[] = {
    { "texels", "texture space of the last pixel evaluated: the pyramid, its footprint (the "
                "parallelogram of its quad's derivatives), the levels read magnified, the taps "
                "(disc area: weight)", lod_cell },
    { "lod", "the level each textured pixel of the triangle reads, two mixed by their weights",
      lod_cell },
    { "quads", "2 x 2 quads: covered and helper pixels; the quad grid", quads_cell },
};

static void overlay(const struct lesson_canvas *c, const struct tri_setup *t,
                    const struct raster_params *p, const struct trace_event *last)
{
    if (strcmp(c->view, "texels") == 0 && drawn_scene(p))
        draw_texels(c, p, drawn_scene(p)->w, drawn_scene(p)->h);
    else if (strcmp(c->view, "quads") == 0)
        draw_quads(c, t, last);
}

/* --- the watch panel ------------------------------------------------------------------ */

/* From a quad's (u, v) on: the pixel as the steps so far tell it. */
static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    (void)t;
    buf[0] = '\0';
    struct look lk;
    bool step = ev->kind == TRACE_STEP && ev->line >= L_EVAL && ev->line <= L_FILTER;
    if ((step || ev->kind == TRACE_PIXEL_WRITE) && look_at(p, &lk))
        describe(&lk, buf, n);
}

/* The triangle's texture, its pyramid and the filter. */
static void constants(const struct tri_setup *t, const struct raster_params *p, char *buf, size_t n)
{
    (void)t;
    const struct texture *tex = p->texture;
    if (!tex) {
        snprintf(buf, n, "no image texture: the vertex colour%s", p->checker ? " and the checker" : "");
        return;
    }
    enum tex_filter f = tex_filter_of(p);
    int at = snprintf(buf, n, "%s, %d x %d, %d levels, %s\nfilter %s", tex->name, tex->level[0].w,
                      tex->level[0].h, tex->nlevels, tex->wrap == TEXTURE_REPEAT ? "repeat" : "clamp",
                      filter_word[f]);
    if (f == FILTER_ANISO && at >= 0 && (size_t)at < n)
        snprintf(buf + at, n - (size_t)at, ", at most %d probes", tex_max_aniso_of(p));
}

static const int cell_lines[] = { L_EVAL, L_FILTER, -1 };

const struct lesson_explorer lesson_09_explorer = {
    .lesson = &lesson_09,
    .views = views,
    .nviews = sizeof views / sizeof views[0],
    .overlay = overlay,
    .constants = constants,
    .watch = watch,
    .swatches = swatches,
    .cell_lines = cell_lines,
};
