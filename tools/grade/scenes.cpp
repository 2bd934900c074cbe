// tools/grade/scenes.cpp -- the grading scenes: each small, each made so that some classic bugs
// show in it and, as far as a scene can manage it, in no other. Seed 0 gives the public scenes
// (scenes/grade/); any other seed moves, resizes and recolours every scene within ranges where
// each of its bugs still shows, so that a class cannot hard-code the images.
#include "grade.h"

#include <cstdarg>
#include <cstdint>
#include <cmath>
#include <cstdio>

// A random number source as small as a scene needs (splitmix64, Steele, Lea and Flood 2014).
struct Rng {
    uint64_t state;
    bool fixed; // seed 0: every Vary gives its base value
};

static double Uniform(Rng *rng) {
    uint64_t z = (rng->state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

// base, or a value within spread of it.
static double Vary(Rng *rng, double base, double spread) {
    return rng->fixed ? base : base + spread * (2 * Uniform(rng) - 1);
}

// A scene's text, written a line at a time.
struct Text {
    std::string s;
};
static void Line(Text *t, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void Line(Text *t, const char *format, ...) {
    char line[512];
    va_list args;
    va_start(args, format);
    vsnprintf(line, sizeof line, format, args);
    va_end(args);
    t->s += line;
    t->s += '\n';
}

// The lines every grading scene opens with: its purpose, its size, the assignment's camera.
static void Header(Text *t, const char *bugs, const char *purpose, int w, int h, const char *shading,
                   double ambient) {
    Line(t, "# reveals: %s", bugs);
    t->s += purpose;
    Line(t, "size %d %d", w, h);
    Line(t, "camera perspective 0 0 0 2 2");
    Line(t, "shading %s", shading);
    Line(t, "ambient %.4g", ambient);
    Line(t, "depth 10");
}

static void Triangle(Text *t, double ax, double ay, double az, double bx, double by, double bz,
                     double cx, double cy, double cz, const char *material) {
    Line(t, "triangle %.4g %.4g %.4g   %.4g %.4g %.4g   %.4g %.4g %.4g   %s", ax, ay, az, bx, by, bz,
         cx, cy, cz, material);
}

// A square wall across the view at depth z, facing the eye (or away from it: back).
static void Wall(Text *t, double z, double half, const char *material, bool back = false) {
    if (back)
        Triangle(t, 0, half, z, half, -half, z, -half, -half, z, material);
    else
        Triangle(t, 0, half, z, -half, -half, z, half, -half, z, material);
}

static GradingScene Camera(Rng *r) {
    Text t;
    Header(&t, "upside-down mirrored",
           "# A red corner at the top left of a grey wall; no light (ambient 1). A screen upside\n"
           "# down puts it at the bottom left, a mirrored one at the top right.\n",
           64, 64, "floor", 1);
    double g = Vary(r, 0.5, 0.1), x = Vary(r, -2, 0.3), y = Vary(r, 2, 0.3), s = Vary(r, 1.8, 0.3);
    Line(&t, "material grey diffuse %.3g %.3g %.3g", g, g, g);
    Line(&t, "material red diffuse %.3g %.3g %.3g", Vary(r, 0.9, 0.1), Vary(r, 0.1, 0.1), 0.1);
    Triangle(&t, x, y, -4, x, y - s, -4, x + s, y, -4, "red"); // (the nearer shape first)
    Wall(&t, -5, 20, "grey");
    return {"camera", t.s};
}

static GradingScene Aspect(Rng *r) {
    Text t;
    int w = r->fixed ? 96 : 80 + 16 * (int)(3 * Uniform(r));
    Header(&t, "aspect",
           "# A wide image of round shapes; no light (ambient 1). Pixels are square: a pixel's\n"
           "# height on the screen is the screen's width over the image's width, as its width\n"
           "# is. Taken from the image's height, it stretches the spheres into tall ellipses.\n",
           w, 48, "floor", 1);
    Line(&t, "material white diffuse 0.9 0.9 0.9");
    Line(&t, "material blue diffuse 0.2 0.3 %.3g", Vary(r, 0.9, 0.1));
    double x = Vary(r, 1.7, 0.15), radius = Vary(r, 0.5, 0.05); // (apart: no sphere hides another)
    Line(&t, "sphere 0 0 -5  %.4g  white", Vary(r, 0.8, 0.1));
    Line(&t, "sphere %.4g 0 -5  %.4g  blue", -x, radius);
    Line(&t, "sphere %.4g 0 -5  %.4g  blue", x, radius);
    return {"aspect", t.s};
}

static GradingScene FarRoot(Rng *r) {
    Text t;
    Header(&t, "far-root",
           "# A red sphere whose middle a blue wall cuts; no light (ambient 1). The near root of\n"
           "# the quadratic is the sphere's front, before the wall: a red disc. The far root lies\n"
           "# behind the wall, so a tracer that takes it sees only blue.\n",
           64, 64, "floor", 1);
    double z = Vary(r, -6, 1);
    Line(&t, "material red diffuse %.3g 0.1 0.1", Vary(r, 0.9, 0.1));
    Line(&t, "material blue diffuse 0.1 0.1 %.3g", Vary(r, 0.9, 0.1));
    Line(&t, "sphere 0 0 %.4g  %.4g  red", z, Vary(r, 2, 0.4));
    Wall(&t, z, 20, "blue");
    return {"far_root", t.s};
}

static GradingScene Acne(Rng *r) {
    Text t;
    Header(&t, "acne sphere-tmin triangle-tmin",
           "# A low pyramid pointing at the eye and a ball before its tip, lit from the eye. Every\n"
           "# shadow ray starts on a surface: one that may hit the surface it leaves (no offset,\n"
           "# or a test that ignores tMin) finds it at t near 0 about half the time, and speckles\n"
           "# it with shadow: both shapes, only the ball, or only the pyramid.\n",
           64, 64, "floor", Vary(r, 0.2, 0.05));
    double apex = Vary(r, -4, 0.3), base = apex - Vary(r, 3, 0.5);
    Line(&t, "light 0 0 %.3g", Vary(r, 0, 0.3)); // (on the axis: the scene stays symmetric)
    Line(&t, "material white diffuse 1 1 1");
    Line(&t, "material ball diffuse %.3g %.3g 0.3", Vary(r, 0.9, 0.1), Vary(r, 0.8, 0.1));
    Line(&t, "sphere 0 0 %.4g  %.4g  ball", apex + 1, Vary(r, 0.6, 0.1)); // (before the pyramid)
    Triangle(&t, 0, 0, apex, 9, 0, base, 0, 9, base, "white");
    Triangle(&t, 0, 0, apex, 0, 9, base, -9, 0, base, "white");
    Triangle(&t, 0, 0, apex, -9, 0, base, 0, -9, base, "white");
    Triangle(&t, 0, 0, apex, 0, -9, base, 9, 0, base, "white");
    return {"acne", t.s};
}

static GradingScene Beyond(Rng *r) {
    Text t;
    Header(&t, "beyond",
           "# A wall facing the eye, a light between them, and a second wall behind the eye that\n"
           "# the eye never sees. Each shadow ray, from the wall to the light (D = light - P),\n"
           "# would meet the hidden wall at t > 1: beyond the light, so it must not cast a shadow\n"
           "# (only 0 < t < 1 blocks).\n",
           64, 64, "floor", Vary(r, 0.2, 0.05));
    Line(&t, "light 0 0 %.4g", Vary(r, -2, 0.4));
    Line(&t, "material white diffuse %.3g %.3g 1", Vary(r, 0.95, 0.05), Vary(r, 0.95, 0.05));
    Wall(&t, Vary(r, -4, 0.5), 20, "white");
    Wall(&t, Vary(r, 2, 0.5), 40, "white", true);
    return {"beyond", t.s};
}

static GradingScene Normals(Rng *r) {
    Text t;
    Header(&t, "normals",
           "# A wall seen from behind (its winding, (b - a) x (c - a), points away from the eye),\n"
           "# lit by a light behind it. Turned toward the viewer, the wall's normal faces away\n"
           "# from the light, so the wall shows only the ambient floor; a tracer that never turns\n"
           "# normals lights it through.\n",
           64, 64, "floor", Vary(r, 0.2, 0.05));
    Line(&t, "light %.3g %.3g %.4g", Vary(r, 0, 0.5), Vary(r, 0, 0.5), Vary(r, -8, 1));
    Line(&t, "material white diffuse 1 %.3g %.3g", Vary(r, 0.95, 0.05), Vary(r, 0.95, 0.05));
    Wall(&t, Vary(r, -4, 0.5), 20, "white", true);
    return {"normals", t.s};
}

static GradingScene Triangles(Rng *r) {
    Text t;
    Header(&t, "edges inside-gamma inside-beta cramer-sign t-sign plane-axis plane-order",
           "# Four triangles meeting at the middle in a diamond, and a floor and a ceiling beyond\n"
           "# it; no light (ambient 1). The middle column and row of this odd-sized image look\n"
           "# exactly along the shared edges (beta or gamma exactly 0: a test that wants them\n"
           "# above 0 draws black lines there); around the diamond lie the regions just outside\n"
           "# each edge and corner, which an inside test with a wrong bound fills or leaves; the\n"
           "# floor and ceiling face up and down, where the plane test must not drop z; a wall\n"
           "# behind the eye shows only where t's sign is wrong.\n",
           65, 65, "floor", 1);
    double s = Vary(r, 1.5, 0.2), y = Vary(r, 1.7, 0.1), z = -4;
    Line(&t, "material white diffuse %.3g %.3g 0.9", Vary(r, 0.9, 0.1), Vary(r, 0.9, 0.1));
    Line(&t, "material floor diffuse 0.3 %.3g 0.3", Vary(r, 0.6, 0.1));
    Line(&t, "material behind diffuse 0.8 0.2 %.3g", Vary(r, 0.8, 0.1));
    Triangle(&t, 0, 0, z, s, 0, z, 0, s, z, "white");
    Triangle(&t, 0, 0, z, 0, s, z, -s, 0, z, "white");
    Triangle(&t, 0, 0, z, -s, 0, z, 0, -s, z, "white");
    Triangle(&t, 0, 0, z, 0, -s, z, s, 0, z, "white");
    for (int side = -1; side <= 1; side += 2) { // the floor (y < 0), then the ceiling
        double h = side * y;
        Triangle(&t, -6, h, -4.2, 6, h, -4.2, 6, h, -12, "floor");
        Triangle(&t, -6, h, -4.2, 6, h, -12, -6, h, -12, "floor");
    }
    Wall(&t, 4, 40, "behind");
    return {"triangles", t.s};
}

static GradingScene Nearest(Rng *r) {
    Text t;
    Header(&t, "first-hit",
           "# A far wall, a diamond before it and a small square nearer still, listed far\n"
           "# first; no light (ambient 1). The nearest hit over the list shows all three; a\n"
           "# search that stops at the first hit it finds shows the wall alone.\n",
           64, 64, "floor", 1);
    double d = Vary(r, 1.2, 0.2), n = Vary(r, 0.4, 0.1);
    Line(&t, "material blue diffuse 0.1 0.2 %.3g", Vary(r, 0.8, 0.1));
    Line(&t, "material red diffuse %.3g 0.1 0.1", Vary(r, 0.9, 0.1));
    Line(&t, "material green diffuse 0.1 %.3g 0.1", Vary(r, 0.8, 0.1));
    Wall(&t, Vary(r, -8, 1), 40, "blue");
    Triangle(&t, 0, d, -5, -d, 0, -5, d, 0, -5, "red");
    Triangle(&t, 0, -d, -5, d, 0, -5, -d, 0, -5, "red");
    Triangle(&t, -n, n, -3, -n, -n, -3, n, -n, -3, "green");
    Triangle(&t, -n, n, -3, n, -n, -3, n, n, -3, "green");
    return {"nearest", t.s};
}

static GradingScene Lights(Rng *r) {
    Text t;
    Header(&t, "nl-clamp l-length",
           "# A wall facing the eye, one light before it and one behind it. The light behind\n"
           "# has N.L < 0 everywhere on the wall and must add nothing (clamp N.L at 0, or skip\n"
           "# it); the one before lights the wall by N.L with L of unit length, whatever its\n"
           "# distance.\n",
           64, 64, "floor", 0.1);
    Line(&t, "light 0 0 %.4g  %.3g %.3g 0.8", Vary(r, -1, 0.3), Vary(r, 0.8, 0.1), Vary(r, 0.8, 0.1));
    Line(&t, "light 0 0 %.4g  %.3g %.3g %.3g", Vary(r, -6, 0.5), Vary(r, 0.6, 0.1),
         Vary(r, 0.6, 0.1), 0.6);
    Line(&t, "material white diffuse %.3g 0.9 %.3g", Vary(r, 0.9, 0.1), Vary(r, 0.9, 0.1));
    Wall(&t, Vary(r, -4, 0.3), 20, "white");
    return {"lights", t.s};
}

static GradingScene Bright(Rng *r) {
    Text t;
    Header(&t, "clamp",
           "# A wall lit by a light twice as bright as white: its middle comes out above 1 in\n"
           "# each channel, and must be clamped to 255, not wrapped around past it.\n",
           64, 64, "floor", 0.2);
    Line(&t, "light 0 0 %.3g  %.3g %.3g %.3g", Vary(r, -1, 0.3), Vary(r, 2.5, 0.3),
         Vary(r, 2.5, 0.3), Vary(r, 2.5, 0.3));
    Line(&t, "material warm diffuse 0.9 %.3g %.3g", Vary(r, 0.6, 0.1), Vary(r, 0.45, 0.1));
    Wall(&t, Vary(r, -4, 0.3), 20, "warm");
    return {"bright", t.s};
}

static GradingScene Reflect(Rng *r) {
    Text t;
    Header(&t, "reflect",
           "# A mirror facing the eye, a green wall behind the eye and a red one behind the\n"
           "# mirror; no light, so every colour is its own (ambient 1). R = D - 2 (D.N) N turns\n"
           "# the eye's rays back to the green wall; the wrong sign sends them on through the\n"
           "# mirror to the red one.\n",
           64, 64, "floor", 1);
    Line(&t, "material mirror mirror 1");
    Line(&t, "material green diffuse 0.2 %.3g 0.2", Vary(r, 0.8, 0.1));
    Line(&t, "material red diffuse %.3g 0.1 0.1", Vary(r, 0.9, 0.1));
    Wall(&t, Vary(r, -4, 0.5), 20, "mirror");
    Wall(&t, Vary(r, 3, 0.5), 40, "green", true);
    Wall(&t, Vary(r, -8, 1), 40, "red");
    return {"reflect", t.s};
}

static GradingScene Depth(Rng *r) {
    Text t;
    Header(&t, "no-limit depth-9 depth-11",
           "# The eye inside twelve nested boxes whose walls are 90% mirror; no light (ambient\n"
           "# 1). Each eye ray reflects from wall to wall forever, so only the limit ends it:\n"
           "# with at most 10 rays in a chain, a pixel is 1 - 0.9^10 of the walls' own colour.\n"
           "# One ray more or less, or no limit, shows as a brighter or darker image.\n",
           64, 64, "floor", 1);
    double gap = Vary(r, 3, 0.3), far = 3000;
    Line(&t, "material glassy diffuse %.3g %.3g 1 mirror %.3g", Vary(r, 0.3, 0.1),
         Vary(r, 0.5, 0.1), Vary(r, 0.9, 0.03));
    for (int box = 1; box <= 12; box++) {
        double d = box * gap;
        Triangle(&t, 0, far, -d, -far, -far, -d, far, -far, -d, "glassy");
        Triangle(&t, 0, far, d, far, -far, d, -far, -far, d, "glassy");
        Triangle(&t, -d, 0, far, -d, -far, -far, -d, far, -far, "glassy");
        Triangle(&t, d, 0, far, d, far, -far, d, -far, -far, "glassy");
        Triangle(&t, 0, -d, far, far, -d, -far, -far, -d, -far, "glassy");
        Triangle(&t, 0, d, far, -far, d, -far, far, d, -far, "glassy");
    }
    return {"depth", t.s};
}

static GradingScene Phong(Rng *r) {
    Text t;
    Header(&t, "phong-view phong-shadow phong-tint",
           "# A shiny ball lit from above, its highlight half in the shadow of a small ball out\n"
           "# of view (shading phong). The highlight is white (ks (R.V)^n adds to every channel),\n"
           "# sits where R, the light's mirror direction, meets V, toward the eye, and is gone\n"
           "# where the light is hidden.\n",
           64, 64, "phong", 0.1);
    // The highlight is where N halves the way to the light and to the eye; the dark ball sits on
    // the way from there to the light, a little to the side, so that it hides half of it.
    double ly = Vary(r, 6, 0.5), toLight = std::sqrt(ly * ly + 36);
    double nx = 0, ny = ly / toLight, nz = 6 / toLight + 1, n = std::sqrt(ny * ny + nz * nz);
    double px = 2 * nx / n, py = 2 * ny / n, pz = -6 + 2 * nz / n;
    Line(&t, "light 0 %.4g 0", ly);
    Line(&t, "material shiny diffuse %.3g 0.15 %.3g specular 0.35 %.4g", Vary(r, 0.5, 0.05),
         Vary(r, 0.15, 0.05), Vary(r, 10, 2));
    Line(&t, "material dark diffuse 0.2 0.2 0.2");
    Line(&t, "sphere 0 0 -6  2  shiny");
    Line(&t, "sphere %.4g %.4g %.4g  0.3  dark", px + Vary(r, 0.25, 0.05), py + 0.4 * (ly - py),
         pz + 0.4 * (0 - pz));
    return {"phong", t.s};
}

// The grading scenes for a seed, in the handouts' order: the camera, the sphere, the triangle,
// the nearest hit, shadows, the floor's lighting, colours, mirrors, the depth, Phong.
std::vector<GradingScene> MakeGradingScenes(unsigned long seed) {
    Rng rng = {seed * 0x2545f4914f6cdd1dULL + 1, seed == 0};
    GradingScene (*const makers[])(Rng *) = {Camera,  Aspect, FarRoot, Triangles, Nearest,
                                            Acne,    Beyond, Normals, Lights,    Bright,
                                            Reflect, Depth,  Phong};
    std::vector<GradingScene> scenes;
    for (auto make : makers)
        scenes.push_back(make(&rng));
    return scenes;
}
