/* cli.c - lesson_main: options, headless modes, exit codes. */
#define _POSIX_C_SOURCE 200809L   /* unlink */

#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "draw/paint.h"
#include "explore/replay.h"
#include "util/file.h"

/* --- writing files ------------------------------------------------------------ */

bool write_coverage_pgm(FILE *out, const struct target *fb)
{
    fprintf(out, "P5\n%d %d\n255\n", fb->w, fb->h);
    size_t n = (size_t)fb->w * (size_t)fb->h;
    return fwrite(fb->count, 1, n, out) == n;
}

static bool pgm_writer(FILE *out, void *ctx) { return write_coverage_pgm(out, ctx); }
static bool png_writer(FILE *out, void *ctx) { return write_color_png(out, ctx); }

/* --- options --------------------------------------------------------------------- */

#define PARAM_OPTIONS_MAX 16    /* distinct parameter options over every lesson */

static int param_options(const struct lesson *l, const struct lesson_param *rows[PARAM_OPTIONS_MAX]);

static void usage(const struct lesson *l, FILE *out)
{
    fprintf(out,
        "Usage: %s [OPTION]...\n"
        "%s.\n"
        "Without a headless option, opens the interactive explorer.\n"
        "\n"
        "  --scene FILE            use this scene (or builtin:NAME) instead of builtin:%s\n"
        "  --variant NAME          run a variant of the algorithm (see below)\n"
        "  --dump-coverage FILE    headless: write coverage counts as a binary PGM\n"
        "  --dump-image FILE       headless: write the final colour buffer as PNG (textures: below)\n"
        "  --figure FILE           headless: export the explorer's view (.png, .svg, .pdf)\n"
        "  --step N|end            the step to show (figure and explorer; default 0)\n"
        "  --view NAME             the view to show (figure and explorer)\n"
        "  --size WxH              figure or window size in pixels (default 1280x800)\n"
        "  --zoom PX               screen pixels per scene pixel (default: fit)\n"
        "  --scale F               interface scale for text and panels (default 1)\n"
        "  --theme dark|light      colours: dark for the screen (default), light for paper\n"
        "  --paper a4|letter       a PDF figure on a page of paper, its cell numbers 6 pt or more\n"
        "  --figure-part all|canvas  the whole view, or the pixel grid alone (no panel, no bar)\n",
        l->id, l->title, l->builtin_scene);
    const struct lesson_param *rows[PARAM_OPTIONS_MAX];
    int nrows = param_options(l, rows);
    for (int i = 0; i < nrows; i++) {     /* the lessons' parameters (their tables) */
        char opt[64];
        snprintf(opt, sizeof opt, "--%s%s%s", rows[i]->option, rows[i]->arg ? " " : "",
                 rows[i]->arg ? rows[i]->arg : "");
        fprintf(out, "  %-24s%s\n", opt, rows[i]->help);
    }
    fprintf(out,
        "  --keys FILE             explorer: read key names from FILE, one per line\n"
        "  --list-scenes           list the built-in scenes\n"
        "  --help                  show this help\n"
        "  --version               show the version\n"
        "\n"
        "Variants:\n");
    for (int i = 0; i < l->nvariants; i++)
        fprintf(out, "  %-22s  %s%s\n", l->variants[i].name, l->variants[i].what,
                i == 0 ? " (default)" : "");
    fprintf(out,
        "\nTextures: a scene line 'texture FILE.png [repeat|clamp]' (or builtin:NAME) applies\n"
        "to the textured triangles after it. This program draws such a triangle %s;\n"
        "'texture checker N' darkens the checker's dark squares, as every program does.\n",
        l->texturing ? l->texturing : "in its vertex colour (the image is read, and checked, but not drawn)");
    fprintf(out,
        "\nLines: a scene line 'line x0 y0 z0 r0 g0 b0  x1 y1 z1 r1 g1 b1' is a segment;\n"
        "this program %s.\n",
        l->lines ? l->lines : "reads and checks it, then ignores it: it draws the triangles alone");
    fprintf(out,
        "\nExit status: 0 success, 1 failure while running, 2 bad command line or input.\n");
}

static int bad_usage(const struct lesson *l, const char *fmt, const char *arg)
{
    fprintf(stderr, "%s: ", l->id);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\nTry '%s --help' for more information.\n", l->id);
    return EXIT_USAGE;
}

static bool parse_uint(const char *s, uint64_t max, uint64_t *out)
{
    if (!*s || s[strspn(s, "0123456789")] != '\0' || strlen(s) > 18)
        return false;
    unsigned long long v = strtoull(s, NULL, 10);
    if (v > max)
        return false;
    *out = v;
    return true;
}

static bool parse_positive(const char *s, double max, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !(v > 0) || v > max)
        return false;
    *out = v;
    return true;
}

