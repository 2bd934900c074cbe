// app/probe.cpp -- the handout's debugging advice as a feature: fire one ray, read the hit.
//
// `--ray` and `--rays` print the nearest hit of a ray as one JSON line; `--pixel` prints the whole
// tree of rays behind one pixel. Numbers are printed in the shortest form that reads back
// exactly.
#include "app.h"

#include <cstdio>
#include <cstdlib>

// The shortest decimal that reads back as exactly v: `4.2`, not `4.2000000000000002` (at most 17
// significant digits for double, 9 for float). Every hit and ray is finite (the fuzz check holds
// them to it), but the output must be JSON whatever happens, so a NaN would print as 0 and an
// infinity as the largest finite number.
static std::string Number(real v) {
    if (v == 0 || std::isnan(v)) // -0 (a normal turned toward the ray) reads as 0
        v = 0;
    if (std::isinf(v))
        v = std::copysign(std::numeric_limits<real>::max(), v);
    char text[32];
    int digits = 1;
    for (; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, (double)v);
#ifdef RT_FLOAT
        if (strtof(text, nullptr) == v)
#else
        if (strtod(text, nullptr) == v)
#endif
            break;
    }
    // %g writes 20 as `2e+01` when one digit is enough. A whole number below 1e15 (float: 1e7)
    // is written out instead (`20`, `1000`): every whole number below 2^53 is a double (below
    // 2^24 a float), so a number whose shortest digits make such a whole number is exactly it,
    // and %.0f writes those same digits.
    const int kWholeDigits = sizeof(real) == sizeof(double) ? 15 : 7;
    if (v == 0) // (log10 of 0 is -infinity, which no int holds)
        return text;
    int exponent = (int)std::floor(std::log10(std::fabs((double)v)));
    if (digits <= exponent + 1 && exponent < kWholeDigits)
        snprintf(text, sizeof text, "%.0f", (double)v);
    return text;
}

static std::string Triple(vec3 v) {
    return "[" + Number(v.x) + "," + Number(v.y) + "," + Number(v.z) + "]";
}

// How many bytes of s, from `at`, make one well-formed UTF-8 character other than ASCII (RFC
// 3629: no overlong forms, no surrogates, nothing past U+10FFFF); 0 if they do not.
static size_t Utf8Length(const std::string &s, size_t at) {
    unsigned char c = (unsigned char)s[at];
    size_t length = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : 2;
    if (c < 0xc2 || c > 0xf4 || at + length > s.size())
        return 0;
    unsigned char next = (unsigned char)s[at + 1]; // the second byte's range depends on the first
    unsigned char low = c == 0xe0 ? 0xa0 : c == 0xf0 ? 0x90 : 0x80;
    unsigned char high = c == 0xed ? 0x9f : c == 0xf4 ? 0x8f : 0xbf;
    if (next < low || next > high)
        return 0;
    for (size_t k = 2; k < length; k++)
        if (((unsigned char)s[at + k] & 0xc0) != 0x80)
            return 0;
    return length;
}

// A JSON string (RFC 8259): quotes, backslashes and control characters escaped, well-formed
// UTF-8 (a material named `é`) passed through as it is, and any other byte, which no UTF-8
// reader could decode, written as U+FFFD, the replacement character: the output is always valid.
static std::string Quoted(const std::string &s) {
    std::string out = "\"";
    for (size_t i = 0; i < s.size(); i++) {
        unsigned char c = (unsigned char)s[i];
        size_t length = c >= 0x80 ? Utf8Length(s, i) : 1;
        if (c == '"' || c == '\\') {
            out += '\\';
            out += (char)c;
        } else if (c < 32 || c == 127) {
            char escape[8];
            snprintf(escape, sizeof escape, "\\u%04x", c);
            out += escape;
        } else if (length == 0) {
            out += "\\ufffd";
        } else {
            out += s.substr(i, length);
            i += length - 1;
        }
    }
    return out + "\"";
}

