/* test_print.c - figures for print (lessons/CONVENTIONS.md, "Figures for print"):
 * --theme dark|light and --figure-part all|canvas give a valid file for
 * every lesson, every view and every format, the same bytes every time; the
 * light theme is white paper with dark ink, the canvas part is the pixel
 * grid without panel or scrub bar; figures/list holds a light PDF of every
 * lesson, and bad values are usage errors that write nothing. */
#define _XOPEN_SOURCE 700   /* mkdtemp */

#include <cairo.h>
#include <math.h>
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "draw/paint.h"
#include "draw/export.h"
#include "draw/painter.h"
#include "testlib.h"

#define FIG_W 480
#define FIG_H 300

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    cr_assert_not_null(buf);
    *len = fread(buf, 1, (size_t)n, f);
    buf[*len] = '\0';
    fclose(f);
    return buf;
}

static bool same_bytes(const char *a, const char *b)
{
    size_t na = 0, nb = 0;
    char *x = slurp(a, &na), *y = slurp(b, &nb);
    bool same = x && y && na == nb && memcmp(x, y, na) == 0;
    free(x);
    free(y);
    return same;
}

static bool starts_with(const char *path, const char *magic, size_t n)
{
    size_t len = 0;
    char *buf = slurp(path, &len);
    bool ok = buf && len > n && memcmp(buf, magic, n) == 0;
    free(buf);
    return ok;
}

/* 0xRRGGBB of pixel (x, y) of a PNG. */
static uint32_t png_pixel(const char *path, int x, int y, int *w, int *h)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    cr_assert_eq(cairo_surface_status(s), CAIRO_STATUS_SUCCESS, "%s is not a PNG", path);
    cairo_surface_flush(s);
    *w = cairo_image_surface_get_width(s);
    *h = cairo_image_surface_get_height(s);
    const unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    uint32_t v = *(const uint32_t *)(data + (size_t)y * (size_t)stride + 4 * (size_t)x) & 0xffffff;
    cairo_surface_destroy(s);
    return v;
}

static double luma_of(uint32_t c)
{
    return (0.299 * (c >> 16 & 255) + 0.587 * (c >> 8 & 255) + 0.114 * (c & 255)) / 255;
}

/* Every lesson x every view (the built-in ones, the lesson's own, one edge
 * alone) x PNG, SVG, PDF with --theme light --figure-part canvas: a valid
 * file; PNG and PDF drawn twice are the same bytes. (SVG twice in one
 * process is not: cairo numbers its ids per process; the next test draws
 * them in processes of their own.) */
