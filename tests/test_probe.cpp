// tests/test_probe.cpp -- the probes (--ray, --rays, --pixel), the debug views and --compare,
// each against hits and colours worked out by hand on the assignment scene.
#include "../app/app.h"
#include "test.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

// The number after `"key":` in a JSON line (the first occurrence at or after `from`).
static double JsonNumber(const std::string &json, const std::string &key, size_t from = 0) {
    size_t at = json.find("\"" + key + "\":", from);
    return at == std::string::npos ? NAN : strtod(json.c_str() + at + key.size() + 3, nullptr);
}

// The k-th number of the array after `"key":[`.
static double JsonArray(const std::string &json, const std::string &key, int k) {
    size_t at = json.find("\"" + key + "\":[");
    if (at == std::string::npos)
        return NAN;
    const char *p = json.c_str() + at + key.size() + 4;
    for (int i = 0; i < k; i++)
        p = strchr(p, ',') + 1;
    return strtod(p, nullptr);
}

static void TestProbeRays() {
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);

    // Straight ahead: the big mirror sphere (centre z = -16, radius 2) at t = 14, exactly
    Ray ahead = {{0, 0, 0}, {0, 0, -1}};
    CHECK(ProbeRayJson(&scene, &settings, &ahead) ==
              "{\"hit\":true,\"t\":14,\"point\":[0,0,-14],\"normal\":[0,0,1],\"front\":true,"
              "\"shape\":\"sphere\",\"index\":0,\"material\":\"mirror\"}",
          "probe straight ahead: sphere 0 at t = 14, the README's JSON exactly");

    // Down and ahead, d = (1, -1, -6): the floor y = -2 at t = 2, point (2, -2, -12); it lies
    // on the floor's second triangle (z = -12 is beyond the diagonal's -13.75 at x = 2)
    Ray down = {{0, 0, 0}, {1, -1, -6}};
    std::string j = ProbeRayJson(&scene, &settings, &down);
    CHECK_NEAR(JsonNumber(j, "t"), 2, 4 * kRelTol, "probe at the floor: t = 2");
    CHECK(std::fabs(JsonArray(j, "point", 0) - 2) < 1e-5 &&
              std::fabs(JsonArray(j, "point", 1) + 2) < 1e-5 &&
              std::fabs(JsonArray(j, "point", 2) + 12) < 1e-5,
          "probe at the floor: point (2, -2, -12)");
    CHECK(JsonArray(j, "normal", 1) == 1 &&
              j.find("\"front\":true,\"shape\":\"triangle\",\"index\":3,\"material\":\"white\"") !=
                  std::string::npos,
          "probe at the floor: triangle 3, white, normal (0, 1, 0), from the front: " + j);

    // t is in units of the direction as given: |d| = 1000 reaches the sphere at t = 0.014
    Ray scaled = {{0, 0, 0}, {0, 0, -1000}};
    CHECK_NEAR(JsonNumber(ProbeRayJson(&scene, &settings, &scaled), "t"), 0.014, 0.014 * kRelTol,
               "probe with |d| = 1000: t = 0.014");
    Ray up = {{0, 0, 0}, {0, 1, 0}};
    CHECK(ProbeRayJson(&scene, &settings, &up) == "{\"hit\":false}", "probe upward: no hit");

    // Whole numbers are written out: d = (0.1, 0.1, -1) meets the back wall z = -20 at t = 20,
    // the point (2, 2, -20); %g alone would write `2e+01`
    Ray wall = {{0, 0, 0}, {real(0.1), real(0.1), -1}};
    j = ProbeRayJson(&scene, &settings, &wall);
    CHECK(j.find("\"t\":20,\"point\":[2,2,-20]") != std::string::npos,
          "probe at the back wall: t = 20, point (2, 2, -20), written out: " + j);
}

