/* runner.c - the runner's main: the student's code, linked with the student
 * library (src/exercise/student-library.txt), draws the scenes the judge
 * sends and sends back what it drew (wire.h). It decides nothing: the
 * comparisons, the reference and the verdict are the judge's, in another
 * process. What the student's code prints goes to fd 1 and 2, the log. */
#define _POSIX_C_SOURCE 200809L

#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "exercise/wire.h"

void exercise_rasterize(const struct tri_setup *t, const struct raster_params *p,
                        struct target *fb, struct trace *tr);
/* lesson 06's: weak, as only its exercise has one */
__attribute__((weak)) void exercise_clip(struct poly *out, const struct poly *in, const struct plane *pl);

bool wire_send(int fd, uint32_t type, const void *a, size_t alen, const void *b, size_t blen)
{
    struct wire_header h = { type, (uint32_t)(alen + blen) };
    const void *part[3] = { &h, a, b };
    size_t len[3] = { sizeof h, alen, blen };
    for (int k = 0; k < 3; k++) {
        const char *p = part[k];
        for (size_t done = 0; done < len[k];) {
            ssize_t w = write(fd, p + done, len[k] - done);
            if (w <= 0)
                return false;
            done += (size_t)w;
        }
    }
    return true;
}

bool wire_read(int fd, void *buf, size_t n)
{
    char *p = buf;
    for (size_t done = 0; done < n;) {
        ssize_t r = read(fd, p + done, n - done);
        if (r <= 0)
            return false;
        done += (size_t)r;
    }
    return true;
}

static void send_event(void *ctx, const struct trace_event *ev)
{
    (void)ctx;
    /* with the texels read since the event before (lesson 09: per written pixel) */
    struct texel_reads r = *exercise_texel_reads();
    exercise_texel_reads_clear();
    if (!wire_send(WIRE_FD_OUT, WIRE_EVENT, ev, sizeof *ev, &r, sizeof r))
        _exit(0);   /* the judge is gone */
}

/* Has the judge asked to stop this scene? (a WIRE_STOP waiting) */
static bool stop_asked(void)
{
    struct pollfd p = { .fd = WIRE_FD_IN, .events = POLLIN };
    if (poll(&p, 1, 0) != 1)
        return false;
    struct wire_header h;
    return wire_read(WIRE_FD_IN, &h, sizeof h) && h.type == WIRE_STOP && h.len == 0;
}

/* The pixels of fb that differ from prev, as wire_pixel records into *buf
 * (their length returned; prev updated to fb). */
static size_t changed(struct target *fb, struct target *prev, char **buf, size_t *cap)
{
    int n = fb->samples ? fb->samples->n : 1;
    int pn = prev->samples ? prev->samples->n : 1;
    size_t rec = sizeof(struct wire_pixel) + (n > 1 ? (size_t)n * 8 : 0), len = 0;
    size_t npix = (size_t)fb->w * (size_t)fb->h;
    for (size_t i = 0; i < npix; i++) {
        bool diff = fb->color[i] != prev->color[i] || memcmp(&fb->depth[i], &prev->depth[i], sizeof(float))
                    || fb->count[i] != prev->count[i] || n != pn;
        if (!diff && n > 1)
            diff = memcmp(&fb->samples->color[i * (size_t)n], &prev->samples->color[i * (size_t)n], 4 * (size_t)n)
                   || memcmp(&fb->samples->depth[i * (size_t)n], &prev->samples->depth[i * (size_t)n], 4 * (size_t)n);
        if (!diff)
            continue;
        if (len + rec > *cap) {
            size_t c = *cap ? *cap * 2 : 1 << 16;
            char *b = realloc(*buf, c);
            if (!b)
                _exit(3);
            *buf = b, *cap = c;
        }
        struct wire_pixel px = { (uint32_t)i, fb->color[i], fb->depth[i], fb->count[i] };
        memcpy(*buf + len, &px, sizeof px);
        len += sizeof px;
        if (n > 1) {
            memcpy(*buf + len, &fb->samples->color[i * (size_t)n], 4 * (size_t)n);
            memcpy(*buf + len + 4 * (size_t)n, &fb->samples->depth[i * (size_t)n], 4 * (size_t)n);
            len += 8 * (size_t)n;
        }
    }
    if (n != pn && !(n > 1 ? target_multisample(prev, n) : target_multisample(prev, 1)))
        _exit(3);
    memcpy(prev->color, fb->color, npix * 4);
    memcpy(prev->depth, fb->depth, npix * 4);
    memcpy(prev->count, fb->count, npix);
    if (n > 1) {
        memcpy(prev->samples->color, fb->samples->color, npix * (size_t)n * 4);
        memcpy(prev->samples->depth, fb->samples->depth, npix * (size_t)n * 4);
    }
    return len;
}

