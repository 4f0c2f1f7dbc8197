/* test_layers.c - the folders of src/ include each other only downwards, in
 * the order src/layers.h lists (so there is no cycle between folders).
 *
 * The folder graph comes from the #include "..." lines of every .c and .h
 * file under src/: an include resolves beside the including file first,
 * then under src/ (the compiler's -Isrc), as the compiler resolves it. */
#define _POSIX_C_SOURCE 200809L   /* opendir */

#include <criterion/criterion.h>
#include <ctype.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "layers.h"

static const char *const layers[] = { TRISTEP_LAYERS };
#define NLAYERS ((int)(sizeof layers / sizeof layers[0]))
#define MAXF 32     /* folders seen, listed or not */

struct graph {
    int nf;
    char folder[MAXF][32];
    int edges[MAXF][MAXF];              /* includes from folder i into folder j */
    char example[MAXF][MAXF][160];      /* the first file:line that made the edge */
    char unresolved[512];               /* an include found nowhere */
};

static int folder_id(struct graph *g, const char *name)
{
    for (int i = 0; i < g->nf; i++)
        if (strcmp(g->folder[i], name) == 0)
            return i;
    cr_assert_lt(g->nf, MAXF);
    snprintf(g->folder[g->nf], sizeof g->folder[0], "%s", name);
    return g->nf++;
}

static int rank(const char *folder)
{
    for (int i = 0; i < NLAYERS; i++)
        if (strcmp(layers[i], folder) == 0)
            return i;
    return -1;
}

static void add_edge(struct graph *g, const char *from, const char *to, const char *where)
{
    int a = folder_id(g, from), b = folder_id(g, to);
    if (a != b && g->edges[a][b]++ == 0)
        snprintf(g->example[a][b], sizeof g->example[a][b], "%s", where);
}

static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The folder of a path under src/ ("src/draw/paint.h" -> "draw", "src/lesson.h" -> "."). */
static void folder_of(const char *path, char *out, size_t n)
{
    const char *rest = path + strlen("src/");
    const char *slash = strchr(rest, '/');
    if (!slash)
        snprintf(out, n, ".");
    else
        snprintf(out, n, "%.*s", (int)(slash - rest), rest);
}

static void scan_file(struct graph *g, const char *path)
{
    FILE *f = fopen(path, "r");
    cr_assert(f, "cannot read %s", path);
    char from[32], line[512];
    folder_of(path, from, sizeof from);
    folder_id(g, from);
    for (int no = 1; fgets(line, sizeof line, f); no++) {
        const char *s = line;
        while (isspace((unsigned char)*s))
            s++;
        if (*s++ != '#')
            continue;
        while (isspace((unsigned char)*s))
            s++;
        if (strncmp(s, "include", 7) != 0)
            continue;
        s += 7;
        while (isspace((unsigned char)*s))
            s++;
        if (*s != '"')
            continue;       /* <system> headers */
        const char *e = strchr(s + 1, '"');
        if (!e)
            continue;
        char name[256], beside[768], under[300], where[160], to[32];
        snprintf(name, sizeof name, "%.*s", (int)(e - s - 1), s + 1);
        const char *dir_end = strrchr(path, '/');
        snprintf(beside, sizeof beside, "%.*s/%s", (int)(dir_end - path), path, name);
        snprintf(under, sizeof under, "src/%s", name);
        snprintf(where, sizeof where, "%.140s:%d", path, no);
        if (exists(beside))
            folder_of(beside, to, sizeof to);
        else if (exists(under))
            folder_of(under, to, sizeof to);
        else {
            snprintf(g->unresolved, sizeof g->unresolved, "%s: \"%s\" is not under src/", where,
                     name);
            continue;
        }
        add_edge(g, from, to, where);
    }
    fclose(f);
}

static void scan_dir(struct graph *g, const char *dir)
{
    DIR *d = opendir(dir);
    cr_assert(d, "cannot list %s (the tests run from the repository's root)", dir);
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.')
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        struct stat st;
        if (stat(path, &st) != 0)
            continue;
        size_t n = strlen(de->d_name);
        if (S_ISDIR(st.st_mode))
            scan_dir(g, path);
        else if (n > 2 && (strcmp(de->d_name + n - 2, ".c") == 0 || strcmp(de->d_name + n - 2, ".h") == 0))
            scan_file(g, path);
    }
    closedir(d);
}

/* The graph as text: "cli -> app (3), draw (2), ..." per folder. */
static void describe(const struct graph *g, char *buf, size_t n)
{
    size_t at = 0;
    buf[0] = '\0';
    for (int a = 0; a < g->nf && at < n; a++) {
        at += (size_t)snprintf(buf + at, n - at, "\n  %-8s ->", g->folder[a]);
        for (int b = 0; b < g->nf && at < n; b++)
            if (g->edges[a][b])
                at += (size_t)snprintf(buf + at, n - at, " %s (%d)", g->folder[b], g->edges[a][b]);
    }
}

