/* builtin.c - the built-in scenes: their text, parsed by the same parser as
 * files (scene_builtin in scene.c). */
#include "scene.h"

#include <string.h>

const struct builtin_scene builtin_scenes[] = {
    { "triangle", "one Gouraud-shaded triangle, vertices off the pixel centres",
        "# one triangle: A red, B green, C blue\n"
        "size 32 24\n"
        "background 0.08 0.08 0.1\n"
        "tri  4.3 2.6 1  0.95 0.2 0.15   28.7 9.2 1  0.2 0.85 0.3   11.5 21.4 1  0.2 0.35 0.95\n"
    },
    { "shared-edge", "two triangles sharing a diagonal through pixel centres",
        "# two triangles sharing the diagonal from (1.5, 1.5) to (13.5, 13.5):\n"
        "# every edge passes through pixel centres, so the fill rule decides them\n"
        "size 16 16\n"
        "tri  1.5 1.5 1  1 0.55 0.1   13.5 1.5 1  1 0.55 0.1   13.5 13.5 1  1 0.55 0.1\n"
        "tri  1.5 1.5 1  0.2 0.5 1    13.5 13.5 1  0.2 0.5 1   1.5 13.5 1  0.2 0.5 1\n"
    },
    { "fan", "eight triangles around a vertex on a pixel centre",
        "# a fan of eight triangles around (16.5, 12.5); every vertex is a pixel centre\n"
        "size 33 25\n"
        "background 0.08 0.08 0.1\n"
        "tri  16.5 12.5 1  1 1 1  27.5 12.5 1  1 0.3 0.3  24.5 4.5 1  1 0.7 0.2\n"
        "tri  16.5 12.5 1  1 1 1  24.5 4.5 1  1 0.7 0.2  16.5 1.5 1  0.8 1 0.2\n"
        "tri  16.5 12.5 1  1 1 1  16.5 1.5 1  0.8 1 0.2  8.5 4.5 1  0.3 1 0.4\n"
        "tri  16.5 12.5 1  1 1 1  8.5 4.5 1  0.3 1 0.4  5.5 12.5 1  0.2 0.9 0.9\n"
        "tri  16.5 12.5 1  1 1 1  5.5 12.5 1  0.2 0.9 0.9  8.5 20.5 1  0.3 0.5 1\n"
        "tri  16.5 12.5 1  1 1 1  8.5 20.5 1  0.3 0.5 1  16.5 23.5 1  0.6 0.3 1\n"
        "tri  16.5 12.5 1  1 1 1  16.5 23.5 1  0.6 0.3 1  24.5 20.5 1  1 0.3 0.8\n"
        "tri  16.5 12.5 1  1 1 1  24.5 20.5 1  1 0.3 0.8  27.5 12.5 1  1 0.3 0.3\n"
    },
    { "overlap", "two triangles crossing in depth",
        "# two triangles crossing in depth: nearer (smaller z) wins\n"
        "size 32 24\n"
        "background 0.08 0.08 0.1\n"
        "tri  2 3 1    1 0.3 0.2   30 6 4    1 0.6 0.2   8 22 1   1 0.4 0.3\n"
        "tri  4 20 4   0.2 0.4 1   29 2 1    0.3 0.8 1   26 22 2  0.2 0.6 0.9\n"
    },
    { "mesh", "a jittered grid mesh of 40 triangles",
        "# a 5 x 4 grid of quads, inner vertices jittered by quarter pixels\n"
        "size 49 32\n"
        "background 0.08 0.08 0.1\n"
        "tri  2 2 1  0.25 0.3 0.9  10.75 2 1  0.39 0.3 0.78  9.75 9.5 1  0.39 0.45 0.78\n"
        "tri  2 2 1  0.25 0.3 0.9  9.75 9.5 1  0.39 0.45 0.78  2 7.5 1  0.25 0.45 0.9\n"
        "tri  10.75 2 1  0.39 0.3 0.78  19 2 1  0.53 0.3 0.66  9.75 9.5 1  0.39 0.45 0.78\n"
        "tri  19 2 1  0.53 0.3 0.66  18.75 8.75 1  0.53 0.45 0.66  9.75 9.5 1  0.39 0.45 0.78\n"
        "tri  19 2 1  0.53 0.3 0.66  29 2 1  0.67 0.3 0.54  29.75 7.5 1  0.67 0.45 0.54\n"
        "tri  19 2 1  0.53 0.3 0.66  29.75 7.5 1  0.67 0.45 0.54  18.75 8.75 1  0.53 0.45 0.66\n"
        "tri  29 2 1  0.67 0.3 0.54  39 2 1  0.81 0.3 0.42  29.75 7.5 1  0.67 0.45 0.54\n"
        "tri  39 2 1  0.81 0.3 0.42  38.5 8.25 1  0.81 0.45 0.42  29.75 7.5 1  0.67 0.45 0.54\n"
        "tri  39 2 1  0.81 0.3 0.42  47 2 1  0.95 0.3 0.3  47 7.5 1  0.95 0.45 0.3\n"
        "tri  39 2 1  0.81 0.3 0.42  47 7.5 1  0.95 0.45 0.3  38.5 8.25 1  0.81 0.45 0.42\n"
        "tri  2 7.5 1  0.25 0.45 0.9  9.75 9.5 1  0.39 0.45 0.78  2 14.75 1  0.25 0.6 0.9\n"
        "tri  9.75 9.5 1  0.39 0.45 0.78  11 16 1  0.39 0.6 0.78  2 14.75 1  0.25 0.6 0.9\n"
        "tri  9.75 9.5 1  0.39 0.45 0.78  18.75 8.75 1  0.53 0.45 0.66  18.75 15.25 1  0.53 0.6 0.66\n"
        "tri  9.75 9.5 1  0.39 0.45 0.78  18.75 15.25 1  0.53 0.6 0.66  11 16 1  0.39 0.6 0.78\n"
        "tri  18.75 8.75 1  0.53 0.45 0.66  29.75 7.5 1  0.67 0.45 0.54  18.75 15.25 1  0.53 0.6 0.66\n"
        "tri  29.75 7.5 1  0.67 0.45 0.54  27.75 16.5 1  0.67 0.6 0.54  18.75 15.25 1  0.53 0.6 0.66\n"
        "tri  29.75 7.5 1  0.67 0.45 0.54  38.5 8.25 1  0.81 0.45 0.42  38 14.5 1  0.81 0.6 0.42\n"
        "tri  29.75 7.5 1  0.67 0.45 0.54  38 14.5 1  0.81 0.6 0.42  27.75 16.5 1  0.67 0.6 0.54\n"
        "tri  38.5 8.25 1  0.81 0.45 0.42  47 7.5 1  0.95 0.45 0.3  38 14.5 1  0.81 0.6 0.42\n"
        "tri  47 7.5 1  0.95 0.45 0.3  47 16.75 1  0.95 0.6 0.3  38 14.5 1  0.81 0.6 0.42\n"
        "tri  2 14.75 1  0.25 0.6 0.9  11 16 1  0.39 0.6 0.78  10.25 24 1  0.39 0.75 0.78\n"
        "tri  2 14.75 1  0.25 0.6 0.9  10.25 24 1  0.39 0.75 0.78  2 21.75 1  0.25 0.75 0.9\n"
        "tri  11 16 1  0.39 0.6 0.78  18.75 15.25 1  0.53 0.6 0.66  10.25 24 1  0.39 0.75 0.78\n"
        "tri  18.75 15.25 1  0.53 0.6 0.66  21 23.75 1  0.53 0.75 0.66  10.25 24 1  0.39 0.75 0.78\n"
        "tri  18.75 15.25 1  0.53 0.6 0.66  27.75 16.5 1  0.67 0.6 0.54  27.5 23.75 1  0.67 0.75 0.54\n"
        "tri  18.75 15.25 1  0.53 0.6 0.66  27.5 23.75 1  0.67 0.75 0.54  21 23.75 1  0.53 0.75 0.66\n"
        "tri  27.75 16.5 1  0.67 0.6 0.54  38 14.5 1  0.81 0.6 0.42  27.5 23.75 1  0.67 0.75 0.54\n"
        "tri  38 14.5 1  0.81 0.6 0.42  38.75 23 1  0.81 0.75 0.42  27.5 23.75 1  0.67 0.75 0.54\n"
        "tri  38 14.5 1  0.81 0.6 0.42  47 16.75 1  0.95 0.6 0.3  47 21.5 1  0.95 0.75 0.3\n"
        "tri  38 14.5 1  0.81 0.6 0.42  47 21.5 1  0.95 0.75 0.3  38.75 23 1  0.81 0.75 0.42\n"
        "tri  2 21.75 1  0.25 0.75 0.9  10.25 24 1  0.39 0.75 0.78  2 30 1  0.25 0.9 0.9\n"
        "tri  10.25 24 1  0.39 0.75 0.78  10.25 30 1  0.39 0.9 0.78  2 30 1  0.25 0.9 0.9\n"
        "tri  10.25 24 1  0.39 0.75 0.78  21 23.75 1  0.53 0.75 0.66  18.5 30 1  0.53 0.9 0.66\n"
        "tri  10.25 24 1  0.39 0.75 0.78  18.5 30 1  0.53 0.9 0.66  10.25 30 1  0.39 0.9 0.78\n"
        "tri  21 23.75 1  0.53 0.75 0.66  27.5 23.75 1  0.67 0.75 0.54  18.5 30 1  0.53 0.9 0.66\n"
        "tri  27.5 23.75 1  0.67 0.75 0.54  29.5 30 1  0.67 0.9 0.54  18.5 30 1  0.53 0.9 0.66\n"
        "tri  27.5 23.75 1  0.67 0.75 0.54  38.75 23 1  0.81 0.75 0.42  37 30 1  0.81 0.9 0.42\n"
        "tri  27.5 23.75 1  0.67 0.75 0.54  37 30 1  0.81 0.9 0.42  29.5 30 1  0.67 0.9 0.54\n"
        "tri  38.75 23 1  0.81 0.75 0.42  47 21.5 1  0.95 0.75 0.3  37 30 1  0.81 0.9 0.42\n"
        "tri  47 21.5 1  0.95 0.75 0.3  47 30 1  0.95 0.9 0.3  37 30 1  0.81 0.9 0.42\n"
    },
    { "edge-steps", "one triangle small enough to read every edge value as it is stepped",
        "# lesson 03's triangle: A red, B green, C blue, vertices off the pixel centres\n"
        "size 20 14\n"
        "background 0.08 0.08 0.1\n"
        "tri  2.3 1.6 1  0.95 0.2 0.15   18.6 5.2 2  0.2 0.85 0.3   6.4 12.7 1.5  0.2 0.35 0.95\n"
    },
    { "float-drift", "two large triangles sharing an edge through pixel centres, for float stepping",
        "# edges AB and BC pass through a pixel centre every few pixels; exact stepping\n"
        "# leaves those centres to one triangle (top-left rule), single-precision\n"
        "# float stepping rounds the rule's -1 away and draws them twice\n"
        "size 256 192\n"
        "background 0.08 0.08 0.1\n"
        "tri  2.5 3.5 1  1 0.55 0.1   250.5 65.5 1  1 0.75 0.2   50.5 185.5 1  0.9 0.4 0.1\n"
        "tri  250.5 65.5 1  0.2 0.5 1   253.5 188.5 1  0.3 0.7 1   50.5 185.5 1  0.2 0.4 0.9\n"
    },
    { "floor", "a receding textured floor of two triangles (lesson 04)",
        "# a floor seen from height 1 by a camera of focal length 32 px, horizon at y = 2:\n"
        "# the floor point (X, Z) appears at x = 32 + 32 X / Z, y = 2 + 32 / Z.\n"
        "# Corners X = -1, +1 at Z = 1 (near) and Z = 8 (far); s = (X + 1) / 2, t = (Z - 1) / 7\n"
        "size 64 40\n"
        "background 0.08 0.08 0.1\n"
        "texture checker 8\n"
        "tri  0 34 1  0.95 0.85 0.6 0 0   64 34 1  0.95 0.85 0.6 1 0   36 6 8  0.6 0.75 0.95 1 1\n"
        "tri  0 34 1  0.95 0.85 0.6 0 0   36 6 8  0.6 0.75 0.95 1 1   28 6 8  0.6 0.75 0.95 0 1\n"
    },
    { "cases-a-b", "seed 002's two cases side by side: middle vertex left [A], right [B]",
        "# left: case [A], the middle vertex lies left of the long edge 1-2;\n"
        "# right: case [B], the middle vertex lies right of the long edge 1-3.\n"
        "# Vertices off the pixel centres, so every edge needs its prestep.\n"
        "size 40 24\n"
        "background 0.08 0.08 0.1\n"
        "tri  10.3 2.6 1  0.95 0.2 0.15   14.6 21.4 2  0.2 0.35 0.95   3.2 12.7 1.5  0.2 0.85 0.3\n"
        "tri  26.2 2.3 1  0.95 0.2 0.15   37.4 9.8 1.5  0.2 0.85 0.3   24.7 21.6 2  0.2 0.35 0.95\n"
    },
    { "offgrid-strip", "twelve triangles sharing edges, vertices off the pixel grid",
        "# a 3 x 2 strip of quads, two triangles each, no vertex on a pixel centre\n"
        "# or a pixel corner: walking an edge from its vertex without a prestep\n"
        "# samples it at the wrong height, and neighbours disagree on their seams\n"
        "size 32 20\n"
        "background 0.08 0.08 0.1\n"
        "tri  1.4 1.6 1  1 0.55 0.1   11.3 1.6 1  1 0.55 0.1   10.6 8.7 1  1 0.55 0.1\n"
        "tri  1.4 1.6 1  0.2 0.5 1   10.6 8.7 1  0.2 0.5 1   1.4 10.2 1  0.2 0.5 1\n"
        "tri  11.3 1.6 1  0.95 0.75 0.2   20.7 1.6 1  0.95 0.75 0.2   10.6 8.7 1  0.95 0.75 0.2\n"
        "tri  20.7 1.6 1  0.3 0.75 0.95   21.2 9.8 1  0.3 0.75 0.95   10.6 8.7 1  0.3 0.75 0.95\n"
        "tri  20.7 1.6 1  1 0.55 0.1   30.6 1.6 1  1 0.55 0.1   30.6 10.6 1  1 0.55 0.1\n"
        "tri  20.7 1.6 1  0.2 0.5 1   30.6 10.6 1  0.2 0.5 1   21.2 9.8 1  0.2 0.5 1\n"
        "tri  1.4 10.2 1  0.95 0.75 0.2   10.6 8.7 1  0.95 0.75 0.2   11.7 18.4 1  0.95 0.75 0.2\n"
        "tri  1.4 10.2 1  0.3 0.75 0.95   11.7 18.4 1  0.3 0.75 0.95   1.4 18.4 1  0.3 0.75 0.95\n"
        "tri  10.6 8.7 1  1 0.55 0.1   21.2 9.8 1  1 0.55 0.1   11.7 18.4 1  1 0.55 0.1\n"
        "tri  21.2 9.8 1  0.2 0.5 1   19.6 18.4 1  0.2 0.5 1   11.7 18.4 1  0.2 0.5 1\n"
        "tri  21.2 9.8 1  0.95 0.75 0.2   30.6 10.6 1  0.95 0.75 0.2   30.6 18.4 1  0.95 0.75 0.2\n"
        "tri  21.2 9.8 1  0.3 0.75 0.95   30.6 18.4 1  0.3 0.75 0.95   19.6 18.4 1  0.3 0.75 0.95\n"
    },
    { "blocks", "one triangle over a grid of 8 x 8 blocks: empty, full and partial (lesson 05)",
        "# one triangle of about 1,100 pixels: its box holds 48 blocks of 8 x 8,\n"
        "# some outside an edge (empty), some inside all three (full), the rest\n"
        "# crossed by an edge (partial). Depths differ, so colour is perspective-correct.\n"
        "size 64 48\n"
        "background 0.08 0.08 0.1\n"
        "tri  3.3 5.6 1.2  0.95 0.2 0.15   60.2 12.4 3  0.2 0.85 0.3   22.7 45.1 2  0.2 0.35 0.95\n"
    },
    { "blocks-exhibits", "a small triangle inside one block, a sliver and a wide triangle (lesson 05 exhibits)",
        "# what block classification by corners can get wrong:\n"
        "# a small triangle none of whose box corners it contains,\n"
        "# a sliver passing between the corners of the blocks it crosses,\n"
        "# and a wide triangle whose blocks are often inside one edge only\n"
        "size 64 48\n"
        "background 0.08 0.08 0.1\n"
        "tri  11.3 14.55 1  1 0.85 0.2   9.55 9.55 1  1 0.85 0.2   14.55 9.3 1  1 0.85 0.2\n"
        "tri  18.3 2.2 1  0.3 0.9 1   61.6 21.7 1  0.3 0.9 1   61.4 22.6 1  0.3 0.9 1\n"
        "tri  2.6 22.4 1  1 0.4 0.3   40.3 28.2 2  0.9 0.6 0.3   12.2 46.5 1.5  1 0.5 0.6\n"
    },
};

const int builtin_scene_count = (int)(sizeof builtin_scenes / sizeof builtin_scenes[0]);

const struct builtin_scene *builtin_find(const char *name)
{
    for (int i = 0; i < builtin_scene_count; i++)
        if (strcmp(builtin_scenes[i].name, name) == 0)
            return &builtin_scenes[i];
    return NULL;
}
