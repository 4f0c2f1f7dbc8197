/* Lesson 09, what the explorer adds (compiled only in the narrated build;
 * the algorithm is textures.c, the texture unit sampling.c).
 *
 * The watch panel tells what each step of a quad computed, from the
 * event's aux values (textures.h says which is which): the pixel's (u, v)
 * and whether it is a helper, the quad's derivatives, rho and lambda, and
 * the levels and weight the filter took. */
#include <stdio.h>

#include "lesson_explorer.h"
#include "textures.h"

extern const struct lesson lesson_09;

static const char *const filter_word[] = { "?", "nearest", "bilinear", "mip-bilinear", "trilinear",
                                           "aniso" };

static void watch(const struct tri_setup *t, const struct raster_params *p,
                  const struct trace_event *ev, char *buf, size_t n)
{
    (void)t, (void)p;
    buf[0] = '\0';
    if (ev->kind != TRACE_STEP)
        return;
    const float *a = ev->aux;
    switch (ev->line) {
    case L_EVAL:
        snprintf(buf, n, "%s (%d, %d): u %.4g, v %.4g (level-0 texels), 1/z %.4g\n",
                 (ev->flags & TRACE_INSIDE) ? "covered" : "helper (evaluated, never written)",
                 ev->x, ev->y, a[AUX_U], a[AUX_V], a[AUX_Q]);
        break;
    case L_LOD:
        if (!(ev->flags & TRACE_INSIDE)) {
            snprintf(buf, n, "a helper beyond the horizon: the last level, lambda %.4g\n",
                     a[AUX_LAMBDA]);
            break;
        }
        snprintf(buf, n, "du/dx %.4g, dv/dx %.4g\ndu/dy %.4g, dv/dy %.4g\nrho %.4g, lambda %.4g\n",
                 a[AUX_DUDX], a[AUX_DVDX], a[AUX_DUDY], a[AUX_DVDY], a[AUX_RHO], a[AUX_LAMBDA]);
        break;
    case L_FILTER: {
        int f = ev->mask[2] <= FILTER_ANISO ? ev->mask[2] : 0;
        snprintf(buf, n, "%s at u %.4g, v %.4g: lambda %.4g, levels %d and %d, mix %.4g, taps %d\n",
                 filter_word[f], a[AUX_U], a[AUX_V], a[AUX_USED_LAMBDA], (int)a[AUX_LEVEL0],
                 (int)a[AUX_LEVEL1], a[AUX_MIX], ev->mask[1]);
        break;
    }
    default:
        break;
    }
}

const struct lesson_explorer lesson_09_explorer = {
    .lesson = &lesson_09,
    .watch = watch,
};
