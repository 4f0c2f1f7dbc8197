/* Lesson 09: texture mapping: 2 x 2 quads, derivatives, mip-maps and
 * filtering.
 *
 * Built on lesson 05's blocks: the box is cut into 8 x 8 blocks, each
 * tested for emptiness by its corners; a block that is not empty, full or
 * partial, is walked in 2 x 2 quads, as GPUs walk a triangle, every pixel
 * tested:
 *
 *        x0   x0+1                  the quad of pixel (x, y) is the one
 *      +----+----+                  whose top-left pixel is (x & ~1, y & ~1)
 *  y0  | TL | TR |   du/dx = u(TR) - u(TL)       (coarse derivatives:
 *      +----+----+   du/dy = u(BL) - u(TL)        one set per quad)
 *  y0+1| BL | BR |
 *      +----+----+
 *
 * A quad with any covered pixel evaluates (s, t) at all four centres, the
 * uncovered ones too (helper pixels: evaluated, never written), so that
 * the differences exist; they give rho, the level of detail lambda =
 * log2(rho), and the texture unit (sampling.c) filters: nearest, bilinear,
 * mip-bilinear, trilinear (the default) or aniso. The pixel's colour is
 * the filtered texel times the interpolated vertex colour, rounded once.
 * (s, t) and the colour are perspective-correct (lesson 04): 1/z, s/z,
 * t/z and colour/z are linear in the screen, weighted by the barycentric
 * weights of the exact edge values (lesson 02).
 *
 * This file reads: the pixel's values, the quad, the blocks, the variants.
 * The fast twin (quads_sse.c) draws the same pixels four lanes at a time.
 */
#include <math.h>

#include "shade/shade.h"
#include "textures.h"

static const char *const pseudocode[] = {
    "setup: F0k, box; 1/z, s/z, t/z, colour/z at A, B, C",  /* 0 */
    "loop over the box's 8 x 8 blocks, by their corners:",   /* 1 */
    "  empty: skip",                                          /* 2 */
    "  else loop over its 2 x 2 quads (x & ~1, y & ~1):",    /* 3 */
    "    covered = F01, F02, F03 >= 0 at each pixel",        /* 4 */
    "    no pixel covered: skip the quad",                    /* 5 */
    "    (s, t) = (s/z, t/z) / (1/z) at all 4, helpers too", /* 6 */
    "    du/dx, dv/dx, du/dy, dv/dy: top-left differences",  /* 7 */
    "    rho = longer derivative; lambda = log2 rho",        /* 8 */
    "    covered: texel = filter(s, t, lambda): levels, taps", /* 9 */
    "      colour = texel x vertex colour, rounded; write",  /* 10 */
    NULL,
};

#define CORNERS_COST { .mul = 4, .add = 7 }     /* one edge at a block's four corners */
/* A pixel centre's values (at_pixel): three weights F / 2 area and three
 * over z (divisions, counted as multiplications), 1/z, s and t summed, s
 * and t divided by 1/z. Its colour, a covered pixel's: three channels
 * summed and divided. */
#define TEX_EVAL_COST { .mul = 14, .add = 9 }
/* ... a textured pixel's (s, t) by one reciprocal (textures.h): q = sum F_k
 * Q_k, its reciprocal, s and t summed and multiplied by it. */
#define TEX_EVAL_RECIP_COST { .mul = 12, .add = 6 }
#define TEX_COLOUR_COST { .mul = 12, .add = 9 }
/* The texture unit (sampling.c), per tap: a bilinear tap (u, v, the
 * weights, three channels lerped three times), the level of detail, the
 * mix of two levels, the modulation by the vertex colour. */
#define BILINEAR_TAP_COST { .mul = 11, .add = 22 }
#define LOD_COST { .mul = 9, .add = 3 }
#define MIX_COST { .mul = 3, .add = 6 }
#define MODULATE_COST { .mul = 3, .add = 3 }

enum tex_filter tex_filter_of(const struct raster_params *p)
{
    int f = p->knob[P_FILTER];
    return f >= FILTER_NEAREST && f <= FILTER_ANISO ? (enum tex_filter)f : FILTER_TRILINEAR;
}

