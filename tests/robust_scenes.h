// tests/robust_scenes.h -- the scenes of rt's robustness claims, shared by the tests (which
// assert them) and `make bench` (which measures the table in docs/bench/robustness.md).
#ifndef RT_ROBUST_SCENES_H
#define RT_ROBUST_SCENES_H

#include "../ray.h"

#include <string>

// p turned by 0.7 radians about the axis (1, 2, 3) when `turn`, computed in long double and
// rounded once: the corners of a turned shape are no longer on the grid of the unturned one.
vec3 Turn(vec3 p, bool turn);

// An empty scene with one white matte material, "wall".
Scene WallScene();

// The lengths L of the closed boxes the robustness tables claim, k = 0, 1, 2: 1e2, 1e8 and 1e12
// (float: 1e2, 1e3 and 1e4).
double ClaimedBoxLength(int k);

// A closed box [-2, 2] x [-1.5, 1.5] x [-L/2, L/2] of 12 triangles, two per face, faces in order
// (triangles 2f and 2f + 1 make face f), turned or not.
Scene BoxScene(double length, bool turn);

// The two triangles (a, c, b) and (a, d, c) of the floor y = 0 of half-size `half`, turned or
// not; *corners gets a, b, c, d.
Scene FloorScene(real half, bool turn, vec3 corners[4]);

// What `rays` random rays from random points inside BoxScene(length, turn) do: how many escape,
// how many of their mirror rays (from the wall they meet) escape, and how many mirror rays meet
// the face they left, which a convex box never allows. Deterministic for a given seed.
struct BoxLeaks {
    int escapes, mirrorEscapes, reHits;
};
BoxLeaks CountBoxLeaks(double length, bool turn, int rays, uint64_t seed);

// A uniformly random unit direction from two uniform numbers in [0, 1).
vec3 UnitDirection(real u1, real u2);

// The assignment scene as scene-file text at 64 x 64: every length times `scale`, moved by
// `shift` along (1, -1, 1), seen by a camera of kind `camera` (perspective, screen or lookat);
// `glass` makes the big sphere glass of index 1.5.
std::string AssignmentText(double scale, double shift, const char *camera, bool glass);

// A scene with every position and length (of shapes, lights and a perspective camera) multiplied
// by `scale`, then moved by `shift`.
Scene TransformedScene(const Scene &original, real scale, vec3 shift);

// A closed, watertight sphere of 8 * 4^level triangles (a subdivided octahedron, corners
// pushed out to radius r) around c, added to the scene with material 0: rays aimed at its corners
// and edge midpoints meet shared edges and corners, where ties between triangles are decided by
// their order in the scene.
void AddOctasphere(Scene *scene, vec3 c, real r, int level);

// ---- closed meshes seen from inside: the leak detector ----------------------------------------

// A camera at `eye` looking along `view` (lookat, 100 degrees), size x size pixels, a green
// background, ambient 0, 100 rays a chain; material 0, "wall": white diffuse under
// `shading path` (no lamp: no light at all), or a perfect mirror under `shading floor`; material
// 1, glass of index 1.5. Inside a closed mesh of walls every pixel is black; a pixel with green
// in it is a ray that got out.
Scene LeakScene(bool mirrorWalls, vec3 eye, vec3 view, int size);

// "rotate x X rotate y Y rotate z Z", the angles in degrees, to 17 digits.
std::string TurnWords(double x, double y, double z);

// The box [-w/2, w/2] x [-h/2, h/2] x [-l/2, l/2] as `mesh` makes it from an OBJ file of its 8
// corners (x, then y, then z) and 6 quads, each a fan of two triangles, moved by the transform
// words (as after `mesh FILE MATERIAL`); false where the words are refused.
bool AddMeshBox(Scene *scene, double w, double h, double l, const std::string &words);

// A prism of length l along z whose cross-section is a triangle with a corner of `degrees` and
// two sides of 10 from it, its centroid at the origin, then moved by the words; 8 triangles.
bool AddPrism(Scene *scene, double degrees, double l, const std::string &words);

// The pixels with any green in the scene's image at one sample (seed: the path tracer's).
int PixelsThatSeeOut(const Scene *scene, int seed);

// ---- smooth meshes ---------------------------------------------------------------------------

// An icosphere of radius 1 at the origin, 20 * 4^level triangles, with the true sphere's normals
// at its vertices (`vn`), as OBJ text.
std::string IcosphereObj(int level);

// The OBJ text `obj` as the `mesh` statement reads it, with material 0 and the statement's words
// (transform words, `smooth`, `flat`), into the scene: its triangles, and its corner normals where
// it is smooth. The file is written as dir/mesh.obj. False with *error where it is refused.
bool AddMeshText(Scene *scene, const std::string &dir, const std::string &obj,
                 const std::string &words, std::string *error);

#endif
