/* texref.c - the independent reference for textured pixels (texref.h),
 * each rule of lessons/CONVENTIONS.md "Textures" written out where it is used. */
#include "texref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *texref_filter_name(enum texref_filter f)
{
    static const char *const names[TEXREF_FILTERS] = { "nearest", "bilinear", "mip-bilinear",
                                                       "trilinear", "aniso" };
    return f >= 0 && f < TEXREF_FILTERS ? names[f] : "?";
}

/* --- the pyramid ---------------------------------------------------------------- */

static bool power_of_two(int n)
{
    for (int p = 1; p <= 4096; p *= 2)
        if (n == p)
            return true;
    return false;
}

bool texref_init(struct texref *r, int w, int h, const uint32_t *image, enum texref_wrap wrap)
{
    memset(r, 0, sizeof *r);
    r->wrap = wrap;
    if (!power_of_two(w) || !power_of_two(h))
        return false;
    /* level 0: the image, channel by channel */
    r->w[0] = w, r->h[0] = h;
    r->rgb[0] = malloc((size_t)w * h * 3);
    if (!r->rgb[0])
        return false;
    for (long i = 0; i < (long)w * h; i++) {
        r->rgb[0][3 * i + 0] = (uint8_t)(image[i] >> 16);
        r->rgb[0][3 * i + 1] = (uint8_t)(image[i] >> 8);
        r->rgb[0][3 * i + 2] = (uint8_t)image[i];
    }
    r->nlevels = 1;
    /* level k + 1: max(1, W/2) x max(1, H/2), each texel the integer mean of
     * the texels of level k it covers, rounded half up: (sum + n/2) / n */
    for (int k = 0; r->w[k] > 1 || r->h[k] > 1; k++) {
        int nw = r->w[k] > 1 ? r->w[k] / 2 : 1, nh = r->h[k] > 1 ? r->h[k] / 2 : 1;
        int fx = r->w[k] / nw, fy = r->h[k] / nh;       /* 2 or 1 */
        uint8_t *out = malloc((size_t)nw * nh * 3);
        if (!out) {
            texref_free(r);
            return false;
        }
        for (int y = 0; y < nh; y++)
            for (int x = 0; x < nw; x++)
                for (int c = 0; c < 3; c++) {
                    int sum = 0, n = fx * fy;
                    for (int j = 0; j < fy; j++)
                        for (int i = 0; i < fx; i++)
                            sum += r->rgb[k][3 * ((fy * y + j) * r->w[k] + fx * x + i) + c];
                    out[3 * (y * nw + x) + c] = (uint8_t)((sum + n / 2) / n);
                }
        r->w[k + 1] = nw, r->h[k + 1] = nh, r->rgb[k + 1] = out;
        r->nlevels = k + 2;
    }
    return true;
}

void texref_free(struct texref *r)
{
    for (int k = 0; k < TEXREF_LEVELS; k++)
        free(r->rgb[k]);
    memset(r, 0, sizeof *r);
}

/* repeat: i mod n, the mathematical one (never negative); clamp: 0..n-1 */
static long long wrap_index(long long i, int n, enum texref_wrap wrap)
{
    if (wrap == TEXREF_CLAMP)
        return i < 0 ? 0 : i > n - 1 ? n - 1 : i;
    long long m = i - (long long)n * (long long)floor((double)i / n);
    return m;
}

void texref_texel(const struct texref *r, int k, long long i, long long j, double out[3])
{
    long long x = wrap_index(i, r->w[k], r->wrap), y = wrap_index(j, r->h[k], r->wrap);
    for (int c = 0; c < 3; c++)
        out[c] = r->rgb[k][3 * (y * r->w[k] + x) + c];
}

/* --- filters ---------------------------------------------------------------------- */

static void nearest(const struct texref *r, double s, double t, double out[3])
{
    double u = s * r->w[0], v = t * r->h[0];
    texref_texel(r, 0, (long long)floor(u), (long long)floor(v), out);
}

/* i0 = floor(u - 1/2), a = frac(u - 1/2); the four texels weighted
 * (1-a)(1-b), a(1-b), (1-a)b, ab */
