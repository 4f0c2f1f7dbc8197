/* test_large.c - the memory a scene of many triangles takes in the explorer.
 *
 * The bound is 2,000,000 triangles at 1920 x 1080 within 2 GiB;
 * `make bench` opens that scene (330 MB of text) in every lesson and
 * reports its peak memory against the bound. Within the test budget, a
 * child process does what the window does with a scene file (load it,
 * hand it to the explorer, count every step of lesson 05 and of the two
 * lessons it is compared with, step to the end and back) for 20,000 and
 * 200,000 triangles, and the kernel's peak resident size of each
 * (getrusage) tells what a triangle costs. The pictures kept for stepping
 * (checkpoints) grow with the scene's events up to their cap, so they are
 * counted apart:
 *
 *   per triangle  ((peak - checkpoints)(200k) - (peak - checkpoints)(20k)) / 180,000
 *                 <= PER_TRI_BYTES
 *   the rest      (peak - checkpoints)(200k) - 200,000 * PER_TRI_BYTES <= FIXED_MIB
 *   checkpoints   <= REPLAY_CHECKPOINT_BYTES, by construction (asserted)
 *
 * and FIXED_MIB + 2,000,000 * PER_TRI_BYTES + REPLAY_CHECKPOINT_BYTES stays
 * under 2 GiB (asserted first). */
#define _XOPEN_SOURCE 700

#include <criterion/criterion.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench/bigscene.h"
#include "draw/paint.h"
#include "testlib.h"

#define PER_TRI_BYTES 560.0     /* the scene's 192, three runs' step counts and counters 3 x 96, slack */
#define FIXED_MIB 300.0         /* pictures but the checkpoints, fonts, cairo, the process */
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZER_FACTOR 2.0    /* AddressSanitizer's shadow memory and redzones */
#else
#define SANITIZER_FACTOR 1.0
#endif

struct usage {
    bool ok;
    double peak_mib, checkpoints_mib;
    int ntris;
};

/* In a child: the window's path through a scene file of n triangles. */
static struct usage measure(const char *dir, long n)
{
    char scene[300];
    snprintf(scene, sizeof scene, "%s/big-%ld.scene", dir, n);
    cr_assert(big_scene_file(scene, n, 17), "cannot write %s", scene);
    int fd[2];
    cr_assert_eq(pipe(fd), 0);
    fflush(NULL);
    pid_t pid = fork();
    cr_assert_neq(pid, -1);
    if (pid == 0) {
        struct usage u = { .ok = false };
        struct scene s;
        char err[512];
        const struct lesson *l = NULL;
        for (int i = 0; all_lessons[i]; i++)
            if (strncmp(all_lessons[i]->id, "05", 2) == 0)
                l = all_lessons[i];
        struct explorer ex;
        struct explorer_desc d = { .lesson = l, .give_scene = &s, .count_later = true };
        if (l && scene_load(&s, scene, err, sizeof err) && explorer_fonts(err, sizeof err)
            && explorer_init(&ex, &d, err, sizeof err)) {
            u.ok = explorer_frame_ms(&ex, 1280, 800, 1) >= 0;
            while (u.ok && explorer_counting(&ex))
                u.ok = explorer_count(&ex, 100);
            u.ok = u.ok && explorer_set_step(&ex, ex.replay.total);
            for (int i = 0; u.ok && i < 5; i++)
                u.ok = explorer_move(&ex, STEP_TRIANGLE, -1);
            u.ok = u.ok && explorer_set_step(&ex, ex.replay.total / 3);
            u.ntris = ex.scene.ntris;
            u.checkpoints_mib = (double)ex.replay.check_used / 1048576;
            struct rusage ru;
            getrusage(RUSAGE_SELF, &ru);
            u.peak_mib = (double)ru.ru_maxrss / 1024;
            explorer_free(&ex);
        }
        _exit(write(fd[1], &u, sizeof u) == (ssize_t)sizeof u ? 0 : 1);
    }
    close(fd[1]);
    struct usage u = { .ok = false };
    ssize_t got = read(fd[0], &u, sizeof u);
    close(fd[0]);
    int st;
    waitpid(pid, &st, 0);
    remove(scene);
    cr_assert(got == (ssize_t)sizeof u && u.ok && u.ntris == n,
              "%ld triangles: the explorer failed (child status %d)", n, st);
    return u;
}