enum {
    OPT_SCENE = 256, OPT_VARIANT, OPT_DUMP_COVERAGE, OPT_DUMP_IMAGE, OPT_FIGURE, OPT_STEP,
    OPT_VIEW, OPT_SIZE, OPT_ZOOM, OPT_SCALE, OPT_THEME, OPT_PART, OPT_PAPER, OPT_KEYS, OPT_LIST_SCENES,
    OPT_HELP, OPT_VERSION,
    OPT_PARAM,      /* OPT_PARAM + i: the i-th option of the lessons' parameter tables */
};

static const struct option long_options[] = {
    { "scene", required_argument, NULL, OPT_SCENE },
    { "variant", required_argument, NULL, OPT_VARIANT },
    { "dump-coverage", required_argument, NULL, OPT_DUMP_COVERAGE },
    { "dump-image", required_argument, NULL, OPT_DUMP_IMAGE },
    { "figure", required_argument, NULL, OPT_FIGURE },
    { "step", required_argument, NULL, OPT_STEP },
    { "view", required_argument, NULL, OPT_VIEW },
    { "size", required_argument, NULL, OPT_SIZE },
    { "zoom", required_argument, NULL, OPT_ZOOM },
    { "scale", required_argument, NULL, OPT_SCALE },
    { "theme", required_argument, NULL, OPT_THEME },
    { "figure-part", required_argument, NULL, OPT_PART },
    { "paper", required_argument, NULL, OPT_PAPER },
    { "keys", required_argument, NULL, OPT_KEYS },
    { "list-scenes", no_argument, NULL, OPT_LIST_SCENES },
    { "help", no_argument, NULL, OPT_HELP },
    { "version", no_argument, NULL, OPT_VERSION },
    { NULL, 0, NULL, 0 },
};
#define FIXED_OPTIONS (sizeof long_options / sizeof long_options[0] - 1)

/* The options of every lesson's parameters, each once, in the order of the
 * lessons (every program links them all, and accepts them all: an option
 * of a row the lesson lacks is checked, then ignored unless its slot is
 * shared): writes them to rows and returns how many. */
static int param_options(const struct lesson *l, const struct lesson_param *rows[PARAM_OPTIONS_MAX])
{
    int n = 0;
    for (int k = 0; all_lessons[k] || l; k++) {
        const struct lesson *from = all_lessons[k] ? all_lessons[k] : l;
        for (int i = 0; from->params && from->params[i].option; i++) {
            bool seen = false;
            for (int j = 0; j < n; j++)
                seen |= strcmp(rows[j]->option, from->params[i].option) == 0;
            if (!seen && n < PARAM_OPTIONS_MAX)
                rows[n++] = &from->params[i];
        }
        if (!all_lessons[k])
            break;
    }
    return n;
}

/* Option --row->option given as arg: into o->params, or an exit status. */
static int param_option(const struct lesson *l, const struct lesson_param *row, const char *arg,
                        struct cli_options *o)
{
    uint64_t u = 1;
    bool named = row->arg && row->words;        /* a value by its name: --filter trilinear */
    int v = named ? lesson_param_named(row, arg) : 0;
    if (named && v >= 0)
        u = (uint64_t)v;
    if (row->arg && (named ? v < 0 : !parse_uint(arg, (uint64_t)row->max, &u) || !lesson_param_allows(row, (int)u))) {
        char range[64], fmt[128];
        lesson_param_range(row, range, sizeof range);
        snprintf(fmt, sizeof fmt, "--%s '%%s': expected %s", row->option, range);
        return bad_usage(l, fmt, arg);
    }
    int i;
    if (lesson_param(l, row->option, &i))
        *lesson_param_slot(l, i, &o->params) = (int)u;
    else if (row->slot == PARAM_SUBPIXEL_BITS)
        o->params.subpixel_bits = (int)u;
    else if (row->slot == PARAM_SAMPLES)
        o->params.samples = (int)u;
    return -1;
}

