/* keys.c - fuzz harness: --keys text -> script_parse (fuzz.h). */
#include <string.h>

#include "app/script.h"
#include "fuzz.h"

int fuzz_keys(const uint8_t *data, size_t size)
{
    struct script s;
    char err[512];
    if (!script_parse(&s, "fuzz.keys", (const char *)data, size, err, sizeof err)) {
        fuzz_check_message(err, "fuzz.keys");
        if (s.n != 0 || s.cmd)
            fuzz_fail("a rejected script keeps commands");
        return 0;
    }
    int last = 0;
    for (size_t i = 0; i < s.n; i++) {
        const struct script_cmd *c = &s.cmd[i];
        if (c->line <= last)
            fuzz_fail("command %zu: line %d after line %d", i, c->line, last);
        last = c->line;
        switch (c->kind) {
        case SCRIPT_WAIT: break;
        case SCRIPT_DRAG: {
            const int v[4] = { c->x1, c->y1, c->x2, c->y2 };
            for (int k = 0; k < 4; k++)
                if (v[k] < -SCRIPT_COORD_MAX || v[k] > SCRIPT_COORD_MAX)
                    fuzz_fail("command %zu: drag coordinate %d", i, v[k]);
            break;
        }
        case SCRIPT_KEY: {
            const char *nul = memchr(c->key, '\0', sizeof c->key);
            size_t n = nul ? (size_t)(nul - c->key) : sizeof c->key;
            if (n == 0 || n > SCRIPT_KEY_MAX)
                fuzz_fail("command %zu: key name of %zu bytes", i, n);
            for (size_t k = 0; k < n; k++)
                if ((unsigned char)c->key[k] < 32 || c->key[k] == 127)
                    fuzz_fail("command %zu: control character in the key name", i);
            if (c->mods & ~(unsigned)(SCRIPT_SHIFT | SCRIPT_CTRL))
                fuzz_fail("command %zu: modifiers %#x", i, c->mods);
            break;
        }
        default: fuzz_fail("command %zu: kind %d", i, (int)c->kind);
        }
    }
    script_free(&s);
    return 0;
}