Test(print, light_canvas_figures_of_every_lesson_view_and_format, .timeout = 240)
{
    char dir[] = "/tmp/tristep-print-XXXXXX";
    cr_assert(mkdtemp(dir));
    char why[256];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    int files = 0;
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        struct scene s;
        char err[256];
        cr_assert(scene_builtin(&s, l->builtin_scene, err, sizeof err), "%s", err);
        struct explorer ex;
        struct raster_params prm = default_params();
        struct explorer_desc d = { .lesson = l, .scene = &s, .scene_name = l->builtin_scene,
                                   .params = &prm,
                                   .step_end = true, .theme = THEME_LIGHT, .part = PART_CANVAS };
        cr_assert(explorer_init(&ex, &d, err, sizeof err), "%s: %s", l->id, err);
        /* half-way, so that the current step, its cells and the lesson's
         * drawings are on the figure too */
        cr_assert(explorer_set_step(&ex, ex.replay.total / 2));
        int nviews = explorer_view_count(&ex);
        for (int v = 0; v <= nviews; v++) {
            const char *view = v < nviews ? explorer_view_name(&ex, v) : "edge-bc";
            cr_assert(explorer_set_view_name(&ex, view), "%s: view %s", l->id, view);
            static const char *const formats[] = { "png", "pdf", "svg" };
            for (int f = 0; f < 3; f++) {
                char a[512], b[512];
                snprintf(a, sizeof a, "%s/%s-%s-a.%s", dir, l->id, view, formats[f]);
                snprintf(b, sizeof b, "%s/%s-%s-b.%s", dir, l->id, view, formats[f]);
                cr_assert(explorer_export(&ex, a, FIG_W, FIG_H, err, sizeof err), "%s: %s", a, err);
                files++;
                if (f == 0) {
                    cr_expect(starts_with(a, "\x89PNG\r\n\x1a\n", 8), "%s is not a PNG", a);
                    int w, h;
                    uint32_t corner = png_pixel(a, 1, 1, &w, &h);
                    cr_expect(w == FIG_W && h == FIG_H, "%s is %d x %d", a, w, h);
                    /* the pixel grid alone: no panel at the right, no bar at the bottom */
                    uint32_t right = png_pixel(a, FIG_W - 2, FIG_H / 2, &w, &h);
                    uint32_t bottom = png_pixel(a, FIG_W / 2, FIG_H - 2, &w, &h);
                    cr_expect_eq(corner, 0xffffffu, "%s: the page is %06x, not white", a,
                                 (unsigned)corner);
                    cr_expect_eq(right, 0xffffffu, "%s: %06x at the right, a panel?", a, (unsigned)right);
                    cr_expect_eq(bottom, 0xffffffu, "%s: %06x at the bottom, a bar?", a,
                                 (unsigned)bottom);
                } else if (f == 1) {
                    cr_expect(starts_with(a, "%PDF-", 5), "%s is not a PDF", a);
                } else {
                    cr_expect(starts_with(a, "<?xml", 5), "%s is not an SVG", a);
                }
                if (f < 2) {
                    cr_assert(explorer_export(&ex, b, FIG_W, FIG_H, err, sizeof err), "%s: %s", b, err);
                    cr_expect(same_bytes(a, b), "%s and its second drawing differ", a);
                    remove(b);
                }
                remove(a);
            }
        }
        explorer_free(&ex);
        scene_free(&s);
    }
    rmdir(dir);
    cr_expect_gt(files, 5 * 3 * 8);
}

static int run_program(const char *lesson, const char *args)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s/%s %s >/dev/null 2>&1", test_build_dir(), lesson, args);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* From the command line, in processes of their own: every lesson, every
 * format, both themes and both parts, the same bytes twice. */
Test(print, command_line_figures_are_reproducible_in_every_theme_and_part, .timeout = 240)
{
    char dir[] = "/tmp/tristep-print-XXXXXX";
    cr_assert(mkdtemp(dir));
    static const char *const themes[] = { "dark", "light" }, *const parts[] = { "all", "canvas" };
    static const char *const formats[] = { "png", "svg", "pdf" };
    for (int i = 0; all_lessons[i]; i++)
        for (int t = 0; t < 2; t++)
            for (int p = 0; p < 2; p++)
                for (int f = 0; f < 3; f++) {
                    char a[512], b[512], args[1400];
                    snprintf(a, sizeof a, "%s/a.%s", dir, formats[f]);
                    snprintf(b, sizeof b, "%s/b.%s", dir, formats[f]);
                    for (int k = 0; k < 2; k++) {
                        snprintf(args, sizeof args, "--figure %s --step end --size %dx%d "
                                 "--theme %s --figure-part %s", k ? b : a, FIG_W, FIG_H,
                                 themes[t], parts[p]);
                        cr_assert_eq(run_program(all_lessons[i]->id, args), 0, "%s %s",
                                     all_lessons[i]->id, args);
                    }
                    cr_expect(same_bytes(a, b), "%s --theme %s --figure-part %s: .%s not "
                              "reproducible", all_lessons[i]->id, themes[t], parts[p], formats[f]);
                    remove(a);
                    remove(b);
                }
    rmdir(dir);
}

/* The light theme is dark ink on white, the dark theme the opposite; the
 * whole view keeps its panel, the canvas part does not. */
