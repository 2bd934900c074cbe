// robust/rescale.cpp -- rays whose direction is too large or too small to square, rescaled.
//
// A shape test squares and divides the ray's direction (d.d, the shear d[kx] / d[kz]): a
// direction of 1e-200 or 1e200 leaves the range of numbers there. The search therefore multiplies
// such a direction by a power of two that brings its largest component into [1, 2), which is
// exact, searches along it, and multiplies the t it finds back. Every t' in the scaled interval
// comes back inside the caller's (tMin, tMax), so no shape found there is refused on the way back.
// ScaleRay, ScaledRay and ScaleBack are in robust.h; this file holds the rare part, for a
// direction outside the window.
#include "robust.h"

// Where ScaledInterval cuts the search at one end of the interval, `end`, whose next number
// inward is `inward`. Where scaling back rounds (k < 0 and t below the normal numbers), a t'
// past halfway between end 2^-k and inward 2^-k comes back as `inward` (rounding to nearest)
// and one short of it as `end`, so the cut is halfway; elsewhere scaling back is exact, and the
// cut is inward 2^-k. (Exact: for k < 0 both are scaled up, and the halfway point of two numbers
// that came from neighbours in t has a bit to spare in t'.)
static real CutAt(real end, real inward, int k) {
    real a = ScaleByPowerOfTwo(end, -k), b = ScaleByPowerOfTwo(inward, -k);
    if (k >= 0 || !std::isfinite(a) || !std::isfinite(b))
        return b;
    return a + (b - a) / 2;
}

// The scaled ray's interval: (tMin 2^-k, tMax 2^-k), cut so that every t' in it comes back
// (ScaleBack, t = t' 2^k) inside (tMin, tMax). Between normal numbers the scaling is exact and
// cuts nothing; at the ends of the range t' 2^k overflows or rounds to 0, and a shape found
// there would be refused on the way back, leaving no answer: a search for any hit, stopped at
// it, would miss a nearer shape that blocks the ray, and the nearest hit one farther. So each
// end is cut where t' 2^k crosses it (CutAt), then checked against ScaleBack's own rounding and
// moved one step where it falls on the wrong side (a tie rounds to even). ScaleByPowerOfTwo
// rounds monotonically, so every t' between the two ends comes back inside, and none outside
// them would. (Only a direction outside the window comes here.)
static void ScaledInterval(real tMin, real tMax, int k, real *lo, real *hi) {
    real first = CutAt(tMin, NextAfter(tMin, true), k); // the least t' above tMin
    if (!(ScaleByPowerOfTwo(first, k) > tMin))
        first = NextAfter(first, true);
    real last = CutAt(tMax, NextAfter(tMax, false), k); // the largest t' below tMax
    if (!(ScaleByPowerOfTwo(last, k) < tMax))
        last = NextAfter(last, false);
    *lo = NextAfter(first, false), *hi = NextAfter(last, true); // (both ends open)
}

bool RescaleRay(const Ray *ray, ScaledRay *s) {
    s->exponent = UnitExponent(ray->dir);
    s->ray = {ray->origin, ScaleByPowerOfTwo(ray->dir, s->exponent)};
    ScaledInterval(s->tMin, s->tMax, s->exponent, &s->tMin, &s->tMax);
    return MaxComponent(s->ray.dir) >= 1 && IsFinite(s->ray.dir);
}