/* A cycle through the folder graph as "a -> b (file:line) -> a (file:line)", or false. */
static bool dfs(const struct graph *g, int v, int *state, int *stack, int depth, char *out, size_t n)
{
    state[v] = 1;
    stack[depth] = v;
    for (int w = 0; w < g->nf; w++) {
        if (!g->edges[v][w])
            continue;
        if (state[w] == 1) {
            size_t at = 0;
            int k = depth;
            while (stack[k] != w)
                k--;
            at += (size_t)snprintf(out + at, n - at, "%s", g->folder[w]);
            for (; k <= depth && at < n; k++) {
                int to = k < depth ? stack[k + 1] : w;
                at += (size_t)snprintf(out + at, n - at, " -> %s (%s)", g->folder[to],
                                       g->example[stack[k]][to]);
            }
            return true;
        }
        if (state[w] == 0 && dfs(g, w, state, stack, depth + 1, out, n))
            return true;
    }
    state[v] = 2;
    return false;
}

static bool find_cycle(const struct graph *g, char *out, size_t n)
{
    int state[MAXF] = { 0 }, stack[MAXF];
    for (int v = 0; v < g->nf; v++)
        if (state[v] == 0 && dfs(g, v, state, stack, 0, out, n))
            return true;
    return false;
}

/* The first problem of the graph, or false when it keeps the order. */
static bool violation(const struct graph *g, char *out, size_t n)
{
    if (g->unresolved[0]) {
        snprintf(out, n, "%s", g->unresolved);
        return true;
    }
    for (int a = 0; a < g->nf; a++)
        if (rank(g->folder[a]) < 0) {
            snprintf(out, n, "src/%s is not in src/layers.h: add it in its place", g->folder[a]);
            return true;
        }
    char cycle[1024];
    if (find_cycle(g, cycle, sizeof cycle)) {
        snprintf(out, n, "a cycle between folders: %s", cycle);
        return true;
    }
    for (int a = 0; a < g->nf; a++)
        for (int b = 0; b < g->nf; b++)
            if (g->edges[a][b] && rank(g->folder[a]) < rank(g->folder[b])) {
                snprintf(out, n, "%s includes %s/, a later layer (src/layers.h)",
                         g->example[a][b], g->folder[b]);
                return true;
            }
    return false;
}

Test(layers, src_includes_only_earlier_layers)
{
    static struct graph g;
    scan_dir(&g, "src");
    cr_assert_geq(g.nf, NLAYERS - 1, "found only %d folders under src/", g.nf);
    char why[1200], graph[2048];
    describe(&g, graph, sizeof graph);
    cr_assert_not(violation(&g, why, sizeof why), "%s\nthe folder graph:%s", why, graph);
}

/* The check itself fails on what it must catch. */
Test(layers, check_catches_a_cycle_and_an_upward_include)
{
    static struct graph g;
    char why[1200];
    add_edge(&g, "app", "draw", "src/app/app.c:1");
    add_edge(&g, "draw", "explore", "src/draw/paint.h:1");
    cr_assert_not(violation(&g, why, sizeof why), "%s", why);

    add_edge(&g, "draw", "cli", "src/draw/export.c:9");   /* what figure.c once did */
    cr_assert(violation(&g, why, sizeof why));
    cr_assert(strstr(why, "src/draw/export.c:9 includes cli/"), "%s", why);

    add_edge(&g, "cli", "app", "src/cli/cli.c:14");
    add_edge(&g, "app", "cli", "src/app/app.h:5");
    cr_assert(violation(&g, why, sizeof why));
    cr_assert(strstr(why, "cycle") && strstr(why, "-> app (src/cli/cli.c:14)"), "%s", why);

    static struct graph h;
    add_edge(&h, "gui", "draw", "src/gui/x.c:1");
    cr_assert(violation(&h, why, sizeof why));
    cr_assert(strstr(why, "src/gui is not in src/layers.h"), "%s", why);
}

/* Every file of src/ stays readable in one sitting: under 700 lines (a file
 * growing past this is the sign that it holds two concerns). */
#define SRC_LINES_MAX 700

static void longest_in(const char *dir, char *longest, size_t n, int *lines)
{
    DIR *d = opendir(dir);
    cr_assert(d, "cannot list %s", dir);
    struct dirent *de;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.')
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        struct stat st;
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            longest_in(path, longest, n, lines);
            continue;
        }
        size_t len = strlen(de->d_name);
        if (len < 3 || (strcmp(de->d_name + len - 2, ".c") != 0 && strcmp(de->d_name + len - 2, ".h") != 0))
            continue;
        FILE *f = fopen(path, "r");
        cr_assert(f, "cannot read %s", path);
        int count = 0;
        for (int c; (c = getc(f)) != EOF;)
            count += c == '\n';
        fclose(f);
        if (count > *lines) {
            *lines = count;
            snprintf(longest, n, "%s", path);
        }
    }
    closedir(d);
}

Test(layers, every_src_file_under_700_lines)
{
    char longest[512] = "";
    int lines = 0;
    longest_in("src", longest, sizeof longest, &lines);
    cr_assert_gt(lines, 0, "no source under src/");
    cr_assert_lt(lines, SRC_LINES_MAX, "%s has %d lines: split it by concern", longest, lines);
}