Test(print, light_is_paper_and_canvas_drops_the_panel)
{
    char dir[] = "/tmp/tristep-print-XXXXXX";
    cr_assert(mkdtemp(dir));
    char path[512], args[1024];
    snprintf(path, sizeof path, "%s/f.png", dir);
    struct { const char *opts; bool light, panel; } cases[] = {
        { "--theme dark", false, true }, { "--theme light", true, true },
        { "--theme light --figure-part canvas", true, false },
        { "--figure-part canvas", false, false },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        snprintf(args, sizeof args, "--figure %s --step 300 --size 1280x800 %s", path, cases[c].opts);
        cr_assert_eq(run_program("02-barycentric", args), 0, "%s", args);
        int w, h;
        uint32_t page = png_pixel(path, 4, 4, &w, &h);
        uint32_t side = png_pixel(path, 1270, 400, &w, &h);     /* the panel, if any */
        cr_expect(cases[c].light ? luma_of(page) > 0.9 : luma_of(page) < 0.2,
                  "%s: the page is %06x", cases[c].opts, (unsigned)page);
        /* the panel's colour differs from the page's; without it the canvas runs on */
        cr_expect(cases[c].panel ? side != page : side == page, "%s: %06x at the right, page %06x",
                  cases[c].opts, (unsigned)side, (unsigned)page);
    }
    remove(path);
    rmdir(dir);
}

Test(print, bad_theme_or_part_is_a_usage_error_that_writes_nothing)
{
    char dir[] = "/tmp/tristep-print-XXXXXX";
    cr_assert(mkdtemp(dir));
    char path[512], args[1024];
    snprintf(path, sizeof path, "%s/f.png", dir);
    const char *bad[] = { "--theme sepia", "--theme", "--figure-part panel", "--figure-part ''",
                          "--theme Light" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(args, sizeof args, "--figure %s %s", path, bad[i]);
        cr_expect_eq(run_program("03-edge-stepping", args), 2, "%s", bad[i]);
        FILE *f = fopen(path, "rb");
        cr_expect_null(f, "%s wrote %s", bad[i], path);
        if (f)
            fclose(f);
    }
    rmdir(dir);
}

/* figures/list draws a light PDF of every lesson, and the lesson's text
 * links it. */
Test(print, every_lesson_has_a_light_pdf_in_the_list_and_links_it)
{
    size_t len = 0;
    char *list = slurp("figures/list", &len);
    cr_assert_not_null(list, "figures/list not found");
    for (int i = 0; all_lessons[i]; i++) {
        const struct lesson *l = all_lessons[i];
        bool listed = false;
        char name[128] = "";
        for (char *line = list; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
            char out[128], les[128];
            if (sscanf(line, "%127s %127s", out, les) != 2 || out[0] == '#')
                continue;
            size_t n = strlen(out);
            if (strcmp(les, l->id) == 0 && n > 10 && strcmp(out + n - 10, "-light.pdf") == 0
                && strstr(line, "--theme light")) {
                listed = true;
                snprintf(name, sizeof name, "%s", out);
                break;
            }
        }
        cr_expect(listed, "figures/list has no light PDF of %s", l->id);
        if (!listed)
            continue;
        char path[256], link[256];
        snprintf(path, sizeof path, "figures/%s", name);
        cr_expect(starts_with(path, "%PDF-", 5), "%s is not committed", path);
        snprintf(path, sizeof path, "lessons/%s/README.md", l->id);
        snprintf(link, sizeof link, "(../../figures/%s)", name);
        cr_expect(strstr(test_read_text(path), link) != NULL, "%s does not link %s", path, link);
    }
    free(list);
}

/* No two committed figures are the same picture under two names. */
Test(print, no_two_committed_figures_are_identical)
{
    size_t len = 0;
    char *list = slurp("figures/list", &len);
    cr_assert_not_null(list);
    char names[128][64];
    int n = 0;
    for (char *line = list; line && *line && n < 128;
         line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        char out[64];
        if (sscanf(line, "%63s", out) == 1 && out[0] != '#')
            snprintf(names[n++], 64, "%s", out);
    }
    cr_assert_gt(n, 10);
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            char pa[128], pb[128];
            snprintf(pa, sizeof pa, "figures/%.63s", names[a]);
            snprintf(pb, sizeof pb, "figures/%.63s", names[b]);
            cr_expect(!same_bytes(pa, pb), "%s and %s are the same file", names[a], names[b]);
        }
    free(list);
}

/* --- the light palette in grey and for a deuteranope ------------------------------- */

