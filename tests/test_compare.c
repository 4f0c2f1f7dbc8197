/* test_compare.c - the explorer runs earlier lessons on the same scene, and
 * their counters are what those lessons really do. */
#include <criterion/criterion.h>
#include <string.h>

#include "draw/paint.h"

extern const struct lesson lesson_03, lesson_05;

static void open_lesson(struct explorer *ex, const struct lesson *l, struct scene *s)
{
    char err[256];
    cr_assert(scene_builtin(s, l->builtin_scene, err, sizeof err), "%s", err);
    struct explorer_desc d = { .lesson = l, .scene = s, .scene_name = l->builtin_scene };
    cr_assert(explorer_init(ex, &d, err, sizeof err), "%s", err);
}

/* Lesson 02 tests every pixel of each triangle's clamped bounding box. */
static uint64_t box_pixels(const struct scene *s)
{
    uint64_t n = 0;
    for (int i = 0; i < s->ntris; i++) {
        struct tri_setup t;
        if (tri_setup(&t, s->tris[i].v, s->w, s->h))
            n += (uint64_t)(t.maxx - t.minx + 1) * (uint64_t)(t.maxy - t.miny + 1);
    }
    return n;
}

Test(compare, lesson05_shows_lessons_02_and_03_on_its_scene)
{
    struct scene s;
    struct explorer ex;
    open_lesson(&ex, &lesson_05, &s);
    cr_assert_eq(ex.ncompare, 2);
    cr_expect_str_eq(ex.compare[0]->id, "02-barycentric");
    cr_expect_str_eq(ex.compare[1]->id, "03-edge-stepping");
    const struct trace_counters *l02 = &ex.compare_replay[0].sums[s.ntris];
    const struct trace_counters *l03 = &ex.compare_replay[1].sums[s.ntris];
    const struct trace_counters *l05 = &ex.replay.sums[s.ntris];
    uint64_t box = box_pixels(&s);
    cr_expect_eq(l02->tested, box, "lesson 02 tests its whole box: %llu of %llu",
                 (unsigned long long)l02->tested, (unsigned long long)box);
    cr_expect_eq(l03->tested, box, "so does lesson 03");
    cr_expect_lt(l05->tested, box, "blocks skip tests: full blocks and empty blocks");
    cr_expect_eq(l02->covered, l05->covered, "all three cover the same pixels");
    cr_expect_eq(l03->covered, l05->covered);
    explorer_free(&ex);
    scene_free(&s);
}

Test(compare, lesson03_multiplies_less_than_lesson02_per_pixel)
{
    struct scene s;
    struct explorer ex;
    open_lesson(&ex, &lesson_03, &s);
    cr_assert_eq(ex.ncompare, 1);
    const struct trace_counters *l02 = &ex.compare_replay[0].sums[s.ntris];
    const struct trace_counters *l03 = &ex.replay.sums[s.ntris];
    cr_expect_eq(l02->tested, l03->tested);
    cr_expect_geq(l02->mul, 6 * l02->tested, "lesson 02: three edge functions of two products");
    cr_expect_lt(l03->mul * 5, l02->mul, "lesson 03 multiplies only per row and per triangle: "
                 "%llu against lesson 02's %llu", (unsigned long long)l03->mul,
                 (unsigned long long)l02->mul);
    explorer_free(&ex);
    scene_free(&s);
}

Test(compare, dragging_a_vertex_recounts_the_comparison)
{
    struct scene s;
    struct explorer ex;
    open_lesson(&ex, &lesson_05, &s);
    uint64_t before = ex.compare_replay[0].sums[s.ntris].tested;
    explorer_set_step(&ex, 1);
    cr_assert(explorer_move_vertex(&ex, 0, 1.5, 1.5));
    uint64_t after = ex.compare_replay[0].sums[ex.scene.ntris].tested;
    cr_expect_neq(before, after, "moving A grows the box lesson 02 tests");
    cr_expect_eq(after, box_pixels(&ex.scene));
    explorer_free(&ex);
    scene_free(&s);
}