/* Returns -1 to go on, or an exit status. */
static int parse_options(const struct lesson *l, int argc, char **argv, struct cli_options *o)
{
    *o = (struct cli_options){ .variant = &l->variants[0], .params = lesson_params_default(l) };
    const struct lesson_param *rows[PARAM_OPTIONS_MAX];
    int nrows = param_options(l, rows);
    struct option options[FIXED_OPTIONS + PARAM_OPTIONS_MAX + 1];
    memcpy(options, long_options, FIXED_OPTIONS * sizeof *options);
    for (int i = 0; i < nrows; i++)
        options[FIXED_OPTIONS + (size_t)i] = (struct option){ rows[i]->option,
            rows[i]->arg ? required_argument : no_argument, NULL, OPT_PARAM + i };
    options[FIXED_OPTIONS + (size_t)nrows] = (struct option){ NULL, 0, NULL, 0 };
    opterr = 0;   /* our own messages, in the same form as every other error */
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":", options, NULL)) != -1) {
        uint64_t u;
        switch (c) {
        case OPT_SCENE: o->scene_path = optarg; break;
        case OPT_VARIANT:
            o->variant = lesson_variant(l, optarg);
            if (!o->variant)
                return bad_usage(l, "no variant '%s' (see --help)", optarg);
            break;
        case OPT_DUMP_COVERAGE: o->dump_coverage = optarg; break;
        case OPT_DUMP_IMAGE: o->dump_image = optarg; break;
        case OPT_FIGURE:
            if (!has_suffix(optarg, ".png") && !has_suffix(optarg, ".svg") && !has_suffix(optarg, ".pdf"))
                return bad_usage(l, "--figure '%s': the name must end in .png, .svg or .pdf", optarg);
            o->figure = optarg;
            break;
        case OPT_STEP:
            if (strcmp(optarg, "end") == 0)
                o->step_end = true;
            else if (parse_uint(optarg, UINT64_MAX / 2, &u))
                o->step = u, o->step_end = false;
            else
                return bad_usage(l, "--step '%s': expected a step number or 'end'", optarg);
            break;
        case OPT_VIEW: o->view = optarg; break;
        case OPT_SIZE: {
            int w, h, n = 0;
            if (sscanf(optarg, "%dx%d%n", &w, &h, &n) != 2 || optarg[n] || w < 64 || h < 64
                || w > 8192 || h > 8192)
                return bad_usage(l, "--size '%s': expected WxH, each 64..8192", optarg);
            o->width = w, o->height = h;
            break;
        }
        case OPT_ZOOM:
            if (!parse_positive(optarg, 1024, &o->zoom))
                return bad_usage(l, "--zoom '%s': expected screen pixels per pixel, up to 1024", optarg);
            break;
        case OPT_SCALE:
            if (!parse_positive(optarg, 8, &o->scale) || o->scale < 0.25)
                return bad_usage(l, "--scale '%s': expected a factor in 0.25..8", optarg);
            break;
        case OPT_THEME:
            if (!theme_from_name(optarg, &o->theme))
                return bad_usage(l, "--theme '%s': expected dark or light", optarg);
            break;
        case OPT_PART:
            if (!figure_part_from_name(optarg, &o->part))
                return bad_usage(l, "--figure-part '%s': expected all or canvas", optarg);
            break;
        case OPT_PAPER:
            if (!paper_from_name(optarg, &o->paper))
                return bad_usage(l, "--paper '%s': expected a4 or letter", optarg);
            break;
        case OPT_KEYS: o->keys = optarg; break;
        case OPT_LIST_SCENES:
            for (int i = 0; i < builtin_scene_count; i++)
                printf("builtin:%-14s %s\n", builtin_scenes[i].name, builtin_scenes[i].what);
            return EXIT_OK;
        case OPT_HELP: usage(l, stdout); return EXIT_OK;
        case OPT_VERSION: printf("tristep %s, lesson %s\n", TRISTEP_VERSION, l->id); return EXIT_OK;
        case ':':
            return bad_usage(l, "option '%s' needs a value", argv[optind - 1]);
        default:
            if (c >= OPT_PARAM && c < OPT_PARAM + nrows) {
                int status = param_option(l, rows[c - OPT_PARAM], optarg, o);
                if (status >= 0)
                    return status;
                break;
            }
            /* an unknown short option inside a bundle ("-qz") leaves optind
             * on the bundle or past it: name the letter getopt saw */
            if (optopt > 0 && optopt < 256) {
                char opt[3] = { '-', (char)optopt, '\0' };
                return bad_usage(l, "unknown option '%s'", opt);
            }
            return bad_usage(l, "unknown option '%s'", argv[optind - 1]);
        }
    }
    if (optind < argc)
        return bad_usage(l, "unexpected argument '%s' (scenes are given with --scene)", argv[optind]);
    if (o->paper != PAPER_NONE && !(o->figure && has_suffix(o->figure, ".pdf")))
        return bad_usage(l, "--paper '%s': a page is for a PDF figure (--figure FILE.pdf)",
                         o->paper == PAPER_A4 ? "a4" : "letter");
    return -1;
}

/* --- the program ------------------------------------------------------------------- */