static double srgb_linear(uint32_t c, int shift)
{
    double v = (c >> shift & 255) / 255.0;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

/* CIE L*a*b* (D65) of linear RGB. */
static void lab_of(const double rgb[3], double out[3])
{
    double X = (0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2]) / 0.9505;
    double Y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    double Z = (0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2]) / 1.089;
    double f[3] = { X, Y, Z };
    for (int i = 0; i < 3; i++)
        f[i] = f[i] > 216.0 / 24389 ? cbrt(f[i]) : (24389.0 / 27 * f[i] + 16) / 116;
    out[0] = 116 * f[1] - 16, out[1] = 500 * (f[0] - f[1]), out[2] = 200 * (f[1] - f[2]);
}

/* The colour as seen (deuteranope) or printed in grey (L* alone). Machado,
 * Oliveira and Fernandes 2009, deuteranopia at severity 1.0, on linear RGB. */
static void seen(uint32_t c, bool deuteranope, double out[3])
{
    double rgb[3] = { srgb_linear(c, 16), srgb_linear(c, 8), srgb_linear(c, 0) };
    if (deuteranope) {
        static const double M[3][3] = { { 0.367322, 0.860646, -0.227968 },
                                        { 0.280085, 0.672501, 0.047413 },
                                        { -0.011820, 0.042940, 0.968881 } };
        double d[3];
        for (int i = 0; i < 3; i++)
            d[i] = fmin(1, fmax(0, M[i][0] * rgb[0] + M[i][1] * rgb[1] + M[i][2] * rgb[2]));
        memcpy(rgb, d, sizeof d);
    }
    lab_of(rgb, out);
}

/* Printed in grey, two colours are told apart by lightness alone: 10 L*
 * (about a 10 % step of grey, which laser and inkjet halftones keep) between
 * the cells a lesson is read by, 5 against the white page for the lightest
 * (a box drawn on it, not a message), 15 between the edges (thin lines
 * need more) and 30 between an edge and the page. A deuteranope sees the
 * colours through Machado's matrix: 10 (cells; 5 for the lightest against
 * the page) and 20 (edges) CIE76 units apart, well above the 2.3 of a
 * just-noticeable difference. */
#define GREY_CELLS 10.0
#define GREY_PAGE 5.0
#define GREY_EDGES 15.0
#define GREY_EDGE_PAGE 30.0
#define DEUTERANOPE_CELLS 10.0
#define DEUTERANOPE_EDGES 20.0

static void expect_apart(const char *what, const uint32_t *c, const char *const *names, int n,
                         double grey, double grey_page, double deut)
{
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            double a[3], b[3], da[3], db[3];
            seen(c[i], false, a), seen(c[j], false, b);
            seen(c[i], true, da), seen(c[j], true, db);
            double dl = fabs(a[0] - b[0]);
            double de = sqrt((da[0] - db[0]) * (da[0] - db[0]) + (da[1] - db[1]) * (da[1] - db[1])
                             + (da[2] - db[2]) * (da[2] - db[2]));
            double want = i == 0 ? grey_page : grey;      /* colour 0 is the page */
            cr_log_info("%s %s-%s: L* %.1f apart, deuteranope %.1f", what, names[i], names[j], dl, de);
            cr_expect_geq(dl, want, "light %s: %s and %s are %.1f L* apart in grey, want %.0f", what,
                          names[i], names[j], dl, want);
            double want_deut = i == 0 ? fmin(deut, grey_page) : deut;
            cr_expect_geq(de, want_deut, "light %s: %s and %s are %.1f apart for a deuteranope, want %.0f",
                          what, names[i], names[j], de, want_deut);
        }
}

