// tests/exercise.cpp -- one input through the scene reader, the renderer and the probe reader.
#include "exercise.h"
#include "../app/app.h"

// Scenes larger than this are read but not rendered: the fuzzer should spend its time reading.
static const size_t kMaxShapesToRender = 64;

// Every ray of the tree and every hit must be finite numbers, and so must the colour.
static bool TreeIsFinite(const std::vector<RayNode> &tree, std::string *why) {
    for (const RayNode &n : tree) {
        bool ok = IsFinite(n.ray.origin) && IsFinite(n.ray.dir) && IsFinite(n.light) &&
                  (!n.found || (IsFinite(n.record.point) && IsFinite(n.record.normal) &&
                                std::isfinite(n.record.t)));
        if (!ok) {
            *why = "a ray of kind " + std::to_string(n.kind) + " or its hit is not finite";
            return false;
        }
    }
    return true;
}

// Renders 4 x 4 pixels, each as a recorded ray tree, and checks every number in it.
static bool RenderTiny(const Scene *scene, std::string *why) {
    RenderSettings settings = {4,  4,  1, SAMPLES_GRID, scene->depth, 1, kRobustMethods, nullptr,
                               {}, {}, {}};
    PlanRender(scene, &settings);
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 4; i++) {
            std::vector<RayNode> tree;
            TraceLog log = {RayStats{}, &tree, -1, 0};
            Ray ray;
            GetCameraRay(&settings.camera, 4, 4, SamplePosition(i, j, 0, 1), &ray);
            TraceRay(scene, &settings, RAY_PRIMARY, &ray, &kNoSelfHit, RayChain{1, 1}, &log);
            if (!TreeIsFinite(tree, why)) {
                *why = "pixel (" + std::to_string(i) + ", " + std::to_string(j) + "): " + *why;
                return false;
            }
        }
    }
    return true;
}

// An error "FILE:LINE: message" of any file: a mesh file that a `mesh` statement names.
static bool InSomeFile(const std::string &error) {
    for (size_t k = 1; k < error.size(); k++) {
        size_t end = error.find_first_not_of("0123456789", k + 1);
        if (error[k] == ':' && end != std::string::npos && end > k + 1 &&
            error.compare(end, 2, ": ") == 0)
            return true;
    }
    return false;
}

bool ExerciseSceneText(const std::string &text, std::string *why) {
    Scene scene;
    std::string error;
    if (!ParseSceneText(text, "fuzz.scene", &scene, &error)) {
        bool located = (error.rfind("fuzz.scene:", 0) == 0 ||
                        (text.find("mesh") != std::string::npos && InSomeFile(error))) &&
                       error.find('\n') == std::string::npos;
        *why = "error without file and line: " + error;
        return located;
    }
    if (scene.spheres.size() + scene.triangles.size() <= kMaxShapesToRender &&
        !RenderTiny(&scene, why))
        return false;
    RenderSettings settings = {4, 4, 1, SAMPLES_GRID, 1, 1, kRobustMethods, nullptr, {}, {}, {}};
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