// Material names are JSON strings: UTF-8 passes through, a byte no UTF-8 reader could decode
// becomes U+FFFD, a quote is escaped.
static void TestProbeNames() {
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);
    const char *names[][2] = {{"\xc3\xa9", "\"\xc3\xa9\""},                   // é, two bytes
                              {"\xe2\x82\xac", "\"\xe2\x82\xac\""},           // €, three bytes
                              {"a\xff\"", "\"a\\ufffd\\\"\""},                // not UTF-8; a quote
                              {"\xc3", "\"\\ufffd\""},                        // cut short
                              {"\xed\xa0\x80", "\"\\ufffd\\ufffd\\ufffd\""}}; // a surrogate
    Ray ahead = {{0, 0, 0}, {0, 0, -1}};
    for (auto &name : names) {
        scene.materials[scene.spheres[0].material].name = name[0];
        std::string j = ProbeRayJson(&scene, &settings, &ahead);
        CHECK(j.find(std::string("\"material\":") + name[1] + "}") != std::string::npos,
              std::string("probe names the material as the JSON string ") + name[1] + ": " + j);
    }
}

struct ProbeLineCase {
    const char *line;
    bool ok, blank;
    const char *message;
};

static const ProbeLineCase kProbeLines[] = {
    {"0 0 0 0 0 -1", true, false, ""},
    {"  1e0\t-2 +3  0 0 -1  # trailing comment\r", true, false, ""},
    {"", true, true, ""},
    {"   # only a comment", true, true, ""},
    {"1 2 3", false, false, "expected 6 numbers OX OY OZ DX DY DZ, found 3 values"},
    {"foo", false, false, "expected 6 numbers OX OY OZ DX DY DZ, found 1 value"},
    {"0 0 0 0 0 -1 7", false, false, "expected 6 numbers"},
    {"0 0 0 0 0 0", false, false, "direction is zero"},
    {"nan 0 0 0 0 1", false, false, "not a decimal number"},
    {"0 0 0 inf 0 1", false, false, "not a decimal number"},
    {"0 0 0 1e400 0 1", false, false, "out of range"},
};

static void TestProbeLines() {
    for (const ProbeLineCase &c : kProbeLines) {
        Ray ray;
        bool blank = false;
        std::string error;
        bool ok = ParseProbeLine(c.line, &ray, &blank, &error);
        CHECK(ok == c.ok && (!ok || blank == c.blank) &&
                  (ok || error.find(c.message) != std::string::npos),
              std::string("probe line `") + c.line + "`: " + (c.ok ? "read" : c.message));
    }
    CHECK(ProbeErrorJson("say \"hi\"\\") == "{\"error\":\"say \\\"hi\\\"\\\\\"}",
          "probe error JSON escapes quotes and backslashes");
}

// The ray tree of pixel (110, 330): a floor point in the red sphere's shadow, so the primary
// node has one child, a shadow ray blocked by sphere 2; pixel (300, 300) sees the big mirror,
// whose reflection ray hits the lit floor, whose shadow ray reaches the light.
static void TestPixelTrees() {
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);
    std::string shadowed = PixelTreeJson(&scene, &settings, 110, 330);
    CHECK(shadowed.rfind("{\"kind\":\"primary\",\"origin\":[0,0,0]", 0) == 0 &&
              shadowed.find("\"material\":\"white\"") != std::string::npos &&
              shadowed.find("\"children\":[{\"kind\":\"shadow\"") != std::string::npos &&
              shadowed.find("\"shape\":\"sphere\",\"index\":2,\"material\":\"red\"") !=
                  std::string::npos,
          "pixel (110, 330): primary on the floor, shadow ray blocked by the red sphere");
    CHECK_NEAR(JsonArray(shadowed, "color", 0), 0.2, kRelTol,
               "pixel (110, 330): the tree's colour is the ambient floor 0.2");

    std::string mirror = PixelTreeJson(&scene, &settings, 300, 300);
    size_t reflection = mirror.find("\"kind\":\"reflection\"");
    size_t shadow = mirror.find("\"kind\":\"shadow\"");
    CHECK(reflection != std::string::npos && shadow > reflection &&
              mirror.find("\"hit\":null,\"color\":[1,1,1]") != std::string::npos,
          "pixel (300, 300): mirror -> reflection -> floor -> unblocked shadow ray (light 1 1 1)");
}

