/* test_scene.c - the scene parser and writer (lessons/CONVENTIONS.md, scene files).
 * Malformed scenes are tested in test_cli.c, in-process and through every
 * lesson program. */
#define _POSIX_C_SOURCE 200809L   /* mkstemp, fdopen */

#include <criterion/criterion.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/parse.h"   /* scene_number */
#include "testlib.h"

static struct scene parse_ok(const char *text)
{
    struct scene s;
    char err[256] = "";
    bool ok = scene_parse(&s, "test.scene", text, strlen(text), err, sizeof err);
    cr_assert(ok, "scene rejected: %s\n--- text:\n%s", err, text);
    return s;
}

static void expect_vertex(const struct vertex *v, const double want[8], const char *what)
{
    const double got[8] = { v->x, v->y, v->z, v->r, v->g, v->b, v->s, v->t };
    for (int i = 0; i < 8; i++)
        cr_expect_eq(got[i], want[i], "%s: field %c = %.17g, expected %.17g", what,
                     "xyzrgbst"[i], got[i], want[i]);
}

Test(scene, size_alone_is_a_scene)
{
    struct scene s = parse_ok("size 64 48\n");
    cr_expect_eq(s.w, 64);
    cr_expect_eq(s.h, 48);
    cr_expect_eq(s.ntris, 0);
    cr_expect_eq(s.checker, 0);
    cr_expect(!s.has_st);
    cr_expect(s.background[0] == 0 && s.background[1] == 0 && s.background[2] == 0);
    cr_expect_eq(scene_background(&s), 0xff000000u, "default background: opaque black");
    scene_free(&s);
}

Test(scene, every_keyword)
{
    struct scene s = parse_ok(
        "size 64 48\n"
        "background 0.1 0.2 1\n"
        "texture checker 8\n"
        "tri  10.5 4 1   1 0 0    50 20.25 2   0 1 0    20 40 1.5   0 0 1\n"
        "tri  1 2 3  0.5 0.25 0.125  0.5 0.5  4 5 6  0 0 0  1 0  7 8 9  1 1 1  0 1\n");
    cr_expect_eq(s.w, 64);
    cr_expect_eq(s.h, 48);
    cr_expect_eq(s.background[0], 0.1);
    cr_expect_eq(s.background[1], 0.2);
    cr_expect_eq(s.background[2], 1.0);
    cr_expect_eq(scene_background(&s), 0xff1a33ffu);
    cr_expect_eq(s.checker, 8);
    cr_expect(s.has_st);
    cr_assert_eq(s.ntris, 2);
    expect_vertex(&s.tris[0].v[0], (double[8]){ 10.5, 4, 1, 1, 0, 0, 0, 0 }, "tri 1 A");
    expect_vertex(&s.tris[0].v[1], (double[8]){ 50, 20.25, 2, 0, 1, 0, 0, 0 }, "tri 1 B");
    expect_vertex(&s.tris[0].v[2], (double[8]){ 20, 40, 1.5, 0, 0, 1, 0, 0 }, "tri 1 C");
    expect_vertex(&s.tris[1].v[0], (double[8]){ 1, 2, 3, 0.5, 0.25, 0.125, 0.5, 0.5 }, "tri 2 A");
    expect_vertex(&s.tris[1].v[1], (double[8]){ 4, 5, 6, 0, 0, 0, 1, 0 }, "tri 2 B");
    expect_vertex(&s.tris[1].v[2], (double[8]){ 7, 8, 9, 1, 1, 1, 0, 1 }, "tri 2 C");
    scene_free(&s);
}

Test(scene, comments_blank_lines_and_spacing)
{
    struct scene s = parse_ok(
        "# a comment on the first line\n"
        "\n"
        "   \t  \n"
        "size\t16   8   # trailing comment\n"
        "#tri 1 2 3 is commented out\n"
        "  tri 1 1 1 1 1 1   2 1 1 1 1 1   1 2 1 1 1 1#no space before the comment\n"
        "\n"
        "# last line has no newline");
    cr_expect_eq(s.w, 16);
    cr_expect_eq(s.h, 8);
    cr_assert_eq(s.ntris, 1);
    cr_expect_eq(s.tris[0].v[2].y, 2);
    cr_expect_eq(s.tris[0].v[2].b, 1);
    scene_free(&s);
}

