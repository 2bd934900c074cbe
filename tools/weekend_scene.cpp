// tools/weekend_scene.cpp -- prints scenes/weekend.scene, the final scene of Ray Tracing in One
// Weekend (book 1, §14.1, "A Final Render"): its loop over a 22 x 22 grid of small spheres,
// each diffuse, metal or glass by a random number, written out as rt's statements.
//
// The book draws its numbers with random_double() = rand() / (RAND_MAX + 1.0) from C's rand()
// left at its default seed, 1. This program draws the same sequence on any system: GNU libc's
// rand() (its TYPE_3 additive feedback generator, `random_r.c`), written out below. It also takes
// them in the order the book's program takes them when g++ builds it: g++ evaluates a call's
// arguments from the last to the first, so `point3 center(a + 0.9*random_double(), 0.2, b +
// 0.9*random_double())` draws z before x, `color::random()` draws blue, green, then red, and
// `color::random() * color::random()` draws its right-hand factor first. So on a GNU system the
// scene is the very one the book's program draws (bench/weekend.sh checks it against that
// program, with `numbers`). `make build/weekend_scene && build/weekend_scene >scene`.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

// GNU libc's rand() from its default seed, 1 (P. Selinger, "The GLIBC pseudo-random number
// generator", 2007): r[0] = 1; r[i] = 16807 r[i - 1] mod (2^31 - 1) for i = 1..30; r[i] =
// r[i - 31] for i = 31..33; r[i] = r[i - 31] + r[i - 3] (mod 2^32) from i = 34 on; the k-th
// number rand() returns is r[k + 344] >> 1.
struct GlibcRand {
    std::vector<uint32_t> r;
};

static void Seed(GlibcRand *g) {
    g->r = {1};
    for (int i = 1; i < 31; i++)
        g->r.push_back((uint32_t)(16807 * (uint64_t)g->r[i - 1] % 2147483647));
    for (int i = 31; i < 34; i++)
        g->r.push_back(g->r[i - 31]);
    for (int i = 34; i < 344; i++) // (the numbers srand discards)
        g->r.push_back(g->r[i - 31] + g->r[i - 3]);
}

static uint32_t Rand(GlibcRand *g) {
    size_t i = g->r.size();
    g->r.push_back(g->r[i - 31] + g->r[i - 3]);
    return g->r[i] >> 1;
}

// The book's random_double(): rand() / (RAND_MAX + 1.0), in [0, 1); and in [lo, hi).
static double RandomDouble(GlibcRand *g) { return Rand(g) / (2147483647 + 1.0); }
static double RandomDouble(GlibcRand *g, double lo, double hi) {
    return lo + (hi - lo) * RandomDouble(g);
}

// color::random(lo, hi), blue first (see above).
struct Color {
    double r, g, b;
};
static Color RandomColor(GlibcRand *g, double lo, double hi) {
    Color c;
    c.b = RandomDouble(g, lo, hi), c.g = RandomDouble(g, lo, hi), c.r = RandomDouble(g, lo, hi);
    return c;
}

// x in the shortest decimal that reads back as exactly x, so the file holds the book's numbers.
static const char *Shortest(double x, char *text) {
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(text, 32, "%.*g", digits, x);
        if (std::strtod(text, nullptr) == x)
            break;
    }
    return text;
}

// A sphere of radius r at (x, y, z), and the material it names.
static void Sphere(double x, double y, double z, double r, const char *material) {
    char tx[32], ty[32], tz[32], tr[32];
    printf("sphere %s %s %s %s %s\n", Shortest(x, tx), Shortest(y, ty), Shortest(z, tz),
           Shortest(r, tr), material);
}

// A material named NAME: diffuse (rho), or metal (albedo and fuzz) as rt's tinted, fuzzy mirror.
static void Material(const char *name, const char *kind, Color c, double fuzz) {
    char r[32], g[32], b[32], f[32];
    printf("material %s%s", name, kind);
    if (fuzz > 0)
        printf(" fuzz %s", Shortest(fuzz, f));
    printf(" %s %s %s %s\n", fuzz >= 0 ? "tint" : "diffuse", Shortest(c.r, r), Shortest(c.g, g),
           Shortest(c.b, b));
}