static void TestViews() {
    Scene scene;
    BuildDefaultScene(&scene);
    RenderSettings settings = TestSettings(&scene);
    Image image;
    auto pixel = [&image](int i, int j, int c) { return image.pixels[(j * 512 + i) * 3 + c]; };
    ViewKind view;
    CHECK(FindView("normal", &view) && view == VIEW_NORMAL && !FindView("normals", &view),
          "views are found by their exact names");

    // Normal view: the back wall's normal (0, 0, 1) is drawn (0.5, 0.5, 1) -> (128, 128, 255)
    RayStats stats = {};
    RenderView(&scene, &settings, VIEW_NORMAL, &image, &stats);
    CHECK(stats.primary == 512 * 512 && stats.shadow == 0 && stats.reflection == 0,
          "normal view: one primary ray a pixel, counted, and nothing else");
    CHECK(pixel(256, 100, 0) == 128 && pixel(256, 100, 1) == 128 && pixel(256, 100, 2) == 255,
          "normal view: the back wall is (128, 128, 255)");
    CHECK(pixel(256, 500, 0) == 0 && pixel(256, 500, 2) == 0, "normal view: a miss is black");

    // Shadow view: (110, 330) is blocked (red), (256, 330) is lit (white)
    stats = {};
    RenderView(&scene, &settings, VIEW_SHADOW, &image, &stats);
    CHECK(stats.primary == 512 * 512 && stats.shadow > 0 && stats.shadow < stats.primary,
          "shadow view: a primary ray a pixel, a shadow ray for each hit facing the light");
    CHECK(pixel(110, 330, 0) == 255 && pixel(110, 330, 1) == 0, "shadow view: blocked is red");
    CHECK(pixel(256, 330, 0) == 255 && pixel(256, 330, 1) == 255 && pixel(256, 330, 2) == 255,
          "shadow view: lit is white");

    // Two lights: at (110, 330) the red sphere's shadow from light 1; a second light far to the
    // left, which lights that floor point, puts light 1 in red (0.45: blocked) and light 2 in
    // green (1: lit)
    Scene two = scene;
    two.lights.push_back({{-30, 5, -15}, {1, 1, 1}});
    RenderSettings twoSettings = TestSettings(&two);
    RenderView(&two, &twoSettings, VIEW_SHADOW, &image, &stats);
    CHECK(pixel(110, 330, 0) == 115 && pixel(110, 330, 1) == 255 && pixel(110, 330, 2) == 0,
          "shadow view, two lights: blocked from the first (red 0.45), lit by the second (green)");
    CHECK(pixel(256, 330, 0) == 255 && pixel(256, 330, 1) == 115 && pixel(256, 330, 2) == 0,
          "and at (256, 330) the other way round: lit by the first, the second hidden by the "
          "big sphere: another colour");

    // Depth view: the floor's front edge (nearest) is brighter than the back wall
    RenderView(&scene, &settings, VIEW_DEPTH, &image, &stats);
    CHECK(pixel(256, 350, 0) > pixel(256, 100, 0) && pixel(256, 100, 0) > 0,
          "depth view: the near floor is brighter than the far wall");

    // Object id: the two floor triangles and the spheres get different colours
    RenderView(&scene, &settings, VIEW_ID, &image, &stats);
    CHECK(memcmp(&image.pixels[(330 * 512 + 110) * 3], &image.pixels[(100 * 512 + 256) * 3], 3) !=
              0,
          "id view: the floor and the back wall differ");

    // Cost: a lit floor pixel costs 2 rays (primary, shadow), the mirror reflecting the lit
    // floor 3 (primary, reflection, shadow), so it is drawn hotter
    stats = {};
    RenderView(&scene, &settings, VIEW_COST, &image, &stats);
    CHECK(pixel(300, 300, 1) > pixel(256, 330, 1), "cost view: a reflected pixel costs more");
    // and its rays are the render's own: the same counts as the lit image at one sample a pixel
    Image lit;
    RayStats rendered = {};
    Render(&scene, &settings, &lit, &rendered);
    CHECK(stats.primary == rendered.primary && stats.shadow == rendered.shadow &&
              stats.reflection == rendered.reflection && stats.refraction == rendered.refraction,
          "cost view: it counts the rays the lit image casts, kind by kind");
}

