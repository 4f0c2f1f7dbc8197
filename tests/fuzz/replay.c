/* replay.c - every committed fuzz input through its harness, without
 * libFuzzer (fuzz.h): `fuzz-replay DIR` runs every file of DIR/NAME through
 * harness NAME, for every harness; a failing input aborts with its name on
 * stderr (and the sanitizers' report). */
#define _POSIX_C_SOURCE 200809L   /* opendir and friends */

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "util/file.h"   /* read_text_file */

/* Which input is running, named when it fails: on abort (a violated
 * property), and from the sanitizers' death callback (their reports). */
static char current[4200];

static void name_current(void)
{
    if (current[0])
        fprintf(stderr, "fuzz-replay: FAILED on %s\n", current);
}

static void on_abort(int sig)
{
    name_current();
    signal(sig, SIG_DFL);
    raise(sig);
}

#if defined(__SANITIZE_ADDRESS__)
#define HAVE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HAVE_ASAN 1
#endif
#endif
#ifdef HAVE_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Run every file of dir through h (in name order); returns the count, -1 on error. */
static long replay_dir(const struct fuzz_harness *h, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "fuzz-replay: cannot open %s\n", dir);
        return -1;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            char **nn = realloc(names, cap * sizeof *nn);
            if (!nn)
                abort();
            names = nn;
        }
        if (!(names[n++] = strdup(e->d_name)))
            abort();
    }
    closedir(d);
    qsort(names, n, sizeof *names, by_name);
    long count = 0;
    for (size_t i = 0; i < n; i++) {
        char path[4096], err[512];
        int pn = snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        char *data;
        size_t len;
        if (pn < 0 || (size_t)pn >= sizeof path) {
            fprintf(stderr, "fuzz-replay: %s/%s: name too long\n", dir, names[i]);
            count = -1;
        } else if (!read_text_file(path, &data, &len, err, sizeof err)) {
            fprintf(stderr, "fuzz-replay: %s\n", err);
            count = -1;
        } else {
            snprintf(current, sizeof current, "%s (harness %.20s)", path, h->name);
            h->run((const uint8_t *)data, len);
            current[0] = '\0';
            free(data);
            if (count >= 0)
                count++;
        }
        free(names[i]);
    }
    free(names);
    return count;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: fuzz-replay CORPUS_DIR   (runs CORPUS_DIR/NAME/* through harness NAME)\n");
        return 2;
    }
    signal(SIGABRT, on_abort);
#ifdef HAVE_ASAN
    __sanitizer_set_death_callback(name_current);
#endif
    int status = 0;
    long total = 0;
    for (const struct fuzz_harness *h = fuzz_harnesses; h->name; h++) {
        char dir[4096];
        snprintf(dir, sizeof dir, "%s/%s", argv[1], h->name);
        long n = replay_dir(h, dir);
        if (n < 0) {
            status = 1;
            continue;
        }
        printf("fuzz-replay: %-9s %ld inputs\n", h->name, n);
        total += n;
    }
    printf("fuzz-replay: %ld inputs replayed, none failed\n", total);
    return status;
}