void texref_bilinear(const struct texref *r, int k, double s, double t, double out[3])
{
    double u = s * r->w[k] - 0.5, v = t * r->h[k] - 0.5;
    double i0 = floor(u), j0 = floor(v), a = u - i0, b = v - j0;
    double c00[3], c10[3], c01[3], c11[3];
    texref_texel(r, k, (long long)i0, (long long)j0, c00);
    texref_texel(r, k, (long long)i0 + 1, (long long)j0, c10);
    texref_texel(r, k, (long long)i0, (long long)j0 + 1, c01);
    texref_texel(r, k, (long long)i0 + 1, (long long)j0 + 1, c11);
    for (int c = 0; c < 3; c++)
        out[c] = (1 - a) * (1 - b) * c00[c] + a * (1 - b) * c10[c] + (1 - a) * b * c01[c]
               + a * b * c11[c];
}

static double clamp_lambda(const struct texref *r, double lambda)
{
    double last = r->nlevels - 1;
    return lambda < 0 ? 0 : lambda > last ? last : lambda;
}

/* levels floor(lambda) and floor(lambda) + 1 (the last twice at the end),
 * mixed by frac(lambda) */
void texref_trilinear(const struct texref *r, double lambda, double s, double t, double out[3])
{
    lambda = clamp_lambda(r, lambda);
    int k0 = (int)floor(lambda), k1 = k0 + 1 < r->nlevels ? k0 + 1 : k0;
    double f = lambda - k0, a[3], b[3];
    texref_bilinear(r, k0, s, t, a);
    texref_bilinear(r, k1, s, t, b);
    for (int c = 0; c < 3; c++)
        out[c] = (1 - f) * a[c] + f * b[c];
}

double texref_rho(const struct texref_deriv *d)
{
    double px = sqrt(d->dudx * d->dudx + d->dvdx * d->dvdx);
    double py = sqrt(d->dudy * d->dudy + d->dvdy * d->dvdy);
    return px > py ? px : py;
}

double texref_lambda(const struct texref_deriv *d)
{
    return log2(texref_rho(d));
}

void texref_sample(const struct texref *r, enum texref_filter f, int max_aniso, double s, double t,
                   const struct texref_deriv *d, double out[3])
{
    if (f == TEXREF_NEAREST) {
        nearest(r, s, t, out);
        return;
    }
    double last = r->nlevels - 1;
    double lambda = d->beyond_horizon ? last : texref_lambda(d);
    if (f == TEXREF_BILINEAR || !(lambda > 0)) {
        /* lambda <= 0 magnifies: level 0, bilinear (for aniso too: rho is
         * its P_max, and no footprint longer than a texel needs taps) */
        texref_bilinear(r, 0, s, t, out);
        return;
    }
    if (f == TEXREF_MIP_BILINEAR) {
        lambda = clamp_lambda(r, lambda);
        int k = lambda <= 0.5 ? 0 : (int)ceil(lambda + 0.5) - 1;    /* ties to the finer */
        texref_bilinear(r, k, s, t, out);
        return;
    }
    if (f == TEXREF_TRILINEAR || d->beyond_horizon) {
        texref_trilinear(r, lambda, s, t, out);
        return;
    }
    /* aniso: P_max, P_min the longer and shorter derivative; n taps along
     * the longer one at ((i + 1/2)/n - 1/2) times it, each trilinear at
     * lambda = log2(P_max / n), averaged */
    double px = sqrt(d->dudx * d->dudx + d->dvdx * d->dvdx);
    double py = sqrt(d->dudy * d->dudy + d->dvdy * d->dvdy);
    double pmax = px >= py ? px : py, pmin = px >= py ? py : px;
    double du = px >= py ? d->dudx : d->dudy, dv = px >= py ? d->dvdx : d->dvdy;
    int n;
    if (pmax == 0)
        n = 1;
    else if (pmin == 0)
        n = max_aniso;
    else {
        double ratio = ceil(pmax / pmin);
        n = ratio < max_aniso ? (int)ratio : max_aniso;
    }
    double la = log2(pmax / n);
    out[0] = out[1] = out[2] = 0;
    for (int i = 0; i < n; i++) {
        double o = (i + 0.5) / n - 0.5, tap[3];
        texref_trilinear(r, la, s + o * du / r->w[0], t + o * dv / r->h[0], tap);
        for (int c = 0; c < 3; c++)
            out[c] += tap[c] / n;
    }
}

/* --- triangles: coverage, quads, derivatives ------------------------------------ */

bool texref_target_init(struct texref_target *fb, int w, int h, uint32_t background)
{
    memset(fb, 0, sizeof *fb);
    fb->w = w, fb->h = h;
    size_t n = (size_t)w * h;
    fb->color = malloc(n * sizeof *fb->color);
    fb->z = malloc(n * sizeof *fb->z);
    fb->covered = calloc(n, 1);
    if (!fb->color || !fb->z || !fb->covered) {
        texref_target_free(fb);
        return false;
    }
    for (size_t i = 0; i < n; i++)
        fb->color[i] = background, fb->z[i] = INFINITY;
    return true;
}

