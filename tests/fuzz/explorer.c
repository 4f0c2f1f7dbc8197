/* explorer.c - fuzz harness: scene text -> the explorer (fuzz.h).
 *
 * One lesson and one variant (exhibits included), chosen from the input's
 * first byte, on the scene cut to its first FUZZ_TRIS triangles and at most
 * FUZZ_SIDE pixels a side (its coordinates are kept, up to 16384): replay to the
 * end, to the middle and back to the start, step by every unit in both
 * directions, drag a vertex to a place the input chooses, and paint frames
 * of several views into a small image. */
#include <cairo.h>
#include <stdlib.h>
#include <string.h>

#include "draw/paint.h"
#include "draw/views.h"
#include "explore/explorer.h"
#include "front/front.h"
#include "fuzz.h"

#define FUZZ_TRIS 4
#define FUZZ_SIDE 256
#define FRAME_W 320
#define FRAME_H 200

static int nlessons(void)
{
    int n = 0;
    while (all_lessons[n])
        n++;
    return n;
}

static void paint(struct explorer *ex, cairo_surface_t *surface, int view)
{
    explorer_set_view_name(ex, explorer_view_name(ex, view % explorer_view_count(ex)));
    cairo_t *cr = cairo_create(surface);
    explorer_paint(ex, cr, FRAME_W, FRAME_H);
    cairo_destroy(cr);
}

int fuzz_explorer(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    static bool fonts;
    char err[512];
    if (!fonts) {
        explorer_fonts(err, sizeof err);   /* without DejaVu the text looks different: no matter here */
        fonts = true;
    }
    struct scene s;
    if (!scene_parse(&s, "fuzz.scene", (const char *)data + 1, size - 1, err, sizeof err))
        return 0;
    if (!front_scene(&s)) {   /* a 3-D scene: its screen triangles (false: out of memory) */
        scene_free(&s);
        return 0;
    }
    s.w = s.w > FUZZ_SIDE ? FUZZ_SIDE : s.w;   /* the target stays small for the fuzzer's speed */
    s.h = s.h > FUZZ_SIDE ? FUZZ_SIDE : s.h;
    if (s.ntris > FUZZ_TRIS)
        s.ntris = FUZZ_TRIS;
    const struct lesson *l = all_lessons[data[0] % nlessons()];
    int variant = (data[0] / 8) % l->nvariants;
    struct explorer ex;
    static const int blocks[] = { 4, 8, 16 };
    struct raster_params params = {
        .checker = s.checker, .subpixel_bits = SUBPIXEL_BITS - (data[0] / 32) % 3,
    };
    lesson_param_set(l, &params, "block-size", blocks[(data[0] / 4) % 3]);
    struct explorer_desc d = {
        .lesson = l, .scene = &s, .scene_name = "fuzz.scene",
        .variant = &l->variants[variant], .params = &params, .step_end = true,
    };
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, FRAME_W, FRAME_H);
    if (explorer_init(&ex, &d, err, sizeof err)) {
        paint(&ex, surface, 0);
        explorer_set_step(&ex, ex.replay.total / 2);
        paint(&ex, surface, 1 + data[0]);
        for (int unit = STEP_EVENT; unit <= STEP_TRIANGLE; unit++) {
            explorer_move(&ex, (enum step_unit)unit, 1);
            explorer_move(&ex, (enum step_unit)unit, -1);
        }
        paint(&ex, surface, 2 + data[0]);
        /* a drag to the far corner the input picks (clamped to the scene range) */
        double far = data[size - 1] & 1 ? 1e9 : -1e9;
        explorer_move_vertex(&ex, data[size - 1] % 3, far, -far);
        paint(&ex, surface, 3 + data[0]);
        explorer_set_step(&ex, 0);
        paint(&ex, surface, 4 + data[0]);
        explorer_free(&ex);
    }
    cairo_surface_destroy(surface);
    scene_free(&s);
    return 0;
}
