// student.cpp -- a plain float student solution of the ray-tracing assignment. NOT part of rt.
//
// Why it exists: rt's speed is measured against what a student would write, a plain float
// solution built -O2. This file is that baseline, written the way a careful student writes the
// assignment: the handout's formulas (GetRay, the textbook sphere quadratic with A, B, C,
// Cramer's rule for triangles with the variables A..M), the nearest hit over a list of shapes,
// diffuse shading with an ambient floor, hard shadows with an epsilon offset, perfect mirrors,
// at most 10 rays in a chain, black on a miss; `float` everywhere, one thread, no tricks and no
// hand optimisation.
// It draws the same image as `./ray -o x.png --spp 16`: the assignment scene (scene_default.cpp,
// hard-coded here as a student's main builds it), 512 x 512, 16 samples per pixel at the centres
// of a regular 4 x 4 grid in each pixel (rt's default `--aa grid`), written with libpng's default
// compression. The differences from rt: float instead of double, the handout's methods instead of
// rt's robust ones, a fixed offset of 1e-4 along the normal (rt's `--self-hit epsilon` value)
// instead of rt's error bounds. Samples that graze a shadow edge or a mirror's silhouette can come
// out the other way: about 20 pixels of the 262,144 differ by more than 2/255.
//
// Build: g++ -O2 -std=c++17 bench/student.cpp -o build/student $(pkg-config --cflags --libs libpng)
//        (or `make build/student`)
// Usage: build/student OUT.png [SPP]     SPP: samples per pixel, a square (default 16)
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

struct Vec3 {
    float x, y, z;
};
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(float s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; } // colours
float Dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 Cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3 Normalize(Vec3 a) { return (1 / std::sqrt(Dot(a, a))) * a; }

struct Ray {
    Vec3 origin, dir;
};
struct Material {
    Vec3 diffuse;
    float mirror; // K: the reflected share of the colour
};
struct Sphere {
    Vec3 center;
    float radius;
    int material;
};
struct Triangle {
    Vec3 a, b, c;
    int material;
};
struct Light {
    Vec3 position, intensity;
};
struct Hit {
    float t;
    Vec3 point, normal; // unit normal, turned toward the ray's origin
    int material;
};
struct Scene {
    std::vector<Material> materials;
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    std::vector<Light> lights;
    float ambient;
    int maxDepth; // most rays in one chain, the primary ray included
};

// How far a shadow or mirror ray starts off the surface, against shadow acne. Float points here
// are good to about 1e-5 (1e-5 shows acne); 1e-3 also works but moves shadow edges visibly.
const float kEpsilon = 1e-4f;

// The handout's sphere: A t^2 + B t + C = 0, the nearest root in (tMin, tMax).
bool IntersectSphere(const Sphere &s, const Ray &ray, float tMin, float tMax, Hit *hit) {
    Vec3 oc = ray.origin - s.center;
    float A = Dot(ray.dir, ray.dir);
    float B = 2 * Dot(ray.dir, oc);
    float C = Dot(oc, oc) - s.radius * s.radius;
    float discriminant = B * B - 4 * A * C;
    if (discriminant < 0)
        return false;
    float t = (-B - std::sqrt(discriminant)) / (2 * A);
    if (t <= tMin)
        t = (-B + std::sqrt(discriminant)) / (2 * A);
    if (t <= tMin || t >= tMax)
        return false;
    hit->t = t;
    hit->point = ray.origin + t * ray.dir;
    hit->normal = (1 / s.radius) * (hit->point - s.center);
    hit->material = s.material;
    return true;
}

// The handout's triangle: a + beta (b - a) + gamma (c - a) = e + t d by Cramer's rule.
bool IntersectTriangle(const Triangle &tri, const Ray &ray, float tMin, float tMax, Hit *hit) {
    Vec3 a = tri.a, b = tri.b, c = tri.c, e = ray.origin, d = ray.dir;
    float A = a.x - b.x, B = a.y - b.y, C = a.z - b.z;
    float D = a.x - c.x, E = a.y - c.y, F = a.z - c.z;
    float G = d.x, H = d.y, I = d.z;
    float J = a.x - e.x, K = a.y - e.y, L = a.z - e.z;
    float EIHF = E * I - H * F, GFDI = G * F - D * I, DHEG = D * H - E * G;
    float M = A * EIHF + B * GFDI + C * DHEG;
    if (M == 0)
        return false; // the ray is parallel to the triangle
    float AKJB = A * K - J * B, JCAL = J * C - A * L, BLKC = B * L - K * C;
    float t = -(F * AKJB + E * JCAL + D * BLKC) / M;
    if (t <= tMin || t >= tMax)
        return false;
    float gamma = (I * AKJB + H * JCAL + G * BLKC) / M;
    if (gamma < 0 || gamma > 1)
        return false;
    float beta = (J * EIHF + K * GFDI + L * DHEG) / M;
    if (beta < 0 || beta > 1 - gamma)
        return false;
    hit->t = t;
    hit->point = ray.origin + t * ray.dir;
    hit->normal = Normalize(Cross(b - a, c - a));
    hit->material = tri.material;
    return true;
}

// The nearest hit over the list of shapes, with t in (tMin, tMax).
bool FindNearestHit(const Scene &scene, const Ray &ray, float tMin, float tMax, Hit *hit) {
    bool found = false;
    for (const Sphere &s : scene.spheres)
        if (IntersectSphere(s, ray, tMin, tMax, hit)) {
            tMax = hit->t;
            found = true;
        }
    for (const Triangle &tri : scene.triangles)
        if (IntersectTriangle(tri, ray, tMin, tMax, hit)) {
            tMax = hit->t;
            found = true;
        }
    if (found && Dot(hit->normal, ray.dir) > 0)
        hit->normal = -1 * hit->normal; // turn it toward the viewer
    return found;
}