Test(scene, numbers_in_every_decimal_form)
{
    struct scene s = parse_ok(
        "size 10 10\n"
        "tri -1.5 +2 1e0  .5 0.5e0 5e-1   -16384 16383.99609375 1E3  0 0 0   3. -0 2.5e-3  1 1 1\n");
    cr_assert_eq(s.ntris, 1);
    expect_vertex(&s.tris[0].v[0], (double[8]){ -1.5, 2, 1, 0.5, 0.5, 0.5 }, "A");
    expect_vertex(&s.tris[0].v[1], (double[8]){ -16384, 16383.99609375, 1000, 0, 0, 0 }, "B: at the limits");
    expect_vertex(&s.tris[0].v[2], (double[8]){ 3, 0, 0.0025, 1, 1, 1 }, "C");
    scene_free(&s);
}

Test(scene, crlf_reads_like_lf)
{
    const char *lf = "# x\nsize 20 10\nbackground 0 0.5 1\n\ntri 1 1 1 1 0 0  9 1 1 0 1 0  1 9 1 0 0 1\n";
    char crlf[256];
    size_t n = 0;
    for (const char *p = lf; *p; p++) {
        if (*p == '\n')
            crlf[n++] = '\r';
        crlf[n++] = *p;
    }
    crlf[n] = '\0';
    struct scene a = parse_ok(lf), b = parse_ok(crlf);
    cr_expect(a.w == b.w && a.h == b.h && a.ntris == b.ntris && b.ntris == 1);
    cr_expect(memcmp(a.background, b.background, sizeof a.background) == 0);
    cr_expect(memcmp(a.tris, b.tris, sizeof a.tris[0]) == 0);
    scene_free(&a);
    scene_free(&b);

    /* and an error in a CRLF file names the right line */
    struct scene s;
    char err[256];
    const char *bad = "size 8 8\r\n\r\n# c\r\ntri 1 2 3\r\n";
    cr_assert(!scene_parse(&s, "crlf.scene", bad, strlen(bad), err, sizeof err));
    cr_expect(strncmp(err, "crlf.scene:4: ", 14) == 0, "message: %s", err);
    cr_expect(!strchr(err, '\r') && !strchr(err, '\n'), "one clean line: %s", err);
}

Test(scene, builtin_scenes_all_parse)
{
    cr_assert_gt(builtin_scene_count, 0);
    for (int i = 0; i < builtin_scene_count; i++) {
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, builtin_scenes[i].name, err, sizeof err), "%s", err);
        cr_expect(s.w > 0 && s.h > 0, "builtin:%s", builtin_scenes[i].name);
        cr_expect_eq(builtin_find(builtin_scenes[i].name), &builtin_scenes[i]);
        scene_free(&s);
        /* the same through scene_load's "builtin:" prefix */
        char path[64];
        snprintf(path, sizeof path, "builtin:%s", builtin_scenes[i].name);
        cr_assert(scene_load(&s, path, err, sizeof err), "%s", err);
        scene_free(&s);
    }
    cr_expect_null(builtin_find("no-such-scene"));
}

/* --- round trip: scene_write then scene_parse gives identical values ----------- */

static double any_double(struct rng *r, double lo, double hi)
{
    switch (rng_int(r, 0, 3)) {
    case 0: return rng_range(r, lo, hi);                    /* 17 significant digits */
    case 1: return round(rng_range(r, lo, hi) * 256) / 256;
    case 2: return nextafter(rng_range(r, lo, hi), hi);
    default: return round(rng_range(r, lo, hi) * 10) / 10;  /* short decimals, not binary */
    }
}

