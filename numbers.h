// numbers.h -- the numbers and vectors rt computes with, and the lengths of vectors of any size.
//
// `real` is double, or float when built with -DRT_FLOAT (the ray_float program). Every header of
// rt includes this one, directly or through ray.h. Also here: the hash step MixWord that every
// random number starts from, and the exact powers of two with which SafeLength and SafeNormalize
// measure a vector of 1e-300 or 1e300 without squaring it out of range.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

// ---- numbers -------------------------------------------------------------------------------

#ifdef RT_FLOAT
typedef float real;
#else
typedef double real;
#endif

// No upper bound on a ray parameter.
const real kInfinity = std::numeric_limits<real>::infinity();

// pi, rounded to `real` (the path tracer's densities and areas).
const real kPi = real(3.14159265358979323846);

// Unit roundoff u: the largest relative error of one correctly rounded operation (half an ulp
// of 1). Every tolerance in rt is a multiple of u derived from an error bound, never a fixed
// distance in scene units, so the program behaves the same at any scene scale.
const real kUnitRoundoff = std::numeric_limits<real>::epsilon() * real(0.5);

// Gamma(n) = n u / (1 - n u) bounds the relative error of n chained floating-point operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", 2002, Lemma 3.1; pbrt-v4 §6.8.1).
inline real Gamma(int n) { return (n * kUnitRoundoff) / (1 - n * kUnitRoundoff); }

// One step of a counter-based hash: the word added to the state, then SplitMix64's finaliser
// (Steele, Lea & Flood, "Fast Splittable Pseudorandom Number Generators", OOPSLA 2014). Folding
// the numbers that name a sample (pixel, sample, bounce, ...) in turn gives random bits that
// depend on nothing else, so the image never depends on which thread drew them.
inline uint64_t MixWord(uint64_t z, uint64_t word) {
    z += word + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// ---- vectors -------------------------------------------------------------------------------

struct vec2 {
    real x, y;
};

struct vec3 {
    real x, y, z;
};

typedef vec3 color; // r, g, b in x, y, z; 1 is full intensity

inline vec3 operator+(vec3 a, vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline vec3 operator-(vec3 a, vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline vec3 operator-(vec3 a) { return {-a.x, -a.y, -a.z}; }
inline vec3 operator*(real s, vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline vec3 operator*(vec3 a, vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline real Dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline vec3 Cross(vec3 a, vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline real Length(vec3 a) { return std::sqrt(Dot(a, a)); }
inline vec3 Normalize(vec3 a) { return (1 / Length(a)) * a; }
inline vec3 Abs(vec3 a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
// a.x, a.y or a.z for axis 0, 1, 2
inline real Component(vec3 a, int axis) {
    const real c[3] = {a.x, a.y, a.z};
    return c[axis];
}
inline bool IsFinite(vec3 a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline real MaxComponent(vec3 a) { // of |a|, for finite a
    real m = std::fabs(a.x) > std::fabs(a.y) ? std::fabs(a.x) : std::fabs(a.y);
    return m > std::fabs(a.z) ? m : std::fabs(a.z);
}

// ---- exact rescaling by powers of two (lengths, the sphere test, rays: robust/) -------------
// Multiplying by a power of two changes only the exponent, so it is exact unless the result
// leaves the range of numbers. rt rescales any vector whose squares could overflow or underflow
// (a direction of 1e200 or 1e-200, a sphere of radius 1e-200) to a largest component in [1, 2),
// computes there, and scales the answer back: the same bits as unscaled arithmetic would give
// had it not overflowed.

// A real's bits as an unsigned integer of its size, and its exponent field (IEEE 754 binary64:
// 52 fraction bits and a bias of 1023; binary32 in the float build: 23 and 127).
using RealBits = std::conditional_t<sizeof(real) == 8, uint64_t, uint32_t>;
const int kFractionBits = std::numeric_limits<real>::digits - 1;
const int kExponentBias = std::numeric_limits<real>::max_exponent - 1;

// floor(log2 |x|) for finite x != 0: the exponent field, read directly (std::ilogb is a library
// call, and every search asks for it); subnormal x takes the library's path.
inline int BinaryExponent(real x) {
    RealBits bits;
    memcpy(&bits, &x, sizeof bits);
    int field = (int)((bits >> kFractionBits) & (2 * kExponentBias + 1));
    return field != 0 ? field - kExponentBias : std::ilogb(x);
}

// 2^k: the exponent field written directly when 2^k is a normal number, else the library's.
inline real PowerOfTwo(int k) {
    if (k < 1 - kExponentBias || k > kExponentBias)
        return std::ldexp(real(1), k);
    RealBits bits = (RealBits)(k + kExponentBias) << kFractionBits;
    real x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

// x * 2^k and v * 2^k for any k (in two exact steps when 2^k itself is out of range).
inline real ScaleByPowerOfTwo(real x, int k) {
    const int kMax = std::numeric_limits<real>::max_exponent - 1;
    if (k > -kMax && k < kMax)
        return PowerOfTwo(k) * x;
    return PowerOfTwo(k - k / 2) * (PowerOfTwo(k / 2) * x);
}
inline vec3 ScaleByPowerOfTwo(vec3 v, int k) {
    if (k == 0) // (most calls: nothing to rescale)
        return v;
    return {ScaleByPowerOfTwo(v.x, k), ScaleByPowerOfTwo(v.y, k), ScaleByPowerOfTwo(v.z, k)};
}

// Sizes inside these windows can be squared and multiplied together without leaving the normal
// range of `real`, so the shape tests rescale only what lies outside: a direction whose largest
// component is within 2^+-kDirectionWindow (2^+-64 in double, 2^+-8 in float), a radius or a
// distance from a sphere's centre within 2^+-kLengthWindow (2^+-256, 2^+-32).
const int kDirectionWindow = std::numeric_limits<real>::max_exponent / 16;
const int kLengthWindow = 4 * kDirectionWindow;
inline bool WithinWindow(real m, int window) {
    return m >= PowerOfTwo(-window) && m <= PowerOfTwo(window);
}

// Whether a ray's direction is searched for as it is: inside kDirectionWindow, where no shape test
// squares it out of range (else the search rescales it: SearchList, robust/'s ScaleRay).
inline bool SearchedAsIs(vec3 dir) { return WithinWindow(MaxComponent(dir), kDirectionWindow); }

// The power of two that brings v's largest component into [1, 2): v * 2^UnitExponent(v). 0 for
// a zero or non-finite v (nothing to rescale).
inline int UnitExponent(vec3 v) {
    real m = MaxComponent(v);
    return m > 0 && std::isfinite(m) ? -BinaryExponent(m) : 0;
}

// |v| for v of any finite size, by the same rescaling. Inside the direction window it is not
// needed, and it would change no bit: the largest component's square is a normal number, so the
// others' squares are exact multiples of their rescaled ones, or too small to round the sum.
inline real SafeLength(vec3 v) {
    if (WithinWindow(MaxComponent(v), kDirectionWindow))
        return Length(v);
    int k = UnitExponent(v);
    return ScaleByPowerOfTwo(Length(ScaleByPowerOfTwo(v, k)), -k);
}

// A unit vector in the direction of v, for v of any finite size (1e-300 or 1e300), by rescaling
// before squaring. The zero vector stays zero.
inline vec3 SafeNormalize(vec3 v) {
    vec3 w = ScaleByPowerOfTwo(v, UnitExponent(v));
    real length = Length(w);
    return length > 0 ? (1 / length) * w : w;
}
