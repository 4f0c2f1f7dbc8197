/* test_property.c - seeded random triangles: every exact variant of every
 * lesson, narrated and fast, covers exactly what reference_coverage() covers.
 *
 * 8 categories x CASES_PER_CATEGORY = 100,000 triangles. On one case in
 * TRACE_EVERY the narrated build also runs with a live, unlimited trace, and
 * then frozen at a random step: the picture at step N must be exactly what
 * the run had written when its event N was emitted, and the pixels written
 * must be those of the PIXEL_WRITE events (and full blocks) before step N.
 */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

#define CASES_PER_CATEGORY 12500
#define TRACE_EVERY 8

/* What the sink of a traced run records. */
struct recorder {
    int w, h;
    uint64_t freeze_at;     /* snapshot the counts when this event is emitted */
    uint64_t expected_index;
    bool bad_order;         /* events not numbered 0, 1, 2, ... */
    bool setup_not_first;   /* event 0 is not TRACE_SETUP */
    const struct target *fb;
    uint8_t *written_all;   /* pixels of every PIXEL_WRITE event and full block */
    uint8_t *written_before;/* the same for events numbered < freeze_at */
    uint8_t *snapshot;      /* counts when event freeze_at was emitted */
    bool snapped;
};

static void mark_written(struct recorder *r, uint8_t *mask, const struct trace_event *ev)
{
    if (ev->kind == TRACE_PIXEL_WRITE) {
        if (ev->x >= 0 && ev->x < r->w && ev->y >= 0 && ev->y < r->h)
            mask[(size_t)ev->y * (size_t)r->w + (size_t)ev->x] = 1;
    } else if (ev->kind == TRACE_BLOCK && ev->klass == BLOCK_FULL) {
        /* a full block is filled as part of its own step (FILL) */
        for (int y = ev->y < 0 ? 0 : ev->y; y <= ev->y1 && y < r->h; y++)
            for (int x = ev->x < 0 ? 0 : ev->x; x <= ev->x1 && x < r->w; x++)
                mask[(size_t)y * (size_t)r->w + (size_t)x] = 1;
    }
}

static void record(void *ctx, const struct trace_event *ev)
{
    struct recorder *r = ctx;
    if (ev->index != r->expected_index)
        r->bad_order = true;
    if (ev->index == 0 && ev->kind != TRACE_SETUP)
        r->setup_not_first = true;
    r->expected_index = ev->index + 1;
    if (ev->index == r->freeze_at) {
        memcpy(r->snapshot, r->fb->count, (size_t)r->w * (size_t)r->h);
        r->snapped = true;
    }
    mark_written(r, r->written_all, ev);
    if (ev->index < r->freeze_at)
        mark_written(r, r->written_before, ev);
}

/* counts -> 0/1 */
static void as_set(const uint8_t *in, uint8_t *out, size_t n)
{
    for (size_t i = 0; i < n; i++)
        out[i] = in[i] != 0;
}

struct bufs {
    int w, h;
    size_t n;
    struct target fb;
    uint8_t *ref, *ref_set, *full, *set, *all, *before, *snap;
};

static void bufs_init(struct bufs *b, int w, int h)
{
    b->w = w;
    b->h = h;
    b->n = (size_t)w * (size_t)h;
    cr_assert(target_init(&b->fb, w, h, 0xff000000u));
    uint8_t **m[] = { &b->ref, &b->ref_set, &b->full, &b->set, &b->all, &b->before, &b->snap };
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        cr_assert_not_null(*m[i] = calloc(b->n, 1));
}

static void bufs_free(struct bufs *b)
{
    target_free(&b->fb);
    uint8_t *m[] = { b->ref, b->ref_set, b->full, b->set, b->all, b->before, b->snap };
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
        free(m[i]);
}