static void TestCompare() {
    // Two 2 x 1 images differing in one channel by 3: RMSE = sqrt(9 / 6) = 1.2247, PSNR =
    // 20 log10(255 / 1.2247) = 46.37 dB, largest 3, one pixel over tolerance 2, none over 3
    Image a = {2, 1, {0, 0, 0, 10, 10, 10}}, b = {2, 1, {3, 0, 0, 10, 10, 10}}, heat;
    ImageDifference d;
    CHECK(CompareImages(&a, &b, 2, &d, &heat), "compare: same size");
    CHECK_NEAR(d.rmse, std::sqrt(1.5), 1e-12, "compare: RMSE sqrt(9/6)");
    CHECK_NEAR(d.psnr, 20 * std::log10(255 / std::sqrt(1.5)), 1e-9, "compare: PSNR 46.37 dB");
    CHECK(d.largest == 3 && d.pixelsOver == 1, "compare: largest 3, one pixel over 2");
    CHECK(heat.pixels[0] > 0 && heat.pixels[3] == 0, "compare: the heat map marks the pixel");
    CompareImages(&a, &b, 3, &d, &heat);
    CHECK(d.pixelsOver == 0, "compare: within tolerance 3");
    CompareImages(&a, &a, 0, &d, &heat);
    CHECK(d.rmse == 0 && std::isinf(d.psnr) && d.largest == 0, "compare: identical images");
    Image c = {1, 1, {0, 0, 0}};
    CHECK(!CompareImages(&a, &c, 0, &d, &heat), "compare: different sizes are refused");
}

// One line of the program's standard output, waiting at most `seconds` for it; "" if none came.
static std::string ReadLineWithin(int fd, double seconds) {
    std::string line;
    char c;
    while (line.empty() || line.back() != '\n') {
        pollfd p = {fd, POLLIN, 0};
        if (poll(&p, 1, (int)(seconds * 1000)) <= 0 || read(fd, &c, 1) != 1)
            return "";
        line += c;
    }
    return line;
}

// `--rays -` as a conversation: a program writes one probe line into a pipe and waits for its
// answer before it writes the next. Each answer must come while the input is still open.
static void TestProbeConversation() {
    int in[2], out[2];
    CHECK(pipe(in) == 0 && pipe(out) == 0, "two pipes for a conversation with ray");
    pid_t child = fork();
    if (child == 0) {
        dup2(in[0], 0), dup2(out[1], 1);
        close(in[1]), close(out[0]);
        std::string program = RayProgram();
        execl(program.c_str(), program.c_str(), "--rays", "-", (char *)nullptr);
        _exit(127);
    }
    close(in[0]), close(out[1]);
    std::string answers[2];
    const char *probes[2] = {"0 0 0 0 0 -1\n", "0 0 0 0 1 0\n"};
    for (int k = 0; k < 2 && (k == 0 || !answers[0].empty()); k++) {
        bool written = write(in[1], probes[k], strlen(probes[k])) == (ssize_t)strlen(probes[k]);
        answers[k] = written ? ReadLineWithin(out[0], 10) : "";
    }
    close(in[1]);
    int status = 0;
    if (answers[0].empty())
        kill(child, SIGKILL);
    waitpid(child, &status, 0);
    close(out[0]);
    CHECK(answers[0].find("\"t\":14") != std::string::npos && answers[1] == "{\"hit\":false}\n",
          "--rays - answers each line as it is read, before its input ends (got '" + answers[0] +
              "' and '" + answers[1] + "')");
}

void TestProbes() {
    TestProbeConversation();
    TestProbeRays();
    TestProbeNames();
    TestProbeLines();
    TestPixelTrees();
    TestViews();
    TestCompare();
}
