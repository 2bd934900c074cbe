// tests/exercise.cpp -- one input through the scene reader, the renderer and the probe reader.
#include "exercise.h"

// Scenes larger than this are read but not rendered: the fuzzer should spend its time reading.
static const size_t kMaxShapesToRender = 64;

static bool RenderTiny(const Scene *scene, std::string *why) {
    RenderSettings settings = {4, 4, 1, scene->depth, 1, TRIANGLE_WATERTIGHT, false, {}, {}};
    PlanRender(scene, &settings);
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 4; i++) {
            RayStats stats = {0, 0, 0, 0, 0};
            color c = RenderPixel(scene, &settings, i, j, &stats);
            if (!IsFinite(c)) {
                *why = "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") is not finite";
                return false;
            }
        }
    }
    return true;
}

bool ExerciseSceneText(const std::string &text, std::string *why) {
    Scene scene;
    std::string error;
    if (!ParseSceneText(text, "fuzz.scene", &scene, &error)) {
        bool located = error.rfind("fuzz.scene:", 0) == 0 && error.find('\n') == std::string::npos;
        *why = "error without file and line: " + error;
        return located;
    }
    if (scene.spheres.size() + scene.triangles.size() <= kMaxShapesToRender &&
        !RenderTiny(&scene, why))
        return false;
    RenderSettings settings = {4, 4, 1, 1, 1, TRIANGLE_WATERTIGHT, false, {}, {}};
    PlanRender(&scene, &settings);
    for (size_t start = 0; start < text.size();) {
        size_t end = std::min(text.find('\n', start), text.size());
        Ray ray;
        bool blank = false;
        if (ParseProbeLine(text.substr(start, end - start), &ray, &blank, &error) && !blank)
            ProbeRayJson(&scene, &settings, &ray);
        start = end + 1;
    }
    return true;
}
