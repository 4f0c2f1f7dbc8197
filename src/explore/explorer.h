/* explorer.h - the explorer's state, without a window and without drawing:
 * the scene as a lesson draws it after N events, the current triangle's
 * pixels as the narration left them, stepping by event, row or block, and
 * triangle, variants, dragging, and the layout of a frame. The painter
 * (src/draw/paint.h) draws this state for the SDL window and for PNG, SVG
 * and PDF files.
 *
 * The explorer never re-implements an algorithm: every picture is the
 * lesson's own output replayed to step N (src/explore/replay.h). Only what the
 * current step needs is kept: the target, the per-pixel "cells" of the
 * current triangle (accumulated from its events), and per-triangle counter
 * sums; never every event of the scene.
 */
#ifndef TRISTEP_EXPLORER_H
#define TRISTEP_EXPLORER_H

#include <stdbool.h>
#include <stdint.h>

#include "lesson.h"
#include "lesson_explorer.h"
#include "explore/replay.h"

enum step_unit {
    STEP_EVENT,     /* one event */
    STEP_GROUP,     /* to the next row, block or span (or triangle boundary) */
    STEP_TRIANGLE,  /* to the next triangle boundary */
};

enum numbers_mode { NUMBERS_AUTO, NUMBERS_ALWAYS, NUMBERS_OFF, NUMBERS_MODE_COUNT };

/* Figures for print (lessons/CONVENTIONS.md): the colours, and how much of the view.
 * THEME_DARK is the screen's; THEME_LIGHT draws for paper (dark ink on
 * white). PART_CANVAS is the pixel grid alone, without the panel and the
 * scrub bar. */
enum theme { THEME_DARK, THEME_LIGHT, THEME_COUNT };
enum figure_part { PART_ALL, PART_CANVAS, PART_COUNT };
/* --paper: a PDF figure on a page of paper (src/draw/export.c), or at its
 * own size in points (PAPER_NONE). */
enum paper { PAPER_NONE, PAPER_A4, PAPER_LETTER, PAPER_COUNT };

/* "dark", "light" / "all", "canvas"; the parsers return false on anything else. */
const char *theme_name(enum theme t);
bool theme_from_name(const char *name, enum theme *out);
const char *figure_part_name(enum figure_part f);
bool figure_part_from_name(const char *name, enum figure_part *out);
/* "a4", "letter" (PAPER_NONE has no name: no --paper) */
bool paper_from_name(const char *name, enum paper *out);

/* What the current triangle's narration said about one pixel so far. */
enum cell_flags {
    CELL_TESTED = 1,        /* a pixel test reached it */
    CELL_INSIDE = 2,        /* covered: test said inside, or a full block, span or write */
    CELL_WRITTEN = 4,       /* a pixel write reached it */
    CELL_DEPTH_PASS = 8,    /* ... and passed the depth test */
    CELL_BLOCK = 16,        /* inside a narrated block (class in klass) */
    CELL_SPAN = 32,         /* inside a narrated span */
    CELL_ROW = 64,          /* on a row the algorithm walked */
};

struct cell {
    int64_t e[3];           /* edge values F_ab, F_bc, F_ca of the last test */
    float bary[3];
    float aux[6];
    float z;                /* of the last write */
    uint32_t rgba;
    uint8_t flags;          /* enum cell_flags */
    uint8_t klass;          /* block class when CELL_BLOCK */
    uint8_t line;           /* the line of the event that left aux: the test's, or a step
                             * of the lesson's cell_lines told after it */
};

/* Where things are on the screen, from the window or figure size. */
struct explorer_layout {
    double s;                       /* interface scale */
    double w, h;                    /* the whole frame */
    double cx, cy, cw, ch;          /* canvas (the pixel grid) */
    double px, pw;                  /* panel on the right: x, width */
    double bar_y, bar_h;            /* scrub bar under the canvas */
    double zoom;                    /* screen pixels per scene pixel */
    double ox, oy;                  /* screen position of scene point (0, 0) */
};