int tex_max_aniso_of(const struct raster_params *p)
{
    int n = p->knob[P_MAX_ANISO];
    return n >= 1 && n <= 16 ? n : MAX_ANISO_DEFAULT;
}

/* --- the values at a pixel centre ------------------------------------------ */

/* Everything one triangle's quads share. */
struct run {
    const struct tri_setup *t;
    const struct raster_params *p;
    struct target *fb;
    struct trace *tr;
    const struct texture *tex;      /* NULL: untextured, shaded as every lesson shades */
    const struct tex_stages *st;
    struct tex_options o;
    enum tex_filter filter;
    int max_aniso;
    struct biased_edges e;
    double inv_area2;
    double cz[3][3];            /* per vertex A, B, C: r, g, b */
    double q[3], sq[3], tq[3];  /* ... and 1/z, s/z, t/z: the analytic derivatives' planes */
    double cq[3][3];            /* ... and r/z, g/z, b/z */
    bool by_reciprocal;         /* (s, t) by one reciprocal (textures.h), else by the weights */
    double tie[2];              /* nearest: how close to a texel's edge asks the weights */
};

/* What is interpolated at one pixel centre. */
struct at_pixel {
    double q, s, t, rgb[3];
    float z;                    /* the depth */
};

/* The barycentric weights of A, B, C from the raw edge values (F02, F03,
 * F01 over twice the area), then the planes: 1/z = sum w_k / z_k, and each
 * attribute a = (sum w_k a_k / z_k) / (1/z), in this order, so that a
 * pixel centre exactly on a texel's edge lands where the rule's plain sums
 * put it. A helper's 1/z may be <= 0 (beyond the horizon): its values are
 * then not used. */
static struct at_pixel at_pixel(const struct run *r, const int64_t f[3])
{
    double area2 = (double)r->t->area2;
    if (r->by_reciprocal) {     /* a textured pixel: q = sum F_k Q_k, one reciprocal (textures.h) */
        double fk[3] = { (double)f[EDGE_BC], (double)f[EDGE_CA], (double)f[EDGE_AB] };
        double q = 0, s = 0, t = 0, c[3] = { 0, 0, 0 };
        for (int k = 0; k < 3; k++) {
            q += fk[k] * r->q[k];
            s += fk[k] * r->sq[k], t += fk[k] * r->tq[k];
            for (int i = 0; i < 3; i++)
                c[i] += fk[k] * r->cq[k][i];
        }
        double rq = 1 / q;
        struct at_pixel a = { .q = q / area2, .s = s * rq, .t = t * rq, .z = (float)(area2 * rq) };
        for (int i = 0; i < 3; i++)
            a.rgb[i] = c[i] * rq;
        return a;
    }
    double b[3] = { (double)f[EDGE_BC] / area2, (double)f[EDGE_CA] / area2,
                    (double)f[EDGE_AB] / area2 };
    struct at_pixel a = { 0 };
    double s = 0, t = 0, c[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; k++) {
        double w = b[k] / r->t->v[k].z;
        a.q += w;
        s += w * r->t->v[k].s, t += w * r->t->v[k].t;
        for (int i = 0; i < 3; i++)
            c[i] += w * r->cz[k][i];
    }
    a.s = s / a.q, a.t = t / a.q;
    double z = 1 / a.q;                 /* the depth, and what the colour is multiplied by */
    for (int i = 0; i < 3; i++)
        a.rgb[i] = c[i] * z;
    a.z = (float)z;
    if (r->o.affine) {      /* the exhibit: s and t linear in the screen, as if z were constant */
        a.s = b[0] * r->t->v[0].s + b[1] * r->t->v[1].s + b[2] * r->t->v[2].s;
        a.t = b[0] * r->t->v[0].t + b[1] * r->t->v[1].t + b[2] * r->t->v[2].t;
    }
    return a;
}

/* The analytic derivatives at a pixel: a = A / Q with A and Q linear, so
 * da/dx = (dA/dx - a dQ/dx) / Q. */