// The colour a ray brings back; depth counts the rays in the chain so far (primary = 1).
Vec3 Trace(const Scene &scene, const Ray &ray, int depth) {
    Hit hit;
    if (!FindNearestHit(scene, ray, 0, INFINITY, &hit))
        return {0, 0, 0}; // black background
    const Material &m = scene.materials[hit.material];
    Vec3 start = hit.point + kEpsilon * hit.normal; // off the surface, on the viewer's side
    Vec3 result = {0, 0, 0};
    if (m.mirror < 1) {
        // Diffuse with an ambient floor: kd * max(ambient, sum of I (N.L) over visible lights)
        Vec3 sum = {0, 0, 0};
        for (const Light &light : scene.lights) {
            Vec3 toLight = light.position - hit.point;
            float distance = std::sqrt(Dot(toLight, toLight));
            Vec3 L = (1 / distance) * toLight;
            float nDotL = Dot(hit.normal, L);
            if (nDotL <= 0)
                continue; // the light is behind the surface
            Ray shadow = {start, L};
            Hit blocker;
            if (FindNearestHit(scene, shadow, 0, distance, &blocker))
                continue; // in shadow
            sum = sum + nDotL * light.intensity;
        }
        Vec3 lit = {std::fmax(scene.ambient, sum.x), std::fmax(scene.ambient, sum.y),
                    std::fmax(scene.ambient, sum.z)};
        result = (1 - m.mirror) * (m.diffuse * lit);
    }
    if (m.mirror > 0 && depth < scene.maxDepth) {
        Vec3 r = ray.dir - (2 * Dot(ray.dir, hit.normal)) * hit.normal; // r = d - 2 (d.N) N
        result = result + m.mirror * Trace(scene, Ray{start, Normalize(r)}, depth + 1);
    }
    return result;
}

unsigned char ToByte(float c) {
    if (!(c > 0))
        return 0;
    if (c >= 1)
        return 255;
    return (unsigned char)std::lround(c * 255);
}

bool WritePng(const char *path, int width, int height, const std::vector<unsigned char> &rgb) {
    FILE *file = fopen(path, "wb");
    if (!file)
        return false;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(file);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; y++)
        png_write_row(png, &rgb[(size_t)y * width * 3]);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return fclose(file) == 0;
}

int main(int argc, char **argv) {
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: student OUT.png [SPP]\n");
        return 2;
    }
    int spp = argc == 3 ? atoi(argv[2]) : 16;
    int grid = (int)std::sqrt((float)spp); // samples on a grid x grid raster in each pixel
    if (spp < 1 || grid * grid != spp) {
        fprintf(stderr, "student: SPP must be a square (1, 4, 9, 16, ...)\n");
        return 2;
    }

    // The assignment scene (scene_default.cpp)
    Scene scene;
    enum { MIRROR, RED, BLUE, WHITE };
    scene.materials = {{{1, 1, 1}, 1}, {{1, 0, 0}, 0}, {{0, 0, 1}, 0}, {{1, 1, 1}, 0}};
    scene.spheres = {{{0, 0, -16}, 2, MIRROR}, {{3, -1, -14}, 1, MIRROR}, {{-3, -1, -14}, 1, RED}};
    scene.triangles = {
        {{-8, -2, -20}, {8, -2, -20}, {8, 10, -20}, BLUE},   // back wall
        {{-8, -2, -20}, {8, 10, -20}, {-8, 10, -20}, BLUE},  // back wall
        {{-8, -2, -20}, {8, -2, -10}, {8, -2, -20}, WHITE},  // floor
        {{-8, -2, -20}, {-8, -2, -10}, {8, -2, -10}, WHITE}, // floor
        {{8, -2, -20}, {8, -2, -10}, {8, 10, -20}, RED},     // right wall
    };
    scene.lights = {{{3, 5, -15}, {1, 1, 1}}};
    scene.ambient = 0.2f;
    scene.maxDepth = 10;

    // The handout's Perspective camera: eye at the origin, screen 2 wide at distance 2
    const int width = 512, height = 512;
    const Vec3 eye = {0, 0, 0};
    const float distance = 2, screenWidth = 2, pixelSize = screenWidth / width;

    std::vector<unsigned char> rgb((size_t)width * height * 3);
    for (int j = 0; j < height; j++) {
        for (int i = 0; i < width; i++) {
            Vec3 sum = {0, 0, 0};
            for (int sy = 0; sy < grid; sy++) {
                for (int sx = 0; sx < grid; sx++) {
                    // GetRay: the sample's point on the screen, and the unit vector to it
                    float px = i + (sx + 0.5f) / grid, py = j + (sy + 0.5f) / grid;
                    Vec3 pixel = {eye.x + (px - 0.5f * width) * pixelSize,
                                  eye.y + (0.5f * height - py) * pixelSize, eye.z - distance};
                    Ray ray = {pixel, Normalize(pixel - eye)};
                    sum = sum + Trace(scene, ray, 1);
                }
            }
            Vec3 c = (1.0f / spp) * sum;
            unsigned char *out = &rgb[((size_t)j * width + i) * 3];
            out[0] = ToByte(c.x);
            out[1] = ToByte(c.y);
            out[2] = ToByte(c.z);
        }
    }
    if (!WritePng(argv[1], width, height, rgb)) {
        fprintf(stderr, "student: cannot write %s\n", argv[1]);
        return 3;
    }
    return 0;
}