/* How to start: zero-initialise and set what you need. */
struct explorer_desc {
    const struct lesson *lesson;
    const struct lesson_explorer *side;     /* NULL: the lesson's own (lesson_explorer_of) */
    const struct scene *scene;      /* copied: the explorer owns its own copy */
    struct scene *give_scene;       /* or this one, handed over, not copied (it is left
                                     * empty): a scene of millions of triangles */
    bool count_later;               /* count the events a part at a time (explorer_count)
                                     * after the first step instead of all before it */
    bool scene_is_default;          /* the lesson's built-in scene (X may switch scenes) */
    const char *scene_name;         /* as shown in the panel */
    const struct lesson_variant *variant;   /* NULL: variants[0] */
    /* taken as given (subpixel_bits 0 is whole pixels, as in --dump-coverage);
     * NULL: the defaults, SUBPIXEL_BITS and nothing else set */
    const struct raster_params *params;
    uint64_t step;
    bool step_end;
    double zoom;                    /* 0: fit the scene into the canvas */
    double scale;                   /* 0: 1 */
    enum theme theme;               /* THEME_DARK unless for paper */
    enum figure_part part;          /* PART_ALL: panel and scrub bar too */
};

struct explorer {
    const struct lesson *lesson;
    const struct lesson_explorer *side;     /* what the explorer adds for it, or NULL */
    struct scene scene;
    bool scene_is_default;
    char scene_name[128];
    int variant;                    /* index into lesson->variants */
    front_fn projected_by;          /* what made a 3-D scene's screen triangles (NULL: not yet) */
    struct raster_params params;
    struct run_place at;            /* params.at: the scene drawn */
    struct replay replay;
    uint64_t step;
    bool count_later;               /* explorer_count counts what is left, a part at a time */

    /* the state at `step` */
    struct target fb;               /* the scene as drawn after `step` events */
    int cur;                        /* triangle of the last event; -1 at step 0 */
    uint64_t local;                 /* that event's number inside the triangle */
    struct trace_counters tri_c;    /* the current triangle's counters so far */
    struct trace_event last;        /* the last event that happened */
    bool has_last;
    struct trace_event told[256];   /* the current unit's last event at each line (run_place.told) */
    int focus;                      /* triangle whose vectors are drawn (cur, or 0) */
    struct tri_setup tri;           /* its setup */
    struct cell *cells;             /* cells of the current triangle's region */
    int cell_x0, cell_y0, cell_w, cell_h;
    size_t cell_cap;

    /* row/block/span events of one triangle, for STEP_GROUP */
    int marks_tri;
    uint32_t *marks;
    size_t nmarks, marks_cap;
    struct target scratch;

    /* an exhibit shown against variants[0]: per pixel 0 or EXHIBIT_* */
    struct target exact;
    int exact_upto;
    uint8_t *diff;
    int diff_done;                  /* triangles compared (finished at this step) */
    int own_order;                  /* the exhibit's units in an order of their own: 1, 0, -1 not known */
    uint64_t extra, missing, wrong_colour;

    /* earlier lessons on the same scene (lesson->compare), for the counters */
    int ncompare;
    const struct lesson *compare[LESSON_COMPARE_MAX];
    struct replay compare_replay[LESSON_COMPARE_MAX];

    /* presentation */
    int view;                       /* enum view (src/draw/views.h), then the lesson's */
    int edge;                       /* edges view: -1 all three, or 0..2 */
    enum numbers_mode numbers;
    double zoom;                    /* 0: fit */
    double centre_x, centre_y;      /* scene point at the canvas centre (zoom != 0) */
    double scale;
    enum theme theme;               /* change it with explorer_set_theme */
    double own_background[3];       /* the scene's background (scene.background is the page's on paper) */
    enum figure_part part;          /* PART_CANVAS: the grid fills the frame, no panel, no bar */
    /* printing: the numbers in cells at least this many frame units high, or
     * left out, and drawn over the edges with a halo (0: on screen) */
    double text_min;
    bool pinned;
    int pin_x, pin_y;
    bool help;
    bool playing;
    int speed;                      /* events per second = 2^(speed / 2) */
    int hover_vertex;               /* handle under the mouse or being dragged, -1 none */
    char message[512];
};