Test(large, memory_per_triangle_fits_two_million_in_2_gib, .timeout = 240)
{
    double cap = (double)REPLAY_CHECKPOINT_BYTES / 1048576;
    cr_assert_lt(FIXED_MIB + BIG_SCENE_TRIS * PER_TRI_BYTES / 1048576 + cap, 2048,
                 "the bounds themselves must add up to less than 2 GiB at 2,000,000 triangles");
    char dir[] = "/tmp/tristep-large-XXXXXX";
    cr_assert(mkdtemp(dir), "mkdtemp: %s", strerror(errno));
    struct usage small = measure(dir, 20000), large = measure(dir, 200000);
    rmdir(dir);
    double a = small.peak_mib - small.checkpoints_mib, b = large.peak_mib - large.checkpoints_mib;
    double per_tri = (b - a) * 1048576 / 180000;
    double fixed = b - 200000 * PER_TRI_BYTES / 1048576;
    cr_log_info("lesson 05: peak RSS %.1f MiB at 20,000 triangles (checkpoints %.1f), %.1f MiB "
                "at 200,000 (checkpoints %.1f): %.0f bytes a triangle; at 2,000,000 about %.0f MiB "
                "with the checkpoints at their cap", small.peak_mib, small.checkpoints_mib,
                large.peak_mib, large.checkpoints_mib, per_tri, b + per_tri * 1800000 / 1048576 + cap);
    cr_assert_leq(large.checkpoints_mib, cap);
    cr_assert_leq(per_tri, PER_TRI_BYTES * SANITIZER_FACTOR, "%.0f bytes a triangle (at most %.0f)",
                  per_tri, PER_TRI_BYTES * SANITIZER_FACTOR);
    cr_assert_leq(fixed, FIXED_MIB * SANITIZER_FACTOR, "%.0f MiB besides the triangles (at most %.0f)",
                  fixed, FIXED_MIB * SANITIZER_FACTOR);
}

static const struct lesson *lesson_numbered(const char *id)
{
    for (int i = 0; all_lessons[i]; i++)
        if (strncmp(all_lessons[i]->id, id, 2) == 0)
            return all_lessons[i];
    cr_assert_fail("no lesson %s", id);
    return NULL;
}

/* The window hands a loaded scene over (.give_scene) rather than copying
 * it: a 3-D scene's world goes along, the source is left empty, and the
 * explorer runs exactly as with a copy. */
Test(large, a_given_3d_scene_carries_its_world)
{
    char err[512];
    struct scene given, copied;
    cr_assert(scene_builtin(&given, "model", err, sizeof err), "%s", err);
    cr_assert(scene_builtin(&copied, "model", err, sizeof err), "%s", err);
    int world = given.world.ntris;
    cr_assert_gt(world, 0);
    const struct lesson *l = lesson_numbered("06");
    struct explorer a, b;
    struct explorer_desc da = { .lesson = l, .give_scene = &given, .step_end = true };
    struct explorer_desc db = { .lesson = l, .scene = &copied, .step_end = true };
    cr_assert(explorer_init(&a, &da, err, sizeof err), "%s", err);
    cr_assert(explorer_init(&b, &db, err, sizeof err), "%s", err);
    cr_assert(given.tris == NULL && given.world.tris == NULL && given.world.ntris == 0,
              "the given scene is left empty");
    cr_assert_eq(a.scene.world.ntris, world);
    cr_assert_eq(a.scene.world.camera_line, copied.world.camera_line);
    cr_assert_gt(a.scene.ntris, 0, "the front end made screen triangles");
    cr_assert_eq(a.scene.ntris, b.scene.ntris);
    cr_assert_eq(a.replay.total, b.replay.total);
    cr_assert_gt(a.replay.total, 0);
    explorer_free(&a);
    explorer_free(&b);
    scene_free(&copied);
}

/* Lesson 08 keeps samples the step-back record does not hold: stepping
 * back a triangle at a time from the end must give, at every triangle,
 * the picture (pixels and every sample) of a fresh run to that triangle. */
Test(large, stepping_back_with_samples_matches_a_fresh_run)
{
    char err[512];
    struct scene s;
    cr_assert(scene_builtin(&s, "samples", err, sizeof err), "%s", err);
    const struct lesson *l = lesson_numbered("08");
    struct explorer ex;
    struct raster_params p = lesson_params_default(l);     /* 4 samples */
    struct explorer_desc d = { .lesson = l, .scene = &s, .params = &p, .step_end = true };
    cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s", err);
    cr_assert_eq(ex.params.samples, 4);
    int checked = 0;
    for (int i = ex.scene.ntris - 1; i > 0; i--) {
        cr_assert(explorer_set_step(&ex, ex.replay.start[i] + 1));    /* triangle i's first event */
        if (ex.replay.base_upto != i)
            continue;                   /* triangle i has no events */
        struct replay fresh;
        cr_assert(replay_init(&fresh, &ex.scene, ex.replay.variant, &ex.params));
        struct target t;
        cr_assert(target_init(&t, s.w, s.h, scene_background(&s)));
        cr_assert(target_multisample(&t, ex.params.samples));
        for (int k = 0; k < i; k++) {
            struct tri_setup ts;
            replay_setup(&fresh, k, &ts);
            fresh.variant->rasterize(&ts, &fresh.params, &t, NULL);
        }
        const struct target *b = &ex.replay.base;
        size_t n = (size_t)s.w * (size_t)s.h, m = n * (size_t)ex.params.samples;
        cr_assert(b->samples, "the base picture keeps its samples");
        cr_assert(memcmp(b->color, t.color, n * sizeof *t.color) == 0, "colour at triangle %d", i);
        cr_assert(memcmp(b->samples->color, t.samples->color, m * sizeof *t.samples->color) == 0,
                  "samples at triangle %d", i);
        cr_assert(memcmp(b->samples->depth, t.samples->depth, m * sizeof *t.samples->depth) == 0,
                  "sample depths at triangle %d", i);
        checked++;
        target_free(&t);
        replay_free(&fresh);
    }
    cr_assert_gt(checked, 0);
    explorer_free(&ex);
    scene_free(&s);
}
