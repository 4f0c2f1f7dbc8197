/* scene.c - the scene file parser and writer. */
#include "scene.h"
#include "parse.h"      /* struct parser; the 3-D lines (scene3.c) */

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define MAX_TOKENS 32   /* more than the longest line needs (tri + 24 numbers) */

bool scene_fail(struct parser *p, const char *fmt, ...)
{
    int n = snprintf(p->err, p->errlen, "%s:%d: ", p->name, p->line);
    if (n < 0 || (size_t)n >= p->errlen)
        return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->err + n, p->errlen - (size_t)n, fmt, ap);
    va_end(ap);
    return false;
}
#define fail scene_fail     /* its short name in this file */

/* Decimal numbers only: [sign] digits [. digits] [e [sign] digits], with at
 * least one digit before the exponent. strtod alone would also take "nan",
 * "inf" and hexadecimal, none of which belongs in a scene.
 *
 * Reading is exact: the same double as strtod, bit for bit. Most numbers in
 * a scene have few digits and a small exponent, m * 10^k with m < 2^53 and
 * |k| <= 22: then m and 10^k are both exact doubles and one multiplication
 * or division rounds correctly (Clinger's fast path, 1990), which is what
 * makes a 2,000,000-triangle scene load in a second. Everything else (long
 * mantissas, large exponents, overflow and underflow) goes to strtod. */
