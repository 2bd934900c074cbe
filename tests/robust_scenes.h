// tests/robust_scenes.h -- the scenes of rt's robustness claims, shared by the tests (which
// assert them) and `make bench` (which measures the table in docs/robustness.md).
#ifndef RT_ROBUST_SCENES_H
#define RT_ROBUST_SCENES_H

#include "../ray.h"

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

#endif
