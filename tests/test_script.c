/* test_script.c - reading --keys files (src/app/script.h): what a script
 * may say, and every way it can be wrong reported as FILE:LINE. */
#include <criterion/criterion.h>
#include <string.h>

#include "app/script.h"

static bool parse(struct script *s, const char *text, char *err, size_t n)
{
    return script_parse(s, "k.keys", text, strlen(text), err, n);
}

Test(script, commands_modifiers_aliases_and_comments)
{
    struct script s;
    char err[256] = "";
    cr_assert(parse(&s, "# a comment\n\n  Right  \nshift+ctrl+PgDn\nEsc\r\nwait\n"
                        "drag -5 20 +300 40\nKeypad Enter\n", err, sizeof err), "%s", err);
    cr_assert_eq(s.n, 6);
    cr_assert_eq(s.cmd[0].kind, SCRIPT_KEY);
    cr_assert_str_eq(s.cmd[0].key, "Right");
    cr_assert_eq(s.cmd[0].line, 3);
    cr_assert_eq(s.cmd[0].mods, 0u);
    cr_assert_str_eq(s.cmd[1].key, "PageDown");
    cr_assert_eq(s.cmd[1].mods, (unsigned)(SCRIPT_SHIFT | SCRIPT_CTRL));
    cr_assert_str_eq(s.cmd[2].key, "Escape");
    cr_assert_eq(s.cmd[3].kind, SCRIPT_WAIT);
    cr_assert_eq(s.cmd[4].kind, SCRIPT_DRAG);
    cr_assert(s.cmd[4].x1 == -5 && s.cmd[4].y1 == 20 && s.cmd[4].x2 == 300 && s.cmd[4].y2 == 40);
    cr_assert_str_eq(s.cmd[5].key, "Keypad Enter");
    script_free(&s);
}

struct bad_script {
    const char *what, *text, *message;
};

static const struct bad_script bad_scripts[] = {
    { "drag with 3 numbers", "Right\ndrag 1 2 3\n", "k.keys:2: 'drag' needs 4" },
    { "drag beyond the coordinate range", "drag 0 0 65537 0\n", "k.keys:1: 'drag' needs 4" },
    /* regression: "drag 2147483647 ..." went through sscanf's %d (undefined
     * on overflow) and the in-between points overflowed int */
    { "drag_int_overflow", "drag 0 0 2147483647 -2147483648\n", "k.keys:1: 'drag' needs 4" },
    { "drag with a trailing word", "drag 1 2 3 4 5\n", "k.keys:1: 'drag' needs 4" },
    { "drag with a fraction", "drag 1.5 2 3 4\n", "k.keys:1: 'drag' needs 4" },
    { "modifier alone", "Shift+\n", "k.keys:1: a modifier without a key" },
    /* regression: lines over 255 bytes were cut by fgets and read as two keys */
    { "long_line_split_in_two", "Right\nRightRightRightRightRightRightRightRightRightRightRightRight"
      "RightRightRightRightRightRightRightRightRightRightRightRightRightRightRightRightRight"
      "RightRightRightRightRightRightRightRightRightRightRightRightRightRightRightRightRight"
      "RightRightRightRightRightRightRightRightRightRightRightRightRight\n",
      "k.keys:2: line longer than" },
    { "key name too long", "Right Right Right Right Right Right Right Right Right\n",
      "k.keys:1: 'Right Right" },
    { "control character", "Ri\x01ght\n", "k.keys:1: control character" },
};

Test(script, bad_scripts_name_file_and_line)
{
    for (size_t i = 0; i < sizeof bad_scripts / sizeof bad_scripts[0]; i++) {
        const struct bad_script *b = &bad_scripts[i];
        struct script s;
        char err[256] = "";
        cr_assert_not(parse(&s, b->text, err, sizeof err), "%s: accepted", b->what);
        cr_assert(strncmp(err, b->message, strlen(b->message)) == 0, "%s: message '%s'",
                  b->what, err);
        cr_assert_eq(s.n, 0u, "%s: a failed parse leaves the script empty", b->what);
        cr_assert_null(s.cmd);
    }
}

Test(script, nul_byte_is_an_error)
{
    struct script s;
    char err[256] = "";
    static const char text[] = "Right\nq\0x\n";
    cr_assert_not(script_parse(&s, "k.keys", text, sizeof text - 1, err, sizeof err));
    cr_assert(strstr(err, "k.keys:2: NUL byte"), "%s", err);
}