static const double exact_pow10[23] = {
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static bool parse_number(struct parser *p, const char *tok, double *out)
{
    const char *c = tok;
    bool neg = *c == '-';
    c += *c == '-' || *c == '+';
    uint64_t m = 0;
    int sig = 0;                /* significant digits taken into m */
    bool exact = true;          /* m holds every significant digit */
    long k = 0;                 /* the value is m * 10^k */
    int mant_digits = 0;
    for (; is_digit(*c); c++, mant_digits++) {
        if (sig < 19) {
            m = 10 * m + (uint64_t)(*c - '0');
            sig += m != 0;
        } else {
            exact = false;
        }
    }
    if (*c == '.') {
        for (c++; is_digit(*c); c++, mant_digits++) {
            if (sig < 19) {
                m = 10 * m + (uint64_t)(*c - '0');
                sig += m != 0;
                k--;
            } else {
                exact = false;
            }
        }
    }
    if (mant_digits == 0)
        return fail(p, "'%.40s' is not a number", tok);
    if (*c == 'e' || *c == 'E') {
        c++;
        bool eneg = *c == '-';
        c += *c == '-' || *c == '+';
        if (!is_digit(*c))
            return fail(p, "'%.40s' is not a number", tok);
        long e = 0;
        for (; is_digit(*c); c++)
            if (e < 100000)
                e = 10 * e + (*c - '0');
        k += eneg ? -e : e;
    }
    if (*c != '\0')
        return fail(p, "'%.40s' is not a number", tok);
#if FLT_EVAL_METHOD == 0        /* one rounding per operation (not x87) */
    if (exact && m <= (UINT64_C(1) << 53) && k >= -22 && k <= 22) {
        double v = m == 0 ? 0.0 : k < 0 ? (double)m / exact_pow10[-k] : (double)m * exact_pow10[k];
        *out = neg ? -v : v;
        return true;
    }
#endif
    errno = 0;
    double v = strtod(tok, NULL);
    if ((errno == ERANGE && fabs(v) > 1) || !isfinite(v))
        return fail(p, "'%.40s' is too large", tok);
    *out = v;
    return true;
}

static bool parse_int(struct parser *p, const char *tok, const char *what,
                      int lo, int hi, int *out)
{
    if (tok[strspn(tok, "0123456789")] != '\0' || strlen(tok) > 9)
        return fail(p, "%s '%.40s' is not a whole number in %d..%d", what, tok, lo, hi);
    long v = strtol(tok, NULL, 10);
    if (v < lo || v > hi)
        return fail(p, "%s %ld out of range %d..%d", what, v, lo, hi);
    *out = (int)v;
    return true;
}

static bool in_unit(double v)
{
    return v >= 0.0 && v <= 1.0;
}

/* One vertex of a tri or an end of a line, d[0..per) = x y z r g b [s t],
 * checked against the ranges of lessons/CONVENTIONS.md; `which` names it in
 * messages ("vertex 2", "end 1"). */
static bool check_vertex(struct parser *p, const char *which, const double *d, int per,
                         struct vertex *v)
{
    static const char *const names = "xyzrgbst";
    for (int c = 0; c < 2; c++)
        if (!(d[c] >= -COORD_LIMIT && d[c] < COORD_LIMIT))
            return fail(p, "%s: %c = %g is outside [-%d, %d)", which, names[c], d[c],
                        COORD_LIMIT, COORD_LIMIT);
    if (!(d[2] > 0))
        return fail(p, "%s: z = %g must be positive (view-space depth)", which, d[2]);
    if (!(d[2] >= SCENE_Z_MIN && d[2] <= SCENE_Z_MAX))
        return fail(p, "%s: z = %g is outside [%g, %g]", which, d[2], SCENE_Z_MIN, SCENE_Z_MAX);
    for (int c = 3; c < 6; c++)
        if (!in_unit(d[c]))
            return fail(p, "%s: %c = %g is outside [0, 1]", which, names[c], d[c]);
    for (int c = 6; c < per; c++)
        if (!(fabs(d[c]) <= SCENE_ST_MAX))
            return fail(p, "%s: %c = %g is outside [-%g, %g]", which, names[c], d[c],
                        SCENE_ST_MAX, SCENE_ST_MAX);
    *v = (struct vertex){ .x = d[0], .y = d[1], .z = d[2], .r = d[3], .g = d[4], .b = d[5],
                          .s = per == 8 ? d[6] : 0, .t = per == 8 ? d[7] : 0 };
    return true;
}

static bool parse_tri(struct parser *p, struct scene *s, char **tok, int n)
{
    if (n != 18 && n != 24)
        return fail(p, "'tri' needs 18 numbers (x y z r g b for each vertex) "
                       "or 24 (x y z r g b s t), got %d", n);
    int per = n / 3;
    double num[24];
    for (int i = 0; i < n; i++)
        if (!parse_number(p, tok[i], &num[i]))
            return false;

    struct vertex v[3];
    for (int i = 0; i < 3; i++) {
        char which[16];
        snprintf(which, sizeof which, "vertex %d", i + 1);
        if (!check_vertex(p, which, num + i * per, per, &v[i]))
            return false;
    }
    if (per == 8)
        s->has_st = true;
    if (!scene_add_textured(s, v, per == 8 ? p->texture : 0))
        return fail(p, "out of memory after %d triangles", s->ntris);
    return true;
}

/* `line x0 y0 z0 r0 g0 b0  x1 y1 z1 r1 g1 b1` (lessons/CONVENTIONS.md, "Lines"). */
static bool parse_lineseg(struct parser *p, struct scene *s, char **tok, int n)
{
    if (n != 12)
        return fail(p, "'line' needs 12 numbers (x y z r g b for each end), got %d", n);
    double num[12];
    for (int i = 0; i < n; i++)
        if (!parse_number(p, tok[i], &num[i]))
            return false;
    struct vertex v[2];
    if (!check_vertex(p, "end 1", num, 6, &v[0]) || !check_vertex(p, "end 2", num + 6, 6, &v[1]))
        return false;
    if (!scene_add_line(s, v))
        return fail(p, "out of memory after %d lines", s->nlines);
    return true;
}

bool scene_add_line(struct scene *s, const struct vertex v[2])
{
    if (s->nlines == s->lines_cap) {
        if (s->lines_cap > INT_MAX / 2)
            return false;
        int cap = s->lines_cap ? s->lines_cap * 2 : 16;
        struct scene_line *l = realloc(s->lines, (size_t)cap * sizeof *l);
        if (!l)
            return false;
        s->lines = l;
        s->lines_cap = cap;
    }
    struct scene_line *l = &s->lines[s->nlines++];
    memset(l, 0, sizeof *l);
    memcpy(l->v, v, 2 * sizeof *v);
    /* where it stands among the triangles, in file order */
    l->after = s->world.camera_line ? s->world.ntris : s->ntris;
    return true;
}

bool scene_add(struct scene *s, const struct vertex v[3])
{
    return scene_add_textured(s, v, 0);
}

bool scene_add_textured(struct scene *s, const struct vertex v[3], int texture)
{
    if (s->ntris == s->cap) {
        if (s->cap > INT_MAX / 2)
            return false;
        int cap = s->cap ? s->cap * 2 : 64;
        struct scene_tri *t = realloc(s->tris, (size_t)cap * sizeof *t);
        if (!t)
            return false;
        s->tris = t;
        s->cap = cap;
    }
    struct scene_tri *t = &s->tris[s->ntris++];
    memset(t, 0, sizeof *t);    /* the padding too: scenes compare with memcmp */
    memcpy(t->v, v, 3 * sizeof *v);
    t->texture = texture;
    return true;
}

/* One line, comments already cut, split into tokens. */
static bool parse_line(struct parser *p, struct scene *s, char **tok, int n,
                       int *size_line, int *bg_line)
{
    const char *kw = tok[0];
    if (strcmp(kw, "size") == 0) {
        if (*size_line)
            return fail(p, "'size' given twice (first on line %d)", *size_line);
        if (n != 3)
            return fail(p, "'size' needs 2 whole numbers (width height), got %d", n - 1);
        if (!parse_int(p, tok[1], "width", 1, TARGET_MAX, &s->w) ||
            !parse_int(p, tok[2], "height", 1, TARGET_MAX, &s->h))
            return false;
        *size_line = p->line;
        return true;
    }
    if (strcmp(kw, "background") == 0) {
        if (*bg_line)
            return fail(p, "'background' given twice (first on line %d)", *bg_line);
        if (n != 4)
            return fail(p, "'background' needs 3 numbers (r g b), got %d", n - 1);
        for (int i = 0; i < 3; i++) {
            if (!parse_number(p, tok[1 + i], &s->background[i]))
                return false;
            if (!in_unit(s->background[i]))
                return fail(p, "background %c = %g is outside [0, 1]", "rgb"[i], s->background[i]);
        }
        *bg_line = p->line;
        return true;
    }
    if (strcmp(kw, "texture") == 0) {
        if (n < 2 || strcmp(tok[1], "checker") != 0)
            return scene_texture_line(p, s, tok, n);    /* an image texture */
        if (n != 3)
            return fail(p, "expected 'texture checker N'");
        p->texture = 0;         /* no image texture applies after it */
        return parse_int(p, tok[2], "checker squares", 1, 4096, &s->checker);
    }
    if (strcmp(kw, "tri") == 0) {
        if (!*size_line)
            return fail(p, "'tri' before 'size' (the size must come first)");
        if (s->world.camera_line)
            return fail(p, "'tri' in a 3-D scene (it has a camera on line %d: use tri3)",
                        s->world.camera_line);
        return parse_tri(p, s, tok + 1, n - 1);
    }
    if (strcmp(kw, "line") == 0) {
        if (!*size_line)
            return fail(p, "'line' before 'size' (the size must come first)");
        return parse_lineseg(p, s, tok + 1, n - 1);
    }
    if (scene3_keyword(kw))
        return scene3_line(p, s, tok, n);
    return fail(p, "unknown keyword '%.40s' (expected size, background, texture, tri, line, "
                   "or camera, cull, tri3, obj)", kw);
}

/* One reading of a scene: where messages point, and what was seen so far. */
struct reader {
    struct parser p;
    struct scene *s;
    int size_line, bg_line;
};

static bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next line, line[0..n) with line[n] == '\0', split into tokens in
 * place (it is the reader's own copy). */
static bool read_line(struct reader *r, char *line, size_t n)
{
    struct parser *p = &r->p;
    if (p->line == INT_MAX)
        return fail(p, "more lines than a scene may have");
    p->line++;
    if (memchr(line, '\0', n))
        return fail(p, "NUL byte in the line (is this a text file?)");
    char *hash = memchr(line, '#', n);
    char *end = hash ? hash : line + n;
    *end = '\0';
    char *tok[MAX_TOKENS];
    int ntok = 0;
    for (char *c = line;;) {
        while (c < end && is_blank(*c))
            c++;
        if (c == end)
            break;
        if (ntok == MAX_TOKENS)
            return fail(p, "too many values on one line (at most %d)", MAX_TOKENS - 1);
        tok[ntok++] = c;
        while (c < end && !is_blank(*c))
            c++;
        *c = '\0';
        if (c < end)
            c++;
    }
    return ntok == 0 || parse_line(p, r->s, tok, ntok, &r->size_line, &r->bg_line);
}

static void reader_start(struct reader *r, struct scene *s, const char *name, char *err,
                         size_t errlen)
{
    memset(s, 0, sizeof *s);
    *r = (struct reader){ .p = { .name = name, .line = 0, .err = err, .errlen = errlen }, .s = s };
}

/* After the last line: what only the whole scene shows. Leaves the scene
 * empty on failure, its triangles in an array of their own size on success. */
static bool reader_finish(struct reader *r, bool ok)
{
    if (ok && !r->size_line) {
        if (r->p.line == 0)
            r->p.line = 1;
        ok = fail(&r->p, "missing 'size W H' (the framebuffer size is required)");
    }
    if (ok)
        ok = scene3_finish(&r->p, r->s);    /* a 3-D scene's camera and triangles */
    if (!ok) {
        scene_free(r->s);
        return false;
    }
    struct scene *s = r->s;
    if (s->cap > s->ntris && s->ntris > 0) {
        struct scene_tri *t = realloc(s->tris, (size_t)s->ntris * sizeof *t);
        if (t)
            s->tris = t, s->cap = s->ntris;
    }
    return true;
}

bool scene_parse(struct scene *s, const char *name, const char *text, size_t len,
                 char *err, size_t errlen)
{
    struct reader r;
    reader_start(&r, s, name, err, errlen);
    char *buf = NULL;
    size_t bufcap = 0;
    bool ok = true;
    for (size_t pos = 0; pos < len && ok;) {
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t n = (nl ? (size_t)(nl - text) : len) - pos;
        if (n + 1 > bufcap) {
            char *nb = realloc(buf, n + 1);
            if (!nb) {
                r.p.line++;
                ok = fail(&r.p, "out of memory");
                break;
            }
            buf = nb;
            bufcap = n + 1;
        }
        memcpy(buf, text + pos, n);
        buf[n] = '\0';
        pos += n + 1;
        ok = read_line(&r, buf, n);
    }
    free(buf);
    return reader_finish(&r, ok);
}

bool scene_builtin(struct scene *s, const char *name, char *err, size_t errlen)
{
    const struct builtin_scene *b = builtin_find(name);
    if (!b) {
        snprintf(err, errlen, "builtin:%s:0: no such built-in scene (try --list-scenes)", name);
        return false;
    }
    char label[64];
    snprintf(label, sizeof label, "builtin:%s", name);
    return scene_parse(s, label, b->text, strlen(b->text), err, errlen);
}

/* Read a file in chunks of 1 MiB, each line parsed where it lies in the
 * buffer: a scene of hundreds of megabytes never needs them all in memory. */
#define READ_CHUNK ((size_t)1 << 20)

bool scene_load(struct scene *s, const char *path, char *err, size_t errlen)
{
    if (strncmp(path, "builtin:", 8) == 0)
        return scene_builtin(s, path + 8, err, errlen);
    memset(s, 0, sizeof *s);
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s:0: cannot open: %s", path, strerror(errno));
        return false;
    }
    struct reader r;
    reader_start(&r, s, path, err, errlen);
    size_t cap = READ_CHUNK, have = 0;
    char *buf = malloc(cap + 1);            /* + 1: room for the last line's NUL */
    bool ok = buf != NULL;
    if (!ok)
        snprintf(err, errlen, "%s:0: out of memory", path);
    while (ok) {
        if (have == cap) {                  /* one line longer than the buffer */
            char *nb = cap * 2 > cap ? realloc(buf, cap * 2 + 1) : NULL;
            if (!nb) {
                ok = fail(&r.p, "out of memory (a line longer than %zu bytes)", cap);
                break;
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + have, 1, cap - have, f);
        have += got;
        size_t done = 0;
        for (char *nl; ok && (nl = memchr(buf + done, '\n', have - done)); done = (size_t)(nl - buf) + 1) {
            *nl = '\0';
            ok = read_line(&r, buf + done, (size_t)(nl - buf) - done);
        }
        if (!ok)
            break;
        if (got == 0) {
            if (ferror(f)) {
                snprintf(err, errlen, "%s:0: cannot read: %s", path, strerror(errno));
                ok = false;
            } else if (done < have) {       /* the last line has no newline */
                buf[have] = '\0';
                ok = read_line(&r, buf + done, have - done);
            }
            break;
        }
        memmove(buf, buf + done, have - done);
        have -= done;
    }
    free(buf);
    if (f != stdin)
        fclose(f);
    return reader_finish(&r, ok);
}

/* Shortest text that reads back as the same double. */
static void put_number(FILE *out, double v)
{
    char buf[40];
    for (int prec = 6; prec <= 17; prec++) {
        snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    fprintf(out, " %s", buf);
}

static void put_numbers(FILE *out, const double *v, int n)
{
    for (int i = 0; i < n; i++)
        put_number(out, v[i]);
}

/* The lines that stand before triangle `tri` of the file, from *next on. */
static void write_lines(const struct scene *s, FILE *out, int *next, int tri)
{
    for (; *next < s->nlines && s->lines[*next].after <= tri; ++*next) {
        fputs("line", out);
        for (int k = 0; k < 2; k++) {
            const struct vertex *v = &s->lines[*next].v[k];
            fputs(" ", out);
            put_numbers(out, (const double[]){ v->x, v->y, v->z, v->r, v->g, v->b }, 6);
        }
        fputc('\n', out);
    }
}

/* A 3-D scene as its camera, culling and world triangles (an `obj` line's
 * triangles written out as tri3 lines: the file stands alone). */
static bool write_world(const struct scene *s, FILE *out, int current, int *line)
{
    const struct world *w = &s->world;
    static const char *const culls[] = { "none", "back", "front" };
    const struct camera *c = &w->cam;
    fputs("camera", out);
    put_numbers(out, c->eye, 3);
    put_numbers(out, c->target, 3);
    put_numbers(out, c->up, 3);
    put_numbers(out, (const double[]){ c->fovy, c->near, c->far }, 3);
    fputc('\n', out);
    if (w->cull != CULL_NONE)
        fprintf(out, "cull %s\n", culls[w->cull]);
    for (int i = 0; i < w->ntris; i++) {
        write_lines(s, out, line, i);
        int per = scene_write_texture(s, out, &current, w->tris[i].texture);
        fputs("tri3", out);
        for (int k = 0; k < 3; k++) {
            fputs(" ", out);
            put_numbers(out, w->tris[i].p[k], 3);
            put_numbers(out, w->tris[i].rgb[k], 3);
            if (per == 8)
                put_numbers(out, w->tris[i].st[k], 2);
        }
        fputc('\n', out);
    }
    write_lines(s, out, line, INT_MAX);
    return !ferror(out);
}

bool scene_write(const struct scene *s, FILE *out)
{
    fprintf(out, "size %d %d\n", s->w, s->h);
    fprintf(out, "background");
    for (int i = 0; i < 3; i++)
        put_number(out, s->background[i]);
    fputc('\n', out);
    int current, line = 0;
    scene_write_textures(s, out, &current);
    if (s->world.camera_line)
        return write_world(s, out, current, &line);
    for (int i = 0; i < s->ntris; i++) {
        write_lines(s, out, &line, i);
        int per = scene_write_texture(s, out, &current, s->tris[i].texture);
        fputs("tri", out);
        for (int k = 0; k < 3; k++) {
            const struct vertex *v = &s->tris[i].v[k];
            double d[8] = { v->x, v->y, v->z, v->r, v->g, v->b, v->s, v->t };
            fputs(" ", out);
            for (int c = 0; c < per; c++)
                put_number(out, d[c]);
        }
        fputc('\n', out);
    }
    write_lines(s, out, &line, INT_MAX);
    return !ferror(out);
}

void scene_free(struct scene *s)
{
    scene_textures_release(s);
    free(s->tris);
    free(s->lines);
    free(s->world.tris);
    free(s->world.from);
    memset(s, 0, sizeof *s);
}

bool scene_copy(struct scene *dst, const struct scene *src)
{
    *dst = *src;
    dst->tris = NULL;
    dst->ntris = dst->cap = 0;
    dst->lines = NULL;
    dst->nlines = dst->lines_cap = 0;
    dst->world.tris = NULL;
    dst->world.from = NULL;
    dst->world.ntris = dst->world.cap = 0;
    scene_texture_share(dst, src);
    for (int i = 0; i < src->ntris; i++)
        if (!scene_add_textured(dst, src->tris[i].v, src->tris[i].texture))
            goto oom;
    for (int i = 0; i < src->world.ntris; i++)
        if (!world_add(&dst->world, &src->world.tris[i]))
            goto oom;
    if (src->nlines) {
        dst->lines = malloc((size_t)src->nlines * sizeof *dst->lines);
        if (!dst->lines)
            goto oom;
        memcpy(dst->lines, src->lines, (size_t)src->nlines * sizeof *dst->lines);
        dst->nlines = dst->lines_cap = src->nlines;
    }
    if (src->world.from) {
        dst->world.from = malloc((size_t)(src->ntris ? src->ntris : 1) * sizeof *dst->world.from);
        if (!dst->world.from)
            goto oom;
        memcpy(dst->world.from, src->world.from, (size_t)src->ntris * sizeof *dst->world.from);
    }
    return true;
oom:
    scene_free(dst);
    return false;
}

uint32_t scene_background(const struct scene *s)
{
    return pack_rgb(s->background[0], s->background[1], s->background[2]);
}

bool scene_number(struct parser *p, const char *tok, double *out)
{
    return parse_number(p, tok, out);
}
