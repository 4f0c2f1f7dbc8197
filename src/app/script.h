/* script.h - the --keys file: scripted explorer input, read and checked
 * before the window opens (untrusted text, like a scene). No SDL here: the
 * window turns commands into events; this is only the reading.
 *
 *     # comment lines and blank lines are ignored
 *     Right                 a key, by SDL's name ("PageDown", "v", "Space")
 *     Shift+Right           with modifiers: Shift+, Ctrl+ (any order, repeated)
 *     PgDn                  aliases: PgDn, PgUp, Esc
 *     wait                  one frame, and a tenth of a second of play
 *     drag 10 20 300 40     press at (10, 20), move to (300, 40), release
 *                           (window pixels, each in -SCRIPT_COORD_MAX..SCRIPT_COORD_MAX)
 */
#ifndef TRISTEP_SCRIPT_H
#define TRISTEP_SCRIPT_H

#include <stdbool.h>
#include <stddef.h>

#define SCRIPT_KEY_MAX 40        /* longest key name (SDL's are under 30) */
#define SCRIPT_COORD_MAX 65536   /* |drag coordinate|: far beyond any window */

enum script_kind { SCRIPT_KEY, SCRIPT_WAIT, SCRIPT_DRAG };
enum script_mod { SCRIPT_SHIFT = 1, SCRIPT_CTRL = 2 };

struct script_cmd {
    enum script_kind kind;
    int line;                       /* in the file, for messages */
    unsigned mods;                  /* enum script_mod, for SCRIPT_KEY */
    char key[SCRIPT_KEY_MAX + 1];   /* SDL's key name, aliases resolved */
    int x1, y1, x2, y2;             /* SCRIPT_DRAG */
};

struct script {
    char name[256];                 /* the file, for messages */
    struct script_cmd *cmd;
    size_t n, cap;
};

/* Parse a whole script text. On error returns false, writes one line
 * "name:LINE: message" into err and leaves *s empty. */
bool script_parse(struct script *s, const char *name, const char *text, size_t len,
                  char *err, size_t errlen);
/* Read and parse a file. */
bool script_load(struct script *s, const char *path, char *err, size_t errlen);
void script_free(struct script *s);

#endif
