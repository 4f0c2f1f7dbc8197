/* testlib.c - shared helpers of the test suite (see testlib.h). */
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */

#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --- random numbers ------------------------------------------------------------ */

uint64_t test_seed(void)
{
    const char *s = getenv("TRISTEP_SEED");
    if (s && *s) {
        char *end;
        unsigned long long v = strtoull(s, &end, 0);
        if (*end == '\0')
            return v;
        fprintf(stderr, "TRISTEP_SEED='%s' is not a number; using the default seed\n", s);
    }
    return TEST_DEFAULT_SEED;
}

/* splitmix64 (Steele, Lea, Flood 2014): one add and a mix per number. */
uint64_t rng_next(struct rng *r)
{
    uint64_t z = (r->state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

struct rng rng_for(uint64_t salt)
{
    struct rng r = { test_seed() ^ (salt * 0xd1b54a32d192ed03u) };
    rng_next(&r);
    return r;
}

double rng_unit(struct rng *r)
{
    return (double)(rng_next(r) >> 11) * 0x1p-53;
}

double rng_range(struct rng *r, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(r);
}

int rng_int(struct rng *r, int lo, int hi)
{
    return lo + (int)(rng_next(r) % (uint64_t)(hi - lo + 1));
}

bool rng_chance(struct rng *r, double p)
{
    return rng_unit(r) < p;
}

/* --- random triangles ------------------------------------------------------------- */

const char *tri_category_name(enum tri_category c)
{
    static const char *const names[CAT_COUNT] = {
        "generic", "sliver", "tiny", "large", "offscreen", "degenerate", "centres", "axis",
    };
    return c < CAT_COUNT ? names[c] : "?";
}

struct vertex test_vertex(double x, double y)
{
    return (struct vertex){ .x = x, .y = y, .z = 1, .r = 0.5, .g = 0.5, .b = 0.5 };
}

/* Largest coordinate a generated vertex may have: inside [-16384, 16384). */
#define GEN_LIMIT (COORD_LIMIT - 1.0 / SUBPIXEL_ONE)

static double clamp_coord(double v)
{
    return v < -COORD_LIMIT ? -COORD_LIMIT : v > GEN_LIMIT ? GEN_LIMIT : v;
}

/* Put a coordinate in one of the interesting places near v. */
static double shape_coord(struct rng *r, double v)
{
    switch (rng_int(r, 0, 5)) {
    case 0: return v;                                               /* off the grid */
    case 1: return round(v * SUBPIXEL_ONE) / SUBPIXEL_ONE;          /* on the grid */
    case 2: return (floor(v * SUBPIXEL_ONE) + 0.5) / SUBPIXEL_ONE;  /* a snapping tie */
    case 3: return floor(v) + 0.5;                                  /* a pixel centre */
    case 4: return round(v);                                        /* a pixel corner */
    default: return round(v * 4) / 4;                               /* quarter pixels */
    }
}

static struct vertex make_vertex(struct rng *r, double x, double y)
{
    return (struct vertex){
        .x = clamp_coord(x), .y = clamp_coord(y), .z = rng_range(r, 0.25, 8),
        .r = rng_unit(r), .g = rng_unit(r), .b = rng_unit(r),
        .s = rng_unit(r), .t = rng_unit(r),
    };
}

static void shaped_vertex(struct rng *r, double x, double y, struct vertex *out)
{
    *out = make_vertex(r, shape_coord(r, x), shape_coord(r, y));
}

static void random_winding(struct rng *r, struct vertex v[3])
{
    /* any of the six orders: both windings, any vertex first */
    int i = rng_int(r, 0, 2);
    struct vertex t = v[0]; v[0] = v[i]; v[i] = t;
    if (rng_chance(r, 0.5)) {
        t = v[1]; v[1] = v[2]; v[2] = t;
    }
}

void random_tri(struct rng *r, enum tri_category c, int w, int h, struct vertex v[3])
{
    double cx = rng_range(r, -2, w + 2), cy = rng_range(r, -2, h + 2);
    switch (c) {
    case CAT_GENERIC: {
        double s = rng_range(r, 1, 24);
        for (int i = 0; i < 3; i++)
            shaped_vertex(r, cx + rng_range(r, -s, s), cy + rng_range(r, -s, s), &v[i]);
        break;
    }
    case CAT_SLIVER: {
        double ax = cx + rng_range(r, -30, 30), ay = cy + rng_range(r, -30, 30);
        double bx = cx + rng_range(r, -30, 30), by = cy + rng_range(r, -30, 30);
        shaped_vertex(r, ax, ay, &v[0]);
        shaped_vertex(r, bx, by, &v[1]);
        if (rng_chance(r, 0.5)) {
            /* nearly on AB: a thin wedge along the whole edge */
            double t = rng_unit(r), d = rng_range(r, -0.6, 0.6);
            double len = hypot(bx - ax, by - ay) + 1e-9;
            double px = ax + t * (bx - ax) - d * (by - ay) / len;
            double py = ay + t * (by - ay) + d * (bx - ax) / len;
            v[2] = make_vertex(r, rng_chance(r, 0.5) ? px : round(px * 256) / 256,
                               rng_chance(r, 0.5) ? py : round(py * 256) / 256);
        } else {
            /* a short edge at the end of a long one */
            double d = rng_range(r, 1.0 / 256, 1.5), a = rng_range(r, 0, 6.283185307179586);
            v[2] = make_vertex(r, v[1].x + d * cos(a), v[1].y + d * sin(a));
        }
        break;
    }
    case CAT_TINY:
        for (int i = 0; i < 3; i++)
            shaped_vertex(r, cx + rng_range(r, -0.6, 0.6), cy + rng_range(r, -0.6, 0.6), &v[i]);
        break;
    case CAT_LARGE:
        for (int i = 0; i < 3; i++) {
            if (rng_chance(r, 0.1))     /* out at the coordinate limits */
                v[i] = make_vertex(r, rng_chance(r, 0.5) ? -COORD_LIMIT : GEN_LIMIT,
                                   rng_range(r, -COORD_LIMIT, COORD_LIMIT));
            else
                shaped_vertex(r, rng_range(r, -3.0 * w, 4.0 * w), rng_range(r, -3.0 * h, 4.0 * h), &v[i]);
        }
        break;
    case CAT_OFFSCREEN: {
        /* centred on a border of the target */
        switch (rng_int(r, 0, 3)) {
        case 0: cx = rng_range(r, -4, 4); break;
        case 1: cx = w + rng_range(r, -4, 4); break;
        case 2: cy = rng_range(r, -4, 4); break;
        default: cy = h + rng_range(r, -4, 4); break;
        }
        double s = rng_range(r, 1, w);
        for (int i = 0; i < 3; i++)
            shaped_vertex(r, cx + rng_range(r, -s, s), cy + rng_range(r, -s, s), &v[i]);
        break;
    }
    case CAT_DEGENERATE: {
        /* exactly collinear after snapping: grid points A + m * d */
        double ax = round(cx * 256) / 256, ay = round(cy * 256) / 256;
        double dx = rng_int(r, -512, 512) / 256.0, dy = rng_int(r, -512, 512) / 256.0;
        if (rng_chance(r, 0.25))
            dx = 0;
        else if (rng_chance(r, 0.25))
            dy = 0;
        int m1 = rng_int(r, -8, 8), m2 = rng_int(r, -8, 8);
        switch (rng_int(r, 0, 2)) {
        case 0: break;                          /* collinear */
        case 1: m2 = m1; break;                 /* a repeated vertex */
        default: m1 = m2 = 0; break;            /* all three the same point */
        }
        v[0] = make_vertex(r, ax, ay);
        v[1] = make_vertex(r, ax + m1 * dx, ay + m1 * dy);
        v[2] = make_vertex(r, ax + m2 * dx, ay + m2 * dy);
        break;
    }
    case CAT_CENTRES: {
        int s = rng_int(r, 1, 16);
        for (int i = 0; i < 3; i++)
            v[i] = make_vertex(r, floor(cx) + rng_int(r, -s, s) + 0.5, floor(cy) + rng_int(r, -s, s) + 0.5);
        break;
    }
    case CAT_AXIS:
    default: {
        double s = rng_range(r, 0.5, 20);
        double x0 = shape_coord(r, cx - rng_range(r, 0, s)), x1 = shape_coord(r, cx + rng_range(r, 0, s));
        double y0 = shape_coord(r, cy - rng_range(r, 0, s)), y1 = shape_coord(r, cy + rng_range(r, 0, s));
        switch (rng_int(r, 0, 2)) {
        case 0:     /* horizontal edge, third vertex above or below */
            v[0] = make_vertex(r, x0, y0);
            v[1] = make_vertex(r, x1, y0);
            v[2] = make_vertex(r, shape_coord(r, cx + rng_range(r, -s, s)), rng_chance(r, 0.5) ? y1 : 2 * y0 - y1);
            break;
        case 1:     /* vertical edge, third vertex left or right */
            v[0] = make_vertex(r, x0, y0);
            v[1] = make_vertex(r, x0, y1);
            v[2] = make_vertex(r, rng_chance(r, 0.5) ? x1 : 2 * x0 - x1, shape_coord(r, cy + rng_range(r, -s, s)));
            break;
        default:    /* a right angle: one horizontal and one vertical edge */
            v[0] = make_vertex(r, x0, y0);
            v[1] = make_vertex(r, x1, y0);
            v[2] = make_vertex(r, rng_chance(r, 0.5) ? x0 : x1, y1);
            break;
        }
        break;
    }
    }
    random_winding(r, v);
}

/* --- lessons -------------------------------------------------------------------- */

int exact_variants(struct test_variant *out, int max, int builds)
{
    int n = 0;
    for (int b = 0; b < 2; b++) {
        if (!(builds & (b == 0 ? BUILD_NARRATED : BUILD_FAST)))
            continue;
        const struct lesson *const *list = b == 0 ? all_lessons : all_lessons_fast;
        for (int i = 0; list[i]; i++)
            for (int k = 0; k < list[i]->nvariants; k++) {
                if (variant_against_exact(&list[i]->variants[k]))
                    continue;
                if (n < max)
                    out[n] = (struct test_variant){ list[i], &list[i]->variants[k], b == 0 };
                n++;
            }
    }
    return n;
}

const char *variant_label(const struct test_variant *tv, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s (%s)", tv->lesson->id, tv->variant->name,
             tv->narrated ? "narrated" : "fast");
    return buf;
}

struct raster_params default_params(void)
{
    return (struct raster_params){ .subpixel_bits = SUBPIXEL_BITS };
}

void rasterize_one(const struct lesson_variant *v, const struct raster_params *p,
                   const struct tri_setup *t, struct target *fb, struct trace *tr)
{
    struct raster_params def = default_params();
    v->rasterize(t, p ? p : &def, fb, tr);
}

struct mask_ctx {
    uint8_t *mask;
    int w;
};

static void mask_cover(void *ctx, int x, int y)
{
    struct mask_ctx *m = ctx;
    uint8_t *c = &m->mask[(size_t)y * (size_t)m->w + (size_t)x];
    if (*c < 255)
        (*c)++;
}

void reference_mask(const struct tri_setup *t, uint8_t *mask)
{
    struct mask_ctx m = { mask, t->target_w };
    reference_coverage(t, mask_cover, &m);
}

uint8_t *reference_scene(const struct scene *s)
{
    uint8_t *ref = calloc((size_t)s->w * (size_t)s->h, 1);
    for (int i = 0; ref && i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup(&t, s->tris[i].v, s->w, s->h);
        reference_mask(&t, ref);
    }
    return ref;
}

static int channel(uint32_t c, int k)
{
    return (int)(c >> (16 - 8 * k) & 255);
}

int reference_shading_check(const struct target *fb, const struct tri_setup *t, int tolerance,
                            double depth_rel, char *why, size_t n)
{
    int checked = 0;
    for (int y = 0; y < fb->h; y++)
        for (int x = 0; x < fb->w; x++) {
            size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
            if (!fb->count[i])
                continue;
            double z, rgb[3], st[2];
            reference_shade(t, x, y, true, &z, rgb, st);
            uint32_t want = pack_rgb(rgb[0], rgb[1], rgb[2]);
            for (int c = 0; c < 3; c++)
                if (abs(channel(fb->color[i], c) - channel(want, c)) > tolerance) {
                    snprintf(why, n, "pixel (%d, %d) channel %d is %d, the reference %d", x, y, c,
                             channel(fb->color[i], c), channel(want, c));
                    return -1;
                }
            if (!(fabs(fb->depth[i] - z) <= depth_rel * z)) {
                snprintf(why, n, "pixel (%d, %d) z = %.9g, the reference %.9g", x, y, fb->depth[i], z);
                return -1;
            }
            checked++;
        }
    return checked;
}

/* --- reporting ---------------------------------------------------------------------- */

void print_case(const struct case_info *info)
{
    fprintf(stderr, "FAILED: %s\n  replay: TRISTEP_SEED=0x%llx, case %llu\n",
            info->what ? info->what : "", (unsigned long long)info->seed,
            (unsigned long long)info->index);
    for (int i = 0; info->v && i < info->nv; i++)
        fprintf(stderr, "  %c = (%.17g, %.17g)%s", "ABC"[i % 3], info->v[i].x, info->v[i].y,
                i % 3 == 2 || i == info->nv - 1 ? "\n" : "");
}

static char cell(uint8_t c)
{
    return c == 0 ? '.' : c == 1 ? '#' : c < 10 ? (char)('0' + c) : '+';
}

#define ART_RADIUS 8

bool coverage_equal(const uint8_t *expected, const uint8_t *actual, int w, int h,
                    const struct case_info *info)
{
    size_t n = (size_t)w * (size_t)h, first = 0;
    while (first < n && expected[first] == actual[first])
        first++;
    if (first == n)
        return true;

    int fx = (int)(first % (size_t)w), fy = (int)(first / (size_t)w);
    size_t diffs = 0;
    for (size_t i = first; i < n; i++)
        diffs += expected[i] != actual[i];
    print_case(info);
    fprintf(stderr, "  %zu pixel(s) differ; first at (%d, %d): expected %d, got %d\n",
            diffs, fx, fy, expected[first], actual[first]);
    fprintf(stderr, "  ('.' uncovered, '#' covered once, digits: covered that often, "
                    "'X' differs)\n");
    int x0 = fx - ART_RADIUS < 0 ? 0 : fx - ART_RADIUS;
    int x1 = fx + ART_RADIUS >= w ? w - 1 : fx + ART_RADIUS;
    int y0 = fy - ART_RADIUS < 0 ? 0 : fy - ART_RADIUS;
    int y1 = fy + ART_RADIUS >= h ? h - 1 : fy + ART_RADIUS;
    int cols = x1 - x0 + 1;
    fprintf(stderr, "  columns x = %d..%d, rows y = %d..%d\n", x0, x1, y0, y1);
    fprintf(stderr, "  %5s  %-*s  %-*s  %s\n", "y", cols, "expected", cols, "actual", "diff");
    for (int y = y0; y <= y1; y++) {
        fprintf(stderr, "  %5d  ", y);
        for (int pass = 0; pass < 3; pass++) {
            for (int x = x0; x <= x1; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                char ch = pass == 0 ? cell(expected[i]) : pass == 1 ? cell(actual[i])
                        : expected[i] != actual[i] ? 'X' : '.';
                fputc(ch, stderr);
            }
            fputs(pass < 2 ? "  " : "\n", stderr);
        }
    }
    return false;
}

const char *test_build_dir(void)
{
    const char *b = getenv("TRISTEP_BUILD");
    return b && *b ? b : "build";
}

/* --- a scratch folder ------------------------------------------------------------ */

static char scratch[64];

void test_scratch_make(void)
{
    snprintf(scratch, sizeof scratch, "/tmp/tristep-test-XXXXXX");
    if (!mkdtemp(scratch)) {
        fprintf(stderr, "cannot make a scratch folder %s\n", scratch);
        abort();
    }
}

void test_scratch_remove(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch);
    if (scratch[0] && system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", scratch);
    scratch[0] = '\0';
}

const char *test_scratch_dir(void)
{
    return scratch;
}

const char *test_scratch_path(const char *name)
{
    static char paths[4][256];
    static int slot;
    char *p = paths[slot++ % 4];
    snprintf(p, sizeof paths[0], "%s/%s", scratch, name);
    return p;
}

void test_scratch_put(const char *name, const void *data, size_t n)
{
    const char *path = test_scratch_path(name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, n, f) != n || fclose(f) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        abort();
    }
}