static struct tex_deriv analytic(const struct run *r, const struct at_pixel *a)
{
    double ds[2] = { 0, 0 }, dt[2] = { 0, 0 }, dq[2] = { 0, 0 };
    static const int edge_of[3] = { EDGE_BC, EDGE_CA, EDGE_AB };    /* weight k's edge */
    for (int axis = 0; axis < 2; axis++)
        for (int k = 0; k < 3; k++) {
            int64_t step = axis == 0 ? r->e.dx[edge_of[k]] : r->e.dy[edge_of[k]];
            double dw = (double)step * r->inv_area2;
            dq[axis] += dw * r->q[k];
            ds[axis] += dw * (r->o.affine ? r->t->v[k].s : r->sq[k]);
            dt[axis] += dw * (r->o.affine ? r->t->v[k].t : r->tq[k]);
        }
    double div = r->o.affine ? 1 : a->q;
    double ks = r->o.affine ? 0 : a->s, kt = r->o.affine ? 0 : a->t;
    return (struct tex_deriv){ .dsdx = (ds[0] - ks * dq[0]) / div, .dtdx = (dt[0] - kt * dq[0]) / div,
                               .dsdy = (ds[1] - ks * dq[1]) / div, .dtdy = (dt[1] - kt * dq[1]) / div,
                               .w0 = r->tex->level[0].w, .h0 = r->tex->level[0].h };
}

/* --- one quad ----------------------------------------------------------------- */

/* Pixel i of a quad: 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right. */
#define QX(qx, i) ((qx) + ((i) & 1))
#define QY(qy, i) ((qy) + ((i) >> 1))

/* Narrate a set of derivatives (the quad's at its top-left pixel, or one
 * pixel's) with rho in level-0 texels and the lambda the level-of-detail
 * stage makes of them (an exercise's: make check holds it to log2(rho)). */
static void narrate_deriv(const struct run *r, int x, int y, unsigned covered, const struct tex_deriv *d)
{
    double dudx = d->dsdx * d->w0, dvdx = d->dtdx * d->h0, dudy = d->dsdy * d->w0, dvdy = d->dtdy * d->h0;
    double rho = fmax(sqrt(dudx * dudx + dvdx * dvdx), sqrt(dudy * dudy + dvdy * dvdy));
    NARRATE(r->tr, .kind = TRACE_STEP, .line = L_LOD, .span = L_LOD - L_DERIV, .x = x, .y = y,
            .mask = { (uint16_t)covered }, .flags = d->beyond ? 0 : TRACE_INSIDE,
            .aux = { (float)dudx, (float)dvdx, (float)dudy, (float)dvdy, (float)rho,
                     d->beyond ? (float)(r->tex->nlevels - 1) : (float)r->st->lod(d) });
}

/* The derivatives pixel i uses: the quad's (coarse), its own row's and
 * column's differences (fine), or the exact ones (analytic). */
static struct tex_deriv deriv_of(const struct run *r, const struct at_pixel a[4], int i, bool beyond)
{
    int row = i & 2, col = i & 1;
    int tl = r->o.lod == LOD_FINE ? row : 0, tr = tl + 1;           /* along x */
    int top = r->o.lod == LOD_FINE ? col : 0, bottom = top + 2;     /* along y */
    if (r->o.lod == LOD_ANALYTIC)
        return analytic(r, &a[i]);
    return (struct tex_deriv){ .dsdx = a[tr].s - a[tl].s, .dtdx = a[tr].t - a[tl].t,
                               .dsdy = a[bottom].s - a[top].s, .dtdy = a[bottom].t - a[top].t,
                               .w0 = r->tex->level[0].w, .h0 = r->tex->level[0].h,
                               .beyond = beyond };
}

/* The quad whose top-left pixel is (qx, qy), inside block [xa, xb] x [ya,
 * yb] (clipped to the box). */