void texref_target_free(struct texref_target *fb)
{
    free(fb->color);
    free(fb->z);
    free(fb->lambda);
    free(fb->elongation);
    free(fb->covered);
    memset(fb, 0, sizeof *fb);
}

/* The triangle as the rules see it: snapped to 1/256, counter-clockwise in
 * the sense that every edge function is positive inside. */
struct snapped {
    long long X[3], Y[3], area2;
    struct vertex v[3];
};

/* E_ab(P) = (Xb - Xa)(Py - Ya) - (Yb - Ya)(Px - Xa), P in 1/256 units */
static long long edge(const struct snapped *t, int a, int b, long long px, long long py)
{
    return (t->X[b] - t->X[a]) * (py - t->Y[a]) - (t->Y[b] - t->Y[a]) * (px - t->X[a]);
}

/* top edge: horizontal, interior below (dx > 0 here); left edge: interior
 * at larger x (dy < 0 here) */
static bool top_left(const struct snapped *t, int a, int b)
{
    long long dx = t->X[b] - t->X[a], dy = t->Y[b] - t->Y[a];
    return dy < 0 || (dy == 0 && dx > 0);
}

static bool snap(struct snapped *t, const struct vertex v[3])
{
    for (int k = 0; k < 3; k++) {
        t->v[k] = v[k];
        t->X[k] = lrint(v[k].x * 256);
        t->Y[k] = lrint(v[k].y * 256);
    }
    t->area2 = edge(t, 0, 1, t->X[2], t->Y[2]);
    if (t->area2 < 0) {                                 /* the other winding: swap B and C */
        struct vertex sv = t->v[1];
        long long sx = t->X[1], sy = t->Y[1];
        t->v[1] = t->v[2], t->X[1] = t->X[2], t->Y[1] = t->Y[2];
        t->v[2] = sv, t->X[2] = sx, t->Y[2] = sy;
        t->area2 = -t->area2;
    }
    return t->area2 > 0;
}

static bool covered(const struct snapped *t, int x, int y)
{
    long long px = 256LL * x + 128, py = 256LL * y + 128;
    for (int k = 0; k < 3; k++) {
        long long e = edge(t, k, (k + 1) % 3, px, py);
        if (e < 0 || (e == 0 && !top_left(t, k, (k + 1) % 3)))
            return false;
    }
    return true;
}

/* What is interpolated at a pixel centre (a helper's too): 1/z, and the
 * perspective-correct s, t, r, g, b (when 1/z > 0). */
struct at_pixel {
    double q, z, s, t, rgb[3];
};

static struct at_pixel interpolate_at(const struct snapped *t, long long px, long long py)
{
    double b[3] = { (double)edge(t, 1, 2, px, py) / t->area2,   /* weight of vertex 0 */
                    (double)edge(t, 2, 0, px, py) / t->area2,
                    (double)edge(t, 0, 1, px, py) / t->area2 };
    struct at_pixel a = { 0 };
    double s = 0, tt = 0, c[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; k++) {
        double w = b[k] / t->v[k].z;
        a.q += w;
        s += w * t->v[k].s, tt += w * t->v[k].t;
        c[0] += w * t->v[k].r, c[1] += w * t->v[k].g, c[2] += w * t->v[k].b;
    }
    if (a.q > 0) {
        a.z = 1 / a.q, a.s = s / a.q, a.t = tt / a.q;
        for (int i = 0; i < 3; i++)
            a.rgb[i] = c[i] / a.q;
    }
    return a;
}

/* ... at the centre of pixel (x, y) */
static struct at_pixel interpolate(const struct snapped *t, int x, int y)
{
    return interpolate_at(t, 256LL * x + 128, 256LL * y + 128);
}

/* P_max / P_min of the derivatives */
static double elongation(const struct texref_deriv *d)
{
    double px = sqrt(d->dudx * d->dudx + d->dvdx * d->dvdx);
    double py = sqrt(d->dudy * d->dudy + d->dvdy * d->dvdy);
    double lo = px < py ? px : py, hi = px < py ? py : px;
    return lo > 0 ? hi / lo : INFINITY;
}

/* round(c * 255), halves away from zero, after clamping to [0, 1] */
static uint32_t channel(double c)
{
    c = c > 1 ? 1 : c > 0 ? c : 0;
    return (uint32_t)round(c * 255);
}