static void random_scene(struct rng *r, struct scene *s)
{
    memset(s, 0, sizeof *s);
    s->w = rng_int(r, 1, TARGET_MAX);
    s->h = rng_int(r, 1, TARGET_MAX);
    for (int i = 0; i < 3; i++)
        s->background[i] = rng_chance(r, 0.3) ? (double)rng_int(r, 0, 1) : any_double(r, 0, 1);
    s->checker = rng_chance(r, 0.5) ? rng_int(r, 1, 64) : 0;
    s->has_st = rng_chance(r, 0.5);
    int n = rng_int(r, 0, 20);
    for (int i = 0; i < n; i++) {
        struct vertex v[3];
        for (int k = 0; k < 3; k++) {
            v[k] = (struct vertex){
                .x = any_double(r, -COORD_LIMIT, COORD_LIMIT - 1), .y = any_double(r, -COORD_LIMIT, COORD_LIMIT - 1),
                .z = any_double(r, 1e-3, 1e3),
                .r = any_double(r, 0, 1), .g = any_double(r, 0, 1), .b = any_double(r, 0, 1),
                .s = s->has_st ? any_double(r, -4, 4) : 0, .t = s->has_st ? any_double(r, -4, 4) : 0,
            };
            if (!(v[k].z > 0))
                v[k].z = 1;
        }
        if (rng_chance(r, 0.3))     /* a line here, between the triangles */
            cr_assert(scene_add_line(s, v));
        cr_assert(scene_add(s, v));
    }
    if (rng_chance(r, 0.3))
        cr_assert(scene_add_line(s, (struct vertex[2]){ test_vertex(0.5, 0.5), test_vertex(-7, 3) }));
}

static char *write_to_string(const struct scene *s, size_t *len)
{
    FILE *f = tmpfile();
    cr_assert_not_null(f);
    cr_assert(scene_write(s, f));
    long n = ftell(f);
    cr_assert_geq(n, 0);
    rewind(f);
    char *text = malloc((size_t)n + 1);
    cr_assert_eq(fread(text, 1, (size_t)n, f), (size_t)n);
    text[n] = '\0';
    fclose(f);
    *len = (size_t)n;
    return text;
}

Test(scene, write_then_parse_gives_identical_values)
{
    struct rng r = rng_for(4000);
    for (int i = 0; i < 300; i++) {
        struct scene a, b;
        random_scene(&r, &a);
        size_t len;
        char *text = write_to_string(&a, &len);
        char err[256];
        cr_assert(scene_parse(&b, "roundtrip.scene", text, len, err, sizeof err),
                  "case %d: %s\n%s", i, err, text);
        cr_assert(a.w == b.w && a.h == b.h, "case %d: size", i);
        cr_assert(a.checker == b.checker, "case %d: checker %d vs %d", i, a.checker, b.checker);
        cr_assert(a.ntris == b.ntris, "case %d: %d vs %d triangles", i, a.ntris, b.ntris);
        cr_assert(a.ntris == 0 || a.has_st == b.has_st, "case %d: texture coordinates", i);
        for (int c = 0; c < 3; c++)
            cr_assert(a.background[c] == b.background[c], "case %d: background %.17g vs %.17g",
                      i, a.background[c], b.background[c]);
        for (int t = 0; t < a.ntris; t++)
            for (int k = 0; k < 3; k++) {
                const struct vertex *u = &a.tris[t].v[k], *v = &b.tris[t].v[k];
                const double x[8] = { u->x, u->y, u->z, u->r, u->g, u->b, u->s, u->t };
                const double y[8] = { v->x, v->y, v->z, v->r, v->g, v->b, v->s, v->t };
                for (int f = 0; f < 8; f++)
                    cr_assert(x[f] == y[f], "case %d, triangle %d, vertex %d, %c: wrote %.17g, read %.17g\n%s",
                              i, t, k, "xyzrgbst"[f], x[f], y[f], text);
            }
        cr_assert(a.nlines == b.nlines, "case %d: %d vs %d lines", i, a.nlines, b.nlines);
        for (int l = 0; l < a.nlines; l++) {
            cr_assert(a.lines[l].after == b.lines[l].after, "case %d, line %d: after %d triangles, "
                      "read back after %d", i, l, a.lines[l].after, b.lines[l].after);
            for (int k = 0; k < 2; k++) {
                const struct vertex *u = &a.lines[l].v[k], *v = &b.lines[l].v[k];
                const double x[6] = { u->x, u->y, u->z, u->r, u->g, u->b };
                const double y[6] = { v->x, v->y, v->z, v->r, v->g, v->b };
                for (int f = 0; f < 6; f++)
                    cr_assert(x[f] == y[f], "case %d, line %d, end %d, %c: wrote %.17g, read %.17g",
                              i, l, k, "xyzrgb"[f], x[f], y[f]);
            }
        }
        free(text);
        scene_free(&a);
        scene_free(&b);
    }
}