static const char *kHeader =
    "# Ray Tracing in One Weekend, book 1's final scene (its cover, section 14.1): 483 small\n"
    "# spheres, diffuse, metal or glass, around three big ones, under the book's sky, seen "
    "through\n"
    "# its lens. Written out by tools/weekend_scene.cpp: the book's loop, with its random numbers\n"
    "# (C's rand() from its default seed, 1, as GNU libc draws it), so this is the very scene the\n"
    "# book's program draws. The book renders it at 500 samples a pixel, 50 rays a path:\n"
    "#     ./ray scenes/weekend.scene --spp 500\n"
    "# and with the book's own estimator and Fresnel: --estimator journal --fresnel schlick.\n"
    "size 1200 675\n"
    "camera lookat 13 2 3  0 0 0  0 1 0  20  defocus 0.6 focus 10\n"
    "shading path\n"
    "depth 50\n"
    "background 1 1 1 up 0.5 0.7 1       # the book's sky: white below, blue above\n"
    "material ground diffuse 0.5 0.5 0.5\n"
    "material glass glass 1.5\n"
    "material brown diffuse 0.4 0.2 0.1\n"
    "material bronze mirror 1 tint 0.7 0.6 0.5\n"
    "sphere 0 -1000 0 1000 ground\n"
    "# the small spheres, in the book's order: a diffuse one's reflectance; a metal one's fuzz\n"
    "# and tint (the book's albedo)\n";

// The 22 x 22 grid of small spheres, in the book's order, each drawn as the book draws it. With
// `numbers`, instead of scene statements, the book's own numbers in the form bench/weekend.sh
// makes a copy of the book's program print them (the sphere's kind and colour, then its x and
// z), so that the two can be compared byte for byte.
static void SmallSpheres(GlibcRand *g, bool numbers) {
    int count = 0;
    for (int a = -11; a < 11; a++)
        for (int b = -11; b < 11; b++) {
            double chooseMat = RandomDouble(g);
            double z = b + 0.9 * RandomDouble(g), x = a + 0.9 * RandomDouble(g);
            if (!(std::sqrt((x - 4) * (x - 4) + z * z) > 0.9)) // (clear of the metal sphere)
                continue;
            char name[16];
            snprintf(name, sizeof name, "s%d", ++count);
            if (chooseMat < 0.8) {
                Color right = RandomColor(g, 0, 1), left = RandomColor(g, 0, 1);
                Color albedo = {left.r * right.r, left.g * right.g, left.b * right.b};
                if (numbers)
                    printf("D %.17g %.17g %.17g\n", albedo.r, albedo.g, albedo.b);
                else
                    Material(name, "", albedo, -1);
            } else if (chooseMat < 0.95) {
                Color albedo = RandomColor(g, 0.5, 1);
                double fuzz = RandomDouble(g, 0, 0.5);
                if (numbers)
                    printf("M %.17g %.17g %.17g %.17g\n", albedo.r, albedo.g, albedo.b, fuzz);
                else
                    Material(name, " mirror 1", albedo, fuzz);
            } else {
                snprintf(name, sizeof name, "glass");
                if (numbers)
                    printf("G\n");
            }
            if (numbers)
                printf("C %.17g %.17g\n", x, z);
            else
                Sphere(x, 0.2, z, 0.2, name);
        }
}

int main(int argc, char **argv) {
    GlibcRand g;
    Seed(&g);
    if (argc > 1 && std::string(argv[1]) == "numbers") {
        SmallSpheres(&g, true);
        return 0;
    }
    printf("%s", kHeader);
    SmallSpheres(&g, false);
    printf("# the three big spheres\n");
    Sphere(0, 1, 0, 1, "glass");
    Sphere(-4, 1, 0, 1, "brown");
    Sphere(4, 1, 0, 1, "bronze");
    return 0;
}
