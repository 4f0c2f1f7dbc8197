/* lessons.c - fuzz harness: scene text -> every exact variant of every
 * lesson, narrated and fast, against the reference rasterizer (fuzz.h).
 *
 * The scene is drawn on a target of at most FUZZ_SIDE x FUZZ_SIDE pixels
 * (its top-left corner: a large scene is cut, not skipped), its first
 * FUZZ_TRIS triangles, each at full precision and at the fewer sub-pixel bits
 * of lesson 03's exhibit; lesson 05 at every block size; narrated runs with
 * a trace that records everything and with one that freezes part way, as the
 * explorer's replay does; a textured triangle under its image, through
 * each filter in turn. Coverage must equal the reference's, pixel for
 * pixel. Colours and depths are not compared (they are not exact across
 * lessons) but are computed, so the sanitizers see every value a scene can
 * lead to. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../testlib.h"
#include "front/front.h"
#include "fuzz.h"

#define FUZZ_SIDE 32
#define FUZZ_TRIS 4

static void check(const struct test_variant *tv, const struct tri_setup *t,
                  const struct raster_params *p, struct target *fb, const uint8_t *ref,
                  struct trace *tr, int tri)
{
    target_clear(fb);
    if (tr)
        trace_begin(tr, (uint32_t)tri, tr->limit);
    rasterize_one(tv->variant, p, t, fb, tr);
    if (tr && tr->frozen)
        return;   /* stopped part way: only "no undefined behaviour" holds */
    size_t n = (size_t)fb->w * (size_t)fb->h;
    for (size_t i = 0; i < n; i++)
        if (fb->count[i] != ref[i]) {
            char label[128];
            fuzz_fail("%s, triangle %d, %d sub-pixel bits, knob[0] = %d: pixel (%zu, %zu) covered "
                      "%d times, the reference %d", variant_label(tv, label, sizeof label), tri,
                      p->subpixel_bits, p->knob[0], i % (size_t)fb->w, i / (size_t)fb->w,
                      fb->count[i], ref[i]);
        }
}

int fuzz_lessons(const uint8_t *data, size_t size)
{
    struct scene s;
    char err[512];
    if (!scene_parse(&s, "fuzz.scene", (const char *)data, size, err, sizeof err))
        return 0;
    if (!front_scene(&s)) {   /* a 3-D scene: its screen triangles (false: out of memory) */
        scene_free(&s);
        return 0;
    }
    int w = s.w < FUZZ_SIDE ? s.w : FUZZ_SIDE, h = s.h < FUZZ_SIDE ? s.h : FUZZ_SIDE;
    static struct test_variant tv[MAX_TEST_VARIANTS];
    int nv = exact_variants(tv, MAX_TEST_VARIANTS, BUILD_BOTH);
    if (nv > MAX_TEST_VARIANTS)
        fuzz_fail("more variants than MAX_TEST_VARIANTS");
    struct target fb;
    uint8_t *ref = calloc((size_t)w * (size_t)h, 1);
    if (!ref || !target_init(&fb, w, h, scene_background(&s)))
        abort();
    /* a freezing point from the input itself, so the fuzzer can move it */
    uint64_t freeze = size ? (uint64_t)data[size - 1] * 3u : 7u;

    for (int i = 0; i < s.ntris && i < FUZZ_TRIS; i++) {
        for (int pass = 0; pass < 2; pass++) {
            int bits = pass == 0 ? SUBPIXEL_BITS : (int)((unsigned)i * 3u % SUBPIXEL_BITS);
            struct tri_setup t;
            tri_setup_bits(&t, s.tris[i].v, w, h, bits);
            memset(ref, 0, (size_t)w * (size_t)h);
            reference_mask(&t, ref);
            for (int k = 0; k < nv; k++) {
                static const int blocks[] = { 4, 8, 16 };
                bool by_block = lesson_param(tv[k].lesson, "block-size", NULL);
                for (int b = 0; b < (by_block ? 3 : 1); b++) {
                    struct raster_params base = { .checker = s.checker, .subpixel_bits = bits };
                    struct raster_params p = lesson_params_tri(&base, &s, i);  /* its image texture */
                    lesson_param_set(tv[k].lesson, &p, "block-size", by_block ? blocks[b] : 0);
                    lesson_param_set(tv[k].lesson, &p, "filter", 1 + (i + pass) % 5);
                    lesson_param_set(tv[k].lesson, &p, "affine", (i & 1) != 0);
                    if (!tv[k].narrated) {
                        check(&tv[k], &t, &p, &fb, ref, NULL, i);
                        continue;
                    }
                    struct trace all = { .limit = TRACE_UNLIMITED };
                    struct trace part = { .limit = freeze };
                    check(&tv[k], &t, &p, &fb, ref, NULL, i);
                    check(&tv[k], &t, &p, &fb, ref, &all, i);
                    check(&tv[k], &t, &p, &fb, ref, &part, i);
                }
            }
        }
    }
    target_free(&fb);
    free(ref);
    scene_free(&s);
    return 0;
}
