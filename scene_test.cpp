// scene_test.cpp -- rt's own test scene (`ray test`), as data.
//
// What the assignment scene does not show: two facing mirrors (one behind the eye) that reflect
// each other until the chain limit cuts them off, a partial mirror, two coloured lights casting two
// coloured shadows of each shape, and a checkered floor of 128 triangles whose shared edges must
// not leak (a crack would show as a black line).
#include "ray.h"

// A floor of n x n squares between corners (x0, z0) and (x1, z1) at height y, each square two
// triangles, alternating between two materials like a chessboard; normals point up.
static void AddCheckerFloor(Scene *scene, real x0, real z0, real x1, real z1, real y, int n,
                            int dark, int light) {
    for (int row = 0; row < n; row++) {
        for (int col = 0; col < n; col++) {
            real xa = x0 + (x1 - x0) * col / n, xb = x0 + (x1 - x0) * (col + 1) / n;
            real za = z0 + (z1 - z0) * row / n, zb = z0 + (z1 - z0) * (row + 1) / n;
            int material = (row + col) % 2 ? dark : light;
            vec3 p00 = {xa, y, za}, p10 = {xb, y, za}, p01 = {xa, y, zb}, p11 = {xb, y, zb};
            // wound so that (b - a) x (c - a) points up whichever way x and z run
            bool up = (x1 - x0) * (z0 - z1) > 0;
            scene->triangles.push_back({p00, up ? p11 : p01, up ? p01 : p11, material});
            scene->triangles.push_back({p00, up ? p10 : p11, up ? p11 : p10, material});
        }
    }
}

void BuildTestScene(Scene *scene) {
    InitScene(scene);
    enum { TINTED_MIRROR, MIRROR, GREEN, GOLD, SLATE, IVORY, ORANGE, PLUM, BRICK, TEAL };
    // name             diffuse             ambient             ks n  mirror ior
    scene->materials = {
        {"tinted_mirror", {0.6, 0.8, 0.9}, {0.6, 0.8, 0.9}, 0, 1, 0.85, 0, {0, 0, 0}},
        {"mirror", {1, 1, 1}, {1, 1, 1}, 0, 1, 1, 0, {0, 0, 0}},
        {"green", {0.2, 0.8, 0.3}, {0.2, 0.8, 0.3}, 0, 1, 0, 0, {0, 0, 0}},
        {"gold", {1, 0.8, 0.25}, {1, 0.8, 0.25}, 0, 1, 0.35, 0, {0, 0, 0}},
        {"slate", {0.25, 0.3, 0.4}, {0.25, 0.3, 0.4}, 0, 1, 0, 0, {0, 0, 0}},
        {"ivory", {0.95, 0.92, 0.85}, {0.95, 0.92, 0.85}, 0, 1, 0, 0, {0, 0, 0}},
        {"orange", {1, 0.5, 0.1}, {1, 0.5, 0.1}, 0, 1, 0, 0, {0, 0, 0}},
        {"plum", {0.6, 0.3, 0.7}, {0.6, 0.3, 0.7}, 0, 1, 0, 0, {0, 0, 0}},
        {"brick", {0.75, 0.35, 0.3}, {0.75, 0.35, 0.3}, 0, 1, 0, 0, {0, 0, 0}},
        {"teal", {0.2, 0.55, 0.6}, {0.2, 0.55, 0.6}, 0, 1, 0, 0, {0, 0, 0}},
    };
    // center              radius  material
    scene->spheres = {
        {{-1.5, -0.2, -9}, 0.8, GREEN},
        {{1.4, 0.1, -10.5}, 1.1, MIRROR},
        {{0.2, -0.65, -6.5}, 0.35, GOLD},
        {{2.2, -0.5, -6.8}, 0.5, PLUM},
    };
    AddCheckerFloor(scene, -4, 2, 4, -14, -1, 8, SLATE, IVORY);
    // a                  b                   c                 material
    const Triangle walls[] = {
        {{-4, -1, -14}, {4, -1, -14}, {4, 4, -14}, TINTED_MIRROR}, // back mirror
        {{-4, -1, -14}, {4, 4, -14}, {-4, 4, -14}, TINTED_MIRROR},
        {{-4, -1, 2}, {4, 4, 2}, {4, -1, 2}, TINTED_MIRROR}, // mirror behind the eye
        {{-4, -1, 2}, {-4, 4, 2}, {4, 4, 2}, TINTED_MIRROR},
        {{-4, -1, 2}, {-4, -1, -14}, {-4, 4, -14}, BRICK}, // left wall
        {{-4, -1, 2}, {-4, 4, -14}, {-4, 4, 2}, BRICK},
        {{4, -1, 2}, {4, 4, -14}, {4, -1, -14}, TEAL}, // right wall
        {{4, -1, 2}, {4, 4, 2}, {4, 4, -14}, TEAL},
        {{-2.6, -1, -5.6}, {-1.2, -1, -5.2}, {-1.7, 0.5, -6.4}, ORANGE}, // pyramid
        {{-1.2, -1, -5.2}, {-1.5, -1, -7.0}, {-1.7, 0.5, -6.4}, ORANGE},
        {{-1.5, -1, -7.0}, {-2.6, -1, -5.6}, {-1.7, 0.5, -6.4}, ORANGE},
    };
    scene->triangles.insert(scene->triangles.end(), std::begin(walls), std::end(walls));
    // position          intensity
    scene->lights = {
        {{-2.5, 3.5, -4}, {0.8, 0.75, 0.65}},
        {{2.5, 3, -8}, {0.45, 0.5, 0.7}},
    };
    // eye           distance width  pixels
    scene->camera.perspective = {{0, 0.8, 0}, 1.4, 2, 512, 512};
}
