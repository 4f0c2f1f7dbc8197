/* app.h - the SDL2 explorer window. */
#ifndef TRISTEP_APP_H
#define TRISTEP_APP_H

#include "explore/explorer.h"

/* Exit statuses of the programs (lessons/CONVENTIONS.md). */
enum { EXIT_OK = 0, EXIT_RUN = 1, EXIT_USAGE = 2 };

/* What the window opens on: zero-initialise and set what you need. */
struct app_desc {
    struct explorer_desc explorer;
    const char *view;               /* a view name (already checked), NULL: "color" */
    const char *keys;               /* --keys FILE: scripted input, or NULL */
    int width, height;              /* window size, 0: 1280 x 800 */
};

/* Whether the window reads key k itself (SDL_Keycode: a lowercase letter
 * is its ASCII code); a lesson's parameter keys must not be among them. */
bool app_window_key(int k);

/* Open the explorer's window; returns the program's exit status. */
int explorer_run(const struct app_desc *d);

#endif