static void draw(const struct wire_draw *d, const char *text)
{
    struct scene s;
    char err[512];
    static struct lesson L;
    L.exercise.write_line = d->write_line;
    L.exercise.clip = d->clip;
    exercise_use(&L, exercise_rasterize);
    if (d->clip && !exercise_clip) {
        fprintf(stderr, "lesson 06's exercise is the clipper, exercise_clip(): your file defines none\n");
        _exit(4);
    }
    if (d->clip)
        exercise_use_clip(exercise_clip);
    if (!scene_parse(&s, "judge.scene", text, strlen(text), err, sizeof err)) {
        wire_send(WIRE_FD_OUT, WIRE_DONE, NULL, 0, NULL, 0);
        return;
    }
    bool world = s.world.camera_line > 0;
    if (world) {
        exercise_clip_both_ways(d->both_ways);
        if (!exercise_front(&s))
            _exit(3);
        struct wire_projected pr = { s.ntris, s.world.ntris, *exercise_clip_fault() };
        size_t n = (size_t)s.ntris, nw = (size_t)s.world.ntris;
        size_t len = n * (sizeof(struct scene_tri) + sizeof(int)) + nw;
        char *b = malloc(len + 1);
        if (!b)
            _exit(3);
        memcpy(b, s.tris, n * sizeof(struct scene_tri));
        memcpy(b + n * sizeof(struct scene_tri), s.world.from, n * sizeof(int));
        for (size_t w = 0; w < nw; w++)
            b[n * (sizeof(struct scene_tri) + sizeof(int)) + w] = (char)exercise_clip_as_lesson((int)w);
        if (!wire_send(WIRE_FD_OUT, WIRE_PROJECTED, &pr, sizeof pr, b, len))
            _exit(0);
        free(b);
    }
    struct target fb = { 0 }, prev = { 0 };
    int samples = d->samples > 1 ? d->samples : 1;
    if (!target_init(&fb, s.w, s.h, scene_background(&s)) || !target_init(&prev, s.w, s.h, scene_background(&s))
        || (samples > 1 && (!target_multisample(&fb, samples) || !target_multisample(&prev, samples))))
        _exit(3);
    struct raster_params p = { .checker = d->checker, .subpixel_bits = d->subpixel_bits, .samples = d->samples };
    memcpy(p.knob, d->knob, sizeof p.knob);
    struct run_place at = { .scene = &s };
    if (world)
        p.at = &at;
    char *buf = NULL;
    size_t cap = 0;
    int end = d->first + d->count < s.ntris ? d->first + d->count : s.ntris;
    for (int i = d->first < 0 ? 0 : d->first; i < end && !stop_asked(); i++) {
        struct tri_setup t;
        tri_setup_bits(&t, s.tris[i].v, s.w, s.h, d->subpixel_bits);
        struct raster_params pi = lesson_params_tri(&p, &s, i);
        struct trace tr = { .sink = d->trace == WIRE_TRACE_EVENTS ? send_event : NULL };
        trace_begin(&tr, (uint32_t)i, TRACE_UNLIMITED);
        exercise_fault_clear();
        exercise_variant.rasterize(&t, &pi, &fb, d->trace == WIRE_TRACE_NONE ? NULL : &tr);
        size_t len = changed(&fb, &prev, &buf, &cap);
        size_t rec = sizeof(struct wire_pixel) + (fb.samples ? (size_t)fb.samples->n * 8 : 0);
        struct wire_tri w = { *exercise_fault(), *exercise_texel_fault(), tr.count, tr.c,
                              (uint32_t)(len / rec), fb.samples ? fb.samples->n : 1 };
        if (!wire_send(WIRE_FD_OUT, WIRE_TRI, &w, sizeof w, buf, len))
            _exit(0);
    }
    free(buf);
    target_free(&fb);
    target_free(&prev);
    scene_free(&s);
    wire_send(WIRE_FD_OUT, WIRE_DONE, NULL, 0, NULL, 0);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    wire_send(WIRE_FD_OUT, WIRE_HELLO, NULL, 0, NULL, 0);
    for (;;) {
        struct wire_header h;
        if (!wire_read(WIRE_FD_IN, &h, sizeof h))
            return 0;
        if (h.type == WIRE_STOP)
            continue;       /* a stop that came after the scene's end */
        struct wire_draw d;
        if (h.type != WIRE_DRAW || h.len < sizeof d || !wire_read(WIRE_FD_IN, &d, sizeof d)
            || h.len - sizeof d != d.text_len)
            return 2;
        char *text = malloc((size_t)d.text_len + 1);
        if (!text || !wire_read(WIRE_FD_IN, text, d.text_len))
            return 2;
        text[d.text_len] = '\0';
        draw(&d, text);
        free(text);
    }
}
