/* test_cli.c - the lesson programs themselves, run as a user runs them:
 * bad scenes and bad command lines (exit 2, FILE:LINE: message, no output
 * file), unwritable outputs (exit 1, nothing left), --dump-coverage against
 * the reference byte for byte, --help and --version.
 *
 * Every program build/NN-* found in $TRISTEP_BUILD is run.
 */
#define _POSIX_C_SOURCE 200809L   /* posix_spawn, mkdtemp, opendir */

#include <criterion/criterion.h>
#include <dirent.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "front/front.h"
#include "testlib.h"
#include "util/file.h"

extern char **environ;

/* --- running a program -------------------------------------------------------- */

#define MAX_PROGRAMS 32

struct programs {
    int n;
    char path[MAX_PROGRAMS][512];
    const char *name[MAX_PROGRAMS];     /* "02-barycentric" */
};

static int by_name(const void *a, const void *b)
{
    return strcmp(a, b);
}

/* Every build/NN-* that is an executable file, in order. */
static void find_programs(struct programs *p)
{
    const char *dir = test_build_dir();
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "cannot open the build directory %s (set TRISTEP_BUILD)", dir);
    p->n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        const char *s = e->d_name;
        if (!(s[0] >= '0' && s[0] <= '9' && s[1] >= '0' && s[1] <= '9' && s[2] == '-'))
            continue;
        cr_assert_lt(p->n, MAX_PROGRAMS);
        snprintf(p->path[p->n], sizeof p->path[0], "%s/%s", dir, s);
        struct stat st;
        if (stat(p->path[p->n], &st) == 0 && S_ISREG(st.st_mode) && access(p->path[p->n], X_OK) == 0)
            p->n++;
    }
    closedir(d);
    qsort(p->path, (size_t)p->n, sizeof p->path[0], by_name);
    for (int i = 0; i < p->n; i++)
        p->name[i] = strrchr(p->path[i], '/') + 1;
    cr_assert_gt(p->n, 0, "no lesson programs in %s", dir);
}

/* The lesson whose program this is. */
static const struct lesson *lesson_of(const char *name)
{
    for (int i = 0; all_lessons[i]; i++)
        if (strcmp(all_lessons[i]->id, name) == 0)
            return all_lessons[i];
    return NULL;
}

struct result {
    int status;             /* exit status, or 128 + signal */
    char *out, *err;        /* whole stdout and stderr, NUL-terminated */
    size_t out_len, err_len;
};

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        *len = 0;
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    for (size_t got; (got = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n == cap)
            buf = realloc(buf, (cap *= 2) + 1);
    }
    fclose(f);
    buf[n] = '\0';
    *len = n;
    return buf;
}

/* Run argv (argv[0] is the program's path) with stdout and stderr captured
 * into files in `scratch` (a directory of its own, not the one checked for
 * leftovers). */
static struct result run(char *const argv[], const char *scratch)
{
    char out_path[600], err_path[600];
    snprintf(out_path, sizeof out_path, "%s/stdout", scratch);
    snprintf(err_path, sizeof err_path, "%s/stderr", scratch);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int rc = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    cr_assert_eq(rc, 0, "cannot start %s: %s", argv[0], strerror(rc));
    int ws;
    cr_assert_eq(waitpid(pid, &ws, 0), pid);
    struct result r;
    r.status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
    r.out = slurp(out_path, &r.out_len);
    r.err = slurp(err_path, &r.err_len);
    cr_assert(r.out && r.err);
    return r;
}

static void result_free(struct result *r)
{
    free(r->out);
    free(r->err);
}

static void write_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot write %s", path);
    cr_assert_eq(fwrite(text, 1, len, f), len);
    cr_assert_eq(fclose(f), 0);
}

/* Names in dir other than those listed (NULL-terminated); returns the count
 * and the first such name in first. */
static int stray_files(const char *dir, const char *const keep[], char *first, size_t len)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        bool kept = false;
        for (int i = 0; keep[i]; i++)
            kept |= strcmp(e->d_name, keep[i]) == 0;
        if (!kept && n++ == 0)
            snprintf(first, len, "%s", e->d_name);
    }
    closedir(d);
    return n;
}

static void remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char path[1024];
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode))
            remove_tree(path);
        else
            unlink(path);
    }
    closedir(d);
    rmdir(dir);
}

/* A fresh work directory (checked for leftovers) and a scratch one. */
struct dirs {
    char work[256], scratch[256];
};

/* The directories of the running test, removed by .fini even when an
 * assertion ends the test early. */
static struct dirs *live_dirs;

static void dirs_make(struct dirs *d)
{
    snprintf(d->work, sizeof d->work, "/tmp/tristep-cli-XXXXXX");
    snprintf(d->scratch, sizeof d->scratch, "/tmp/tristep-cli-io-XXXXXX");
    live_dirs = d;
    cr_assert_not_null(mkdtemp(d->work));
    cr_assert_not_null(mkdtemp(d->scratch));
}

static void dirs_remove(struct dirs *d)
{
    remove_tree(d->work);
    remove_tree(d->scratch);
    d->work[0] = d->scratch[0] = '\0';
}

static void remove_live_dirs(void)
{
    if (live_dirs && live_dirs->work[0])
        dirs_remove(live_dirs);
}

/* --- malformed scenes ------------------------------------------------------------- */

#define TRI_OK "1 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1"
#define WITH_LEN(text) text, sizeof text - 1     /* for text with a NUL inside */

struct bad_scene {
    const char *name;
    const char *text;
    size_t len;             /* 0: strlen(text) */
    int line;               /* where the message must point */
};

