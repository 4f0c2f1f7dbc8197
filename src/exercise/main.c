/* main.c - build/exercise-NN: one lesson's explorer on the student's code
 * (what `make exercise` opens), or the lesson's checks on it (`make check`).
 * The Makefile defines LESSON as the lesson's descriptor and links the
 * student's file, which defines exercise_rasterize.
 *
 *     exercise-NN [--file NAME] [--exercise-variant V] [LESSON PROGRAM OPTIONS]      the explorer
 *     exercise-NN --check [--file NAME] [--exercise-variant V] [--check-scene FILE]... [--out DIR] [--open CMD]
 *                 [--seed N] [--search SECONDS]
 *
 * Compiled with EXERCISE_JUDGE it is build/judge-NN, which links no student
 * code: the checks on a runner's results (make check), or a class graded
 * (make grade, grade.c).
 *
 *     judge-NN --check --runner PROGRAM [--log FILE] [--seed N] [--file NAME] ...
 *     judge-NN --grade [GRADE OPTIONS]                  (grade.h)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "exercise/exercise.h"
#include "exercise/gen.h"
#include "exercise/grade.h"
#include "exercise/remote.h"

extern const struct lesson LESSON;
#ifdef EXERCISE_JUDGE
#define exercise_rasterize NULL
#define exercise_clip NULL
#else
void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr);
/* the student's clipper (lesson 06), or the lesson's own from the library's
 * clip_default.c when the file has none */
void exercise_clip(struct poly *out, const struct poly *in, const struct plane *pl);
#endif

int main(int argc, char **argv)
{
    const char *file = "exercise.c", *out_dir = "build/check", *open_cmd = NULL, *variant = NULL;
    const char *runner = NULL, *log = NULL;
    bool check = false;
    unsigned long long seed = 1;   /* the search's: the same scenes every run unless --seed */
    double search = 1.5;        /* seconds of search for the whole lesson */
#ifdef EXERCISE_JUDGE
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--grade") == 0)
            return exercise_grade_main(&LESSON, argc, argv);
#endif
    const char **scenes = calloc((size_t)argc + 1, sizeof *scenes);
    char **rest = calloc((size_t)argc + 3, sizeof *rest);
    if (!scenes || !rest)
        return 1;
    int nscenes = 0, nrest = 0;
    bool variant_given = false;
    rest[nrest++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has_value = i + 1 < argc;
        if (strcmp(a, "--check") == 0)
            check = true;
        else if (strcmp(a, "--file") == 0 && has_value)
            file = argv[++i];
        else if (strcmp(a, "--check-scene") == 0 && has_value)
            scenes[nscenes++] = argv[++i];
        else if (strcmp(a, "--out") == 0 && has_value)
            out_dir = argv[++i];
        else if (strcmp(a, "--open") == 0 && has_value)
            open_cmd = argv[++i];
        else if (strcmp(a, "--exercise-variant") == 0 && has_value)
            variant = argv[++i];
        else if (strcmp(a, "--runner") == 0 && has_value)
            runner = argv[++i];
        else if (strcmp(a, "--log") == 0 && has_value)
            log = argv[++i];
        else if (strcmp(a, "--seed") == 0 && has_value)   /* the fixed scenes' and the search's */
            seed = check_seed = grade_seed(argv[++i]);
        else if (strcmp(a, "--search") == 0 && has_value)
            search = strtod(argv[++i], NULL);
        else {
            variant_given |= strcmp(a, "--variant") == 0 || strncmp(a, "--variant=", 10) == 0;
            rest[nrest++] = argv[i];
        }
    }

    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0) {
            /* the exercise's own options, then the lesson program's */
            printf("Usage: %s [--file NAME] [LESSON PROGRAM OPTION]...      the explorer on your code\n"
                   "       %s --check [--file NAME] [--check-scene FILE]... [--out DIR] [--open CMD] [--seed N] [--search SECONDS]\n"
                   "The lesson's program with your exercise_rasterize() as the variant \"exercise\", or its checks.\n\n"
                   "  --file NAME             the name of the file compiled in (shown and put in commands; default exercise.c)\n"
                   "  --check                 run the lesson's checks on your code (make check), not the explorer\n"
                   "  --check-scene FILE      with --check: check this scene of your own first (make check SCENE=FILE)\n"
                   "  --out DIR               with --check: write counterexamples under DIR/NAME/ (default build/check)\n"
                   "  --open CMD              with --check: the command printed to open a counterexample\n"
                   "  --seed N                with --check: the search's seed (default 1: the same scenes every run)\n"
                   "  --search SECONDS        with --check: how long the search after the fixed scenes runs (default 1.5)\n"
                   "  --exercise-variant V    the graded variant V of the exercise (make check VARIANT=V):\n",
                   argv[0], argv[0]);
            for (const struct exercise_variant *v = LESSON.exercise.variants; v && v->name; v++)
                printf("                            %s: %s\n", v->name, v->what);
            printf("\n");
            break;
        }
    exercise_use(&LESSON, exercise_rasterize);
    if (LESSON.exercise.clip)
        exercise_use_clip(exercise_clip);
    if (variant) {
        const struct exercise_variant *v = exercise_variant_named(&LESSON, variant);
        if (!v) {
            fprintf(stderr, "VARIANT=%s: lesson %.2s has no such variant (", variant, LESSON.id);
            for (const struct exercise_variant *w = LESSON.exercise.variants; w && w->name; w++)
                fprintf(stderr, "%s%s", w == LESSON.exercise.variants ? "variants: " : ", ", w->name);
            fprintf(stderr, "%s)\n", LESSON.exercise.variants && LESSON.exercise.variants->name ? "" : "none");
            free(scenes);
            free(rest);
            return 2;
        }
        exercise_use_variant(v);
    }
    char *runner_argv[] = { (char *)runner, NULL };
    if (runner) {       /* the student's code in a process of its own */
        if (log)
            fclose(fopen(log, "w"));
        remote_configure(&(struct remote_config){ .argv = runner_argv, .log = log });
    }
