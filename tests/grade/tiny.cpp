// tests/grade/tiny.cpp -- a tiny tracer as a student writes it after the handouts, and the same
// tracer with one classic bug, for the tests of the grader: each grading scene must catch its
// bugs, and the grader names a bug by the image this tracer draws with it. Not part of rt: no
// robust step, no speed, one file.
//
//   tiny [--bug NAME] [--triangle cramer|plane] SCENE -o OUT.png
//
// It reads the part of rt's scene format the grading scenes use (size, camera perspective,
// ambient, background, depth, shading floor|phong, light with its intensity, material with
// diffuse, ambient, specular and mirror, sphere, triangle) and draws with the handouts' methods
// as `ray --methods handout` does: the slide's eye ray, the textbook quadratic, Cramer's rule (or
// the second handout's plane test), shadow and mirror rays that start 1e-4 along, normals turned
// toward the viewer, at most `depth` rays in a chain. --bug NAME breaks one step (kBugs).
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

struct V {
    double x, y, z;
};
static V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
static V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
static V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
static V Mul(V a, V b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
static double Dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static V Cross(V a, V b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static double Length(V a) { return std::sqrt(Dot(a, a)); }
static V Unit(V a) { return (1 / Length(a)) * a; }
static double At(V a, int k) { return k == 0 ? a.x : k == 1 ? a.y : a.z; }

struct Material {
    V diffuse = {1, 1, 1}, ambient = {-1, 0, 0}; // (ambient.x < 0: the diffuse colour)
    double mirror = 0, specular = 0, shininess = 1;
};
struct Shape {
    bool sphere;
    V a, b, c; // a sphere: its centre a and radius b.x
    int material;
};
struct Light {
    V position, intensity;
};
// The bugs, one at a time, by the step they break (the grader's table says what each looks like).
enum Bug {
    NONE,
    UPSIDE_DOWN, MIRRORED, ASPECT,                         // get-ray
    FAR_ROOT, SPHERE_TMIN,                                 // sphere
    EDGES, INSIDE_GAMMA, INSIDE_BETA, CRAMER_SIGN, T_SIGN, // cramer
    TRIANGLE_TMIN, PLANE_AXIS, PLANE_ORDER,                // cramer or plane; plane
    FIRST_HIT,                                             // nearest-hit
    ACNE, BEYOND,                                          // shadow
    NL_CLAMP, L_LENGTH,                                    // floor
    REFLECT, NO_LIMIT, DEPTH_9, DEPTH_11,                  // reflect, depth
    PHONG_VIEW, PHONG_SHADOW, PHONG_TINT,                  // phong
    NORMALS, CLAMP,                                        // given code
    BUG_COUNT
};
static const char *kBugs[BUG_COUNT] = {
    "none",          "upside-down", "mirrored",    "aspect",      "far-root",
    "sphere-tmin",   "edges",       "inside-gamma", "inside-beta", "cramer-sign",
    "t-sign",        "triangle-tmin", "plane-axis", "plane-order", "first-hit",
    "acne",          "beyond",      "nl-clamp",    "l-length",    "reflect",
    "no-limit",      "depth-9",     "depth-11",    "phong-view",  "phong-shadow",
    "phong-tint",    "normals",     "clamp"};

struct Scene {
    int width = 512, height = 512, depth = 10;
    V eye = {0, 0, 0};
    double distance = 2, screenWidth = 2, ambient = 0.2;
    bool phong = false, plane = false;
    V background = {0, 0, 0};
    std::vector<Light> lights;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    Bug bug = NONE;
};

const double kEpsilon = 1e-4;

struct Hit {
    double t;
    V point, normal;
    int material;
};

// The slide's quadratic, A t^2 + B t + C = 0, and the least root above tMin.
static bool HitSphere(const Shape *s, Bug bug, V o, V d, double tMin, double tMax, Hit *hit) {
    V oc = o - s->a;
    double A = Dot(d, d), B = 2 * Dot(d, oc), C = Dot(oc, oc) - s->b.x * s->b.x;
    double disc = B * B - 4 * A * C;
    if (disc < 0)
        return false;
    double near = (-B - std::sqrt(disc)) / (2 * A), far = (-B + std::sqrt(disc)) / (2 * A);
    double t = bug == FAR_ROOT ? far : (near > tMin ? near : far);
    if (bug == SPHERE_TMIN) // (the least non-negative root, tMin unused)
        t = near >= 0 ? near : far;
    if (!(bug == SPHERE_TMIN ? t >= 0 && t < tMax : t > tMin && t < tMax))
        return false;
    hit->t = t, hit->point = o + t * d, hit->normal = (1 / s->b.x) * (hit->point - s->a);
    return true;
}

// Cramer's rule with the slides' variables A..M: beta, gamma and t.
static bool Cramer(const Shape *s, Bug bug, V o, V d, double *t) {
    double A = s->a.x - s->b.x, B = s->a.y - s->b.y, C = s->a.z - s->b.z;
    double D = s->a.x - s->c.x, E = s->a.y - s->c.y, F = s->a.z - s->c.z;
    double G = d.x, H = d.y, I = d.z, J = s->a.x - o.x, K = s->a.y - o.y, L = s->a.z - o.z;
    double M = (bug == CRAMER_SIGN ? -A : A) * (E * I - H * F) + B * (G * F - D * I) +
               C * (D * H - E * G);
    if (M == 0)
        return false;
    *t = (bug == T_SIGN ? 1 : -1) * (F * (A * K - J * B) + E * (J * C - A * L) + D * (B * L - K * C)) / M;
    double gamma = (I * (A * K - J * B) + H * (J * C - A * L) + G * (B * L - K * C)) / M;
    double beta = (J * (E * I - H * F) + K * (G * F - D * I) + L * (D * H - E * G)) / M;
    switch (bug) {
    case EDGES: return gamma > 0 && beta > 0 && beta + gamma < 1;
    case INSIDE_GAMMA: return gamma >= 0 && beta >= 0 && gamma <= 1 - gamma;
    case INSIDE_BETA: return gamma >= 0 && gamma <= 1 && beta >= 0 && beta <= 1;
    default: return gamma >= 0 && beta >= 0 && beta <= 1 - gamma;
    }
}

// The second handout's two steps: the plane's t, then the signs of the three edges' cross
// products on the normal's largest coordinate.
static bool PlaneTest(const Shape *s, Bug bug, V o, V d, double *t) {
    V a = s->a, b = s->b, c = s->c, n = Cross(b - a, c - a);
    if (Dot(n, d) == 0)
        return false;
    *t = (bug == T_SIGN ? -1 : 1) * Dot(n, a - o) / Dot(n, d);
    V p = o + *t * d;
    V size = {std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
    int k = size.x > size.y ? (size.x > size.z ? 0 : 2) : (size.y > size.z ? 1 : 2);
    if (bug == PLANE_AXIS)
        k = 2;
    double nk = At(n, k), first = At(Cross(b - a, p - a), k);
    if (bug == PLANE_ORDER)
        first = At(Cross(p - a, b - a), k);
    return !(first * nk < 0 || At(Cross(c - b, p - b), k) * nk < 0 ||
             At(Cross(a - c, p - c), k) * nk < 0);
}

static bool HitTriangle(const Shape *s, const Scene *scene, V o, V d, double tMin, double tMax,
                        Hit *hit) {
    double t;
    Bug bug = scene->bug;
    bool inside = scene->plane || bug == PLANE_AXIS || bug == PLANE_ORDER ? PlaneTest(s, bug, o, d, &t)
                                                                          : Cramer(s, bug, o, d, &t);
    if (!inside || !(bug == TRIANGLE_TMIN ? t > 0 && t < tMax : t > tMin && t < tMax))
        return false;
    hit->t = t, hit->point = o + t * d, hit->normal = Unit(Cross(s->b - s->a, s->c - s->a));
    return true;
}

static bool Nearest(const Scene *scene, V o, V d, double tMin, double tMax, Hit *hit) {
    bool found = false;
    for (const Shape &s : scene->shapes)
        if (s.sphere ? HitSphere(&s, scene->bug, o, d, tMin, tMax, hit)
                     : HitTriangle(&s, scene, o, d, tMin, tMax, hit)) {
            found = true, tMax = hit->t, hit->material = s.material;
            if (scene->bug == FIRST_HIT)
                break;
        }
    if (found && scene->bug != NORMALS && Dot(hit->normal, d) > 0)
        hit->normal = -1 * hit->normal; // toward the viewer
    return found;
}

// Where a ray that leaves a surface may first hit: epsilon along it. (The acne bug: a shadow ray
// that starts at 0.)
static double Start(V d) { return kEpsilon / Length(d); }

static bool Visible(const Scene *scene, V point, V toLight) {
    Hit blocker;
    return !Nearest(scene, point, toLight, scene->bug == ACNE ? 0 : Start(toLight),
                    scene->bug == BEYOND ? INFINITY : 1, &blocker);
}

// The assignment's rule: kd max(ambient, sum of I N.L over the visible lights in front).
static V FloorColor(const Scene *scene, const Hit *hit, const Material *m) {
    V sum = {0, 0, 0};
    for (const Light &light : scene->lights) {
        V toLight = light.position - hit->point;
        double nDotL = Dot(hit->normal, toLight);
        if ((!(nDotL > 0) && scene->bug != NL_CLAMP) || !Visible(scene, hit->point, toLight))
            continue;
        sum = sum + (scene->bug == L_LENGTH ? nDotL : nDotL / Length(toLight)) * light.intensity;
    }
    double a = scene->ambient;
    return Mul(m->diffuse, {std::fmax(a, sum.x), std::fmax(a, sum.y), std::fmax(a, sum.z)});
}

// The second handout's Phong: ka Ia + sum of I (kd N.L + ks max(0, R.V)^n), R = 2 (N.L) N - L.
static V PhongColor(const Scene *scene, const Hit *hit, const Material *m, V d) {
    V result = scene->ambient * (m->ambient.x < 0 ? m->diffuse : m->ambient);
    V v = scene->bug == PHONG_VIEW ? Unit(d) : -1 * Unit(d);
    for (const Light &light : scene->lights) {
        V l = Unit(light.position - hit->point);
        double nDotL = Dot(hit->normal, l);
        if (!(nDotL > 0))
            continue;
        bool visible = Visible(scene, hit->point, light.position - hit->point);
        V term = visible ? nDotL * m->diffuse : V{0, 0, 0};
        if (m->specular > 0 && (visible || scene->bug == PHONG_SHADOW)) {
            V r = (2 * nDotL) * hit->normal - l;
            double s = m->specular * std::pow(std::fmax(0, Dot(r, v)), m->shininess);
            term = term + (scene->bug == PHONG_TINT ? s * m->diffuse : V{s, s, s});
        }
        result = result + Mul(light.intensity, term);
    }
    return result;
}

static V Trace(const Scene *scene, V o, V d, double tMin, int chain) {
    Hit hit;
    if (!Nearest(scene, o, d, tMin, INFINITY, &hit))
        return scene->background;
    const Material *m = &scene->materials[hit.material];
    V result = {0, 0, 0};
    if (m->mirror < 1)
        result = (1 - m->mirror) * (scene->phong ? PhongColor(scene, &hit, m, d)
                                                 : FloorColor(scene, &hit, m));
    int limit = scene->depth + (scene->bug == DEPTH_9 ? -1 : scene->bug == DEPTH_11 ? 1 : 0);
    if (scene->bug == NO_LIMIT)
        limit = 100; // (0.9^100 of a colour: no 8-bit pixel sees a longer chain)
    if (m->mirror > 0 && chain < limit) {
        double s = scene->bug == REFLECT ? 2 : -2;
        V r = d + (s * Dot(d, hit.normal)) * hit.normal;
        result = result + m->mirror * Trace(scene, hit.point, r, Start(r), chain + 1);
    }
    return result;
}

// `material NAME word values ...`: diffuse R G B, ambient R G B, specular KS N, mirror K.
static Material ReadMaterial(const char *line, char *name) {
    Material m;
    char words[8][64] = {};
    int n = sscanf(line, "material %63s %63s %63s %63s %63s %63s %63s %63s %63s", name, words[0],
                   words[1], words[2], words[3], words[4], words[5], words[6], words[7]) - 1;
    for (int k = 0; k < n; k++) {
        double *rest[3] = {};
        std::string w = words[k];
        if (w == "diffuse" || w == "ambient") {
            V *c = w == "diffuse" ? &m.diffuse : &m.ambient;
            rest[0] = &c->x, rest[1] = &c->y, rest[2] = &c->z;
        } else if (w == "specular")
            rest[0] = &m.specular, rest[1] = &m.shininess;
        else if (w == "mirror")
            rest[0] = &m.mirror;
        for (int j = 0; j < 3 && rest[j] && k + 1 < n; j++)
            *rest[j] = atof(words[++k]);
    }
    return m;
}

static bool Read(const char *path, Scene *scene) {
    FILE *f = fopen(path, "r");
    if (!f)
        return false;
    std::map<std::string, int> names;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        if (char *hash = strchr(line, '#'))
            *hash = 0;
        char word[64] = "", name[64] = "";
        double n[12] = {};
        if (sscanf(line, "%63s", word) != 1)
            continue;
        std::string w = word;
        if (w == "size")
            scene->height = sscanf(line, "size %d %d", &scene->width, &scene->height) == 2
                                ? scene->height
                                : scene->width;
        else if (w == "camera")
            sscanf(line, "camera perspective %lf %lf %lf %lf %lf", &scene->eye.x, &scene->eye.y,
                   &scene->eye.z, &scene->distance, &scene->screenWidth);
        else if (w == "ambient")
            sscanf(line, "ambient %lf", &scene->ambient);
        else if (w == "depth")
            sscanf(line, "depth %d", &scene->depth);
        else if (w == "shading")
            scene->phong = sscanf(line, "shading %63s", name) == 1 && strcmp(name, "phong") == 0;
        else if (w == "background")
            sscanf(line, "background %lf %lf %lf", &scene->background.x, &scene->background.y,
                   &scene->background.z);
        else if (w == "light") {
            Light l = {{0, 0, 0}, {1, 1, 1}};
            sscanf(line, "light %lf %lf %lf %lf %lf %lf", &l.position.x, &l.position.y,
                   &l.position.z, &l.intensity.x, &l.intensity.y, &l.intensity.z);
            scene->lights.push_back(l);
        } else if (w == "material") {
            Material m = ReadMaterial(line, name);
            names[name] = (int)scene->materials.size();
            scene->materials.push_back(m);
        } else if (w == "sphere" && sscanf(line, "sphere %lf %lf %lf %lf %63s", &n[0], &n[1], &n[2],
                                           &n[3], name) == 5)
            scene->shapes.push_back({true, {n[0], n[1], n[2]}, {n[3], 0, 0}, {}, names[name]});
        else if (w == "triangle" &&
                 sscanf(line, "triangle %lf %lf %lf %lf %lf %lf %lf %lf %lf %63s", &n[0], &n[1],
                        &n[2], &n[3], &n[4], &n[5], &n[6], &n[7], &n[8], name) == 10)
            scene->shapes.push_back(
                {false, {n[0], n[1], n[2]}, {n[3], n[4], n[5]}, {n[6], n[7], n[8]}, names[name]});
    }
    fclose(f);
    return true;
}

// round(clamp(c, 0, 1) * 255); the clamp bug lets a channel above 1 wrap around, as a cast of
// c * 255 to unsigned char does.
static unsigned char Byte(double c, Bug bug) {
    if (bug == CLAMP && c > 1)
        return (unsigned char)(unsigned)(c * 255 + 0.5);
    return c <= 0 ? 0 : c >= 1 ? 255 : (unsigned char)(c * 255 + 0.5);
}

// The image, row by row from the top, 3 bytes a pixel.
static std::vector<unsigned char> Render(const Scene *scene) {
    std::vector<unsigned char> pixels(3 * scene->width * scene->height);
    double size = scene->screenWidth / scene->width;
    double sizeY = scene->bug == ASPECT ? scene->screenWidth / scene->height : size;
    for (int j = 0; j < scene->height; j++)
        for (int i = 0; i < scene->width; i++) {
            double x = (i + 0.5 - 0.5 * scene->width) * size,
                   y = (0.5 * scene->height - (j + 0.5)) * sizeY;
            if (scene->bug == MIRRORED)
                x = -x;
            if (scene->bug == UPSIDE_DOWN)
                y = -y;
            V toScreen = {x, y, -scene->distance}; // the slide: from the pixel, normalised
            V c = Trace(scene, scene->eye + toScreen, Unit(toScreen), 0, 1);
            unsigned char *p = &pixels[3 * (j * scene->width + i)];
            p[0] = Byte(c.x, scene->bug), p[1] = Byte(c.y, scene->bug), p[2] = Byte(c.z, scene->bug);
        }
    return pixels;
}

int main(int argc, char **argv) {
    const char *scenePath = nullptr, *out = "out.png";
    Bug bug = BUG_COUNT;
    bool plane = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--triangle") == 0 && i + 1 < argc)
            plane = strcmp(argv[++i], "plane") == 0;
        else if (strcmp(argv[i], "--bug") == 0 && i + 1 < argc) {
            const char *name = argv[++i];
            for (int b = 0; b < BUG_COUNT; b++)
                if (strcmp(name, kBugs[b]) == 0)
                    bug = (Bug)b;
            if (bug == BUG_COUNT) {
                fprintf(stderr, "tiny: no bug named %s\n", name);
                return 2;
            }
        } else
            scenePath = argv[i];
    }
    Scene scene;
    if (!scenePath || !Read(scenePath, &scene)) {
        fprintf(stderr, "tiny: cannot read the scene\n");
        return 2;
    }
    scene.bug = bug == BUG_COUNT ? NONE : bug, scene.plane = plane;
    std::vector<unsigned char> pixels = Render(&scene);
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION, image.width = scene.width, image.height = scene.height;
    image.format = PNG_FORMAT_RGB;
    return png_image_write_to_file(&image, out, 0, pixels.data(), 0, nullptr) ? 0 : 1;
}
