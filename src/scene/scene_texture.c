/* scene_texture.c - the image texture lines of a scene (lessons/CONVENTIONS.md, "Textures"):
 *
 *     texture checker 8                    the procedural checker (every lesson)
 *     texture floor.png                    a PNG beside the scene, repeat
 *     texture builtin:bricks clamp         a texture made by code (textures.c)
 *
 * An image texture applies to the tri lines with 24 numbers (x y z r g b s t),
 * the tri3 lines with 24 and the obj lines that follow it, until the next
 * texture line (`texture checker N` included, which ends it). The textures
 * of a scene are loaded once each (the same file and wrap twice is one
 * texture), and its copies share them: nothing changes a texture once read. */
#define _XOPEN_SOURCE 700   /* realpath */

#include <limits.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "parse.h"

struct scene_textures {
    atomic_int refs;                    /* scenes sharing the set */
    int n, cap;
    struct texture *t;
};

int scene_texture_count(const struct scene *s)
{
    return s->textures ? s->textures->n : 0;
}

const struct texture *scene_texture(const struct scene *s, int k)
{
    return k >= 1 && k <= scene_texture_count(s) ? &s->textures->t[k - 1] : NULL;
}

void scene_texture_share(struct scene *dst, const struct scene *src)
{
    dst->textures = src->textures;
    if (dst->textures)
        atomic_fetch_add(&dst->textures->refs, 1);
}

void scene_textures_release(struct scene *s)
{
    struct scene_textures *set = s->textures;
    s->textures = NULL;
    if (!set || atomic_fetch_sub(&set->refs, 1) > 1)
        return;
    for (int i = 0; i < set->n; i++)
        texture_free(&set->t[i]);
    free(set->t);
    free(set);
}

char *scene_relative_path(const struct parser *p, const char *file)
{
    const char *slash = strrchr(p->name, '/');
    size_t dir = file[0] == '/' || !slash ? 0 : (size_t)(slash - p->name) + 1;
    size_t len = dir + strlen(file) + 1;
    char *path = malloc(len);
    if (path)
        snprintf(path, len, "%.*s%s", (int)dir, p->name, file);
    return path;
}

static const char *const wrap_names[] = { [TEXTURE_REPEAT] = "repeat", [TEXTURE_CLAMP] = "clamp" };

/* The texture named by `name` (builtin:NAME, or a path as fopen takes it)
 * with this wrap: its number in the scene's set, loaded unless it is there. */
static bool add_texture(struct parser *p, struct scene *s, const char *shown, const char *name,
                        enum texture_wrap wrap)
{
    bool builtin = strncmp(name, "builtin:", 8) == 0;
    char *full = builtin ? NULL : realpath(name, NULL);    /* written scenes name the file so */
    const char *key = full ? full : name;
    for (int i = 0; i < scene_texture_count(s); i++)
        if (s->textures->t[i].wrap == wrap && strcmp(s->textures->t[i].name, key) == 0) {
            free(full);
            p->texture = i + 1;
            return true;
        }
    if (!s->textures) {
        if (!(s->textures = calloc(1, sizeof *s->textures))) {
            free(full);
            return scene_fail(p, "out of memory");
        }
        atomic_init(&s->textures->refs, 1);
    }
    struct scene_textures *set = s->textures;
    if (set->n == set->cap) {
        int cap = set->cap ? 2 * set->cap : 4;
        struct texture *t = cap < INT_MAX / 4 ? realloc(set->t, (size_t)cap * sizeof *t) : NULL;
        if (!t) {
            free(full);
            return scene_fail(p, "out of memory");
        }
        set->t = t;
        set->cap = cap;
    }
    int w = 0, h = 0;
    uint32_t *image;
    char why[256];
    bool ok = builtin ? texture_builtin(name + 8, &w, &h, &image, why, sizeof why)
                      : texture_read_png(name, &w, &h, &image, why, sizeof why);
    if (ok && !texture_make(&set->t[set->n], key, wrap, w, h, image))
        snprintf(why, sizeof why, "out of memory for %d x %d texels", w, h), ok = false;
    free(image);
    free(full);
    if (!ok)
        return scene_fail(p, "texture '%.200s': %s", shown, why);
    p->texture = ++set->n;
    return true;
}

bool scene_texture_line(struct parser *p, struct scene *s, char **tok, int n)
{
    if (n != 2 && n != 3)
        return scene_fail(p, "expected 'texture FILE.png [repeat|clamp]', 'texture builtin:NAME "
                             "[repeat|clamp]' or 'texture checker N'");
    enum texture_wrap wrap = TEXTURE_REPEAT;
    if (n == 3) {
        if (strcmp(tok[2], "repeat") != 0 && strcmp(tok[2], "clamp") != 0)
            return scene_fail(p, "texture wrap '%.40s': expected repeat or clamp", tok[2]);
        wrap = strcmp(tok[2], "clamp") == 0 ? TEXTURE_CLAMP : TEXTURE_REPEAT;
    }
    if (strncmp(tok[1], "builtin:", 8) == 0)
        return add_texture(p, s, tok[1], tok[1], wrap);
    char *path = scene_relative_path(p, tok[1]);
    if (!path)
        return scene_fail(p, "out of memory");
    bool ok = add_texture(p, s, tok[1], path, wrap);
    free(path);
    return ok;
}

/* Every image texture first, in their order, so the written scene numbers
 * them as this one does; then the checker, which is every lesson's and
 * leaves no image texture in force. */
void scene_write_textures(const struct scene *s, FILE *out, int *current)
{
    for (int i = 0; i < scene_texture_count(s); i++)
        fprintf(out, "texture %s %s\n", s->textures->t[i].name, wrap_names[s->textures->t[i].wrap]);
    *current = scene_texture_count(s);
    if (s->checker) {
        fprintf(out, "texture checker %d\n", s->checker);
        *current = 0;
    }
}

/* A triangle under no image texture after one that had one: the checker's
 * line ends the image texture (the checker applies anyway); without a
 * checker, the triangle is written without s and t, which nothing reads. */
int scene_write_texture(const struct scene *s, FILE *out, int *current, int texture)
{
    const struct texture *t = scene_texture(s, texture);
    if (!t)
        texture = 0;            /* none (or a number no texture has: none either) */
    if (texture != *current && texture > 0) {
        fprintf(out, "texture %s %s\n", t->name, wrap_names[t->wrap]);
        *current = texture;
    } else if (texture != *current && s->checker) {
        fprintf(out, "texture checker %d\n", s->checker);
        *current = 0;
    } else if (texture != *current) {
        return 6;
    }
    return texture > 0 || s->has_st ? 8 : 6;
}
