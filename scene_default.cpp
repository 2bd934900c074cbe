// scene_default.cpp -- the scene every scene starts from (InitScene), and the assignment scene (the
// handout's scene; scenes/reference.scene holds it as a file), as data.
//
// 512 x 512, the handout's Perspective camera at the origin (screen 2 units wide, 2 away), one
// white point light, ambient floor 0.2, black background, at most 10 rays in a chain: two mirror
// spheres and a red one in a box of a blue back wall, a white floor and a red right wall.
#include "ray.h"

void InitScene(Scene *scene) {
    *scene = Scene();
    scene->width = scene->height = 512;
    scene->camera = Camera();
    scene->camera.kind = CAMERA_PERSPECTIVE;
    scene->camera.perspective = {{0, 0, 0}, 2, 2, 512, 512};
    scene->shading = SHADING_FLOOR;
    scene->ambientLight = real(0.2);
    scene->background = {0, 0, 0};
    scene->depth = 10;
}

void BuildDefaultScene(Scene *scene) {
    InitScene(scene); // 512 x 512, camera perspective 0 0 0 2 2, ambient 0.2, floor, depth 10
    enum { MIRROR, RED, BLUE, WHITE };
    // name      diffuse     ambient     ks n  mirror ior emit
    scene->materials = {
        {"mirror", {1, 1, 1}, {1, 1, 1}, 0, 1, 1, 0, {0, 0, 0}},
        {"red", {1, 0, 0}, {1, 0, 0}, 0, 1, 0, 0, {0, 0, 0}},
        {"blue", {0, 0, 1}, {0, 0, 1}, 0, 1, 0, 0, {0, 0, 0}},
        {"white", {1, 1, 1}, {1, 1, 1}, 0, 1, 0, 0, {0, 0, 0}},
    };
    // center          radius  material
    scene->spheres = {
        {{0, 0, -16}, 2, MIRROR},
        {{3, -1, -14}, 1, MIRROR},
        {{-3, -1, -14}, 1, RED},
    };
    // a              b              c               material
    scene->triangles = {
        {{-8, -2, -20}, {8, -2, -20}, {8, 10, -20}, BLUE},   // back wall
        {{-8, -2, -20}, {8, 10, -20}, {-8, 10, -20}, BLUE},  // back wall
        {{-8, -2, -20}, {8, -2, -10}, {8, -2, -20}, WHITE},  // floor
        {{-8, -2, -20}, {-8, -2, -10}, {8, -2, -10}, WHITE}, // floor
        {{8, -2, -20}, {8, -2, -10}, {8, 10, -20}, RED},     // right wall
    };
    // position      intensity
    scene->lights = {
        {{3, 5, -15}, {1, 1, 1}},
    };
}