Test(scene, line_statements_in_file_order)
{
    struct scene s = parse_ok(
        "size 64 48\n"
        "line 0.5 1 2  1 0 0   -16384 16383.5 1e6  0 0.5 1\n"
        "tri  10.5 4 1   1 0 0    50 20.25 2   0 1 0    20 40 1.5   0 0 1\n"
        "line 3 3 1  1 1 1   3 3 1  0 0 0   # zero length: read, draws nothing\n"
        "line 1 2 3  0 0 0   4 5 6  1 1 1\n");
    cr_assert_eq(s.ntris, 1, "a line is no triangle");
    cr_assert_eq(s.nlines, 3);
    expect_vertex(&s.lines[0].v[0], (double[8]){ 0.5, 1, 2, 1, 0, 0, 0, 0 }, "line 1 A");
    expect_vertex(&s.lines[0].v[1], (double[8]){ -16384, 16383.5, 1e6, 0, 0.5, 1, 0, 0 }, "line 1 B");
    expect_vertex(&s.lines[2].v[1], (double[8]){ 4, 5, 6, 1, 1, 1, 0, 0 }, "line 3 B");
    cr_expect_eq(s.lines[0].after, 0, "the first line comes before the triangle");
    cr_expect_eq(s.lines[1].after, 1);
    cr_expect_eq(s.lines[2].after, 1);
    struct scene c;
    cr_assert(scene_copy(&c, &s));
    cr_assert(c.nlines == 3 && c.lines != s.lines && memcmp(c.lines, s.lines, 3 * sizeof *c.lines) == 0,
              "a copy has lines of its own, the same");
    scene_free(&c);
    scene_free(&s);
    /* in a 3-D scene, a line stands among the world triangles */
    s = parse_ok("size 64 48\ncamera 0 0 5  0 0 0  0 1 0  60 0.1 100\n"
                 "tri3 0 0 0 1 1 1  1 0 0 1 1 1  0 1 0 1 1 1\n"
                 "line 1 2 3  0 0 0   4 5 6  1 1 1\n");
    cr_assert_eq(s.nlines, 1);
    cr_expect_eq(s.lines[0].after, 1);
    scene_free(&s);
}

/* --- reading numbers: the same doubles as strtod, bit for bit ---------------------- */

/* A decimal token of the scene grammar: a sign sometimes, 1 to 24 digits
 * (leading zeros too) with or without a point, an exponent sometimes. */
static void random_token(struct rng *r, char *out, size_t len, bool sign)
{
    char digits[32];
    int n = rng_int(r, 1, 24);
    for (int i = 0; i < n; i++)
        digits[i] = (char)('0' + (rng_chance(r, 0.15) ? 0 : rng_int(r, 0, 9)));
    digits[n] = '\0';
    int point = rng_chance(r, 0.7) ? rng_int(r, 0, n) : -1;
    char mant[40];
    if (point < 0)
        snprintf(mant, sizeof mant, "%s", digits);
    else
        snprintf(mant, sizeof mant, "%.*s.%s", point, digits, digits + point);
    char expo[16] = "";
    if (rng_chance(r, 0.4))
        snprintf(expo, sizeof expo, "%c%s%d", rng_chance(r, 0.5) ? 'e' : 'E',
                 rng_chance(r, 0.5) ? "-" : rng_chance(r, 0.3) ? "+" : "", rng_int(r, 0, 40));
    const char *s = !sign ? (rng_chance(r, 0.1) ? "+" : "") : rng_chance(r, 0.5) ? "-" : "";
    snprintf(out, len, "%s%s%s", s, mant, expo);
}