static const struct bad_scene bad_scenes[] = {
    { "unknown keyword", "size 8 8\ncolour 1 0 0\n", 0, 2 },
    { "misspelt tri", "size 8 8\n\ntriangle " TRI_OK "\n", 0, 3 },
    { "tri with 17 numbers", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1\n", 0, 2 },
    { "tri with 19 numbers", "size 8 8\ntri " TRI_OK " 1\n", 0, 2 },
    { "tri with 23 numbers", "size 8 8\ntri 1 1 1 1 1 1 0 0  6 1 1 1 1 1 0 0  1 6 1 1 1 1 0\n", 0, 2 },
    { "tri with no numbers", "size 8 8\ntri\n", 0, 2 },
    { "a word for a number", "size 8 8\ntri 1 1 1 1 1 1  six 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "number with junk", "size 8 8\ntri 1 1 1 1 1 1  6px 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "two points", "size 8 8\ntri 1.2.3 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "nan", "size 8 8\ntri nan 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "NaN in colour", "size 8 8\ntri 1 1 1 NaN 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "inf", "size 8 8\ntri 1 1 1 1 1 1  inf 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "-infinity", "size 8 8\ntri 1 1 1 1 1 1  6 -infinity 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "hex", "size 8 8\ntri 0x10 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "hex float", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 1 1 1  1 0x1p2 1 1 1 1\n", 0, 2 },
    { "huge exponent", "size 8 8\ntri 1e400 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "x at +16384", "size 8 8\n# limit\ntri 16384 1 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 3 },
    { "y at +16384", "size 8 8\ntri 1 1 1 1 1 1  6 16384 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "x at -16384.01", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 1 1 1  -16384.01 6 1 1 1 1\n", 0, 2 },
    { "y at -16384.01", "size 8 8\ntri 1 -16384.01 1 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "z = 0", "size 8 8\ntri 1 1 0 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "z < 0", "size 8 8\ntri 1 1 1 1 1 1  6 1 -2 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "z = -0", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 1 1 1  1 6 -0 1 1 1\n", 0, 2 },
    { "colour > 1", "size 8 8\ntri 1 1 1 1 1 1.5  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "colour < 0", "size 8 8\ntri 1 1 1 1 1 1  6 1 1 -0.1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "background > 1", "size 8 8\nbackground 0 2 0\n", 0, 2 },
    { "background with 2 numbers", "size 8 8\nbackground 0 0\n", 0, 2 },
    { "background twice", "size 8 8\nbackground 0 0 0\nbackground 1 1 1\n", 0, 3 },
    { "missing size", "# no size here\nbackground 0 0 0\n", 0, 2 },
    { "empty file", "", 0, 1 },
    { "only comments", "# one\n# two\n# three\n", 0, 3 },
    { "size twice", "size 8 8\nsize 9 9\n", 0, 2 },
    { "size 0", "size 0 8\n", 0, 1 },
    { "size 16385", "size 8 16385\n", 0, 1 },
    { "size 3.5", "size 3.5 8\n", 0, 1 },
    { "size -8", "size -8 8\n", 0, 1 },
    { "size with one number", "size 8\n", 0, 1 },
    { "size with three numbers", "size 8 8 8\n", 0, 1 },
    { "size in hex", "size 0x10 8\n", 0, 1 },
    { "tri before size", "# first\ntri " TRI_OK "\nsize 8 8\n", 0, 2 },
    { "NUL byte", WITH_LEN("size 8 8\ntri 1 1 1 1 1 1\0 6 1 1 1 1 1  1 6 1 1 1 1\n"), 2 },
    { "texture checker 0", "size 8 8\ntexture checker 0\n", 0, 2 },
    { "texture of another kind", "size 8 8\ntexture stripes 4\n", 0, 2 },
    { "error after CRLF lines", "size 8 8\r\n\r\n# c\r\nbogus 1\r\n", 0, 4 },
    /* regression: any positive z was taken; 1/z of z = 1e-300 overflows the
     * floats lesson 04 interpolates it in, and a NaN colour reached an
     * undefined float-to-int conversion */
    { "z_tiny_overflowed_inverse_depth", "size 8 8\ntri 1 1 1e-300 1 1 1  6 1 1 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "z just below 1e-6", "size 8 8\ntri 1 1 1 1 1 1  6 1 9.99e-7 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    { "z_huge_beyond_float_depth", "size 8 8\ntri 1 1 1 1 1 1  6 1 1e300 1 1 1  1 6 1 1 1 1\n", 0, 2 },
    /* regression: texture coordinates were not checked at all; s = 1e300
     * times the checker count went through an undefined cast to long */
    { "texture_coordinate_huge_overflowed_checker_square", "size 8 8\ntexture checker 4\n"
      "tri 1 1 1 1 1 1 1e300 0  6 1 1 1 1 1 0 0  1 6 1 1 1 1 0 1\n", 0, 3 },
    { "t below -1e6", "size 8 8\ntri 1 1 1 1 1 1 0 0  6 1 1 1 1 1 0 -1000001  1 6 1 1 1 1 0 1\n", 0, 2 },
    { "line with 11 numbers", "size 8 8\nline 1 1 1 1 1 1  6 1 1 1 1\n", 0, 2 },
    { "line with 13 numbers", "size 8 8\nline 1 1 1 1 1 1  6 1 1 1 1 1 1\n", 0, 2 },
    { "line before size", "line 1 1 1 1 1 1  6 1 1 1 1 1\nsize 8 8\n", 0, 1 },
    { "line end at x = 16384", "size 8 8\nline 1 1 1 1 1 1  16384 1 1 1 1 1\n", 0, 2 },
    { "line with z = 0", "size 8 8\ntri " TRI_OK "\nline 1 1 0 1 1 1  6 1 1 1 1 1\n", 0, 3 },
    { "line colour nan", "size 8 8\nline 1 1 1 1 nan 1  6 1 1 1 1 1\n", 0, 2 },
    { "error after good triangles", "size 8 8\ntri " TRI_OK "\ntri " TRI_OK "\n\ntri " TRI_OK " 7\n", 0, 5 },
};
#define N_BAD_SCENES (sizeof bad_scenes / sizeof bad_scenes[0])

static size_t bad_len(const struct bad_scene *b)
{
    return b->len ? b->len : strlen(b->text);
}

/* "FILE:LINE: message\n" and nothing else. */
static void expect_located_message(const char *err, const char *file, int line, const char *what)
{
    char prefix[600];
    int n = snprintf(prefix, sizeof prefix, "%s:%d: ", file, line);
    cr_assert(strncmp(err, prefix, (size_t)n) == 0, "%s: message should start '%s', got '%s'",
              what, prefix, err);
    const char *msg = err + n;
    const char *nl = strchr(msg, '\n');
    cr_assert(nl && nl > msg, "%s: an empty or unterminated message: '%s'", what, err);
    cr_assert(nl[1] == '\0', "%s: more than one line on stderr: '%s'", what, err);
}

Test(cli, malformed_scenes_in_process)
{
    cr_assert_geq(N_BAD_SCENES, 20);
    for (size_t i = 0; i < N_BAD_SCENES; i++) {
        const struct bad_scene *b = &bad_scenes[i];
        struct scene s;
        char err[512] = "";
        cr_assert(!scene_parse(&s, "bad.scene", b->text, bad_len(b), err, sizeof err),
                  "'%s' was accepted", b->name);
        cr_assert_eq(s.ntris, 0, "%s: the scene is left empty", b->name);
        cr_assert_null(s.tris, "%s: the scene is left empty", b->name);
        cr_assert(s.nlines == 0 && !s.lines, "%s: the scene is left without lines", b->name);
        char line[600];
        snprintf(line, sizeof line, "%s\n", err);
        expect_located_message(line, "bad.scene", b->line, b->name);
    }
}

static const char *const keep_scene[] = { "bad.scene", NULL };

Test(cli, malformed_scenes_exit_2_with_file_line_message_and_no_output, .timeout = 120, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char scene[300], out[300], png[300];
    snprintf(scene, sizeof scene, "%s/bad.scene", d.work);
    snprintf(out, sizeof out, "%s/out.pgm", d.work);
    snprintf(png, sizeof png, "%s/out.png", d.work);
    for (int k = 0; k < p.n; k++)
        for (size_t i = 0; i < N_BAD_SCENES; i++) {
            const struct bad_scene *b = &bad_scenes[i];
            write_file(scene, b->text, bad_len(b));
            char *argv[] = { p.path[k], "--scene", scene, "--dump-coverage", out,
                             i % 3 == 0 ? "--dump-image" : NULL, png, NULL };
            struct result r = run(argv, d.scratch);
            char what[200], stray[256] = "";
            snprintf(what, sizeof what, "%s, scene '%s'", p.name[k], b->name);
            cr_assert_eq(r.status, 2, "%s: exit status %d (stderr: %s)", what, r.status, r.err);
            expect_located_message(r.err, scene, b->line, what);
            cr_assert_eq(stray_files(d.work, keep_scene, stray, sizeof stray), 0,
                         "%s: left '%s' behind", what, stray);
            result_free(&r);
        }
    dirs_remove(&d);
}

/* Bad 3-D input (the whole list is read in-process by test_scene3.c): the
 * message names the scene's line, or the OBJ file's own line. */
static const struct bad_scene3 {
    const char *name, *scene, *obj;
    bool in_obj;
    int line;
} bad_scenes3[] = {
    { "up parallel to the view direction", "size 8 8\ncamera 0 0 5  0 0 0  0 0 1  60 0.1 100\n", NULL, false, 2 },
    { "near = 0", "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  60 0 100\n", NULL, false, 2 },
    { "far <= near", "size 8 8\n# c\ncamera 0 0 5  0 0 0  0 1 0  60 2 2\n", NULL, false, 3 },
    { "eye = target", "size 8 8\ncamera 1 2 3  1 2 3  0 1 0  60 0.1 100\n", NULL, false, 2 },
    { "world coordinate beyond 10^6", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 60 0.1 100\n"
      "tri3 0 0 0 1 1 1  1 0 0 1 1 1  0 1e7 0 1 1 1\n", NULL, false, 3 },
    { "missing OBJ", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 60 0.1 100\nobj missing.obj 1 1 1\n", NULL, false, 3 },
    { "OBJ index out of range", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 60 0.1 100\nobj bad.obj 1 1 1\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", true, 5 },
    { "malformed OBJ", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 60 0.1 100\nobj bad.obj 1 1 1\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 zero\n", true, 3 },
    { "non-finite OBJ vertex", "size 8 8\ncamera 0 0 5 0 0 0 0 1 0 60 0.1 100\nobj bad.obj 1 1 1\n",
      "v 0 0 0\nv inf 0 0\n", true, 2 },
};

Test(cli, bad_3d_scenes_and_objs_exit_2_with_file_line_message_and_no_output, .timeout = 120, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char scene[300], obj[300], out[300], png[300];
    snprintf(scene, sizeof scene, "%s/bad.scene", d.work);
    snprintf(obj, sizeof obj, "%s/bad.obj", d.work);
    snprintf(out, sizeof out, "%s/out.pgm", d.work);
    snprintf(png, sizeof png, "%s/out.png", d.work);
    static const char *const keep[] = { "bad.scene", "bad.obj", NULL };
    for (int k = 0; k < p.n; k++)
        for (size_t i = 0; i < sizeof bad_scenes3 / sizeof bad_scenes3[0]; i++) {
            const struct bad_scene3 *b = &bad_scenes3[i];
            write_file(scene, b->scene, strlen(b->scene));
            unlink(obj);
            if (b->obj)
                write_file(obj, b->obj, strlen(b->obj));
            char *argv[] = { p.path[k], "--scene", scene, "--dump-coverage", out, "--dump-image", png, NULL };
            struct result r = run(argv, d.scratch);
            char what[200], stray[256] = "";
            snprintf(what, sizeof what, "%s, 3-D scene '%s'", p.name[k], b->name);
            cr_assert_eq(r.status, 2, "%s: exit status %d (stderr: %s)", what, r.status, r.err);
            expect_located_message(r.err, b->in_obj ? obj : scene, b->line, what);
            cr_assert_eq(r.out_len, 0, "%s: wrote to stdout: %s", what, r.out);
            cr_assert_eq(stray_files(d.work, keep, stray, sizeof stray), 0, "%s: left '%s' behind",
                         what, stray);
            result_free(&r);
        }
    dirs_remove(&d);
}

/* --- malformed command lines ------------------------------------------------------- */

struct bad_args {
    const char *name;
    const char *args[6];    /* after "--dump-coverage OUT"; NULL-terminated */
    const char *mention;    /* the message names this (NULL: not checked) */
};

static const struct bad_args bad_command_lines[] = {
    { "unknown long option", { "--bogus", NULL }, "--bogus" },
    { "unknown short option", { "-x", NULL }, "-x" },
    /* regression: bundled unknown short options named the wrong argument */
    { "bundled short options named the wrong argument", { "-qz", NULL }, "-q" },
    { "missing value of --scene", { "--scene", NULL }, "--scene" },
    { "missing value of --dump-image", { "--dump-image", NULL }, "--dump-image" },
    { "missing value of --variant", { "--variant", NULL }, "--variant" },
    { "bad --step word", { "--step", "abc", NULL }, "abc" },
    { "negative --step", { "--step", "-1", NULL }, "-1" },
    { "fractional --step", { "--step", "1.5", NULL }, "1.5" },
    { "bad --figure suffix", { "--figure", "fig.jpg", NULL }, "fig.jpg" },
    { "--figure without suffix", { "--figure", "fig", NULL }, "fig" },
    { "stray argument", { "scene.txt", NULL }, "scene.txt" },
    { "stray argument after options", { "--step", "3", "extra", NULL }, "extra" },
    { "unknown variant", { "--variant", "no-such-variant", NULL }, "no-such-variant" },
    { "missing scene file", { "--scene", "/nonexistent/dir/x.scene", NULL }, "/nonexistent/dir/x.scene" },
    { "unknown built-in scene", { "--scene", "builtin:no-such-scene", NULL }, NULL },
    { "--size too small", { "--size", "10x10", NULL }, "10x10" },
    { "--size malformed", { "--size", "640by480", NULL }, "640by480" },
    { "--block-size 5", { "--block-size", "5", NULL }, "5" },
    { "--subpixel-bits 9", { "--subpixel-bits", "9", NULL }, "9" },
    { "--zoom 0", { "--zoom", "0", NULL }, "0" },
    { "--scale nan", { "--scale", "nan", NULL }, "nan" },
};
#define N_BAD_ARGS (sizeof bad_command_lines / sizeof bad_command_lines[0])

static const char *const keep_nothing[] = { NULL };

Test(cli, malformed_command_lines_exit_2_with_a_message_and_no_output, .timeout = 120, .fini = remove_live_dirs)
{
    cr_assert_geq(N_BAD_ARGS, 7);
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char out[300];
    snprintf(out, sizeof out, "%s/out.pgm", d.work);
    for (int k = 0; k < p.n; k++)
        for (size_t i = 0; i < N_BAD_ARGS; i++) {
            const struct bad_args *b = &bad_command_lines[i];
            char *argv[12] = { p.path[k], "--dump-coverage", out };
            int n = 3;
            for (int j = 0; b->args[j]; j++)
                argv[n++] = (char *)b->args[j];
            argv[n] = NULL;
            struct result r = run(argv, d.scratch);
            char what[200], stray[256] = "";
            snprintf(what, sizeof what, "%s, %s", p.name[k], b->name);
            cr_assert_eq(r.status, 2, "%s: exit status %d (stderr: %s)", what, r.status, r.err);
            cr_assert_gt(r.err_len, 0, "%s: no message on stderr", what);
            if (b->mention)
                cr_assert(strstr(r.err, b->mention), "%s: the message does not name '%s': %s",
                          what, b->mention, r.err);
            cr_assert_eq(r.out_len, 0, "%s: wrote to stdout: %s", what, r.out);
            cr_assert_eq(stray_files(d.work, keep_nothing, stray, sizeof stray), 0,
                         "%s: left '%s' behind", what, stray);
            result_free(&r);
        }
    dirs_remove(&d);
}

/* --- failures while running ------------------------------------------------------ */

Test(cli, unwritable_output_exits_1_and_leaves_nothing, .timeout = 60, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char out[300], missing[300], png_missing[300];
    snprintf(out, sizeof out, "%s/out.pgm", d.work);
    snprintf(missing, sizeof missing, "%s/no-such-dir/out.pgm", d.work);
    snprintf(png_missing, sizeof png_missing, "%s/no-such-dir/out.png", d.work);
    for (int k = 0; k < p.n; k++) {
        char stray[256] = "";
        /* a directory that does not exist */
        char *a1[] = { p.path[k], "--scene", "builtin:fan", "--dump-coverage", missing, NULL };
        struct result r = run(a1, d.scratch);
        cr_assert_eq(r.status, 1, "%s: exit %d for %s (stderr: %s)", p.name[k], r.status, missing, r.err);
        cr_assert_gt(r.err_len, 0, "%s: no message", p.name[k]);
        cr_assert_eq(stray_files(d.work, keep_nothing, stray, sizeof stray), 0, "%s: left %s", p.name[k], stray);
        result_free(&r);

        /* the coverage file could be written, the image not: neither stays */
        char *a2[] = { p.path[k], "--scene", "builtin:triangle", "--dump-coverage", out, "--dump-image", png_missing, NULL };
        r = run(a2, d.scratch);
        cr_assert_eq(r.status, 1, "%s: exit %d (stderr: %s)", p.name[k], r.status, r.err);
        cr_assert_eq(stray_files(d.work, keep_nothing, stray, sizeof stray), 0,
                     "%s: a failed run left '%s'", p.name[k], stray);
        result_free(&r);

        /* the output path is a directory: it stays a directory, no temp file */
        char dir_out[300];
        snprintf(dir_out, sizeof dir_out, "%s/a-directory", d.work);
        cr_assert_eq(mkdir(dir_out, 0755), 0);
        char *a3[] = { p.path[k], "--scene", "builtin:triangle", "--dump-coverage", dir_out, NULL };
        r = run(a3, d.scratch);
        cr_assert_eq(r.status, 1, "%s: exit %d writing over a directory (stderr: %s)", p.name[k], r.status, r.err);
        const char *keep_dir[] = { "a-directory", NULL };
        cr_assert_eq(stray_files(d.work, keep_dir, stray, sizeof stray), 0, "%s: left '%s'", p.name[k], stray);
        struct stat st;
        cr_assert(stat(dir_out, &st) == 0 && S_ISDIR(st.st_mode));
        rmdir(dir_out);
        result_free(&r);
    }
    dirs_remove(&d);
}

Test(cli, help_and_version_exit_0_on_stdout, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    for (int k = 0; k < p.n; k++) {
        const char *opts[] = { "--help", "--version" };
        for (int i = 0; i < 2; i++) {
            char *argv[] = { p.path[k], (char *)opts[i], NULL };
            struct result r = run(argv, d.scratch);
            cr_assert_eq(r.status, 0, "%s %s: exit %d", p.name[k], opts[i], r.status);
            cr_assert_gt(r.out_len, 0, "%s %s: nothing on stdout", p.name[k], opts[i]);
            cr_assert_eq(r.err_len, 0, "%s %s: stderr: %s", p.name[k], opts[i], r.err);
            if (i == 0)
                cr_assert(strstr(r.out, "--dump-coverage") && strstr(r.out, "--scene"),
                          "%s --help does not describe the options", p.name[k]);
            const struct lesson *l = lesson_of(p.name[k]);
            if (i == 0 && l && !l->lines)
                cr_assert(strstr(r.out, "\nLines: a scene line 'line ") && strstr(r.out, "ignores it"),
                          "%s --help does not say that it ignores lines:\n%s", p.name[k], r.out);
            result_free(&r);
        }
    }
    dirs_remove(&d);
}

Test(cli, every_lesson_has_a_program)
{
    struct programs p;
    find_programs(&p);
    for (int i = 0; all_lessons[i]; i++) {
        bool found = false;
        for (int k = 0; k < p.n; k++)
            found |= strcmp(p.name[k], all_lessons[i]->id) == 0;
        cr_expect(found, "no program %s/%s", test_build_dir(), all_lessons[i]->id);
    }
    for (int k = 0; k < p.n; k++)
        cr_expect_not_null(lesson_of(p.name[k]), "program %s has no lesson", p.name[k]);
}

/* --- --dump-coverage against the reference ----------------------------------------- */

/* Parse a PGM strictly: exactly "P5\nW H\n255\n" then W * H bytes. */
static const uint8_t *pgm_pixels(const char *data, size_t len, int w, int h, const char *what)
{
    char header[64];
    int n = snprintf(header, sizeof header, "P5\n%d %d\n255\n", w, h);
    cr_assert(len >= (size_t)n && memcmp(data, header, (size_t)n) == 0,
              "%s: the header is not 'P5\\n%d %d\\n255\\n'", what, w, h);
    cr_assert_eq(len, (size_t)n + (size_t)w * (size_t)h, "%s: %zu bytes, expected %zu", what,
                 len, (size_t)n + (size_t)w * (size_t)h);
    return (const uint8_t *)data + n;
}

/* The reference picture of a scene file: parse, set up with `bits`
 * fractional bits, reference_mask. */
static uint8_t *reference_of(const char *path, struct scene *s, int bits)
{
    char err[512];
    cr_assert(scene_load(s, path, err, sizeof err), "%s", err);
    cr_assert(front_scene(s));      /* a 3-D scene: its screen triangles */
    uint8_t *mask = calloc((size_t)s->w * (size_t)s->h, 1);
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s->tris[i].v, s->w, s->h, bits);
        reference_mask(&t, mask);
    }
    return mask;
}

static void fprint_vertex(FILE *f, const struct vertex *v, bool st)
{
    fprintf(f, "  %.17g %.17g %.17g %.17g %.17g %.17g", v->x, v->y, v->z, v->r, v->g, v->b);
    if (st)
        fprintf(f, " %.17g %.17g", v->s, v->t);
}

/* Scenes written here with fprintf (not scene_write): random triangles of
 * every category, a jittered strip mesh, 300 copies of one triangle, the
 * 24-number form with a texture, huge triangles at the coordinate limits. */
static void write_scenes(const char *dir, char names[][300], int *count)
{
    struct rng r = rng_for(5000);
    int n = 0;
    for (int kind = 0; kind < 6; kind++) {
        snprintf(names[n], 300, "%s/scene%d.scene", dir, kind);
        FILE *f = fopen(names[n], "w");
        cr_assert_not_null(f);
        int w = rng_int(&r, 20, 70), h = rng_int(&r, 20, 50);
        bool st = kind == 3;
        fprintf(f, "# generated: kind %d\nsize %d %d\nbackground 0.1 0.2 0.3\n", kind, w, h);
        if (st)
            fprintf(f, "texture checker 4\n");
        int ntris = kind == 2 ? 300 : 80;
        struct vertex fixed[3];
        random_tri(&r, CAT_GENERIC, w, h, fixed);
        for (int i = 0; i < ntris; i++) {
            struct vertex v[3];
            if (kind == 2)
                memcpy(v, fixed, sizeof v);                 /* saturation at 255 */
            else if (kind == 4)
                random_tri(&r, CAT_LARGE, w, h, v);         /* far outside, to the limits */
            else if (kind == 5)
                random_tri(&r, i % 2 ? CAT_SLIVER : CAT_CENTRES, w, h, v);
            else
                random_tri(&r, (enum tri_category)(i % CAT_COUNT), w, h, v);
            fprintf(f, "tri");
            for (int k = 0; k < 3; k++)
                fprint_vertex(f, &v[k], st);
            fprintf(f, "\n");
        }
        if (kind == 1) {
            /* a strip of quads sharing vertical edges through centres */
            for (int i = 0; i < 8; i++) {
                double x0 = 2.5 + 2 * i, x1 = x0 + 2;
                fprintf(f, "tri %g 3.25 1 1 0 0  %g 3.25 1 0 1 0  %g 17.75 1 0 0 1\n", x0, x1, x1);
                fprintf(f, "tri %g 3.25 1 1 0 0  %g 17.75 1 0 0 1  %g 17.75 1 0 1 0\n", x0, x1, x0);
            }
        }
        cr_assert_eq(fclose(f), 0);
        n++;
    }
    /* 3-D scenes: a room seen from inside (every wall cut by the near plane
     * and reaching past the guard band), an OBJ model culled */
    snprintf(names[n], 300, "%s/room.scene", dir);
    FILE *f = fopen(names[n++], "w");
    cr_assert_not_null(f);
    fprintf(f, "size 61 43\ncamera 0.3 -0.2 0.1  2 0.5 -1  0.1 1 0  100 0.003 50\n");
    static const int quads[6][4] = { { 0, 1, 3, 2 }, { 4, 6, 7, 5 }, { 0, 4, 5, 1 },
                                      { 2, 3, 7, 6 }, { 0, 2, 6, 4 }, { 1, 5, 7, 3 } };
    for (int q = 0; q < 6; q++)
        for (int t = 0; t < 2; t++) {
            fprintf(f, "tri3");
            for (int k = 0; k < 3; k++) {
                int c = quads[q][t == 0 ? k : (k + 2) % 4];
                fprintf(f, "  %d %d %d  %.3f %.3f %.3f", c & 1 ? 2 : -2, c & 2 ? 1 : -1,
                        c & 4 ? 3 : -3, q / 6.0, k / 3.0, t * 0.5);
            }
            fprintf(f, "\n");
        }
    cr_assert_eq(fclose(f), 0);
    char obj[300];
    snprintf(obj, sizeof obj, "%s/model.obj", dir);
    const char *model = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                        "v 1 1 1\nv -1 1 1\nvt 0.5 0.5\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2/1 3/1 7/1 6/1\n"
                        "f 3//2 4//2 8//2 7//2\nf -8 -3 -1 -4\n";
    write_file(obj, model, strlen(model));
    snprintf(names[n], 300, "%s/model.scene", dir);
    const char *culled = "size 50 40\nbackground 0.1 0.1 0.1\n"
                         "camera 3 2.5 4  0 0 0  0 1 0  50 0.5 20\ncull back\nobj model.obj 0.8 0.6 0.3\n";
    write_file(names[n++], culled, strlen(culled));

    /* a 1 x 1 scene and a scene with no triangles */
    snprintf(names[n], 300, "%s/tiny.scene", dir);
    const char *tiny = "size 1 1\ntri 0 0 1 1 1 1  1 0 1 1 1 1  0 1 1 1 1 1\r\n";
    write_file(names[n++], tiny, strlen(tiny));
    snprintf(names[n], 300, "%s/empty.scene", dir);
    write_file(names[n++], "size 5 3\n", strlen("size 5 3\n"));
    *count = n;
}

/* Run one --dump-coverage (bits < 0: without --subpixel-bits) and compare. */
static void check_dump_bits(const char *program, const char *variant, const char *scene_arg,
                            const char *scene_path, int bits, const struct dirs *d)
{
    char out[300], bits_arg[16];
    snprintf(out, sizeof out, "%s/out.pgm", d->work);
    snprintf(bits_arg, sizeof bits_arg, "%d", bits);
    char *argv[12] = { (char *)program, "--scene", (char *)scene_arg, "--dump-coverage", out };
    int n = 5;
    if (variant) {
        argv[n++] = "--variant";
        argv[n++] = (char *)variant;
    }
    if (bits >= 0) {
        argv[n++] = "--subpixel-bits";
        argv[n++] = bits_arg;
    }
    /* a lesson with samples (08) counts samples, 4 by default: one sample is
     * the pixel centre (its sample counts are test_lesson08.c's) */
    const struct lesson *l = lesson_of(strrchr(program, '/') ? strrchr(program, '/') + 1 : program);
    if (l && lesson_param(l, "samples", NULL)) {
        argv[n++] = "--samples";
        argv[n++] = "1";
    }
    argv[n] = NULL;
    struct result r = run(argv, d->scratch);
    char what[700];
    snprintf(what, sizeof what, "%s%s%s --scene %s%s%s", program, variant ? " --variant " : "",
             variant ? variant : "", scene_arg, bits >= 0 ? " --subpixel-bits " : "",
             bits >= 0 ? bits_arg : "");
    cr_assert_eq(r.status, 0, "%s: exit %d (stderr: %s)", what, r.status, r.err);
    result_free(&r);

    size_t len;
    char *data = slurp(out, &len);
    cr_assert_not_null(data, "%s: no %s", what, out);
    struct scene s;
    uint8_t *ref = reference_of(scene_path, &s, bits >= 0 ? bits : SUBPIXEL_BITS);
    const uint8_t *px = pgm_pixels(data, len, s.w, s.h, what);
    struct case_info info = { what, test_seed(), 0, NULL, 0 };
    cr_assert(coverage_equal(ref, px, s.w, s.h, &info));
    free(ref);
    free(data);
    scene_free(&s);
    unlink(out);
}

static void check_dump(const char *program, const char *variant, const char *scene_arg,
                       const char *scene_path, const struct dirs *d)
{
    check_dump_bits(program, variant, scene_arg, scene_path, -1, d);
}

Test(cli, dump_coverage_equals_the_reference_byte_for_byte, .timeout = 180, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char scenes[16][300];
    int nscenes;
    write_scenes(d.scratch, scenes, &nscenes);
    for (int k = 0; k < p.n; k++) {
        for (int i = 0; i < builtin_scene_count; i++) {
            char arg[64];
            snprintf(arg, sizeof arg, "builtin:%s", builtin_scenes[i].name);
            check_dump(p.path[k], NULL, arg, arg, &d);
        }
        for (int i = 0; i < nscenes; i++)
            check_dump(p.path[k], NULL, scenes[i], scenes[i], &d);
        /* every exact variant of the program's lesson, on the mixed scene */
        const struct lesson *l = lesson_of(p.name[k]);
        cr_assert_not_null(l, "program %s has no lesson", p.name[k]);
        for (int v = 0; v < l->nvariants; v++)
            if (!variant_against_exact(&l->variants[v]))
                check_dump(p.path[k], l->variants[v].name, scenes[0], scenes[0], &d);
    }
    dirs_remove(&d);
}

/* Regression: --subpixel-bits 0 was read as "the default" and snapped to 8
 * bits. Every precision must match the reference snapped the same way. */
/* Scene text `text` with a `line` statement after every line that stands
 * after `size` (the first one at the top of the screen's corner, the others
 * across it, through pixel centres and corners, one of zero length, one
 * far off screen): lessons 01 to 09 read them and draw the triangles alone. */
static char *with_lines(const char *text)
{
    static const char *const lines[] = {
        "line 0 0 1  1 0 0   63.5 40.25 1  0 1 0\n",
        "line 2.5 2.5 0.5  1 1 1   2.5 2.5 0.5  1 1 1\n",
        "line -16384 -3 1e-6  0 0 1   16383.99 7 1e6  1 1 0\n",
        "line 10 1 0.001  1 1 1   10 30 0.001  0 0 0\n",
    };
    size_t n = strlen(text), cap = 2 * n + 4096, len = 0;
    char *out = malloc(cap);
    cr_assert_not_null(out);
    bool sized = false;
    int k = 0;
    for (const char *c = text; *c;) {
        const char *nl = strchr(c, '\n');
        size_t m = nl ? (size_t)(nl - c) + 1 : strlen(c);
        cr_assert_lt(len + m + 200, cap);
        memcpy(out + len, c, m);
        len += m;
        if (!nl)
            out[len++] = '\n';
        sized = sized || strncmp(c, "size", 4) == 0;
        if (sized) {
            const char *l = lines[k++ % 4];
            memcpy(out + len, l, strlen(l));
            len += strlen(l);
        }
        c += m;
    }
    out[len] = '\0';
    return out;
}

/* Run program on scene file `scene` (its name under d->work), dumping
 * coverage and image; the bytes of both, their names saved in *pgm, *png. */
static void dump_both(const char *program, const char *scene, const struct dirs *d,
                      char **pgm, size_t *npgm, char **png, size_t *npng)
{
    char spath[300], cov[300], img[300];
    snprintf(spath, sizeof spath, "%s/%s", d->work, scene);
    snprintf(cov, sizeof cov, "%s/out.pgm", d->work);
    snprintf(img, sizeof img, "%s/out.png", d->work);
    char *argv[] = { (char *)program, "--scene", spath, "--dump-coverage", cov, "--dump-image", img, NULL };
    struct result r = run(argv, d->scratch);
    cr_assert_eq(r.status, 0, "%s --scene %s: exit %d (stderr: %s)", program, spath, r.status, r.err);
    result_free(&r);
    *pgm = slurp(cov, npgm);
    *png = slurp(img, npng);
    cr_assert(*pgm && *png, "%s --scene %s: no output", program, spath);
    unlink(cov);
    unlink(img);
}

Test(cli, line_statements_change_no_pixel_of_lessons_01_to_09, .timeout = 120, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;
    dirs_make(&d);
    int tested = 0;
    for (int k = 0; k < p.n; k++) {
        const struct lesson *l = lesson_of(p.name[k]);
        cr_assert_not_null(l, "program %s has no lesson", p.name[k]);
        if (l->lines)
            continue;       /* the lesson that draws lines */
        /* the lesson's own built-in scene (3-D from lesson 06 on), a 2-D
         * one under an image texture and one of triangles crossing in depth */
        const char *names[] = { l->builtin_scene, "texture-close", "overlap" };
        for (int i = 0; i < 3; i++) {
            const struct builtin_scene *b = builtin_find(names[i]);
            cr_assert_not_null(b, "no built-in scene %s", names[i]);
            char *text = with_lines(b->text);
            cr_assert_not_null(strstr(text, "\nline "));
            char plain[300], lined[300];
            snprintf(plain, sizeof plain, "%s/plain.scene", d.work);
            snprintf(lined, sizeof lined, "%s/lines.scene", d.work);
            write_file(plain, b->text, strlen(b->text));
            write_file(lined, text, strlen(text));
            char *pgm[2], *png[2];
            size_t npgm[2], npng[2];
            dump_both(p.path[k], "plain.scene", &d, &pgm[0], &npgm[0], &png[0], &npng[0]);
            dump_both(p.path[k], "lines.scene", &d, &pgm[1], &npgm[1], &png[1], &npng[1]);
            cr_assert(npgm[0] == npgm[1] && memcmp(pgm[0], pgm[1], npgm[0]) == 0,
                      "%s, builtin:%s: the coverage changed with line statements", p.name[k], names[i]);
            cr_assert(npng[0] == npng[1] && memcmp(png[0], png[1], npng[0]) == 0,
                      "%s, builtin:%s: the image changed with line statements", p.name[k], names[i]);
            for (int j = 0; j < 2; j++)
                free(pgm[j]), free(png[j]);
            free(text);
            tested++;
        }
    }
    cr_assert_geq(tested, 27, "lessons 01 to 09, three scenes each");
    dirs_remove(&d);
}

Test(cli, subpixel_bits_0_was_read_as_8, .timeout = 60, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char scenes[16][300];
    int nscenes;
    write_scenes(d.scratch, scenes, &nscenes);
    for (int k = 0; k < p.n; k++)
        for (int bits = 0; bits <= SUBPIXEL_BITS; bits += 2)
            check_dump_bits(p.path[k], NULL, scenes[5], scenes[5], bits, &d);
    dirs_remove(&d);
}

/* The same regression through --figure: the explorer read 0 as "the default"
 * and drew 8 bits, so --figure --subpixel-bits 0 drew the 8-bit picture.
 * Whole pixels move the triangle's vertices (4.3 -> 4, ...): the figure
 * must change, and 8 bits must be what no option gives. */
Test(cli, figure_subpixel_bits_0_was_drawn_with_8, .timeout = 60, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char path[3][300];
    const char *bits[3] = { "0", "8", NULL };
    size_t len[3];
    char *data[3];
    for (int i = 0; i < 3; i++) {
        snprintf(path[i], sizeof path[i], "%s/bits-%s.png", d.work, bits[i] ? bits[i] : "default");
        char *argv[16] = { p.path[0], "--scene", "builtin:triangle", "--figure", path[i], "--step",
                           "end", "--view", "coverage", "--size", "640x400" };
        if (bits[i])
            argv[11] = "--subpixel-bits", argv[12] = (char *)bits[i];
        struct result r = run(argv, d.scratch);
        cr_assert_eq(r.status, 0, "%s --subpixel-bits %s: exit %d (%s)", p.name[0],
                     bits[i] ? bits[i] : "(none)", r.status, r.err);
        result_free(&r);
        data[i] = slurp(path[i], &len[i]);
        cr_assert(data[i] && len[i] > 0);
    }
    cr_assert(len[0] != len[1] || memcmp(data[0], data[1], len[0]) != 0,
              "--figure with --subpixel-bits 0 draws the same picture as 8");
    cr_assert(len[1] == len[2] && memcmp(data[1], data[2], len[1]) == 0,
              "--subpixel-bits 8 is not the default picture");
    for (int i = 0; i < 3; i++)
        free(data[i]);
    dirs_remove(&d);
}

/* The fonts could not be pinned (no writable TMPDIR): a figure would come
 * out in the system's fonts, so --figure says why and writes nothing. */
Test(cli, figure_without_pinned_fonts_fails_and_says_so, .timeout = 30, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char out[300], missing[300];
    snprintf(out, sizeof out, "%s/figure.png", d.work);
    snprintf(missing, sizeof missing, "%s/no-such-dir", d.work);
    cr_assert_eq(setenv("TMPDIR", missing, 1), 0);
    char *argv[] = { p.path[0], "--figure", out, NULL };
    struct result r = run(argv, d.scratch);
    unsetenv("TMPDIR");
    cr_assert_eq(r.status, 1, "exit %d (stderr: %s)", r.status, r.err);
    cr_assert(strstr(r.err, "fonts") && strstr(r.err, missing), "stderr: %s", r.err);
    char stray[256] = "";
    cr_assert_eq(stray_files(d.work, keep_nothing, stray, sizeof stray), 0, "left %s", stray);
    result_free(&r);
    dirs_remove(&d);
}

/* A --keys file is input like a scene: a line too long for a key name is
 * an error at its line, not cut into two keys; a missing file names itself.
 * Both are found before any window opens. */
Test(cli, keys_file_errors_exit_2_at_their_line, .timeout = 30, .fini = remove_live_dirs)
{
    struct programs p;
    find_programs(&p);
    static struct dirs d;   /* static: .fini may run after the test returned early */
    dirs_make(&d);
    char keys[300], text[400];
    snprintf(keys, sizeof keys, "%s/keys", d.work);
    int n = snprintf(text, sizeof text, "# a comment\nRight\n%0300d\nLeft\n", 7);
    write_file(keys, text, (size_t)n);
    char *argv[] = { p.path[0], "--keys", keys, NULL };
    struct result r = run(argv, d.scratch);
    cr_assert_eq(r.status, 2, "exit %d (stderr: %s)", r.status, r.err);
    char where[320];
    snprintf(where, sizeof where, "%s:3: line longer than", keys);
    cr_assert(strstr(r.err, where), "stderr: %s", r.err);
    result_free(&r);

    remove(keys);
    r = run(argv, d.scratch);
    snprintf(where, sizeof where, "%s:0: cannot open", keys);
    cr_assert_eq(r.status, 2, "exit %d (stderr: %s)", r.status, r.err);
    cr_assert(strstr(r.err, where), "stderr: %s", r.err);
    result_free(&r);
    dirs_remove(&d);
}

/* One suffix test for every file name (figure.c once said >= where cli.c
 * said >): a name is something before its suffix. */
Test(cli, a_file_name_is_more_than_its_suffix)
{
    cr_assert(has_suffix("a.png", ".png"));
    cr_assert(has_suffix("dir/.x.pdf", ".pdf"));
    cr_assert_not(has_suffix(".png", ".png"));
    cr_assert_not(has_suffix("png", ".png"));
    cr_assert_not(has_suffix("a.svg", ".png"));
    cr_assert_not(has_suffix("a.png.tmp", ".png"));
}
