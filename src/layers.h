/* layers.h - the folders of src/ in their dependency order, lowest first.
 *
 *     util <- raster <- scene <- trace <- front <- (src/ itself: lesson.h,
 *     the lesson interface) <- shade <- explore <- draw <- app <- cli <- exercise
 *
 * A file may include the headers of its own folder and of folders before
 * its own in this list, never of a later one: the narration knows nothing
 * of the explorer, the explorer's state nothing of cairo, the painter
 * nothing of SDL or of the command line. The files at the top of src/
 * count as the folder ".". tests/test_layers.c reads the #include lines of
 * every file under src/ and fails on an include against this order (and so
 * on any cycle between folders). A new folder goes into the list in its
 * place. */
#ifndef TRISTEP_LAYERS_H
#define TRISTEP_LAYERS_H

#define TRISTEP_LAYERS \
    "util",    /* writing files all or nothing */ \
    "raster",  /* snapping, triangle setup, the fill rule, the target, lines' diamond rule */ \
    "scene",   /* scene files (2-D and 3-D), OBJ files, the built-in scenes */ \
    "trace",   /* the narration: events, counters, NARRATE */ \
    "front",   /* the 3-D front end: 3-D scene -> screen triangles, narrated */ \
    ".",       /* the lesson interface: lesson.h, lesson_explorer.h */ \
    "shade",   /* shared lesson machinery: shading pixels, four at a time */ \
    "explore", /* the explorer's state: replaying a run to any step */ \
    "draw",    /* the painter (cairo, Pango): views, panel, figures */ \
    "app",     /* the SDL window */ \
    "cli",     /* the programs: options, headless modes */ \
    "exercise" /* a student's rasterizer as a variant, make check */

#endif
