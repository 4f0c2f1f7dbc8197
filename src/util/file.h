/* file.h - reading input files whole, writing output files all or nothing,
 * and naming them. */
#ifndef TRISTEP_FILE_H
#define TRISTEP_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* Read a whole file ("-" is standard input) into a fresh buffer (*text, to
 * free; *len bytes, then a NUL not counted in *len). On failure writes "path:0: message"
 * into err. Every reader of untrusted text (scenes, key scripts) uses it. */
bool read_text_file(const char *path, char **text, size_t *len, char *err, size_t errlen);

/* Write a file all or nothing: `write` produces the bytes into a temporary
 * file beside `path`, which is renamed over `path` only when everything
 * succeeded. On failure nothing is left behind and err says why. */
bool write_file_atomic(const char *path, bool (*write)(FILE *out, void *ctx), void *ctx,
                       char *err, size_t errlen);

/* Whether `name` is something followed by `suffix` (".png" alone is not a
 * PNG file's name: it has no name before the suffix). */
bool has_suffix(const char *name, const char *suffix);

#endif
