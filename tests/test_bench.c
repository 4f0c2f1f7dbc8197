/* test_bench.c - `make bench`'s program runs in its quick mode, so it cannot
 * rot: it finishes, writes its CSV and chart, finds every exact lesson
 * variant exact on every scene (the textured ones too), and its coverage
 * check is not blind (the exhibits are caught). Its textured scenes are
 * what they say (textured, magnified and minified, their coverage the
 * independent reference's), and its measure of agreement counts a known
 * difference exactly. No timing is asserted here. */
#define _POSIX_C_SOURCE 200809L
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "bench/bench.h"
#include "testlib.h"
#include "texref.h"
#include "util/file.h"

#define MAX_CSV_ROWS 512

struct csv_row {
    char scene[16], program[64], variant[64];
    int exhibit;
    double median;
    long long diff_ref, diff_peer;
    double within2, within8;    /* % of covered pixels near llvmpipe's colour, -1: not compared */
};
#define CSV_FIELDS 20

static int run(const char *args, const char *outdir)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s/tristep-bench' %s --out '%s' >'%s/stdout.txt' 2>'%s/stderr.txt'",
             test_build_dir(), args, outdir, outdir, outdir);
    int status = system(cmd);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static int read_csv(const char *path, struct csv_row *rows, int max)
{
    FILE *f = fopen(path, "r");
    cr_assert(f, "%s was not written", path);
    char line[1024];
    int n = 0;
    while (fgets(line, sizeof line, f) && n < max) {
        if (line[0] == '#' || strncmp(line, "scene,", 6) == 0)
            continue;
        struct csv_row *r = &rows[n];
        /* scene,width,height,triangles,pixels,program,variant,exhibit,runs,median_s,... */
        char *field[CSV_FIELDS];
        int k = 0;
        for (char *p = strtok(line, ",\n"); p && k < CSV_FIELDS; p = strtok(NULL, ",\n"))
            field[k++] = p;
        cr_assert_eq(k, CSV_FIELDS, "a CSV row has %d fields", k);
        snprintf(r->scene, sizeof r->scene, "%s", field[0]);
        snprintf(r->program, sizeof r->program, "%s", field[5]);
        snprintf(r->variant, sizeof r->variant, "%s", field[6]);
        r->exhibit = atoi(field[7]);
        r->median = atof(field[9]);
        r->diff_ref = atoll(field[16]);
        r->diff_peer = atoll(field[17]);
        r->within2 = atof(field[18]);
        r->within8 = atof(field[19]);
        n++;
    }
    fclose(f);
    return n;
}

static const struct csv_row *find(const struct csv_row *rows, int n, const char *scene,
                                  const char *program, const char *variant)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(rows[i].scene, scene) && !strcmp(rows[i].program, program)
            && !strcmp(rows[i].variant, variant))
            return &rows[i];
    return NULL;
}

static bool file_starts_with(const char *path, const char *magic, size_t len)
{
    FILE *f = fopen(path, "rb");
    char buf[16] = { 0 };
    bool ok = f && fread(buf, 1, len, f) == len && memcmp(buf, magic, len) == 0;
    if (f)
        fclose(f);
    return ok;
}