static int dump(const struct lesson *l, const struct cli_options *o, const struct scene *s)
{
    struct target fb;
    if (!render_lesson_scene(l, s, o->variant, &o->params, &fb)) {
        fprintf(stderr, "out of memory for a %d x %d target\n", s->w, s->h);
        return EXIT_RUN;
    }
    char err[512];
    int status = EXIT_OK;
    if (o->dump_coverage && !write_file_atomic(o->dump_coverage, pgm_writer, &fb, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = EXIT_RUN;
    }
    if (status == EXIT_OK && o->dump_image
        && !write_file_atomic(o->dump_image, png_writer, &fb, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = EXIT_RUN;
    }
    /* all or nothing: a failed second file takes the first one with it */
    if (status != EXIT_OK && o->dump_coverage)
        unlink(o->dump_coverage);
    target_free(&fb);
    return status;
}

/* The explorer as the command line describes it, for the window and for
 * figures alike: fills *d (its scene name into name[n]) and returns -1, or
 * prints why --view is wrong and returns EXIT_USAGE. */
static int explorer_desc_from_cli(const struct lesson *l, const struct cli_options *o,
                                  const struct scene *s, char *name, size_t n,
                                  struct explorer_desc *d)
{
    if (o->scene_path)
        snprintf(name, n, "%s", o->scene_path);
    else
        snprintf(name, n, "builtin:%s", l->builtin_scene);
    *d = (struct explorer_desc){
        .lesson = l, .scene = s, .scene_name = name, .scene_is_default = !o->scene_path,
        .variant = o->variant, .params = &o->params, .step = o->step, .step_end = o->step_end,
        .zoom = o->zoom, .scale = o->scale, .theme = o->theme, .part = o->part,
    };
    if (o->view) {
        /* check the name first: a bad view is a usage error */
        struct explorer probe = { .lesson = l, .side = lesson_explorer_of(l), .edge = -1 };
        if (!explorer_set_view_name(&probe, o->view)) {
            fprintf(stderr, "%s: --view '%s': no such view; views:", l->id, o->view);
            for (int i = 0; i < explorer_view_count(&probe); i++)
                fprintf(stderr, " %s", explorer_view_name(&probe, i));
            fprintf(stderr, " edge-ab edge-bc edge-ca\n");
            return EXIT_USAGE;
        }
    }
    return -1;
}

/* Headless --figure: draw what the window would show at the chosen step and
 * view. The explorer takes the scene over (the last use of it). */
static int figure_export(const struct lesson *l, const struct cli_options *o, struct scene *s)
{
    char name[160], err[512];
    struct explorer ex;
    struct explorer_desc d;
    int status = explorer_desc_from_cli(l, o, s, name, sizeof name, &d);
    if (status >= 0)
        return status;
    d.scene = NULL;
    d.give_scene = s;
    if (!explorer_fonts(err, sizeof err)) {
        fprintf(stderr, "%s: %s\n", l->id, err);     /* the figure would not be the figure */
        return EXIT_RUN;
    }
    if (!explorer_init(&ex, &d, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return EXIT_RUN;
    }
    if (o->view)
        explorer_set_view_name(&ex, o->view);
    int w = o->width ? o->width : 1280, h = o->height ? o->height : 800;
    status = EXIT_OK;
    if (!explorer_export_paper(&ex, o->figure, w, h, o->paper, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        status = EXIT_RUN;
    }
    explorer_free(&ex);
    return status;
}

/* The window. It takes the scene over, and shows the first step before a
 * large scene's steps are all counted. */
static int window(const struct lesson *l, const struct cli_options *o, struct scene *s)
{
    char name[160];
    struct app_desc a = { .view = o->view, .keys = o->keys, .width = o->width, .height = o->height };
    int status = explorer_desc_from_cli(l, o, s, name, sizeof name, &a.explorer);
    if (status >= 0)
        return status;
    a.explorer.scene = NULL;
    a.explorer.give_scene = s;
    a.explorer.count_later = true;
    return explorer_run(&a);
}

int lesson_main(const struct lesson *l, int argc, char **argv)
{
    struct cli_options o;
    int status = parse_options(l, argc, argv, &o);
    if (status >= 0)
        return status;

    struct scene s;
    char err[512];
    bool loaded = o.scene_path ? scene_load(&s, o.scene_path, err, sizeof err)
                               : scene_builtin(&s, l->builtin_scene, err, sizeof err);
    if (!loaded) {
        fprintf(stderr, "%s\n", err);
        return EXIT_USAGE;
    }
    o.params.at = &(struct run_place){ .scene = &s };
    if (!lesson_front(l, o.variant)(&s)) {    /* a 3-D scene: its screen triangles */
        fprintf(stderr, "out of memory projecting %d triangles\n", s.world.ntris);
        scene_free(&s);
        return EXIT_RUN;
    }
    o.params.checker = s.checker;

    bool headless = o.dump_coverage || o.dump_image || o.figure;
    status = EXIT_OK;
    if (o.dump_coverage || o.dump_image)
        status = dump(l, &o, &s);
    if (status == EXIT_OK && o.figure)
        status = figure_export(l, &o, &s);
    if (!headless)
        status = window(l, &o, &s);
    scene_free(&s);
    return status;
}