void texref_draw_tri(struct texref_target *fb, const struct vertex v[3], const struct texref *tex,
                     enum texref_filter f, int max_aniso)
{
    struct snapped t;
    if (!snap(&t, v))
        return;                                         /* zero area covers nothing */
    long long minx = t.X[0], maxx = t.X[0], miny = t.Y[0], maxy = t.Y[0];
    for (int k = 1; k < 3; k++) {
        minx = t.X[k] < minx ? t.X[k] : minx, maxx = t.X[k] > maxx ? t.X[k] : maxx;
        miny = t.Y[k] < miny ? t.Y[k] : miny, maxy = t.Y[k] > maxy ? t.Y[k] : maxy;
    }
    int x0 = (int)(minx / 256 - 1), x1 = (int)(maxx / 256 + 1);
    int y0 = (int)(miny / 256 - 1), y1 = (int)(maxy / 256 + 1);
    x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > fb->w - 1 ? fb->w - 1 : x1, y1 = y1 > fb->h - 1 ? fb->h - 1 : y1;
    for (int qy = y0 & ~1; qy <= y1; qy += 2)
        for (int qx = x0 & ~1; qx <= x1; qx += 2) {
            bool in[2][2];
            int n = 0;
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 2; i++) {
                    int x = qx + i, y = qy + j;
                    in[j][i] = x < fb->w && y < fb->h && covered(&t, x, y);
                    n += in[j][i];
                }
            if (n == 0)
                continue;
            /* every pixel centre of the quad, helpers included */
            struct at_pixel a[2][2];
            bool beyond = false;
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 2; i++) {
                    a[j][i] = interpolate(&t, qx + i, qy + j);
                    beyond |= !(a[j][i].q > 0);
                }
            fb->helpers += 4 - n;
            fb->shaded += n;
            /* coarse derivatives at the quad's top-left pixel, level-0 texels */
            struct texref_deriv d = { .beyond_horizon = beyond };
            if (tex && !beyond) {
                double W = tex->w[0], H = tex->h[0];
                d.dudx = (a[0][1].s - a[0][0].s) * W, d.dvdx = (a[0][1].t - a[0][0].t) * H;
                d.dudy = (a[1][0].s - a[0][0].s) * W, d.dvdy = (a[1][0].t - a[0][0].t) * H;
            }
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < 2; i++) {
                    if (!in[j][i])
                        continue;
                    const struct at_pixel *p = &a[j][i];
                    size_t idx = (size_t)(qy + j) * fb->w + (size_t)(qx + i);
                    if (fb->covered[idx] < 255)
                        fb->covered[idx]++;
                    if (!(p->z < fb->z[idx]))
                        continue;                       /* nearer wins, ties keep the earlier */
                    double texel[3] = { 255, 255, 255 };
                    if (tex)
                        texref_sample(tex, f, max_aniso, p->s, p->t, &d, texel);
                    fb->z[idx] = p->z;
                    if (tex && fb->lambda)
                        fb->lambda[idx] = beyond ? INFINITY : (float)texref_lambda(&d);
                    if (tex && fb->elongation)
                        fb->elongation[idx] = (float)elongation(&d);
                    fb->color[idx] = 0xff000000u | channel(texel[0] / 255 * p->rgb[0]) << 16
                                   | channel(texel[1] / 255 * p->rgb[1]) << 8
                                   | channel(texel[2] / 255 * p->rgb[2]);
                }
        }
}

bool texref_draw_scene(struct texref_target *fb, const struct scene *s, enum texref_filter f,
                       int max_aniso)
{
    int n = scene_texture_count(s);
    struct texref *refs = calloc((size_t)n + 1, sizeof *refs);
    bool ok = refs != NULL;
    for (int k = 1; ok && k <= n; k++) {
        const struct texture *t = scene_texture(s, k);      /* its level 0 only */
        ok = texref_init(&refs[k], t->level[0].w, t->level[0].h, t->level[0].texel,
                         t->wrap == TEXTURE_CLAMP ? TEXREF_CLAMP : TEXREF_REPEAT);
    }
    for (int i = 0; ok && i < s->ntris; i++) {
        int k = s->tris[i].texture;
        texref_draw_tri(fb, s->tris[i].v, k >= 1 && k <= n ? &refs[k] : NULL, f, max_aniso);
    }
    for (int k = 0; refs && k <= n; k++)
        texref_free(&refs[k]);
    free(refs);
    return ok;
}