// A hit as JSON; on a smooth mesh's triangle, the normal that shading uses (SurfaceNormal) beside
// the geometric one, as "shading_normal".
static std::string HitJson(const Scene *scene, const RayHit *hit) {
    std::string shading = HasCornerNormals(scene, hit)
                              ? ",\"shading_normal\":" + Triple(SurfaceNormal(scene, hit))
                              : "";
    return "{\"hit\":true,\"t\":" + Number(hit->t) + ",\"point\":" + Triple(hit->point) +
           ",\"normal\":" + Triple(hit->normal) + shading +
           ",\"front\":" + (hit->frontFace ? "true" : "false") + ",\"shape\":\"" +
           (hit->shape == SHAPE_SPHERE ? "sphere" : "triangle") +
           "\",\"index\":" + std::to_string(hit->index) +
           ",\"material\":" + Quoted(scene->materials[hit->material].name) + "}";
}

bool ParseProbeLine(const std::string &line, Ray *ray, bool *blank, std::string *error) {
    std::vector<std::string> tokens;
    Tokenize(line, &tokens);
    *blank = tokens.empty();
    if (*blank)
        return true;
    if (tokens.size() != 6) {
        *error = "expected 6 numbers OX OY OZ DX DY DZ, found " + std::to_string(tokens.size()) +
                 (tokens.size() == 1 ? " value" : " values");
        return false;
    }
    real v[6];
    for (int k = 0; k < 6; k++)
        if (!ParseReal(tokens[k], &v[k], error))
            return false;
    ray->origin = {v[0], v[1], v[2]};
    ray->dir = {v[3], v[4], v[5]};
    if (ray->dir.x == 0 && ray->dir.y == 0 && ray->dir.z == 0) {
        *error = "direction is zero";
        return false;
    }
    return true;
}

std::string ProbeErrorJson(const std::string &message) {
    return "{\"error\":" + Quoted(message) + "}";
}

// The direction may be any finite size, 1e-310 or 1e300: the shape tests rescale it (see
// ScaleRay in geometry.cpp), so t is in units of the direction as given.
std::string ProbeRayJson(const Scene *scene, const RenderSettings *settings, const Ray *ray) {
    RayHit hit;
    if (!FindNearestHit(scene, settings->methods, ray, 0, kInfinity, &hit))
        return "{\"hit\":false}";
    return HitJson(scene, &hit);
}

// One node of the tree and, nested, every node whose parent it is.
static std::string NodeJson(const Scene *scene, const std::vector<RayNode> &tree, int index) {
    static const char *kKinds[] = {"primary", "shadow", "reflection", "refraction", "diffuse"};
    const RayNode &n = tree[index];
    std::string children;
    for (int k = index + 1; k < (int)tree.size(); k++)
        if (tree[k].parent == index)
            children += (children.empty() ? "" : ",") + NodeJson(scene, tree, k);
    return std::string("{\"kind\":\"") + kKinds[n.kind] + "\",\"origin\":" + Triple(n.ray.origin) +
           ",\"dir\":" + Triple(n.ray.dir) +
           ",\"hit\":" + (n.found ? HitJson(scene, &n.record) : "null") +
           ",\"color\":" + Triple(n.light) + ",\"children\":[" + children + "]}";
}

std::string PixelTreeJson(const Scene *scene, const RenderSettings *settings, int x, int y) {
    std::vector<RayNode> tree;
    TraceLog log = {RayStats{}, &tree, -1, 0};
    Ray ray;
    GetCameraRay(&settings->camera, settings->width, settings->height, SamplePosition(x, y, 0, 1),
                 &ray);
    color unused; // (under `shading path`, the centre's first path: sample 0)
    TraceEyeRays(scene, settings, &ray, 1, x, y, 0, &log, &unused);
    return NodeJson(scene, tree, 0);
}