/* The traced checks of one case on one narrated variant. */
static void check_traced(struct bufs *b, struct rng *rng, const struct test_variant *tv,
                         const struct tri_setup *t, struct case_info *info)
{
    char what[256];
    const char *label = info->what;

    /* 1. unlimited: count the events */
    struct trace tr = { 0 };
    memset(b->fb.count, 0, b->n);
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    rasterize_one(tv->variant, NULL, t, &b->fb, &tr);
    uint64_t total = tr.count;
    cr_assert(!tr.frozen, "%s: an unlimited trace froze", label);
    cr_assert_geq(total, 1, "%s: no TRACE_SETUP event", label);
    snprintf(what, sizeof what, "%s, live unlimited trace", label);
    info->what = what;
    cr_assert(coverage_equal(b->ref, b->fb.count, b->w, b->h, info));
    memcpy(b->full, b->fb.count, b->n);

    /* 2. unlimited again, recording, with a snapshot at a random step N */
    uint64_t N = (uint64_t)rng_int(rng, 0, (int)(total < 1000000 ? total : 1000000));
    struct recorder rec = { .w = b->w, .h = b->h, .freeze_at = N, .fb = &b->fb,
                            .written_all = b->all, .written_before = b->before,
                            .snapshot = b->snap };
    memset(b->all, 0, b->n);
    memset(b->before, 0, b->n);
    memset(b->fb.count, 0, b->n);
    tr = (struct trace){ .sink = record, .ctx = &rec };
    trace_begin(&tr, 0, TRACE_UNLIMITED);
    rasterize_one(tv->variant, NULL, t, &b->fb, &tr);
    if (!rec.snapped)       /* N == total: the step after the last is the end */
        memcpy(b->snap, b->fb.count, b->n);
    cr_assert_eq(tr.count, total, "%s: %llu events, then %llu in the same run",
                 label, (unsigned long long)total, (unsigned long long)tr.count);
    cr_assert(!rec.bad_order, "%s: events not numbered in order", label);
    cr_assert(!rec.setup_not_first, "%s: the first event is not TRACE_SETUP", label);
    snprintf(what, sizeof what, "%s, pixels of PIXEL_WRITE events and full blocks", label);
    cr_assert(coverage_equal(b->ref_set, b->all, b->w, b->h, info));

    /* 3. frozen at step N: a prefix of the run */
    memset(b->fb.count, 0, b->n);
    trace_begin(&tr, 0, N);
    tr.sink = NULL;
    rasterize_one(tv->variant, NULL, t, &b->fb, &tr);
    cr_assert_eq(tr.frozen, N < total, "%s: frozen at step %llu of %llu", label,
                 (unsigned long long)N, (unsigned long long)total);
    snprintf(what, sizeof what, "%s, frozen at step %llu of %llu: picture vs the run at that step",
             label, (unsigned long long)N, (unsigned long long)total);
    cr_assert(coverage_equal(b->snap, b->fb.count, b->w, b->h, info));
    as_set(b->fb.count, b->set, b->n);
    snprintf(what, sizeof what, "%s, frozen at step %llu of %llu: pixels vs events before it",
             label, (unsigned long long)N, (unsigned long long)total);
    cr_assert(coverage_equal(b->before, b->set, b->w, b->h, info));
    for (size_t i = 0; i < b->n; i++)
        cr_assert_leq(b->fb.count[i], b->full[i], "%s: step %llu wrote pixel %zu more than the full run",
                      label, (unsigned long long)N, i);
    info->what = label;
}

static void property_run(enum tri_category cat, int w, int h)
{
    struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    cr_assert(nv >= 2 && nv <= MAX_TEST_VARIANTS, "%d exact variants", nv);
    struct bufs b;
    bufs_init(&b, w, h);
    struct rng rng = rng_for(1000 + (uint64_t)cat);
    uint64_t covered = 0;

    for (int i = 0; i < CASES_PER_CATEGORY; i++) {
        struct vertex v[3];
        random_tri(&rng, cat, w, h, v);
        struct tri_setup t;
        tri_setup(&t, v, w, h);
        memset(b.ref, 0, b.n);
        reference_mask(&t, b.ref);
        as_set(b.ref, b.ref_set, b.n);
        bool traced = i % TRACE_EVERY == 0;
        for (size_t p = 0; p < b.n; p++)
            covered += b.ref[p];

        for (int k = 0; k < nv; k++) {
            char label[160], what[224];
            snprintf(what, sizeof what, "%s, category %s",
                     variant_label(&tv[k], label, sizeof label), tri_category_name(cat));
            struct case_info info = { what, test_seed(), (uint64_t)i, v, 3 };
            memset(b.fb.count, 0, b.n);
            rasterize_one(tv[k].variant, NULL, &t, &b.fb, NULL);
            cr_assert(coverage_equal(b.ref, b.fb.count, w, h, &info));
            if (traced && tv[k].narrated)
                check_traced(&b, &rng, &tv[k], &t, &info);
        }
    }
    bufs_free(&b);
    /* the category really exercised something (or, degenerate, nothing) */
    if (cat == CAT_DEGENERATE)
        cr_assert_eq(covered, 0, "degenerate triangles covered %llu pixels", (unsigned long long)covered);
    else
        cr_assert_gt(covered, (uint64_t)CASES_PER_CATEGORY / 20, "category %s covered only %llu pixels",
                     tri_category_name(cat), (unsigned long long)covered);
}

Test(property, generic) { property_run(CAT_GENERIC, 53, 37); }
Test(property, sliver) { property_run(CAT_SLIVER, 53, 37); }
Test(property, tiny) { property_run(CAT_TINY, 53, 37); }
Test(property, large) { property_run(CAT_LARGE, 41, 29); }
Test(property, offscreen) { property_run(CAT_OFFSCREEN, 53, 37); }
Test(property, degenerate) { property_run(CAT_DEGENERATE, 53, 37); }
Test(property, centres) { property_run(CAT_CENTRES, 53, 37); }
Test(property, axis) { property_run(CAT_AXIS, 53, 37); }