static void quad(struct run *r, int qx, int qy, int xa, int ya, int xb, int yb)
{
    int64_t f[4][3];
    unsigned covered = 0;
    for (int i = 0; i < 4; i++) {
        int x = QX(qx, i), y = QY(qy, i);
        bool in = x >= xa && x <= xb && y >= ya && y <= yb;
        for (int k = 0; k < 3; k++) {
            f[i][k] = biased_edge_at(&r->e, k, x, y);
            in = in && f[i][k] >= 0;
            f[i][k] -= r->e.bias[k];                /* the edge value itself, for the weights */
        }
        COUNT(r->tr, 3, EDGE_VALUE_COST);
        NARRATE(r->tr, .kind = TRACE_PIXEL_TEST, .line = L_COVER, .x = x, .y = y,
                .e = { f[i][0], f[i][1], f[i][2] }, .flags = in ? TRACE_INSIDE : 0);
        covered |= (unsigned)in << i;
    }
    if (!covered) {
        NARRATE(r->tr, .kind = TRACE_STEP, .line = L_SKIP, .x = qx, .y = qy);
        return;
    }
    /* every centre of the quad, helpers included */
    struct at_pixel a[4];
    bool beyond = false;
    double W = r->tex ? r->tex->level[0].w : 1, H = r->tex ? r->tex->level[0].h : 1;
    for (int i = 0; i < 4; i++) {
        a[i] = at_pixel(r, f[i]);
        if (r->by_reciprocal)
            COUNT(r->tr, 1, TEX_EVAL_RECIP_COST);
        else
            COUNT(r->tr, 1, TEX_EVAL_COST);
        beyond = beyond || !(a[i].q > 0);
        NARRATE(r->tr, .kind = TRACE_STEP, .line = L_EVAL, .x = QX(qx, i), .y = QY(qy, i),
                .flags = (covered >> i & 1) ? TRACE_INSIDE : 0,
                .aux = { (float)(a[i].s * W), (float)(a[i].t * H), (float)a[i].q });
    }
    if (r->tex && r->o.lod == LOD_COARSE) {
        struct tex_deriv d = deriv_of(r, a, 0, beyond);
        narrate_deriv(r, qx, qy, covered, &d);
    }
    for (int i = 0; i < 4; i++) {
        if (!(covered >> i & 1))
            continue;
        int x = QX(qx, i), y = QY(qy, i);
        uint32_t rgba;
        COUNT(r->tr, 1, TEX_COLOUR_COST);
        if (!r->tex) {          /* untextured: the shared shading (and the checker) */
            rgba = shade_pixel(r->p, r->tr, a[i].rgb[0], a[i].rgb[1], a[i].rgb[2], a[i].s, a[i].t);
        } else {
            struct tex_deriv d = deriv_of(r, a, i, beyond);
            if (r->o.lod != LOD_COARSE)
                narrate_deriv(r, x, y, covered, &d);
            if (r->filter == FILTER_NEAREST && r->by_reciprocal
                && (tex_near_edge(a[i].s * W, r->tie[0]) || tex_near_edge(a[i].t * H, r->tie[1]))) {
                /* on a texel's edge, or all but: the weights decide which texel (textures.h) */
                double fk[3] = { (double)f[i][EDGE_BC], (double)f[i][EDGE_CA], (double)f[i][EDGE_AB] };
                tex_st_by_weights(r->t, fk, &a[i].s, &a[i].t);
            }
            struct tex_used u;
            struct texel_rgb texel = tex_filter_texel(r->tex, r->filter, r->max_aniso, a[i].s, a[i].t,
                                                      &d, r->st, &u);
            NARRATE(r->tr, .kind = TRACE_STEP, .line = L_FILTER, .x = x, .y = y,
                    .mask = { (uint16_t)covered, (uint16_t)u.taps, (uint16_t)r->filter },
                    .aux = { (float)(a[i].s * W), (float)(a[i].t * H), u.lambda, (float)u.level0,
                             (float)u.level1, u.mix });
            bool two = u.level1 != u.level0 && u.mix != 0;
            COUNT(r->tr, r->filter == FILTER_NEAREST ? 0 : (unsigned)u.taps * (two ? 2 : 1),
                  BILINEAR_TAP_COST);
            COUNT(r->tr, r->filter == FILTER_NEAREST ? 0 : 1, LOD_COST);
            COUNT(r->tr, two ? (unsigned)u.taps : 0, MIX_COST);
            COUNT(r->tr, 1, MODULATE_COST);
            rgba = tex_modulate(texel, a[i].rgb[0], a[i].rgb[1], a[i].rgb[2]);
        }
        PLOT(r->fb, r->tr, L_WRITE, x, y, a[i].z, rgba);
    }
}

