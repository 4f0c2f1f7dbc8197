/* fonts.c - text in the painter: Pango with DejaVu Sans Mono only, under a
 * fontconfig setup of our own, so that a user's fonts never change a figure. */
#define _POSIX_C_SOURCE 200809L   /* setenv, mkstemp */

#include "painter.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Only DejaVu, with fixed rendering settings: a user's own fontconfig
 * setup must not change a figure. Written to a temporary file
 * because FONTCONFIG_FILE names a file. */
static const char fonts_conf[] =
    "<?xml version=\"1.0\"?>\n"
    "<!DOCTYPE fontconfig SYSTEM \"fonts.dtd\">\n"
    "<fontconfig>\n"
    "  <dir>/usr/share/fonts/truetype/dejavu</dir>\n"
    "  <dir>/usr/share/fonts/dejavu</dir>\n"
    "  <dir>/usr/local/share/fonts/dejavu</dir>\n"
    "  <dir>/opt/homebrew/share/fonts</dir>\n"
    "  <cachedir prefix=\"xdg\">fontconfig</cachedir>\n"
    "  <config><rescan><int>0</int></rescan></config>\n"
    "  <match target=\"pattern\">\n"
    "    <edit name=\"family\" mode=\"assign\" binding=\"strong\"><string>DejaVu Sans Mono</string></edit>\n"
    "  </match>\n"
    "  <match target=\"font\">\n"
    "    <edit name=\"antialias\" mode=\"assign\"><bool>true</bool></edit>\n"
    "    <edit name=\"hinting\" mode=\"assign\"><bool>false</bool></edit>\n"
    "    <edit name=\"rgba\" mode=\"assign\"><const>none</const></edit>\n"
    "  </match>\n"
    "</fontconfig>\n";

static char fonts_path[4096];

static void remove_fonts_conf(void)
{
    if (fonts_path[0])
        unlink(fonts_path);
}

/* Point fontconfig at fonts_conf, in a file of our own under $TMPDIR. */
static bool pin_fonts(char *err, size_t errlen)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    if (snprintf(fonts_path, sizeof fonts_path, "%s/tristep-fonts-XXXXXX", dir)
        >= (int)sizeof fonts_path) {
        snprintf(err, errlen, "cannot pin the fonts: TMPDIR is too long");
        fonts_path[0] = '\0';
        return false;
    }
    int fd = mkstemp(fonts_path);
    if (fd < 0) {
        snprintf(err, errlen, "cannot pin the fonts: cannot create a file in %.400s: %s", dir,
                 strerror(errno));
        fonts_path[0] = '\0';
        return false;
    }
    size_t n = sizeof fonts_conf - 1;
    bool ok = write(fd, fonts_conf, n) == (ssize_t)n;
    int saved = errno;
    if (close(fd) != 0)
        ok = false;
    if (!ok) {
        snprintf(err, errlen, "cannot pin the fonts: cannot write %.400s: %s", fonts_path,
                 strerror(saved));
        unlink(fonts_path);
        fonts_path[0] = '\0';
        return false;
    }
    setenv("FONTCONFIG_FILE", fonts_path, 1);
    atexit(remove_fonts_conf);
    return true;
}

static cairo_font_face_t *face;     /* DejaVu Sans Mono, once found */

/* Find DejaVu Sans Mono through Pango, as every label will. */
static bool find_mono(char *err, size_t errlen)
{
    PangoFontMap *fm = pango_cairo_font_map_get_default();
    PangoContext *ctx = pango_font_map_create_context(fm);
    pango_cairo_context_set_font_options(ctx, font_options());
    PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono 10");
    PangoFont *f = pango_font_map_load_font(fm, ctx, d);
    const char *family = "no font at all";
    PangoFontDescription *got = NULL;
    if (f) {
        got = pango_font_describe(f);
        family = pango_font_description_get_family(got);
        cairo_scaled_font_t *sf = pango_cairo_font_get_scaled_font(PANGO_CAIRO_FONT(f));
        if (family && strcmp(family, "DejaVu Sans Mono") == 0 && sf)
            face = cairo_font_face_reference(cairo_scaled_font_get_font_face(sf));
    }
    if (!face)
        snprintf(err, errlen, "DejaVu Sans Mono not found (fontconfig gave %s): install the "
                 "DejaVu fonts (Debian: fonts-dejavu-core)", family ? family : "a nameless font");
    if (got)
        pango_font_description_free(got);
    if (f)
        g_object_unref(f);
    pango_font_description_free(d);
    g_object_unref(ctx);
    return face != NULL;
}

