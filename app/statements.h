// app/statements.h -- what the scene-file reader (scene_file.cpp) shares with the readers of its
// statements (statements.cpp): a statement as read, the checks of its values, and a reader for
// each statement that adds a shape, a light, a material, the camera or a mesh.
#pragma once
#include "app.h"

#include <cstddef>
#include <string>
#include <vector>

// A limit that keeps a hostile or mistaken file from exhausting memory, high enough for the
// scanned and exported models a mesh statement brings (a scanned statue of a million
// triangles). A triangle costs a few hundred bytes while a render is prepared (the Triangle, its
// block, its set-up and the BVH build's record: docs/speed.md), so 4 million shapes take under
// 2 GB at the peak: what a machine of 4 GB can still hold. (The files themselves are read a line
// at a time, and a line is at most kMaxLineLength long.)
const size_t kMaxObjects = 4000000; // shapes, lights and materials together

// One statement being read, for its handler and for error messages.
struct Statement {
    const char *file;
    int line;
    std::vector<std::string> tokens;
};

// "FILE:LINE: message" into *error, for the statement being read; false.
bool Fail(const Statement *st, const std::string &message, std::string *error);

// Reads `count` numbers from tokens[first...]; the statement must hold exactly `total` tokens.
bool Numbers(const Statement *st, size_t first, int count, size_t total, real *out,
             std::string *error);

// tokens[index] as a whole number in [lo, hi].
bool WholeNumber(const Statement *st, size_t index, int lo, int hi, int *out, std::string *error);

// A colour (diffuse, ambient, background), read from tokens[first...]: each component in [0, 1];
// the message shows the numbers as written.
bool CheckColor(const Statement *st, const std::string &what, size_t first, color c,
                std::string *error);

// The shapes, lights and materials the scene holds so far (against kMaxObjects).
size_t ObjectCount(const Scene *scene);

// One statement each, checked and added to the scene (docs/scene-format.md has their forms).
bool ReadSphere(const Statement *st, Scene *scene, std::string *error);
bool ReadTriangle(const Statement *st, Scene *scene, std::string *error);
bool ReadLight(const Statement *st, Scene *scene, std::string *error);
bool ReadMaterial(const Statement *st, Scene *scene, std::string *error);
bool ReadCamera(const Statement *st, Scene *scene, std::string *error);
bool ReadMesh(const Statement *st, Scene *scene, std::string *error);