/* The diff against the exact rule, per pixel of the finished triangles:
 * covered more often, less often, or as often but in a colour or at a depth
 * not pixel_close() to the exact one. */
enum { EXHIBIT_EXTRA = 1, EXHIBIT_MISSING = 2, EXHIBIT_COLOUR = 3 };

/* Start from a description. On failure (out of memory) nothing is left
 * allocated and err says what could not be done. */
bool explorer_init(struct explorer *ex, const struct explorer_desc *d, char *err, size_t errlen);
void explorer_free(struct explorer *ex);

/* Count events for about `ms` milliseconds (count_later): the lesson's
 * run first, then those of the lessons compared with it. False when out of
 * memory. explorer_counting tells whether anything is left to count. */
bool explorer_count(struct explorer *ex, double ms);
bool explorer_counting(const struct explorer *ex);

/* Replay to a step (clamped to the total) and rebuild the view state. */
bool explorer_set_step(struct explorer *ex, uint64_t step);
/* The step one unit forward (dir > 0) or back (dir < 0) from the current one. */
uint64_t explorer_find_step(struct explorer *ex, enum step_unit unit, int dir);
bool explorer_move(struct explorer *ex, enum step_unit unit, int dir);

/* Switch variant (index into lesson->variants) or params; the step is kept
 * (clamped). Returns false when out of memory. */
bool explorer_set_variant(struct explorer *ex, int index);
bool explorer_set_params(struct explorer *ex, const struct raster_params *p);
/* Dark for the screen, light for paper. On paper the scene is drawn on the
 * page: every run uses white as the scene's background, so that pixels a
 * triangle covers in part (lesson 08's resolved edges) blend with the page,
 * as they would printed, not with a dark background that the page does not
 * show. The step is kept. Returns false when out of memory. */
bool explorer_set_theme(struct explorer *ex, enum theme t);
/* ... its first half: ex->theme = t and the scene's background for it (no run). */
void theme_background(struct explorer *ex, enum theme t);
/* X: the next variant shown against the exact rule (or back to variants[0]);
 * T: the next twin or alternative. */
bool explorer_cycle_exhibit(struct explorer *ex);
bool explorer_cycle_twin(struct explorer *ex);

/* Move vertex `k` (0..2, as labelled A, B, C after setup) of the focus
 * triangle to (x, y) snapped to 1/256 pixel; vertices of other triangles at
 * the same place move with it. The lesson re-runs; the step is kept. In a
 * 3-D scene the model's vertex moves at its own view depth (front.h,
 * front_move_vertex); a vertex the clipper made stays, with a message. */
bool explorer_move_vertex(struct explorer *ex, int k, double x, double y);

/* Triangles finished at this step: those before the current one, and the
 * current one too once its last event has happened. */
int explorer_finished(const struct explorer *ex);
/* What the algorithm did up to this step: the counters of the triangles
 * before the current one plus the current one's so far. */
void explorer_counters(const struct explorer *ex, struct trace_counters *c);

/* The cell of the current triangle at pixel (x, y), or NULL. */
const struct cell *explorer_cell(const struct explorer *ex, int x, int y);

/* Layout of a w x h frame, and screen <-> scene coordinates. */
void explorer_layout(const struct explorer *ex, double w, double h, struct explorer_layout *L);
void explorer_zoom_at(struct explorer *ex, const struct explorer_layout *L, double sx, double sy,
                      double factor);
void explorer_pan(struct explorer *ex, const struct explorer_layout *L, double dx, double dy);
/* The focus triangle's vertex handle near screen point (sx, sy), or -1. */
int explorer_hit_vertex(const struct explorer *ex, const struct explorer_layout *L,
                        double sx, double sy);

#endif