Test(bench, quick_mode_is_exact_and_catches_the_exhibits, .timeout = 120)
{
    char dir[] = "/tmp/tristep-bench-XXXXXX";
    cr_assert(mkdtemp(dir));
    cr_assert_eq(run("--quick --exhibits", dir), 0,
                 "tristep-bench --quick failed; see %s/stdout.txt and stderr.txt", dir);

    static struct csv_row rows[MAX_CSV_ROWS];
    char path[256];
    snprintf(path, sizeof path, "%s/bench.csv", dir);
    int n = read_csv(path, rows, MAX_CSV_ROWS);
    static const char *const scenes[] = { "large", "small", "mixed" };

    /* llvmpipe ran when its rows are there (OSMesa is optional); then every
     * exact variant must agree with it too */
    bool peer = find(rows, n, "large", "llvmpipe", "1 thread") != NULL;
    int exhibits = 0, exhibits_caught = 0;
    for (const struct lesson *const *l = all_lessons_fast; *l; l++) {
        for (int v = 0; v < (*l)->nvariants; v++) {
            const struct lesson_variant *var = &(*l)->variants[v];
            bool caught = false;
            for (int s = 0; s < 3; s++) {
                const struct csv_row *r = find(rows, n, scenes[s], (*l)->id, var->name);
                cr_assert(r, "no row for %s %s on %s", (*l)->id, var->name, scenes[s]);
                cr_expect_gt(r->median, 0, "%s %s on %s: no time", (*l)->id, var->name, scenes[s]);
                if (variant_against_exact(var)) {
                    caught = caught || r->diff_ref > 0;
                    continue;
                }
                cr_expect_eq(r->diff_ref, 0, "%s %s on %s: %lld pixels differ from the reference",
                             (*l)->id, var->name, scenes[s], r->diff_ref);
                if (peer)
                    cr_expect_eq(r->diff_peer, 0, "%s %s on %s: %lld pixels differ from llvmpipe",
                                 (*l)->id, var->name, scenes[s], r->diff_peer);
                else
                    cr_expect_eq(r->diff_peer, -1, "no llvmpipe rows, yet a llvmpipe difference");
            }
            exhibits += variant_against_exact(var);
            exhibits_caught += variant_against_exact(var) && caught;
        }
    }
    for (int s = 0; s < 3 && peer; s++) {
        const struct csv_row *r = find(rows, n, scenes[s], "llvmpipe", "1 thread");
        cr_assert(r);
        cr_expect_eq(r->diff_ref, 0, "llvmpipe differs from the reference on %s by %lld pixels",
                     scenes[s], r->diff_ref);
        /* and its multisampled framebuffer, sample by sample, from the exact
         * rule at the points where it says its samples are */
        const struct csv_row *m = find(rows, n, scenes[s], "llvmpipe", "1 thread 4 samples");
        if (m)
            cr_expect_eq(m->diff_ref, 0, "llvmpipe at 4 samples differs from the reference at its "
                         "samples on %s by %lld pixels", scenes[s], m->diff_ref);
    }
    /* the textured scenes: every texture-mapping lesson's exact variants
     * exact there too, llvmpipe's textured drawing covering what the
     * reference covers, agreement given as shares where llvmpipe ran */
    static const char *const textured[] = { "floor", "small-tex", "mixed-tex" };
    for (int s = 0; s < 3; s++) {
        const struct csv_row *lp = find(rows, n, textured[s], "llvmpipe", "1 thread");
        cr_expect_eq(lp != NULL, peer, "llvmpipe's textured row on %s does not follow its others",
                     textured[s]);
        if (lp)
            cr_expect_eq(lp->diff_ref, 0, "llvmpipe, textured, differs from the reference on %s "
                         "by %lld pixels", textured[s], lp->diff_ref);
        for (const struct lesson *const *l = all_lessons_fast; *l; l++)
            for (int v = 0; (*l)->texturing && v < (*l)->nvariants; v++) {
                const struct lesson_variant *var = &(*l)->variants[v];
                const struct csv_row *r = find(rows, n, textured[s], (*l)->id, var->name);
                cr_assert(r, "no textured row for %s %s on %s", (*l)->id, var->name, textured[s]);
                if (variant_against_exact(var))
                    continue;
                cr_expect_eq(r->diff_ref, 0, "%s %s on %s: %lld pixels differ from the reference",
                             (*l)->id, var->name, textured[s], r->diff_ref);
                cr_expect_eq(r->diff_peer, peer ? 0 : -1, "%s %s on %s: %lld pixels differ from "
                             "llvmpipe", (*l)->id, var->name, textured[s], r->diff_peer);
                cr_expect(peer ? r->within2 >= 0 && r->within2 <= r->within8 && r->within8 <= 100
                               : r->within2 == -1 && r->within8 == -1,
                          "%s %s on %s: agreement %g%%, %g%%", (*l)->id, var->name, textured[s],
                          r->within2, r->within8);
            }
    }
    /* the scenes put edges through pixel centres: a wrong fill rule shows */
    if (exhibits > 0)
        cr_expect_gt(exhibits_caught, 0, "no exhibit differs from the reference on any scene");

    /* the 3-D front end's row: the whole 100,000-triangle mesh, timed */
    const struct csv_row *fe = find(rows, n, "torus-3d", "front-end", "clip+project");
    cr_assert(fe, "no row for the 3-D front end");
    cr_expect_gt(fe->median, 0, "the front end has no time");

    snprintf(path, sizeof path, "%s/bench.png", dir);
    cr_expect(file_starts_with(path, "\x89PNG\r\n\x1a\n", 8), "%s is not a PNG", path);
    /* the markdown table the texts link (make bench writes it to BENCH.md) */
    snprintf(path, sizeof path, "%s/bench.md", dir);
    cr_expect(file_starts_with(path, "# tristep bench", 15), "%s is not the bench's table", path);
    FILE *md = fopen(path, "r");
    int tables = 0, tex_tables = 0, rows_md = 0;
    char mline[1024];
    while (md && fgets(mline, sizeof mline, md)) {
        tables += strncmp(mline, "| program | variant | median ms | spread | Mtri/s |", 51) == 0;
        tex_tables += strncmp(mline, "| program | variant | median ms | spread | Mpix/s | x llvmpipe |", 64) == 0;
        rows_md += strncmp(mline, "| 0", 3) == 0;
    }
    if (md)
        fclose(md);
    cr_expect_eq(tables, 3, "%s: %d tables, one per scene expected", path, tables);
    cr_expect_eq(tex_tables, 3, "%s: %d textured tables, one per scene expected", path, tex_tables);
    cr_expect_gt(rows_md, 3 * 5, "%s: only %d lesson rows", path, rows_md);
    snprintf(path, sizeof path, "%s/bench.svg", dir);
    cr_expect(file_starts_with(path, "<?xml", 5), "%s is not an SVG", path);

    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

Test(bench, bad_options_exit_2)
{
    char dir[] = "/tmp/tristep-bench-XXXXXX";
    cr_assert(mkdtemp(dir));
    cr_expect_eq(run("--quick --runs 0", dir), 2);
    cr_expect_eq(run("--frobnicate", dir), 2);
    char path[256];
    snprintf(path, sizeof path, "%s/bench.csv", dir);
    cr_expect_null(fopen(path, "r"), "a refused run wrote %s", path);

    /* an --out that cannot be made is refused before any timing, not found
     * unwritable at the end of the run */
    char cmd[512];
    snprintf(cmd, sizeof cmd, "'%s/tristep-bench' --quick --no-large-scene --out '%s/no/such' "
             ">'%s/stdout.txt' 2>'%s/stderr.txt'", test_build_dir(), dir, dir, dir);
    int status = system(cmd);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 2, "an --out in a missing directory: %d",
              status);
    snprintf(path, sizeof path, "%s/stdout.txt", dir);
    char *out, err[256];
    size_t len;
    cr_assert(read_text_file(path, &out, &len, err, sizeof err), "%s", err);
    cr_expect_null(strstr(out, "round 1"), "timed before finding --out unusable:\n%s", out);
    free(out);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

/* The measure of agreement on a real picture (the reference's, of a tiny
 * textured scene) against a copy with known differences: one pixel 3
 * levels off in red, one 9 off in green, one 2 off in blue, one off only
 * in alpha, and an uncovered pixel far off, which does not count. */
Test(bench, agreement_counts_a_known_difference)
{
    static const char text[] =
        "size 16 12\n"
        "texture builtin:checker-numbers repeat\n"
        "tri  1.5 1 1  1 1 1 0 0   14.25 2 2  1 0.5 1 1.5 0   3 11 3  0.5 1 1 0 2\n";
    struct scene s;
    char err[256];
    cr_assert(scene_parse(&s, "tiny", text, sizeof text - 1, err, sizeof err), "%s", err);
    struct texref_target fb;
    cr_assert(texref_target_init(&fb, s.w, s.h, scene_background(&s)));
    cr_assert(texref_draw_scene(&fb, &s, TEXREF_TRILINEAR, 1));
    size_t n = (size_t)s.w * (size_t)s.h;
    uint32_t *other = malloc(n * sizeof *other);
    cr_assert(other);
    memcpy(other, fb.color, n * sizeof *other);
    int64_t covered = 0;
    size_t at[4], found = 0, outside = n;
    for (size_t i = 0; i < n; i++) {
        covered += fb.covered[i] > 0;
        if (fb.covered[i] && found < 4)
            at[found++] = i;
        if (!fb.covered[i])
            outside = i;
    }
    cr_assert_eq(found, 4, "the tiny scene covers %zu pixels", found);
    cr_assert_lt(outside, n, "the tiny scene covers every pixel");
    static const struct { int shift, by; } change[4] = { { 16, 3 }, { 8, 9 }, { 0, 2 }, { 24, 100 } };
    for (int k = 0; k < 4; k++) {
        uint32_t c = other[at[k]];
        int v = (int)(c >> change[k].shift & 255);
        v = v >= 128 ? v - change[k].by : v + change[k].by;
        other[at[k]] = (c & ~(255u << change[k].shift)) | (uint32_t)v << change[k].shift;
    }
    other[outside] ^= 0x00808080u;
    struct bench_agree g = bench_agreement(fb.color, other, fb.covered, n);
    cr_expect_eq(g.pixels, covered);
    cr_expect_eq(g.within2, covered - 2, "within 2: %lld of %lld", (long long)g.within2, (long long)covered);
    cr_expect_eq(g.within8, covered - 1, "within 8: %lld of %lld", (long long)g.within8, (long long)covered);
    /* and symmetric: which picture comes first does not matter */
    struct bench_agree h = bench_agreement(other, fb.color, fb.covered, n);
    cr_expect(h.pixels == g.pixels && h.within2 == g.within2 && h.within8 == g.within8);
    free(other);
    texref_target_free(&fb);
    scene_free(&s);
}

/* The bench's textured scenes (quick size) are what BENCH.md says: the same
 * for the same seed, every triangle under an image texture with finite
 * (s, t), their reference coverage that of the independent reference
 * (tests/texref.c), and the floor both magnified (lambda < 0 near the eye)
 * and minified to the last levels (far away). */
Test(bench, textured_scenes_are_what_they_say)
{
    static struct bench_scene a[3], b[3];
    cr_assert(bench_tex_scenes_make(a, 2024, true));
    cr_assert(bench_tex_scenes_make(b, 2024, true));
    for (int i = 0; i < 3; i++) {
        const struct scene *s = &a[i].s;
        cr_assert_eq(s->ntris, b[i].s.ntris);
        cr_expect_eq(memcmp(s->tris, b[i].s.tris, (size_t)s->ntris * sizeof *s->tris), 0,
                     "%s: another scene from the same seed", a[i].name);
        for (int t = 0; t < s->ntris; t++) {
            const struct texture *tex = scene_texture(s, s->tris[t].texture);
            cr_assert(tex, "%s: triangle %d has no image texture", a[i].name, t);
            cr_assert_eq(tex->level[0].w, 256, "%s: a texture of %d texels", a[i].name, tex->level[0].w);
            for (int k = 0; k < 3; k++)
                cr_assert(isfinite(s->tris[t].v[k].s) && isfinite(s->tris[t].v[k].t));
        }
        struct texref_target fb;
        size_t n = (size_t)s->w * (size_t)s->h;
        cr_assert(texref_target_init(&fb, s->w, s->h, scene_background(s)));
        fb.lambda = malloc(n * sizeof *fb.lambda);
        cr_assert(fb.lambda);
        for (size_t k = 0; k < n; k++)
            fb.lambda[k] = NAN;
        cr_assert(texref_draw_scene(&fb, s, TEXREF_TRILINEAR, 1));
        cr_expect_eq(bench_count_diff(fb.covered, a[i].coverage, n), 0,
                     "%s: the bench's reference coverage is not the independent reference's", a[i].name);
        float lo = INFINITY, hi = -INFINITY;
        for (size_t k = 0; k < n; k++)
            if (!isnan(fb.lambda[k])) {
                lo = fminf(lo, fb.lambda[k]);
                hi = fmaxf(hi, isinf(fb.lambda[k]) ? 99.0f : fb.lambda[k]);
            }
        cr_expect_lt(lo, 0, "%s: nothing magnified (lambda from %g)", a[i].name, lo);
        cr_expect_gt(hi, i == 0 ? 6 : 1, "%s: nothing minified (lambda up to %g)", a[i].name, hi);
        texref_target_free(&fb);
    }
    bench_scenes_free(a);
    bench_scenes_free(b);
}