Test(print, light_cells_and_edges_stay_apart_in_grey_and_for_a_deuteranope)
{
    const struct palette *p = &palette_light;
    uint32_t cells[] = { p->canvas, p->untested, p->covered, p->outside };
    static const char *const cell_names[] = { "page", "not tested", "covered", "outside" };
    expect_apart("cells", cells, cell_names, 4, GREY_CELLS, GREY_PAGE, DEUTERANOPE_CELLS);
    uint32_t sides[] = { p->canvas, p->fail_one, p->covered, p->fail_two };  /* the edges view */
    static const char *const side_names[] = { "page", "outside one edge", "inside", "outside two" };
    expect_apart("edge cells", sides, side_names, 4, GREY_CELLS, GREY_PAGE, DEUTERANOPE_CELLS);
    uint32_t blocks[] = { p->canvas, p->block_empty, p->partial_inside, p->partial_outside, p->block_full };
    static const char *const block_names[] = { "page", "empty block", "partial block, inside",
                                               "partial block, outside", "full block" };
    expect_apart("blocks", blocks, block_names, 5, GREY_CELLS, GREY_PAGE, DEUTERANOPE_CELLS);
    uint32_t edges[] = { p->canvas, p->edge[0], p->edge[1], p->edge[2] };
    static const char *const edge_names[] = { "page", "edge 0", "edge 1", "edge 2" };
    expect_apart("edges", edges, edge_names, 4, GREY_EDGES, GREY_EDGE_PAGE, DEUTERANOPE_EDGES);
    /* the dark theme is for the screen, not checked here; and the test can
     * fail: the light palette of before (covered 0x9fd89f beside outside
     * 0xeab0b7) was 4 L* apart */
    double a[3], b[3];
    seen(0x9fd89f, false, a), seen(0xeab0b7, false, b);
    cr_expect_lt(fabs(a[0] - b[0]), GREY_CELLS, "the measure does not see what it should");
}

/* --- pages of paper -------------------------------------------------------------------- */

/* The page of a PDF: its MediaBox, as cairo writes it (uncompressed). */
static bool media_box(const char *path, double *w, double *h)
{
    size_t len = 0;
    char *pdf = slurp(path, &len);
    if (!pdf)
        return false;
    const char *m = NULL;         /* the file holds NULs: search all of it */
    for (size_t i = 0; !m && i + 11 <= len; i++)
        if (memcmp(pdf + i, "/MediaBox [", 11) == 0)
            m = pdf + i;
    double x0, y0;
    bool ok = m && sscanf(m, "/MediaBox [ %lf %lf %lf %lf", &x0, &y0, w, h) == 4 && x0 == 0 && y0 == 0;
    free(pdf);
    return ok;
}

Test(print, paper_puts_a_pdf_figure_on_an_a4_or_letter_page, .timeout = 120)
{
    char dir[] = "/tmp/tristep-paper-XXXXXX";
    cr_assert(mkdtemp(dir));
    static const struct { const char *paper, *size; double w, h; } pages[] = {
        { "a4", "1280x800", 842, 595 },        /* a wide view: the page in landscape */
        { "letter", "1280x800", 792, 612 },
        { "a4", "600x900", 595, 842 },         /* a tall one: in portrait */
        { "letter", "600x900", 612, 792 },
        { NULL, "1280x800", 1280, 800 },       /* no --paper: the view's own size */
    };
    for (size_t i = 0; i < sizeof pages / sizeof pages[0]; i++) {
        char path[512], args[1024];
        snprintf(path, sizeof path, "%s/f%zu.pdf", dir, i);
        snprintf(args, sizeof args, "--figure %s --view edges --step 300 --size %s --theme light%s%s",
                 path, pages[i].size, pages[i].paper ? " --paper " : "", pages[i].paper ? pages[i].paper : "");
        cr_assert_eq(run_program("02-barycentric", args), 0, "%s", args);
        double w = 0, h = 0;
        cr_assert(media_box(path, &w, &h), "%s: no MediaBox", path);
        cr_expect(w == pages[i].w && h == pages[i].h, "%s: page %g x %g pt, want %g x %g", args, w, h,
                  pages[i].w, pages[i].h);
        unlink(path);
    }
    /* a page is for a PDF; a bad name is a usage error; neither writes */
    const char *bad[][2] = { { "f.png", "--paper a4" }, { "f.svg", "--paper letter" },
                             { "f.pdf", "--paper a3" }, { "f.pdf", "--paper A4" },
                             { "f.pdf", "--paper" } };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char path[512], args[1024];
        snprintf(path, sizeof path, "%s/%s", dir, bad[i][0]);
        snprintf(args, sizeof args, "--figure %s %s", path, bad[i][1]);
        cr_expect_eq(run_program("02-barycentric", args), 2, "%s", args);
        cr_expect(access(path, F_OK) != 0, "%s wrote %s", args, path);
        unlink(path);
    }
    cr_expect_eq(run_program("02-barycentric", "--paper a4 --dump-image /dev/null"), 2,
                 "--paper without a PDF figure");
    rmdir(dir);
}