#ifdef EXERCISE_JUDGE
    if (!check || !runner) {
        fprintf(stderr, "%s: the judge only checks a runner's results (--check --runner PROGRAM) or grades (--grade)\n",
                argv[0]);
        return 2;
    }
#endif
    int status;
    if (check) {
        char cmd[600];
        if (!open_cmd) {
            snprintf(cmd, sizeof cmd, "make exercise LESSON=%.2s%s%s FILE=%s", LESSON.id,
                     variant ? " VARIANT=" : "", variant ? variant : "", file);
            open_cmd = cmd;
        }
        struct check_options o = {
            .file = file, .scenes = scenes, .out_dir = out_dir, .open_cmd = open_cmd,
            .params = { .subpixel_bits = SUBPIXEL_BITS }, .out = stdout,
            .progress = isatty(STDOUT_FILENO), .program = argv[0],
            .seed = seed, .search_seconds = search > 0 && search < 3600 ? search : 0,
        };
        struct check_result r;
        bool ok = exercise_check_guarded(&LESSON, &o, &r);
        status = ok ? 0 : r.nchecks == 0 ? 2 : 1;     /* 2: a SCENE= file that does not load */
        if (runner) {
            remote_shutdown();
            struct stat st;
            if (log && !ok && stat(log, &st) == 0 && st.st_size > 0)
                printf("(what your program printed: %s)\n", log);
        }
    } else {
        /* the lesson program, on the exercise variant unless told otherwise */
        struct lesson l;
        struct lesson_variant variants[2];
        exercise_lesson(&l, variants, &LESSON, file);
        if (!variant_given) {
            rest[nrest++] = "--variant";
            rest[nrest++] = "exercise";
        }
        status = lesson_main(&l, nrest, rest);
    }
    free(scenes);
    free(rest);
    return status;
}
