/* script.c - reading a --keys file (script.h). */
#include "script.h"

#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/file.h"   /* read_text_file */

static bool fail(const struct script *s, int line, char *err, size_t errlen, const char *fmt, ...)
{
    int n = snprintf(err, errlen, "%s:%d: ", s->name, line);
    if (n >= 0 && (size_t)n < errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err + n, errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

static bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* A whole number in -SCRIPT_COORD_MAX..SCRIPT_COORD_MAX at *p, then spaces. */
static bool parse_coord(const char **p, int *out)
{
    const char *c = *p;
    bool neg = *c == '-';
    if (*c == '-' || *c == '+')
        c++;
    if (*c < '0' || *c > '9')
        return false;
    long v = 0;
    for (; *c >= '0' && *c <= '9'; c++) {
        v = v * 10 + (*c - '0');
        if (v > SCRIPT_COORD_MAX)
            return false;
    }
    if (*c && !is_space(*c))
        return false;
    while (is_space(*c))
        c++;
    *out = (int)(neg ? -v : v);
    *p = c;
    return true;
}

static bool has_prefix(const char *s, const char *prefix)
{
    for (; *prefix; s++, prefix++) {
        char a = *s >= 'A' && *s <= 'Z' ? (char)(*s - 'A' + 'a') : *s;
        if (a != *prefix)
            return false;
    }
    return true;
}

static bool parse_cmd(const struct script *s, int line, const char *text, struct script_cmd *c,
                      char *err, size_t errlen)
{
    *c = (struct script_cmd){ .kind = SCRIPT_KEY, .line = line };
    if (strcmp(text, "wait") == 0) {
        c->kind = SCRIPT_WAIT;
        return true;
    }
    if (strncmp(text, "drag", 4) == 0 && (text[4] == '\0' || is_space(text[4]))) {
        const char *p = text + 4;
        while (is_space(*p))
            p++;
        c->kind = SCRIPT_DRAG;
        if (!parse_coord(&p, &c->x1) || !parse_coord(&p, &c->y1) || !parse_coord(&p, &c->x2)
            || !parse_coord(&p, &c->y2) || *p)
            return fail(s, line, err, errlen, "'drag' needs 4 whole numbers X1 Y1 X2 Y2, "
                        "each in -%d..%d", SCRIPT_COORD_MAX, SCRIPT_COORD_MAX);
        return true;
    }
    const char *name = text;
    for (;;) {
        if (has_prefix(name, "shift+"))
            c->mods |= SCRIPT_SHIFT, name += 6;
        else if (has_prefix(name, "ctrl+"))
            c->mods |= SCRIPT_CTRL, name += 5;
        else
            break;
    }
    static const char *const alias[][2] = {
        { "pgdn", "PageDown" }, { "pgup", "PageUp" }, { "esc", "Escape" },
    };
    for (size_t i = 0; i < sizeof alias / sizeof alias[0]; i++)
        if (has_prefix(name, alias[i][0]) && name[strlen(alias[i][0])] == '\0')
            name = alias[i][1];
    size_t n = strlen(name);
    if (n == 0)
        return fail(s, line, err, errlen, "a modifier without a key");
    if (n > SCRIPT_KEY_MAX)
        return fail(s, line, err, errlen, "'%.40s...' is not a key name (too long)", name);
    for (const char *q = name; *q; q++)
        if ((unsigned char)*q < 32 || (unsigned char)*q == 127)
            return fail(s, line, err, errlen, "control character in a key name");
    memcpy(c->key, name, n + 1);
    return true;
}

bool script_parse(struct script *s, const char *name, const char *text, size_t len,
                  char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    char buf[SCRIPT_KEY_MAX + 64];   /* longer lines are errors whatever they hold */
    int line = 0;
    for (size_t pos = 0; pos < len;) {
        if (line == INT_MAX) {
            fail(s, line, err, errlen, "more lines than a script may have");
            goto error;
        }
        line++;
        size_t end = pos;
        while (end < len && text[end] != '\n')
            end++;
        size_t a = pos, b = end;
        pos = end + 1;
        while (a < b && (is_space(text[a])))
            a++;
        while (b > a && is_space(text[b - 1]))
            b--;
        if (a == b || text[a] == '#')
            continue;
        if (b - a >= sizeof buf) {
            fail(s, line, err, errlen, "line longer than %d characters (too long for a key, "
                 "'wait' or 'drag')", (int)sizeof buf - 1);
            goto error;
        }
        memcpy(buf, text + a, b - a);
        buf[b - a] = '\0';
        if (strlen(buf) != b - a) {
            fail(s, line, err, errlen, "NUL byte in the line (is this a text file?)");
            goto error;
        }
        if (s->n == s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 32;
            struct script_cmd *c = cap <= (size_t)-1 / sizeof *c ? realloc(s->cmd, cap * sizeof *c) : NULL;
            if (!c) {
                fail(s, line, err, errlen, "out of memory");
                goto error;
            }
            s->cmd = c;
            s->cap = cap;
        }
        if (!parse_cmd(s, line, buf, &s->cmd[s->n], err, errlen))
            goto error;
        s->n++;
    }
    return true;
error:
    script_free(s);
    return false;
}

bool script_load(struct script *s, const char *path, char *err, size_t errlen)
{
    char *text;
    size_t len;
    memset(s, 0, sizeof *s);
    if (!read_text_file(path, &text, &len, err, errlen))
        return false;
    bool ok = script_parse(s, path, text, len, err, errlen);
    free(text);
    return ok;
}

void script_free(struct script *s)
{
    free(s->cmd);
    s->cmd = NULL;
    s->n = s->cap = 0;
}