/* --- blocks (lesson 05), then quads ---------------------------------------------- */

void textures_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr, const struct tex_stages *st,
                        struct tex_options o)
{
    NARRATE_SETUP(tr, t, L_SETUP);
    if (t->empty)
        return;
    o.affine = o.affine || p->knob[P_AFFINE];
    struct run r = { .t = t, .p = p, .fb = fb, .tr = tr, .tex = p->texture, .st = st, .o = o,
                     .filter = o.no_mipmaps ? FILTER_BILINEAR : tex_filter_of(p),
                     .max_aniso = tex_max_aniso_of(p), .inv_area2 = 1.0 / (double)t->area2 };
    biased_edges_setup(&r.e, t, true);
    for (int k = 0; k < 3; k++) {
        const struct vertex *v = &t->v[k];
        r.q[k] = 1 / v->z;
        r.sq[k] = v->s * r.q[k], r.tq[k] = v->t * r.q[k];
        r.cz[k][0] = v->r, r.cz[k][1] = v->g, r.cz[k][2] = v->b;
        for (int i = 0; i < 3; i++)
            r.cq[k][i] = r.cz[k][i] * r.q[k];
    }
    /* the exhibit's linear (s, t) and the analytic derivatives (which need
     * 1/z itself) keep the weights */
    r.by_reciprocal = r.tex && !o.affine && o.lod != LOD_ANALYTIC;
    if (r.tex)
        tex_tie_bounds(t, r.tex->level[0].w, r.tex->level[0].h, r.tie);
    for (int by = t->miny - t->miny % TEX_BLOCK; by <= t->maxy; by += TEX_BLOCK) {
        int ya = by < t->miny ? t->miny : by;
        int yb = by + TEX_BLOCK - 1 > t->maxy ? t->maxy : by + TEX_BLOCK - 1;
        for (int bx = t->minx - t->minx % TEX_BLOCK; bx <= t->maxx; bx += TEX_BLOCK) {
            int xa = bx < t->minx ? t->minx : bx;
            int xb = bx + TEX_BLOCK - 1 > t->maxx ? t->maxx : bx + TEX_BLOCK - 1;
            /* lesson 05's corners; a block that is not empty is walked quad by
             * quad, full or partial: its quads still evaluate four centres each,
             * and a pixel's edge test costs little beside its texels */
            bool empty = tex_block_empty(&r.e, xa, ya, xb, yb);
            COUNT(tr, 3, CORNERS_COST);
            int line = empty ? L_EMPTY : L_QUADS;
            NARRATE(tr, .kind = TRACE_BLOCK, .line = (uint8_t)line, .span = (uint8_t)(line - L_BLOCKS),
                    .x = xa, .y = ya, .x1 = xb, .y1 = yb,
                    .klass = (uint8_t)(empty ? BLOCK_EMPTY : BLOCK_PARTIAL), .aux = { TEX_BLOCK });
            if (empty)
                continue;
            /* blocks start on even pixels, so a quad never straddles two */
            for (int qy = ya & ~1; qy <= yb; qy += 2)
                for (int qx = xa & ~1; qx <= xb; qx += 2)
                    quad(&r, qx, qy, xa, ya, xb, yb);
        }
    }
}

/* --- the variants ------------------------------------------------------------------- */

static void rasterize_quads(const struct tri_setup *t, const struct raster_params *p,
                            struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .lod = LOD_COARSE });
}

static void rasterize_no_mipmaps(const struct tri_setup *t, const struct raster_params *p,
                                 struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .no_mipmaps = true });
}

static void rasterize_affine(const struct tri_setup *t, const struct raster_params *p,
                             struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .affine = true });
}

static void rasterize_fine(const struct tri_setup *t, const struct raster_params *p,
                           struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .lod = LOD_FINE });
}

static void rasterize_analytic(const struct tri_setup *t, const struct raster_params *p,
                               struct target *fb, struct trace *tr)
{
    textures_rasterize(t, p, fb, tr, &tex_stages_lesson, (struct tex_options){ .lod = LOD_ANALYTIC });
}