bool explorer_fonts(char *err, size_t errlen)
{
    static bool done, ok;
    static char why[512];
    if (!done) {
        done = true;
        ok = pin_fonts(why, sizeof why) && find_mono(why, sizeof why);
    }
    if (!ok && err)
        snprintf(err, errlen, "%s", why);
    return ok;
}

cairo_font_options_t *font_options(void)
{
    static cairo_font_options_t *o;
    if (!o) {
        o = cairo_font_options_create();
        cairo_font_options_set_antialias(o, CAIRO_ANTIALIAS_GRAY);
        cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_NONE);
        cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_OFF);
        cairo_font_options_set_subpixel_order(o, CAIRO_SUBPIXEL_ORDER_DEFAULT);
    }
    return o;
}

/* The DejaVu Sans Mono face, for the numbers in cells (drawn as one batch
 * of glyphs: thousands of labels per frame); NULL when it is missing. */
cairo_font_face_t *mono_face(void)
{
    explorer_fonts(NULL, 0);
    return face;
}

/* --- text ------------------------------------------------------------------------ */

double text_px(const struct painter *p, double size)
{
    double px = size * p->s;
    return fmax(px, p->text_min);
}

double draw_text(struct painter *p, double x, double y, double width, const char *str,
                 double size, uint32_t colour, bool markup)
{
    PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono");
    pango_font_description_set_absolute_size(d, text_px(p, size) * PANGO_SCALE);
    pango_layout_set_font_description(p->layout, d);
    pango_font_description_free(d);
    pango_layout_set_width(p->layout, width > 0 ? (int)(width * PANGO_SCALE) : -1);
    pango_layout_set_wrap(p->layout, PANGO_WRAP_WORD_CHAR);
    if (markup)
        pango_layout_set_markup(p->layout, str, -1);
    else {
        pango_layout_set_attributes(p->layout, NULL);
        pango_layout_set_text(p->layout, str, -1);
    }
    set_rgb(p->cr, colour);
    cairo_move_to(p->cr, x, y);
    pango_cairo_show_layout(p->cr, p->layout);
    /* forget the current point, or the next cairo_arc would start with a
     * line from here (a stray line from a label to a vertex handle) */
    cairo_new_path(p->cr);
    int w, h;
    pango_layout_get_size(p->layout, &w, &h);
    return (double)h / PANGO_SCALE;
}

double text_width(struct painter *p, const char *str, double size)
{
    PangoFontDescription *d = pango_font_description_from_string("DejaVu Sans Mono");
    pango_font_description_set_absolute_size(d, text_px(p, size) * PANGO_SCALE);
    pango_layout_set_font_description(p->layout, d);
    pango_font_description_free(d);
    pango_layout_set_width(p->layout, -1);
    pango_layout_set_attributes(p->layout, NULL);
    pango_layout_set_text(p->layout, str, -1);
    int w, h;
    pango_layout_get_size(p->layout, &w, &h);
    return (double)w / PANGO_SCALE;
}

void batch_add(cairo_t *cr, struct glyph_batch *b, double cx, double cy, const char *str,
               double advance)
{
    int len = (int)strlen(str);
    if (b->n + len > b->cap) {
        int cap = b->cap ? b->cap * 2 : 4096;
        while (cap < b->n + len)
            cap *= 2;
        cairo_glyph_t *g = realloc(b->g, (size_t)cap * sizeof *g);
        if (!g)
            return;
        b->g = g;
        b->cap = cap;
    }
    cairo_glyph_t *glyphs = NULL;
    int n = 0;
    double x = cx - advance * len / 2;
    cairo_scaled_font_t *sf = cairo_get_scaled_font(cr);
    if (cairo_scaled_font_text_to_glyphs(sf, x, cy, str, len, &glyphs, &n, NULL, NULL, NULL)
        == CAIRO_STATUS_SUCCESS) {
        for (int i = 0; i < n && b->n < b->cap; i++)
            b->g[b->n++] = glyphs[i];
    }
    cairo_glyph_free(glyphs);
}