void test_scratch_text(const char *name, const char *text)
{
    test_scratch_put(name, text, strlen(text));
}

/* --- numbers the texts quote ------------------------------------------------- */

const char *test_read_text(const char *path)
{
    static char text[1 << 18];
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s not found (run the tests from the project's top folder)\n", path);
        abort();
    }
    size_t n = fread(text, 1, sizeof text - 1, f);
    bool whole = feof(f);
    fclose(f);
    if (!whole) {
        fprintf(stderr, "%s is longer than %zu bytes\n", path, sizeof text - 1);
        abort();
    }
    text[n] = '\0';
    return text;
}

double number_before(const char *text, const char *m, double *tol)
{
    const char *e = m;
    while (e > text && (e[-1] == '*' || e[-1] == '`'))
        e--;
    const char *b = e;
    while (b > text && strchr("0123456789.,", b[-1]))
        b--;
    if (b > text + 1 && b[-1] == '-' && strchr("eE", b[-2]))
        for (b -= 2; b > text && strchr("0123456789.", b[-1]); b--)
            ;
    char num[64];
    size_t n = 0;
    for (const char *p = b; p < e && n + 1 < sizeof num; p++)
        if (*p != ',')
            num[n++] = *p;
    num[n] = '\0';
    char *stop;
    double v = strtod(num, &stop);
    if (n == 0 || *stop)
        return NAN;
    const char *dot = strchr(num, '.'), *ex = strpbrk(num, "eE");
    int digits = dot ? (int)((ex ? ex : num + n) - dot - 1) : 0;
    int exponent = ex ? atoi(ex + 1) : 0;
    if (tol)
        *tol = 0.5 * pow(10, exponent - digits);
    return v;
}

double text_number(const char *path, const char *key, double *tol)
{
    const char *text = test_read_text(path);
    char marker[128];
    snprintf(marker, sizeof marker, "<!--=%s-->", key);
    const char *at = strstr(text, marker);
    double v = at ? number_before(text, at, tol) : NAN;
    if (isnan(v)) {
        fprintf(stderr, "%s quotes no number marked %s\n", path, marker);
        abort();
    }
    return v;
}

/* --- narration ----------------------------------------------------------------- */

void test_collect(void *ctx, const struct trace_event *ev)
{
    struct test_events *e = ctx;
    if (e->n == e->cap) {
        e->cap = e->cap ? 2 * e->cap : 4096;
        e->ev = realloc(e->ev, e->cap * sizeof *e->ev);
        if (!e->ev) {
            fprintf(stderr, "out of memory collecting events\n");
            abort();
        }
    }
    e->ev[e->n++] = *ev;
}