static bool same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

Test(scene, numbers_read_as_strtod_reads_them)
{
    /* hard cases first: exactly 2^53, the ties just past it, the ends of
     * the fast path, denormals, many digits, long zeros */
    static const char *const hard[] = {
        "9007199254740992", "9007199254740993", "9007199254740995", "1e22", "1e23", "1e-22",
        "1e-23", "0.1", "0.3", "123456789012345678", "1234567890123456789012", "4.9e-324",
        "2.2250738585072011e-308", "2.2250738585072014e-308", "1.7976931348623157e308",
        "0.000000000000000000000000000001", "100000000000000000000000", "3.", ".5",
        "0.99999999999999999", "1.00000000000000011102230246251565404236316680908203125",
        "1.0000000000000001110223024625156540423631668090820312500000001", "8.5e-1", "+7",
        "000000000000000000000000000000000000012.5", "1e0000000000000000000000001",
    };
    enum { N = 20000 };
    static char tok[N][64];
    int n = 0;
    for (size_t i = 0; i < sizeof hard / sizeof hard[0]; i++)
        snprintf(tok[n++], sizeof tok[0], "%s", hard[i]);
    struct rng r = rng_for(0x57d0);
    while (n < N) {
        random_token(&r, tok[n], sizeof tok[n], false);
        errno = 0;
        double v = strtod(tok[n], NULL);
        if (v > 0 && isfinite(v) && !(errno == ERANGE && v > 1))
            n++;                /* a depth the scene accepts */
    }
    /* every token through the scene folder's number reader (scene_number,
     * the one parse_tri calls): a depth must now lie in [SCENE_Z_MIN,
     * SCENE_Z_MAX], which would leave out most of the hard cases */
    char err[256];
    for (int i = 0; i < N; i++) {
        struct parser p = { .name = "numbers.scene", .line = i + 1, .err = err, .errlen = sizeof err };
        double got, want = strtod(tok[i], NULL);
        cr_assert(scene_number(&p, tok[i], &got), "%s", err);
        cr_assert(same_bits(got, want), "'%s' read as %a, strtod says %a", tok[i], got, want);
    }

    /* signed, as x in a scene text: minus zero stays minus zero */
    size_t cap = (size_t)N * 120, len = 0;
    char *text = malloc(cap);
    struct scene s;
    len = (size_t)snprintf(text, cap, "size 8 8\n");
    int m = 0;
    static char xs[N][64];
    snprintf(xs[m++], sizeof xs[0], "-0");
    snprintf(xs[m++], sizeof xs[0], "-0.000e5");
    while (m < N) {
        random_token(&r, xs[m], sizeof xs[m], true);
        double v = strtod(xs[m], NULL);
        if (v >= -COORD_LIMIT && v < COORD_LIMIT)
            m++;
    }
    for (int i = 0; i < N; i++)
        len += (size_t)snprintf(text + len, cap - len, "tri %s 1 1 0 0 0  2 1 1 0 0 0  1 2 1 0 0 0\n",
                                xs[i]);
    cr_assert(scene_parse(&s, "signed.scene", text, len, err, sizeof err), "%s", err);
    for (int i = 0; i < N; i++) {
        double want = strtod(xs[i], NULL);
        cr_assert(same_bits(s.tris[i].v[0].x, want), "'%s' read as %a, strtod says %a", xs[i],
                  s.tris[i].v[0].x, want);
    }
    scene_free(&s);
    free(text);
}

