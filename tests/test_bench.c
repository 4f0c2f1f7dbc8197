/* test_bench.c - `make bench`'s program runs in its quick mode, so it cannot
 * rot: it finishes, writes its CSV and chart, finds every exact lesson
 * variant exact on every scene, and its coverage check is not blind (the
 * exhibits are caught). No timing is asserted here. */
#define _POSIX_C_SOURCE 200809L
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "testlib.h"
#include "util/file.h"

#define MAX_CSV_ROWS 512

struct csv_row {
    char scene[16], program[64], variant[64];
    int exhibit;
    double median;
    long long diff_ref, diff_peer;
};

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
        char *field[18];
        int k = 0;
        for (char *p = strtok(line, ",\n"); p && k < 18; p = strtok(NULL, ",\n"))
            field[k++] = p;
        cr_assert_eq(k, 18, "a CSV row has %d fields", k);
        snprintf(r->scene, sizeof r->scene, "%s", field[0]);
        snprintf(r->program, sizeof r->program, "%s", field[5]);
        snprintf(r->variant, sizeof r->variant, "%s", field[6]);
        r->exhibit = atoi(field[7]);
        r->median = atof(field[9]);
        r->diff_ref = atoll(field[16]);
        r->diff_peer = atoll(field[17]);
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
    int tables = 0, rows_md = 0;
    char mline[1024];
    while (md && fgets(mline, sizeof mline, md)) {
        tables += strncmp(mline, "| program | variant | median ms | spread |", 42) == 0;
        rows_md += strncmp(mline, "| 0", 3) == 0;
    }
    if (md)
        fclose(md);
    cr_expect_eq(tables, 3, "%s: %d tables, one per scene expected", path, tables);
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
