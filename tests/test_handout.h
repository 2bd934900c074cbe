// tests/test_handout.h -- what the two files of the handouts' checks share (test_handout.cpp, the
// rays and shapes; test_handout_light.cpp, the light).
#pragma once
#include "test.h"

// One check: `should` is the prediction worked out by hand, `got` what came out, `cause` the
// likely mistake (TestAdvice: rt's harness prints all three; a kit's may blame an earlier step).
#define ADVISE(ok, should, got, cause) TestAdvice((ok), __FILE__, __LINE__, (should), (got), (cause))

std::string Num(double x);
std::string Vec(vec3 v);
bool Near(double a, double b);
bool Near(vec3 a, vec3 b);
std::string Found(bool hit, real t); // "you report t = 4", or "you report no hit"
Material Plain(color kd);            // a matte material of diffuse (and ambient) colour kd

// The groups of test_handout_light.cpp.
void TestShadow();
void TestFloor();
void TestReflect();
void TestDepth();
void TestPhong();
void TestRefraction();
void TestClamp();
