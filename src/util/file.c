/* file.c - reading input files whole, writing output files all or nothing (file.h). */
#define _POSIX_C_SOURCE 200809L   /* mkstemp, fdopen */

#include "file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool write_file_atomic(const char *path, bool (*write)(FILE *out, void *ctx), void *ctx,
                       char *err, size_t errlen)
{
    size_t n = strlen(path);
    char *tmp = malloc(n + 16);
    if (!tmp) {
        snprintf(err, errlen, "%s: out of memory", path);
        return false;
    }
    snprintf(tmp, n + 16, "%s.tmp-XXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        free(tmp);
        return false;
    }
    FILE *out = fdopen(fd, "wb");
    if (!out) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        unlink(tmp);
        free(tmp);
        return false;
    }
    bool ok = write(out, ctx);
    ok = fflush(out) == 0 && ok && !ferror(out);
    int saved = errno;
    if (fclose(out) != 0)
        ok = false;
    /* mkstemp creates the file 0600; give it the usual permissions */
    if (ok) {
        mode_t mask = umask(0);
        umask(mask);
        chmod(tmp, 0666 & ~mask);
    }
    if (ok && rename(tmp, path) != 0) {
        saved = errno;
        ok = false;
    }
    if (!ok) {
        snprintf(err, errlen, "%s: cannot write: %s", path, saved ? strerror(saved) : "write failed");
        unlink(tmp);
    }
    free(tmp);
    return ok;
}

bool has_suffix(const char *name, const char *suffix)
{
    size_t n = strlen(name), m = strlen(suffix);
    return n > m && strcmp(name + n - m, suffix) == 0;
}

bool read_text_file(const char *path, char **text, size_t *len, char *err, size_t errlen)
{
    *text = NULL;
    *len = 0;
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s:0: cannot open: %s", path, strerror(errno));
        return false;
    }
    char *buf = NULL;
    size_t n = 0, cap = 0;
    bool ok = true;
    for (;;) {
        if (n == cap) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *nb = ncap > cap ? realloc(buf, ncap) : NULL;
            if (!nb) {
                ok = false;
                snprintf(err, errlen, "%s:0: out of memory", path);
                break;
            }
            buf = nb;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    if (ok && ferror(f)) {
        ok = false;
        snprintf(err, errlen, "%s:0: cannot read: %s", path, strerror(errno));
    }
    if (f != stdin)
        fclose(f);
    if (!ok) {
        free(buf);
        return false;
    }
    buf[n] = '\0';         /* always room: the loop ends with n < cap */
    *text = buf;
    *len = n;
    return true;
}
