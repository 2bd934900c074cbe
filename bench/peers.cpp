// bench/peers.cpp -- the noise of an image against a converged one, in linear light (`rtbench
// noise`, for bench/peers.sh, which sets rt beside the programs a user might pick instead).
//
// Two programs that write their pixels with different curves (rt sRGB, smallpt x^(1/2.2)) are
// compared on the light itself: each image is decoded by its own curve and the root mean square
// of the differences taken over every channel. The reference is the same program at many more
// samples with other random numbers, so its own noise adds to the measured one; with N samples a
// pixel against a reference of R, the measured square is sigma^2 (1/N + 1/R), and the noise of one
// sample a pixel, sigma, follows. Time to a given error is then sigma^2 times the time of a sample,
// whatever the error chosen: the figure two programs are compared by.
#include "../app/app.h"

#include <cmath>
#include <cstdio>
#include <string>

// The curves a program writes its 8-bit values with: sRGB (rt), x^(1/2.2) (smallpt), x^(1/2)
// (Ray Tracing in One Weekend's linear_to_gamma).
enum Curve { CURVE_SRGB, CURVE_GAMMA, CURVE_SQRT };

// One 8-bit channel value back to linear light by the curve the program wrote it with.
static double Decode(int v, Curve curve) {
    double x = v / 255.0;
    if (curve == CURVE_GAMMA)
        return std::pow(x, 2.2);
    if (curve == CURVE_SQRT)
        return x * x;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

static Curve CurveNamed(const std::string &name) {
    return name == "srgb" ? CURVE_SRGB : name == "sqrt" ? CURVE_SQRT : CURVE_GAMMA;
}

// rtbench noise IMAGE CURVE N REFERENCE CURVE R, each CURVE srgb, gamma (x^(1/2.2)) or sqrt:
// prints sigma, the noise of one sample a pixel. (With N = 1 and R huge: the RMS difference
// itself.)
int NoiseMain(char **argv) {
    Image a, b;
    std::string error;
    if (!ReadImage(argv[0], &a, &error) || !ReadImage(argv[3], &b, &error)) {
        fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    Curve curveA = CurveNamed(argv[1]), curveB = CurveNamed(argv[4]);
    double n = atof(argv[2]), r = atof(argv[5]);
    if (a.width != b.width || a.height != b.height || !(n > 0) || !(r > 0)) {
        fprintf(stderr, "noise: images of different sizes, or no sample counts\n");
        return 1;
    }
    double sum = 0;
    for (size_t k = 0; k < a.pixels.size(); k++) {
        double d = Decode(a.pixels[k], curveA) - Decode(b.pixels[k], curveB);
        sum += d * d;
    }
    double square = sum / a.pixels.size();
    printf("%.6g\n", std::sqrt(square / (1 / n + 1 / r)));
    return 0;
}