/* The page of lesson 02's edges view on A4 (1440 x 900, the figure of
 * figures/list) drawn at 8 pixels a point: the height of the tallest
 * glyph of black ink in it (the cell numbers' digits; the edges, labels
 * and grid are in colours or grey), in points, or 0 without any. */
extern const struct lesson lesson_02;

static double tallest_black_glyph_pt(double zoom)
{
    char why[256];
    cr_assert(explorer_fonts(why, sizeof why), "%s", why);
    struct scene s;
    cr_assert(scene_builtin(&s, "triangle", why, sizeof why), "%s", why);
    struct raster_params prm = default_params();
    struct explorer_desc d = { .lesson = &lesson_02, .scene = &s, .scene_name = "builtin:triangle",
                               .params = &prm, .step = 300, .zoom = zoom, .theme = THEME_LIGHT,
                               .part = PART_CANVAS };
    struct explorer ex;
    cr_assert(explorer_init(&ex, &d, why, sizeof why), "%s", why);
    cr_assert(explorer_set_view_name(&ex, "edges"));
    enum { PX_PER_PT = 8 };
    double pw, ph;
    paper_page_size(PAPER_A4, 1440, 900, &pw, &ph);
    cr_assert(pw == 842 && ph == 595, "A4 landscape is %g x %g pt", pw, ph);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)pw * PX_PER_PT,
                                                      (int)ph * PX_PER_PT);
    cairo_t *cr = cairo_create(img);
    cairo_set_source_rgb(cr, 1, 1, 1);      /* the paper */
    cairo_paint(cr);
    cairo_scale(cr, PX_PER_PT, PX_PER_PT);
    explorer_paint_page(&ex, cr, 1440, 900, PAPER_A4);
    cairo_destroy(cr);
    cairo_surface_flush(img);
    const unsigned char *px = cairo_image_surface_get_data(img);
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int stride = cairo_image_surface_get_stride(img), tallest = 0;
    for (int x = 0; x < w; x++)
        for (int y = 0, run = 0; y < h; y++) {
            uint32_t c = *(const uint32_t *)(px + (size_t)y * (size_t)stride + (size_t)x * 4);
            bool ink = (c >> 16 & 255) < 40 && (c >> 8 & 255) < 40 && (c & 255) < 40;
            run = ink ? run + 1 : 0;
            tallest = run > tallest ? run : tallest;
        }
    cairo_surface_destroy(img);
    explorer_free(&ex);
    return (double)tallest / PX_PER_PT;
}

/* On paper the numbers in cells are at least 6 pt (a digit, 0.73 em of
 * DejaVu Sans Mono, at least 4.3 pt tall), or left out where the cells are
 * too small to hold them at that size. */
Test(print, paper_numbers_are_six_points_or_none, .timeout = 60)
{
    double big = tallest_black_glyph_pt(48), small = tallest_black_glyph_pt(32);
    cr_log_info("digits %.2f pt tall at zoom 48, %.2f pt at zoom 32", big, small);
    cr_expect_geq(big, 6 * 0.7, "at zoom 48 the cell numbers print %.2f pt tall", big);
    cr_expect_lt(big, 6 * 1.5, "at zoom 48 black ink %.2f pt tall: not digits", big);
    cr_expect_eq(small, 0, "at zoom 32 the cells hold numbers %.2f pt tall, below 6 pt", small);
}

/* On paper the canvas's labels and names (drawn in interface pixels, then
 * fitted to the page) are never smaller than the cell numbers' floor; the
 * panel's text and the screen's are drawn at their own size. */
Test(print, paper_labels_are_never_below_the_numbers_floor)
{
    struct explorer ex = { 0 };
    struct painter p = { .ex = &ex, .s = 1.5 };
    cr_expect_float_eq(text_px(&p, 10), 15, 1e-12, "on screen 10 px at scale 1.5");
    p.text_min = 22;       /* 6 pt on a page that shrinks the figure 11/3 times */
    cr_expect_float_eq(text_px(&p, 10), 22, 1e-12, "a label below the floor is raised to it");
    cr_expect_float_eq(text_px(&p, 20), 30, 1e-12, "a label above the floor keeps its size");
}
