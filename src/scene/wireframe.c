/* wireframe.c - a scene as lesson 00 draws it: lines and triangle edges. */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

/* A snapped end, ordered by x, then y. */
struct end {
    int32_t x, y;
};

static int end_cmp(struct end a, struct end b)
{
    return a.x != b.x ? (a.x > b.x) - (a.x < b.x) : (a.y > b.y) - (a.y < b.y);
}

/* The edges drawn so far: an open-addressing set of (smaller end, larger end). */
struct edge_set {
    struct end (*key)[2];
    size_t cap;             /* a power of two, at least twice the edges */
};

static size_t edge_hash(const struct end k[2], size_t cap)
{
    uint64_t h = 0x9e3779b97f4a7c15u;
    const int32_t v[4] = { k[0].x, k[0].y, k[1].x, k[1].y };
    for (int i = 0; i < 4; i++) {
        h ^= (uint32_t)v[i];
        h *= 0xff51afd7ed558ccdu;
        h ^= h >> 33;
    }
    return (size_t)h & (cap - 1);
}

/* Add the edge k; false when it was there already. */
static bool edge_set_add(struct edge_set *s, const struct end k[2])
{
    for (size_t i = edge_hash(k, s->cap);; i = (i + 1) & (s->cap - 1)) {
        struct end (*slot)[2] = &s->key[i];
        if ((*slot)[0].x == INT32_MIN) {
            memcpy(*slot, k, sizeof *slot);
            return true;
        }
        if (memcmp(*slot, k, sizeof *slot) == 0)
            return false;
    }
}

struct vertex *scene_wireframe(const struct scene *s, int *n)
{
    *n = 0;
    size_t most = (size_t)s->nlines + 3 * (size_t)s->ntris;
    struct vertex *out = malloc(2 * (most ? most : 1) * sizeof *out);
    struct edge_set set = { NULL, 16 };
    while (set.cap < 2 * 3 * (size_t)s->ntris)
        set.cap *= 2;
    set.key = malloc(set.cap * sizeof *set.key);
    if (!out || !set.key) {
        free(out);
        free(set.key);
        return NULL;
    }
    for (size_t i = 0; i < set.cap; i++)
        set.key[i][0].x = INT32_MIN;    /* empty (no snapped coordinate is that far) */
    /* Where a line stands among the triangles: before the first screen
     * triangle made from a world triangle it precedes (3-D), or before
     * that triangle itself (2-D). */
    const int *from = s->world.camera_line ? s->world.from : NULL;
    int line = 0;
    for (int t = 0; t <= s->ntris; t++) {
        int file_tri = t == s->ntris ? INT32_MAX : from ? from[t] : t;
        for (; line < s->nlines && s->lines[line].after <= file_tri; line++) {
            out[2 * *n] = s->lines[line].v[0];
            out[2 * *n + 1] = s->lines[line].v[1];
            ++*n;
        }
        if (t == s->ntris)
            break;
        const struct vertex *v = s->tris[t].v;
        for (int k = 0; k < 3; k++) {
            const struct vertex *p = &v[k], *q = &v[(k + 1) % 3];
            struct end a = { snap_coord(p->x, SUBPIXEL_BITS), snap_coord(p->y, SUBPIXEL_BITS) };
            struct end b = { snap_coord(q->x, SUBPIXEL_BITS), snap_coord(q->y, SUBPIXEL_BITS) };
            if (end_cmp(b, a) < 0) {
                const struct vertex *w = p;
                p = q, q = w;
                struct end e = a;
                a = b, b = e;
            }
            if (!edge_set_add(&set, (struct end[2]){ a, b }))
                continue;       /* shared with an earlier triangle: drawn there */
            out[2 * *n] = *p;
            out[2 * *n + 1] = *q;
            ++*n;
        }
    }
    free(set.key);
    return out;
}
