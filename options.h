// options.h -- the command line of the program (options.cpp), for ray.cpp.
#pragma once

#include "io.h"
#include "ray.h"

// What the command line asks for; zero or empty means "not given".
struct Options {
    std::string scene = "default", output;
    int width = 0, height = 0, spp = 1, depth = 0, threads = 0;
    int sampling = 0;  // --aa: grid, jitter, adaptive, in SampleMethod's order
    int methodSet = 0; // --methods: robust, handout
    int layout = 0;    // --layout: auto, list, bvh, in LayoutChoice's order
    int scatter = 0, lights = 0, roulette = 0; // --scatter, --lights, --roulette (shading
                                               // path): in ScatterMethod's, LightMethod's
                                               // order; on, off
    int seed = 0;                              // --seed (shading path)
    int sphere = -1, triangle = -1, selfHit = -1, cameraRay = -1, fresnel = -1; // -1: from the set
    real epsilon = 0; // --self-hit epsilon=E
    bool stats = false, help = false, version = false;
    bool probeRay = false, pixel = false, view = false, compare = false;
    real probe[6];
    int pixelX = 0, pixelY = 0;
    ViewKind viewKind = VIEW_NORMAL;
    std::string raysFile, compareA, compareB;
    double tolerance = 0;
};

extern const char *kVersion, *kUsage;

// Reads the command line into *opt; false with *error (one line) for anything not allowed:
// unknown options, missing or bad values, an option given twice, modes that do not go together.
bool ParseOptions(int argc, char **argv, Options *opt, std::string *error);

// The methods the options choose: the set (--methods), then each single-method option given.
Methods ChosenMethods(const Options *opt);