static const struct lesson_variant variants[] = {
    { .name = "quads", .kind = VARIANT_ALGORITHM, .rasterize = rasterize_quads,
      .what = "8 x 8 blocks, then 2 x 2 quads with helper pixels, coarse derivatives" },
    { .name = "quads-sse", .kind = VARIANT_TWIN, .rasterize = tex_rasterize_sse,
      .what = "the same quads, four pixels in four SSE lanes" },
    { .name = "no-mipmaps", .kind = VARIANT_CONTRAST, .rasterize = rasterize_no_mipmaps,
      .what = "level 0 always, bilinear: minification aliases" },
    { .name = "affine", .kind = VARIANT_EXHIBIT, .rasterize = rasterize_affine,
      .what = "exhibit: (s, t) interpolated linearly in the screen (lesson 04's swim)" },
    { .name = "fine-lod", .kind = VARIANT_CONTRAST, .rasterize = rasterize_fine,
      .what = "fine derivatives: each pixel its own row's and column's differences" },
    { .name = "analytic-lod", .kind = VARIANT_CONTRAST, .rasterize = rasterize_analytic,
      .what = "analytic derivatives at each pixel centre, no quads needed" },
    { .name = "tiles", .kind = VARIANT_TWIN, .rasterize = tex_rasterize_tiled,
      .what = "the same quads on lesson 07's 64 x 64 tiles, bins and workers: colour and depth in "
              "cache, the textures shared, one worker per core (or --threads N)" },
};

_Static_assert(L_SETUP == TEX_LINE_SETUP && L_BLOCKS == TEX_LINE_BLOCKS,
               "the tiled twin tells its set-up and its steps of lesson 07 at these lines");
_Static_assert(TEX_P_THREADS == P_AFFINE + 1, "--threads is the row after --affine");

static const char *const filter_names[] = { "nearest", "bilinear", "mip-bilinear", "trilinear",
                                            "aniso" };

static const char *const compare[] = { "05-block-classification", NULL };

const struct lesson lesson_09 = {
    .id = "09-textures",
    .title = "texture mapping: quads, derivatives, mip-maps",
    .pseudocode = pseudocode,
    .builtin_scene = "texture-floor",
    .exhibit_scene = "texture-wall",
    .perspective = true,
    .variants = variants,
    .nvariants = sizeof variants / sizeof variants[0],
    .params = (const struct lesson_param[]){
        [P_FILTER] = { .option = "filter", .arg = "NAME", .name = "filter", .key = 'g',
                       .words = filter_names, .min = FILTER_NEAREST, .max = FILTER_ANISO,
                       .def = FILTER_TRILINEAR,
                       .help = "texture filter: nearest, bilinear, mip-bilinear, trilinear, aniso" },
        [P_MAX_ANISO] = { .option = "max-aniso", .arg = "N", .name = "max aniso", .key = ']',
                          .key_down = '[', .min = 1, .max = 16, .def = MAX_ANISO_DEFAULT,
                          .help = "most probes of the aniso filter (1..16)" },
        [P_AFFINE] = { .option = "affine", .name = "texturing",
                       .help = "texture affinely, not perspective-correct (lesson 04's exhibit)",
                       .words = (const char *const[]){ "perspective", "affine" },
                       .key = 'p', .min = 0, .max = 1 },
        [TEX_P_THREADS] = { .option = "threads", .arg = "N", .name = "threads",
                            .help = "worker threads of a tiled lesson, 1..64 (default: one per core)",
                            .min = 1, .max = 64 },
        { 0 } },
    .rasterize_scene = (const rasterize_scene_fn[]){ NULL, NULL, NULL, NULL, NULL, NULL,
                                                     tex_tiled_scene },
    .narration_units = tex_units,
    .cost_tested = (const struct cost_term[]){ COST_TERM(3, EDGE_VALUE_COST), { 0 } },
    .cost_covered = (const struct cost_term[]){
        COST_TERM(1, TEX_COLOUR_COST), COST_TERM(1, PACK_RGB_COST), { 0 } },
    .compare = compare,
    .texturing = "by its image: 2 x 2 quads with helper pixels, coarse derivatives, the level of "
                 "detail and --filter (trilinear by default), times the vertex colour",
    .exercise = { .write_line = L_WRITE, .textures = true, .lod_line = L_LOD },
};