Test(scene, number_grammar_at_its_edges)
{
    static const char *const good[] = { "1.", ".5", "+.5e-0", "1E+2", "-0", "0e999999999999" };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char text[160];
        snprintf(text, sizeof text, "size 8 8\ntri %s 1 1 0 0 0  2 1 1 0 0 0  1 2 1 0 0 0\n", good[i]);
        struct scene s = parse_ok(text);
        cr_expect(same_bits(s.tris[0].v[0].x, strtod(good[i], NULL)), "'%s'", good[i]);
        scene_free(&s);
    }
    static const char *const bad[] = { "1e", "1e+", "1E-", ".", "+", "-", "1.5e3.2", "--1",
                                       "1..2", "e5", ".e1", "+-1", "1e5e", "1,5", "0x", "1f",
                                       "\xc2\xbd", "1e999999999999999999999" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[160], err[256], want[64];
        snprintf(text, sizeof text, "size 8 8\n# c\ntri 1 1 1 0 0 0  2 1 1 0 0 %s  1 2 1 0 0 0\n",
                 bad[i]);
        struct scene s;
        cr_assert_not(scene_parse(&s, "bad.scene", text, strlen(text), err, sizeof err),
                      "'%s' was taken for a number", bad[i]);
        snprintf(want, sizeof want, "bad.scene:3: '%s' is ", bad[i]);
        cr_expect(strncmp(err, want, strlen(want)) == 0, "'%s': %s", bad[i], err);
    }
}

/* --- scene_load reads a file in chunks: the same scene as scene_parse --------------- */

Test(scene, load_in_chunks_equals_parse)
{
    /* 3 MiB of text: lines across every chunk boundary, a comment line
     * longer than a chunk, no newline after the last line */
    FILE *f = tmpfile();
    cr_assert_not_null(f);
    struct rng r = rng_for(0x10ad);
    fprintf(f, "size 640 480\nbackground 0.25 0.5 0.75\n");
    int n = 0;
    for (long bytes = 0; bytes < 3L << 20; n++) {
        if (n == 5000) {
            fputc('#', f);
            for (int i = 0; i < (3 << 19); i++)
                fputc('x', f);
            fputc('\n', f);
        }
        bytes = ftell(f);
        fprintf(f, "tri");
        for (int k = 0; k < 3; k++)
            fprintf(f, " %.17g %.5f %.3g %.9f 0.5 1", rng_range(&r, 0, 640), rng_range(&r, 0, 480),
                    rng_range(&r, 0.1, 99), rng_unit(&r));
        if (rng_chance(&r, 0.01))
            fprintf(f, "   # a remark");
        fputc('\n', f);
    }
    fprintf(f, "tri 1 1 1 0 0 0  2 1 1 0 0 0  1 2 1 0 0 0");   /* no newline */
    long len = ftell(f);
    rewind(f);
    char *text = malloc((size_t)len);
    cr_assert_eq(fread(text, 1, (size_t)len, f), (size_t)len);
    fclose(f);

    char path[] = "/tmp/tristep-load-XXXXXX";
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    FILE *out = fdopen(fd, "wb");
    cr_assert_eq(fwrite(text, 1, (size_t)len, out), (size_t)len);
    cr_assert_eq(fclose(out), 0);

    struct scene a, b;
    char err[256];
    cr_assert(scene_parse(&a, path, text, (size_t)len, err, sizeof err), "%s", err);
    cr_assert(scene_load(&b, path, err, sizeof err), "%s", err);
    cr_assert_eq(a.ntris, n + 1);
    cr_assert_eq(b.ntris, a.ntris);
    cr_assert(a.w == b.w && a.h == b.h && memcmp(a.background, b.background, sizeof a.background) == 0);
    cr_assert(memcmp(a.tris, b.tris, (size_t)a.ntris * sizeof *a.tris) == 0,
              "the triangles read in chunks differ from those parsed whole");
    scene_free(&a);
    scene_free(&b);

    /* an error far into the file names its line */
    int line = 1;
    for (long i = 0; i < len; i++)
        line += text[i] == '\n';
    out = fopen(path, "ab");
    fprintf(out, "\ntri 1 1 1 0 0 0  2 1 1 0 0 0  1 2 1 0 0 oops\n");
    fclose(out);
    cr_assert_not(scene_load(&b, path, err, sizeof err));
    char want[300];
    snprintf(want, sizeof want, "%s:%d: 'oops' is not a number", path, line + 1);
    cr_expect_str_eq(err, want);
    cr_assert_null(b.tris, "nothing is kept after an error");
    remove(path);
    free(text);
}