struct texref_diff texref_compare(const struct texref_target *ref, const struct target *fb, int levels)
{
    struct texref_diff d = { 0, 0, -1, -1 };
    for (int y = 0; y < ref->h && y < fb->h; y++)
        for (int x = 0; x < ref->w && x < fb->w; x++) {
            size_t i = (size_t)y * ref->w + x, j = (size_t)y * fb->w + x;
            if (fb->count && fb->count[j] != ref->covered[i])
                d.coverage++;
            if (!ref->covered[i])
                continue;
            bool near = true;
            for (int shift = 0; shift < 24; shift += 8) {
                int c = (int)(ref->color[i] >> shift & 255) - (int)(fb->color[j] >> shift & 255);
                near &= c <= levels && c >= -levels;
            }
            if (!near && d.colour++ == 0)
                d.x = x, d.y = y;
        }
    return d;
}

/* --- the ideal picture -------------------------------------------------------------- */

/* The mean of the level-0 texels under n x n samples of pixel (x, y), each
 * at its own perspective-correct (s, t) on the triangle's plane (those
 * beyond its horizon left out): false when none is left. */
static bool box_mean(const struct snapped *t, const struct texref *tex, int x, int y, int n,
                     double out[3])
{
    double sum[3] = { 0, 0, 0 };
    long used = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            /* sample (i, j) at ((i + 1/2) / n, (j + 1/2) / n) of the pixel, in 1/256 units */
            struct at_pixel a = interpolate_at(t, 256LL * x + (512LL * i + 256) / (2 * n),
                                               256LL * y + (512LL * j + 256) / (2 * n));
            if (!(a.q > 0))
                continue;
            double texel[3];
            texref_texel(tex, 0, (long long)floor(a.s * tex->w[0]), (long long)floor(a.t * tex->h[0]), texel);
            for (int c = 0; c < 3; c++)
                sum[c] += texel[c];
            used++;
        }
    for (int c = 0; c < 3; c++)
        out[c] = used ? sum[c] / (double)used : 0;
    return used > 0;
}

bool texref_ideal_scene(struct texref_ideal *id, const struct scene *s, int n)
{
    memset(id, 0, sizeof *id);
    id->w = s->w, id->h = s->h;
    size_t npx = (size_t)s->w * (size_t)s->h;
    id->rgb = calloc(3 * npx, sizeof *id->rgb);
    id->textured = calloc(npx, sizeof *id->textured);
    double *z = malloc(npx * sizeof *z);
    int ntex = scene_texture_count(s);
    struct texref *refs = calloc((size_t)ntex + 1, sizeof *refs);
    bool ok = id->rgb && id->textured && z && refs && n >= 1 && n <= 256;
    for (size_t i = 0; ok && i < npx; i++)
        z[i] = INFINITY;
    for (int k = 1; ok && k <= ntex; k++) {
        const struct texture *tx = scene_texture(s, k);        /* its level 0 only */
        ok = texref_init(&refs[k], tx->level[0].w, tx->level[0].h, tx->level[0].texel,
                         tx->wrap == TEXTURE_CLAMP ? TEXREF_CLAMP : TEXREF_REPEAT);
    }
    for (int i = 0; ok && i < s->ntris; i++) {
        struct snapped t;
        if (!snap(&t, s->tris[i].v))
            continue;
        int k = s->tris[i].texture;
        const struct texref *tex = k >= 1 && k <= ntex ? &refs[k] : NULL;
        for (int y = 0; y < s->h; y++)
            for (int x = 0; x < s->w; x++) {
                size_t p = (size_t)y * (size_t)s->w + (size_t)x;
                if (!covered(&t, x, y))
                    continue;
                struct at_pixel a = interpolate(&t, x, y);
                if (!(a.q > 0) || !(a.z < z[p]))
                    continue;                           /* nearer wins, ties keep the earlier */
                z[p] = a.z;
                double texel[3] = { 255, 255, 255 };
                id->textured[p] = tex && box_mean(&t, tex, x, y, n, texel);
                for (int c = 0; c < 3; c++) {
                    double v = a.rgb[c] > 1 ? 1 : a.rgb[c] > 0 ? a.rgb[c] : 0;
                    id->rgb[3 * p + c] = texel[c] * v;
                }
            }
    }
    for (int k = 0; refs && k <= ntex; k++)
        texref_free(&refs[k]);
    free(refs);
    free(z);
    if (!ok)
        texref_ideal_free(id);
    return ok;
}

void texref_ideal_free(struct texref_ideal *id)
{
    free(id->rgb);
    free(id->textured);
    memset(id, 0, sizeof *id);
}
