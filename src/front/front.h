/* front.h - the 3-D front end: the world triangles of a 3-D scene become the
 * screen-space triangles every lesson rasterizes (lessons/CONVENTIONS.md, "3-D scenes").
 *
 *   world --look-at--> view --clip d >= near, d <= far--> --project--> screen
 *         --guard band (only what reaches beyond [-16384, 16384))--> --fan, cull--> 2-D triangles
 *
 * Lesson 06's algorithm. Every stage is a function of its own, and
 * front_pipeline() runs them in that order, once for every program:
 * front_scene() silently for the screen triangles every lesson draws,
 * lesson 06 again, narrated, for the explorer's steps (at the lines of
 * enum front_line of its pseudo-code).
 */
#ifndef TRISTEP_FRONT_H
#define TRISTEP_FRONT_H

#include <stdbool.h>

#include "raster/raster.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* The lines of lesson 06's pseudo-code that the front end's steps are told
 * at (TRACE_FRONT events; lesson 06 adds the rasterizer's line after them). */
enum front_line {
    FRONT_LINE_EACH,        /* for each world triangle */
    FRONT_LINE_VIEW,        /* world -> view */
    FRONT_LINE_NEAR,        /* clip against d >= near */
    FRONT_LINE_FAR,         /* clip against d <= far */
    FRONT_LINE_PROJECT,     /* project */
    FRONT_LINE_GUARD,       /* the guard band */
    FRONT_LINE_FAN,         /* fan and cull */
    FRONT_LINES
};

/* A vertex of a polygon on its way through the pipeline. In view space pos
 * is (x_v, y_v, d), in screen space (x_s, y_s, d): d, the positive view
 * depth, is the vertex's z from projection on. */
struct pvert {
    double pos[3];
    double rgb[3];
    double st[2];       /* texture coordinates, clipped as the colour is */
};

/* A triangle grows by at most one vertex per plane it is clipped against:
 * 3 + 2 (near, far) + 4 (guard band) = 9. */
#define POLY_MAX 12

struct poly {
    int n;
    struct pvert v[POLY_MAX];
};

/* The camera made ready: gluLookAt's basis (f forward, s to the right, u up)
 * and the projection's constants, for a W x H framebuffer. */
struct frustum {
    double eye[3], s[3], u[3], f[3];
    double g;                    /* 1 / tan(fovy / 2) */
    double aspect;               /* W / H */
    double half_w, half_h;       /* W / 2, H / 2 */
    double near, far;
};

void frustum_init(struct frustum *v, const struct camera *c, int w, int h);

/* World to view space: q = p - eye, x_v = s.q, y_v = u.q, d = f.q. */
struct pvert view_vertex(const struct frustum *v, const double p[3], const double rgb[3]);

/* A clipping plane: keeps the vertices whose pos[axis] is >= at (keep = +1)
 * or <= at (keep = -1). Depth planes clip in view space, where every value
 * is linear along an edge; guard-band planes clip in screen space, where
 * 1/d and colour/d are (so the colours stay perspective-correct). */
enum plane_id { PLANE_NEAR, PLANE_FAR, PLANE_LEFT, PLANE_RIGHT, PLANE_TOP, PLANE_BOTTOM };

struct plane {
    enum plane_id id;
    const char *name;            /* "d >= near", "x >= -16384", ... */
    int axis;                    /* 0 x, 1 y, 2 d */
    double at;
    int keep;                    /* +1 or -1 */
    bool screen;                 /* clips in screen space */
};

struct plane depth_plane(const struct frustum *v, enum plane_id id);   /* PLANE_NEAR or PLANE_FAR */

/* The guard band: x >= -16384, x <= 16383, y >= -16384, y <= 16383, in this order. */
#define GUARD_BAND COORD_LIMIT
extern const struct plane guard_planes[4];

/* The canonical order of an edge's ends: is a before b, lexicographically
 * on the position? */
bool pvert_before(const struct pvert *a, const struct pvert *b);

/* Sutherland-Hodgman against one plane: walks the edges v[0] -> v[1], ...,
 * v[n-1] -> v[0]; a vertex inside is kept; an edge with one end strictly
 * inside and the other outside gets a new vertex, computed from the edge's
 * ends in canonical order, so that two triangles sharing the edge make the
 * very same vertex; its clipped coordinate is set to the plane exactly.
 * Told on tr (NULL: silent): the plane (FRONT_PLANE, x the plane's id, y the
 * vertices in), then each vertex kept or dropped and each vertex made
 * (FRONT_KEEP, FRONT_DROP, FRONT_NEW: x the plane's id, aux its position and,
 * for a new one, t). */
void clip_polygon(struct poly *out, const struct poly *in, const struct plane *pl,
                  struct trace *tr);
/* The same clipper on a polygon of the plane (pos[0], pos[1]; pos[2] 1):
 * what of p lies in x0 <= x <= x1, y0 <= y <= y1, in place. For the
 * explorer's drawings (lesson 06's views, lesson 09's footprints). */
void clip_polygon_rect(struct poly *p, double x0, double y0, double x1, double y1);

/* View to screen: x_s = W/2 (1 + g x_v / (a d)), y_s = H/2 (1 - g y_v / d). */
void project(const struct frustum *v, struct poly *p);

/* Does every vertex lie in [-16384, 16384) on both axes (then it is used as
 * it is)? If not, clip_guard_band clips against the four guard planes. */
bool in_guard_band(const struct poly *p);
void clip_guard_band(struct poly *p, struct trace *tr);

/* Snapped twice the signed area of a screen triangle, as the facing rule
 * reads it: (x1-x0)(y2-y0) - (x2-x0)(y1-y0) on the 1/256 grid; negative means
 * counter-clockwise to the viewer, front-facing. */
int64_t facing_area(const struct vertex v[3]);
bool culled(enum cull cull, const struct vertex v[3]);

/* The polygon as a fan from its first vertex, culled: writes at most
 * POLY_MAX - 2 triangles into out and returns how many (each told on tr:
 * FRONT_TRIANGLE, drawn or culled). */
int fan(const struct poly *p, enum cull cull, struct vertex out[][3], struct trace *tr);

/* A stage done another way: lesson 06's exhibits of the classic slips, and
 * its clipping in clip space, run the same pipeline with one stage
 * replaced. NULL members: the lesson's. */
struct front_way {
    /* clipping against d >= near, then d <= far (clip_polygon) */
    void (*clip)(struct poly *out, const struct poly *in, const struct plane *pl, struct trace *tr);
    /* near, far and the projection at once, from view space to the screen
     * (clipping in homogeneous clip space, as the APIs do) */
    void (*clip_project)(const struct frustum *v, struct poly *p);
    /* x and y after projection (the guard band) */
    void (*screen)(const struct frustum *v, struct poly *p);
};

/* The whole pipeline for one world triangle, in its order: view, near, far,
 * project, guard band, fan and cull. Writes at most POLY_MAX - 2 triangles
 * and returns how many. way NULL: the lesson's. tr NULL: silent; else every
 * step is told (TRACE_FRONT, at the lines of enum front_line), the first
 * being FRONT_WORLD, about world triangle tr->part. */
int front_pipeline(const struct frustum *v, enum cull cull, const struct world_tri *t,
                   const struct front_way *way, struct trace *tr, struct vertex out[][3]);

/* The lesson's pipeline, silent. */
int front_triangle(const struct frustum *v, enum cull cull, const struct world_tri *t,
                   struct vertex out[][3]);

/* A 3-D scene's screen triangles: replaces s->tris with what the pipeline
 * makes of s->world (and fills s->world.from). A 2-D scene is left as it is.
 * False only when out of memory. */
bool front_scene(struct scene *s);

/* The same with a stage done another way (lesson 06's exhibits of the
 * classic slips and its alternatives). */
bool front_scene_way(struct scene *s, const struct front_way *way);

/* The same with another pipeline for each world triangle (the exercise's,
 * around the student's clipper), writing at most POLY_MAX - 2 triangles. */
typedef int (*pipeline_fn)(const struct frustum *v, enum cull cull, const struct world_tri *t,
                           struct vertex out[][3]);
bool front_scene_with(struct scene *s, pipeline_fn pipeline);

/* Dragging a vertex of a 3-D scene (the explorer): the world vertex of the
 * world triangle that screen triangle i came from which projects to
 * (ox, oy) moves, at its own view depth, to where it projects to (x, y).
 * Every world vertex at the same place moves with it, so a closed mesh
 * stays closed. Returns false when none of them projects there (a vertex
 * made by the clipper): the world is left as it was. Run the front end
 * again afterwards. */
bool front_move_vertex(struct scene *s, int i, double ox, double oy, double x, double y);

#endif
