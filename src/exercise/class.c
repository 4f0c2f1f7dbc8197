/* class.c - a class's work as make grade finds it (class.h): who handed
 * in what, under which safe folder name, and untrusted text made safe to
 * show in a CSV field or a JSON string. */
#define _GNU_SOURCE

#include "exercise/class.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool ends_c(const char *n)
{
    size_t k = strlen(n);
    return k > 2 && strcmp(n + k - 2, ".c") == 0;
}

/* The exercise file in a student's folder: exercise.c (the least deep),
 * else its only .c file; never through a symbolic link. */
static void find_file(const char *dir, int depth, char **best, int *best_depth, int *ncfiles, char **only)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        char *p;
        if (asprintf(&p, "%s/%s", dir, e->d_name) < 0)
            continue;
        struct stat st;
        if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode) && depth < 6) {
            find_file(p, depth + 1, best, best_depth, ncfiles, only);
        } else if (lstat(p, &st) == 0 && S_ISREG(st.st_mode) && ends_c(e->d_name)) {
            ++*ncfiles;
            if (!*only)
                *only = strdup(p);
            if (!strcmp(e->d_name, "exercise.c") && (!*best || depth < *best_depth)) {
                free(*best);
                *best = strdup(p);
                *best_depth = depth;
            }
        }
        free(p);
    }
    closedir(d);
}

static void locate(struct sub *s, const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0) {
        s->problem = "cannot be read";
    } else if (S_ISREG(st.st_mode)) {
        s->file = strdup(path);
    } else if (S_ISDIR(st.st_mode)) {
        char *best = NULL, *only = NULL;
        int depth = 0, n = 0;
        find_file(path, 0, &best, &depth, &n, &only);
        if (best || n == 1)
            s->file = best ? best : only;
        if (best)
            free(only);
        if (!s->file)
            s->problem = n ? "no exercise.c in the folder, and more than one .c file" : "no .c file in the folder";
    } else {
        s->problem = S_ISLNK(st.st_mode) ? "a symbolic link, not a file or a folder (never followed)"
                                         : "not a file or a folder";
    }
}

/* A folder name of [A-Za-z0-9._-], no leading dot or dash, unique among
 * those given so far (a second "-2", ...): two names that read alike both
 * keep their row. */
static void safe_name(struct sub *subs, int n, struct sub *s, bool one)
{
    char base[48];
    size_t k = 0;
    const char *name = s->entry;
    size_t len = strlen(name);
    if (!one && ends_c(name))
        len -= 2;
    for (size_t i = 0; i < len && k + 1 < sizeof base; i++) {
        unsigned char c = (unsigned char)name[i];
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'
                  || ((c == '.' || c == '-') && k > 0);
        char ch = ok ? (char)c : '_';
        if (ch == '_' && k > 0 && base[k - 1] == '_')
            continue;
        base[k++] = ch;
    }
    base[k] = '\0';
    if (!k || strspn(base, "_") == k)
        snprintf(base, sizeof base, "student");
    for (int tries = 1;; tries++) {
        if (tries == 1)
            snprintf(s->safe, sizeof s->safe, "%s", base);
        else
            snprintf(s->safe, sizeof s->safe, "%s-%d", base, tries);
        bool taken = false;
        for (int i = 0; i < n && !taken; i++)
            taken = &subs[i] != s && !strcmp(subs[i].safe, s->safe);
        if (!taken)
            return;
    }
}

static int by_entry(const void *a, const void *b)
{
    return strcmp(((const struct sub *)a)->entry, ((const struct sub *)b)->entry);
}

struct sub *list_class(const char *dir, bool one, int *n)
{
    *n = 0;
    struct sub *subs = NULL;
    if (one) {
        subs = calloc(1, sizeof *subs);
        subs[0].entry = strdup("submission");
        locate(&subs[0], dir);
        *n = 1;
    } else {
        DIR *d = opendir(dir);
        if (!d)
            return NULL;
        struct dirent *e;
        int cap = 0;
        while ((e = readdir(d))) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char *p;
            if (asprintf(&p, "%s/%s", dir, e->d_name) < 0)
                continue;
            struct stat st;
            bool dir = lstat(p, &st) == 0 && S_ISDIR(st.st_mode), link = !dir && S_ISLNK(st.st_mode);
            if (!dir && !link && !ends_c(e->d_name)) {     /* a README, a .zip: not a submission */
                free(p);
                continue;
            }
            if (*n == cap) {
                cap = cap ? 2 * cap : 64;
                subs = realloc(subs, (size_t)cap * sizeof *subs);
            }
            subs[*n] = (struct sub){ .entry = strdup(e->d_name) };
            locate(&subs[*n], p);
            free(p);
            ++*n;
        }
        closedir(d);
        if (*n)
            qsort(subs, (size_t)*n, sizeof *subs, by_entry);
    }
    for (int i = 0; i < *n; i++)
        safe_name(subs, i, &subs[i], one);
    return subs;
}

void free_class(struct sub *subs, int n)
{
    for (int i = 0; subs && i < n; i++)
        free(subs[i].entry), free(subs[i].file);
    free(subs);
}

/* Text as it may go into a CSV field or JSON string: valid UTF-8, no
 * control characters (each a space), invalid bytes as '?'. */
void clean_text(const char *in, char *out, size_t n)
{
    size_t k = 0;
    const unsigned char *p = (const unsigned char *)in;
    while (*p && k + 5 < n) {
        int len = *p < 0x80 ? 1 : (*p >> 5) == 6 ? 2 : (*p >> 4) == 14 ? 3 : (*p >> 3) == 30 ? 4 : 0;
        bool ok = len > 0;
        for (int i = 1; i < len && ok; i++)
            ok = (p[i] & 0xc0) == 0x80;
        if (!ok) {
            out[k++] = '?';
            p++;
            continue;
        }
        if (len == 1) {
            out[k++] = *p < 0x20 || *p == 0x7f ? ' ' : (char)*p;
        } else {
            memcpy(out + k, p, (size_t)len);
            k += (size_t)len;
        }
        p += len;
    }
    out[k] = '\0';
}

/* A CSV field: clean, quoted, a field a spreadsheet would read as a
 * formula (= + - @, or a tab or return first) led by a quote mark. */
void csv_field(FILE *f, const char *s, bool first)
{
    char c[1200];
    clean_text(s, c, sizeof c);
    if (!first)
        fputc(',', f);
    fputc('"', f);
    if (strchr("=+-@\t\r", c[0]) && c[0])
        fputc('\'', f);
    for (const char *p = c; *p; p++) {
        if (*p == '"')
            fputc('"', f);
        fputc(*p, f);
    }
    fputc('"', f);
}

void json_string(FILE *f, const char *s, size_t len)
{
    char *c = malloc(len * 4 + 8), *t = malloc(len + 1);
    if (!c || !t) {
        free(c), free(t);
        fputs("\"\"", f);
        return;
    }
    memcpy(t, s, len);
    t[len] = '\0';
    /* newlines kept: the output of a test is its report */
    fputc('"', f);
    for (char *line = t, *next; line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        clean_text(line, c, len * 4 + 8);
        for (const char *p = c; *p; p++) {
            if (*p == '"' || *p == '\\')
                fputc('\\', f);
            fputc(*p, f);
        }
        if (next)
            fputs("\\n", f);
    }
    fputc('"', f);
    free(c);
    free(t);
}
