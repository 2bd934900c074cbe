// tests/test_program.cpp -- the program from the outside, as the README describes it.
//
// Runs ./ray (or $RAY) in a fresh temporary directory: the default output name, the PNG's size
// and format, identical bytes for any thread count, the --stats lines, and bad input: exit
// status 2 (3 for I/O), one `ray: ` line, and no output file touched.
#include "../app/app.h"
#include "test.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <vector>

std::string ReadFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool FileExists(const std::string &path) { return std::ifstream(path).good(); }

std::string RayPath() {
    std::string program = RayProgram();
    if (program[0] != '/') {
        char *cwd = realpath(".", nullptr);
        program = std::string(cwd) + "/" + program;
        free(cwd);
    }
    return program;
}

int RunRayAfter(const std::string &dir, const std::string &pipe, const std::string &args,
                std::string *stderrText) {
    std::string command =
        "cd '" + dir + "' && " + pipe + " '" + RayPath() + "' " + args + " >out.txt 2>err.txt";
    int status = system(command.c_str());
    *stderrText = ReadFile(dir + "/err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int RunRay(const std::string &dir, const std::string &args, std::string *stderrText) {
    return RunRayAfter(dir, "", args, stderrText);
}

// A render that asks for more threads than the system gives (here 1,024 under a limit of 400 MB
// of address space, where each thread's stack of 8 MB alone needs 8 GB) goes on with those it has:
// the same bytes as one thread, no abort. (Not under the address sanitizer, whose own
// reservations no such limit allows.)
#if defined(__SANITIZE_ADDRESS__)
#define RT_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_ADDRESS_SANITIZER 1
#endif
#endif
static void TestThreadsRefused(const std::string &dir) {
#ifndef RT_ADDRESS_SANITIZER
    std::string err;
    int one = RunRay(dir, "--threads 1 --size 8x1024 -o one.png", &err);
    int many = RunRayAfter(dir, "ulimit -s 8192 && ulimit -v 400000 &&",
                           "--threads 1024 --size 8x1024 -o many.png", &err);
    CHECK(one == 0 && many == 0 && ReadFile(dir + "/many.png") == ReadFile(dir + "/one.png"),
          "--threads 1024 under a 400 MB limit: the threads there are, the same bytes (" + err +
              ")");
#else
    (void)dir;
#endif
}

static void TestDefaultRun(const std::string &dir) {
    std::string err;
    int status = RunRay(dir, "--threads 1 --stats", &err);
    CHECK(status == 0, "`ray` with no scene exits 0");
    Image image;
    std::string readError;
    bool read = ReadImage((dir + "/reference.png").c_str(), &image, &readError);
    CHECK(read && image.width == 512 && image.height == 512,
          "`ray` writes reference.png, a 512 x 512 PNG");
    // The floor pixel in the red sphere's shadow, read back from the file: 0.2 * 255 = 51
    CHECK(read && image.pixels[(330 * 512 + 110) * 3] == 51,
          "reference.png: pixel (110, 330) is 51");
    std::string header = ReadFile(dir + "/reference.png").substr(0, 26);
    CHECK(header.size() == 26 && header.compare(1, 3, "PNG") == 0 && header[24] == 8 &&
              header[25] == 2,
          "reference.png is an 8-bit RGB PNG (IHDR bit depth 8, colour type 2)");
    CHECK(err.find("\nrays: primary=262144 shadow=") != std::string::npos &&
              err.find(" refraction=0 diffuse=0 total=") != std::string::npos,
          "--stats prints the rays: line as docs/command-line.md shows it");
    CHECK(err.find("\neffects: shadows reflection\n") != std::string::npos,
          "--stats: the assignment scene uses shadows and reflection, nothing else");
    CHECK(err.find("image: 512x512, 1 spp, depth 10, 1 thread\n") != std::string::npos,
          "--stats --threads 1: 'image: 512x512, 1 spp, depth 10, 1 thread'");
    status = RunRay(dir, "--threads 8 --size 6x3 --stats -o rows.png", &err);
    CHECK(status == 0 && err.find("image: 6x3, 1 spp, depth 10, 3 threads\n") != std::string::npos,
          "--stats says the threads that rendered: 3 for 3 rows, though --threads 8 (" + err + ")");

    std::string oneThread = ReadFile(dir + "/reference.png");
    status = RunRay(dir, "--threads 2 -o two.png", &err);
    CHECK(status == 0 && ReadFile(dir + "/two.png") == oneThread,
          "--threads 1 and --threads 2 write identical bytes");
    TestThreadsRefused(dir);
    status = RunRay(dir, "test --size 32x16 --spp 4 --depth 3", &err);
    Image test;
    CHECK(status == 0 && ReadImage((dir + "/test.png").c_str(), &test, &readError) &&
              test.width == 32 && test.height == 16,
          "`ray test --size 32x16` writes test.png, 32 wide and 16 high");
}

struct BadRun {
    const char *args;
    int status;
    const char *message; // a piece of the one error line
};

static const BadRun kBadRuns[] = {
    {"--bogus", 2, "unknown option"},
    {"--size=64", 2, "unknown option '--size=64': write '--size 64'"},
    {"--thread 2", 2, "unknown option '--thread': did you mean '--threads'? (see ray --help)"},
    {"--szie 8", 2, "unknown option '--szie': did you mean '--size'?"},
    {"--vie normal", 2, "did you mean '--view'?"},
    {"-size 8", 2, "unknown option '-size': did you mean '--size'?"}, // (one dash short)
    {"---threads 2", 2, "did you mean '--threads'?"},
    {"--o x.png", 2, "did you mean '-o'?"},
    {"--ray=0", 2, "write '--ray' and then its values, each a word of its own"},
    {"--stats=1", 2, "write '--stats' alone: it takes no value"},
    {"--size", 2, "needs 1 value"},
    {"--size 0", 2, "between 1 and 16384"},
    {"--size 16385", 2, "between 1 and 16384"},
    {"--size 12x", 2, "not a whole number"},
    {"--spp 0", 2, "between 1 and 65536"},
    {"--spp nan", 2, "not a whole number"},
    {"--depth 1001", 2, "between 1 and 1000"},
    {"--threads 0", 2, "between 1 and 1024"},
    {"--threads 2.5", 2, "not a whole number"},
    {"--triangle moller", 2, "watertight, cramer or plane"},
    {"--methods student", 2, "robust or handout"},
    {"--self-hit epsilon=0", 2, "E must be a distance > 0"},
    {"--self-hit epsilon=abc", 2, "E must be a distance > 0"},
    {"--self-hit skip=1", 2, "only epsilon takes a value"},
    {"--self-hit nudge", 2, "bound, epsilon or skip"},
    {"--fresnel fast", 2, "exact or schlick"},
    {"default test", 2, "more than one scene"},
    {"nosuchscene", 2,
     "nosuchscene: No such file or directory (nor is it a built-in scene: those "
     "are default and test)"},
    {"-o missing_dir/x.png", 3, "missing_dir/x.png"},
    {"--size 8 --size 9", 2, "--size given twice"},
    {"--tolerance 2", 2, "--tolerance goes with --compare"},
    {"--aa jitter", 2, "--aa changes nothing with one sample a pixel"},
    {"--methods handout --layout bvh", 2, "--layout auto, list and bvh go with the robust"},
    {"--sphere textbook --layout list", 2, "go with the robust sphere and triangle tests"},
};

static void TestBadInput(const std::string &dir) {
    // An existing output file must survive every failed run byte for byte
    std::string keep = "precious bytes\n";
    std::ofstream(dir + "/keep.png") << keep;
    for (const BadRun &bad : kBadRuns) {
        std::string err;
        std::string args = std::string(bad.args);
        if (args.find("-o ") == std::string::npos)
            args = "-o keep.png " + args;
        int status = RunRay(dir, args, &err);
        std::string name = std::string("`ray ") + bad.args + "`";
        CHECK(status == bad.status, name + ": exit status " + std::to_string(bad.status) +
                                        " (got " + std::to_string(status) + ")");
        bool oneLine = err.compare(0, 5, "ray: ") == 0 && err.find('\n') == err.size() - 1;
        CHECK(oneLine && err.find(bad.message) != std::string::npos,
              name + ": one line `ray: ...` naming the problem (got: " + err + ")");
        CHECK(ReadFile(dir + "/keep.png") == keep, name + ": the existing output is untouched");
    }
    std::string err;
    // Options that would change nothing in the mode chosen are errors
    const char *unused[][2] = {
        {"--ray 0 0 0 0 0 -1 --spp 4", "--spp changes nothing with --ray"},
        {"--pixel 1 1 --aa jitter", "--aa changes nothing with --pixel"},
        {"--compare a.png b.png --size 10", "--size changes nothing"},
        {"--view cost --spp 4", "--spp changes nothing with --view"},
        {"--ray 0 0 0 0 0 -1 --fresnel schlick", "--fresnel changes nothing with --ray"},
        {"--ray 0 0 0 0 0 -1 --camera-ray slides", "--camera-ray changes nothing with --ray"},
        {"--view normal --self-hit skip", "--self-hit changes nothing with --view normal"},
        {"--view shadow --fresnel schlick", "--fresnel changes nothing with --view shadow"},
        {"--view id --depth 3", "--depth changes nothing with --view normal, depth or id"},
        {"--view shadow --depth 3", "--depth changes nothing with --view shadow"},
        {"--compare a.png b.png my.scene", "changes nothing with --compare"}};
    for (auto &u : unused)
        CHECK(RunRay(dir, u[0], &err) == 2 && err.find(u[1]) != std::string::npos,
              std::string("`ray ") + u[0] + "`: exit 2, \"" + u[1] + "\"");
    CHECK(RunRay(dir, "--spp 0 -o fresh.png", &err) == 2 && !FileExists(dir + "/fresh.png"),
          "a failed run creates no output file");
    CHECK(RunRay(dir, "--help", &err) == 0 &&
              ReadFile(dir + "/out.txt").find("--threads") != std::string::npos,
          "--help exits 0 and lists the options");
    CHECK(RunRay(dir, "--version", &err) == 0 && ReadFile(dir + "/out.txt").rfind("rt ", 0) == 0,
          "--version exits 0 and names rt");
}

// A screen camera keeps its shape: a --size of another shape would stretch the pixels, and is
// refused with the size that fits; the scene's own size is warned of.
static void TestScreenCameraSizes(const std::string &dir) {
    std::string err;
    CHECK(SquarePixels(8, 8, 1e308, 1e308) && !SquarePixels(8, 8, 1e308, 5e307) &&
              SquarePixels(8, 4, 1e-310, 5e-311),
          "square pixels judged for edges of 1e308 (8 x 8 times 1e308 would overflow) and 1e-310");
    // A screen camera keeps its shape: a --size of another shape would stretch the pixels
    char cwd[4096];
    std::string handout2 =
        std::string(getcwd(cwd, sizeof cwd) ? cwd : ".") + "/scenes/handout2.scene";
    CHECK(RunRay(dir, handout2 + " --size 300x300 -o sq.png", &err) == 2 &&
              err.find("--size 300x225 keeps them square") != std::string::npos,
          "a 4 x 3 screen camera at --size 300x300: refused, with the size that keeps it");
    CHECK(RunRay(dir, handout2 + " --size 80x60 -o ok.png", &err) == 0,
          "and at --size 80x60, its own shape, rendered");
    // A 3 x 1 screen 100 pixels wide would need 33.3 rows: the size named is the nearest that
    // fits, and renders
    std::ofstream(dir + "/wide.scene")
        << "camera screen 0 0 0 -1.5 -0.5 -1 3 0 0 0 1 0\nsize 102 34\n";
    CHECK(RunRay(dir, "wide.scene --size 100x33 -o w.png", &err) == 2 &&
              err.find("--size 99x33 keeps them square") != std::string::npos &&
              RunRay(dir, "wide.scene --size 99x33 -o w.png", &err) == 0,
          "a 3 x 1 screen at --size 100x33: refused, and the size it names, 99x33, rendered");
    CHECK(RunRay(dir, handout2 + " --size 33x24 -o near.png", &err) == 2 &&
              err.find("--size 32x24 keeps them square") != std::string::npos,
          "a 4 x 3 screen camera at --size 33x24: the nearest size that fits, 32x24, named");
    // A screen 16400 times as tall as wide: 16384 rows, the limit, are within 1 part in 256
    std::ofstream(dir + "/tall.scene") << "camera screen 0 0 0 -0.5 -8200 -1 1 0 0 0 16400 0\n";
    CHECK(RunRay(dir, "tall.scene --size 1x100 -o t.png", &err) == 2 &&
              err.find("--size 1x16384 keeps them square") != std::string::npos &&
              RunRay(dir, "tall.scene --size 1x16384 -o t.png", &err) == 0,
          "a 1 x 16400 screen at --size 1x100: the size at the limit, 1x16384, named and rendered");
    // A screen no size can fit (2 x 1e-6): --size is warned of, not refused, or no size would do
    std::ofstream(dir + "/slit.scene") << "camera screen 0 0 0 -1 0 -1 2 0 0 0 1e-6 0\nsize 8 8\n";
    CHECK(RunRay(dir, "slit.scene --size 16x4 -o slit.png", &err) == 0 &&
              err.find("warning: --size 16x4: the scene's screen camera is 2 x 1e-06") !=
                  std::string::npos &&
              err.find("no size up to 16384 x 16384 keeps them square") != std::string::npos,
          "a 2 x 1e-6 screen at --size 16x4: rendered, warned that no size fits (" + err + ")");
    // A sheared screen's pixels are parallelograms: a size can make their sides equal, not square
    std::ofstream(dir + "/sheared.scene") << "camera screen 0 0 0 -1 -1 -1 2 0 0 1 2 0\n";
    CHECK(RunRay(dir, "sheared.scene --size 64x64 -o sh.png", &err) == 2 &&
              err.find("not be equal-sided (the screen is sheared: they are parallelograms)") !=
                  std::string::npos &&
              err.find("keeps them equal-sided") != std::string::npos,
          "a sheared screen at a size of another shape: refused, its pixels not called square (" +
              err + ")");
    // The scene's own size is the scene's to choose: rendered, with a warning
    std::ofstream(dir + "/stretched.scene")
        << "camera screen 0 0 0 -2 -1.5 -1 4 0 0 0 3 0\nsize 512 512\n";
    CHECK(RunRay(dir, "stretched.scene -o s.png", &err) == 0 &&
              err.find("warning: the scene's screen camera is 4 x 3 and its image 512 x 512") !=
                  std::string::npos &&
              err.find("`size 512 384` keeps them square") != std::string::npos,
          "a 4 x 3 screen camera at the default 512 x 512: rendered, with a warning naming a size");
    CHECK(RunRay(dir, "stretched.scene --ray 0 0 0 0 0 -1", &err) == 0 && err.empty(),
          "and probed with --ray, which draws no image: no warning (" + err + ")");
}

// Warnings for what a render would hide: a light or the eye inside a sphere, a scene that can
// only be one colour. Probes and views draw no lit image, and are not warned.
static void TestHiddenWarnings(const std::string &dir) {
    std::string err;
    // What a render would hide without a word: a light inside a sphere lights nothing outside
    // it, and an eye inside a (not glass) sphere sees only its inside. Probes say nothing.
    std::ofstream(dir + "/inside.scene") << "size 8 8\nmaterial m\nmaterial g glass 1.5\n"
                                            "sphere 0 0 0 2 m\nlight 0 0 -5\nsphere 0 0 -5 1 m\n"
                                            "light 9 0 -5\nsphere 9 0 -5 1 g\n";
    CHECK(RunRay(dir, "inside.scene -o in.png", &err) == 0 &&
              err == "ray: warning: the light at (0 0 -5) is inside the sphere at (0 0 -5) of "
                     "radius 1: its shadow rays end on that sphere, so nothing outside it is lit "
                     "by that light\nray: warning: the light at (9 0 -5) is inside the sphere at "
                     "(9 0 -5) of radius 1: its shadow rays end on that sphere, so nothing outside "
                     "it is lit by that light\nray: warning: the eye rays start at (0 0 0), inside "
                     "the sphere at (0 0 0) of radius 2: the image shows that sphere from inside\n",
          "a light inside a sphere, even glass, and the eye inside one: warned of (" + err + ")");
    std::ofstream(dir + "/glass.scene") << "size 8 8\nmaterial g glass 1.5\nsphere 0 0 0 2 g\n"
                                           "light 0 5 0\n";
    CHECK(RunRay(dir, "glass.scene -o gl.png", &err) == 0 && err.empty() &&
              RunRay(dir, "inside.scene --ray 0 0 0 0 0 -1", &err) == 0 && err.empty(),
          "the eye inside a glass sphere (it sees through it), and a probe: no warning (" + err +
              ")");
    std::ofstream(dir + "/nested.scene") << "size 8 8\nmaterial g glass 1.5\nmaterial m\n"
                                            "sphere 0 0 0 1 g\nsphere 0 0 0 2 m\n";
    CHECK(RunRay(dir, "nested.scene -o ne.png", &err) == 0 &&
              err.find("the eye rays start at (0 0 0), inside the sphere at (0 0 0) of radius "
                       "2:") != std::string::npos &&
              RunRay(dir, "nested.scene -o ne.png --camera-ray slides", &err) == 0 &&
              err.find("inside") == std::string::npos &&
              err.find("no eye ray met a shape") != std::string::npos,
          "the eye inside glass inside an opaque sphere: warned of the opaque one; with the "
          "slides' eye rays, which start on the screen, outside both and looking away, not, but "
          "that no eye ray met a shape (" +
              err + ")");
    // The slides' eye rays start on the screen, 2 in front of the eye: inside this sphere
    std::ofstream(dir + "/screen.scene") << "size 8 8\nmaterial m\nsphere 0 0 -1.5 1 m\n";
    CHECK(RunRay(dir, "screen.scene -o sc.png", &err) == 0 && err.empty() &&
              RunRay(dir, "screen.scene -o sc.png --methods handout", &err) == 0 &&
              err.find("the eye rays start at (0 0 -2), inside the sphere at (0 0 -1.5)") !=
                  std::string::npos,
          "a sphere around the screen but not the eye: warned of with the slides' eye rays "
          "(--methods handout) alone (" +
              err + ")");
    // A scene that can only be one colour: rendered, with a warning; probed, or seen in a view,
    // without one
    std::ofstream(dir + "/dark.scene") << "size 8 8\nshading path\nmaterial m\nsphere 0 0 -5 1 m\n";
    CHECK(RunRay(dir, "dark.scene -o d.png", &err) == 0 &&
              err ==
                  "ray: warning: nothing gives off light (no light that shines, no material that "
                  "emits, a black background): every pixel is black\n" &&
              RunRay(dir, "dark.scene --ray 0 0 0 0 0 -1", &err) == 0 && err.empty() &&
              RunRay(dir, "dark.scene --view normal -o n.png", &err) == 0 && err.empty(),
          "a scene where nothing gives light: rendered with one warning, probed and viewed "
          "without (" +
              err + ")");
}

// Scene files through the program: the default output name, errors with file and line, calm
// handling of empty, binary, huge-line and directory input.
static void TestSceneFilesInProgram(const std::string &dir) {
    char *here = realpath("scenes/reference.scene", nullptr);
    std::string reference = here ? here : "scenes/reference.scene";
    free(here);
    std::string err;
    CHECK(RunRay(dir, "'" + reference + "' --size 64", &err) == 0 &&
              FileExists(dir + "/reference.png"),
          "`ray path/reference.scene` writes reference.png in the current directory");

    char *gallery = realpath("scenes/effects.scene", nullptr);
    CHECK(
        gallery && RunRay(dir, std::string("'") + gallery + "' --size 40x25 --stats", &err) == 0 &&
            err.find("\neffects: shadows reflection refraction specular\n") != std::string::npos &&
            FileExists(dir + "/effects.png"),
        "--stats on the effects gallery: shadows reflection refraction specular");
    free(gallery);
    // A scene of spheres alone: no triangles to report; --layout bvh gives the spheres a tree
    std::ofstream(dir + "/balls.scene") << "material m diffuse 1 1 1\nsphere 0 0 -5 1 m\n";
    CHECK(RunRay(dir, "balls.scene --size 8 --stats", &err) == 0 &&
              err.rfind("triangles: none\n", 0) == 0,
          "--stats on spheres alone: 'triangles: none'");
    CHECK(RunRay(dir, "balls.scene --size 8 --stats --layout bvh", &err) == 0 &&
              err.rfind("triangles: none; spheres: 1 in a BVH of 1 nodes of 4\n", 0) == 0,
          "--stats with --layout bvh on spheres alone: 'triangles: none; spheres: 1 in a BVH of 1 "
          "nodes of 4'");

    std::ofstream(dir + "/typo.scene") << "# a scene with a typo\nmaterial red diffuse 1 0 0\n"
                                          "spher 0 0 -5 1 red\n";
    CHECK(
        RunRay(dir, "typo.scene", &err) == 2 &&
            err == "ray: typo.scene:3: unknown keyword 'spher' (did you mean 'sphere'?)\n" &&
            !FileExists(dir + "/typo.png"),
        "a typo: exit 2, `ray: typo.scene:3: unknown keyword 'spher' (did you mean 'sphere'?)`, no "
        "image (got " +
            err + ")");

    std::ofstream(dir + "/empty.scene");
    Image image;
    std::string readError;
    CHECK(RunRay(dir, "empty.scene --size 8", &err) == 0 &&
              ReadImage((dir + "/empty.png").c_str(), &image, &readError) && image.width == 8 &&
              image.pixels == std::vector<uint8_t>(8 * 8 * 3, 0),
          "an empty scene file renders the black background");

    std::string garbage;
    for (int k = 0; k < 4096; k++)
        garbage += (char)((k * 7919) % 256);
    std::ofstream(dir + "/garbage.scene", std::ios::binary) << garbage;
    CHECK(RunRay(dir, "garbage.scene", &err) == 2 && err.rfind("ray: garbage.scene:", 0) == 0,
          "binary garbage: exit 2 with file and line (got " + err + ")");

    std::ofstream(dir + "/long.scene") << "# " << std::string(1 << 20, 'x') << "\nsize 4 4\n";
    CHECK(RunRay(dir, "long.scene", &err) == 0, "a 1 MB comment line is read calmly");
    std::string numbers;
    for (int k = 0; k < 200000; k++)
        numbers += " 1.5";
    std::ofstream(dir + "/numbers.scene") << "ambient" << numbers << "\n";
    CHECK(RunRay(dir, "numbers.scene", &err) == 2 &&
              err == "ray: numbers.scene:1: line longer than 65536 characters\n",
          "a 1 MB line of numbers: one error line (got " + err.substr(0, 80) + ")");
    CHECK(RunRay(dir, "/tmp", &err) == 2 && err.find("is a directory") != std::string::npos,
          "a directory as the scene: exit 2");
    CHECK(RunRay(dir, "missing.scene", &err) == 2 &&
              err == "ray: missing.scene: No such file or directory\n",
          "a missing scene file: exit 2 (got " + err + ")");
}

std::string ReadOutput(const std::string &dir) { return ReadFile(dir + "/out.txt"); }

static void TestProbesInProgram(const std::string &dir) {
    std::string err;
    CHECK(RunRay(dir, "--ray 0 0 0 0 0 -1", &err) == 0 &&
              ReadOutput(dir).rfind("{\"hit\":true,\"t\":14,", 0) == 0,
          "--ray 0 0 0 0 0 -1: the mirror sphere at t = 14");
    CHECK(RunRay(dir, "--ray 0 0 0 0 0 0", &err) == 2 &&
              err.find("direction is zero") != std::string::npos,
          "--ray with a zero direction: exit 2");
    CHECK(RunRay(dir, "--ray 0 0 0 0 0", &err) == 2, "--ray with 5 numbers: exit 2");

    std::ofstream(dir + "/rays.txt") << "# probes\n0 0 0 0 0 -1\n\n0 0 0 0 1 0\nbad line\n"
                                        "0 0 0 1 -1 -6\n";
    int status = RunRay(dir, "--rays rays.txt", &err);
    std::string out = ReadOutput(dir);
    CHECK(status == 2 && std::count(out.begin(), out.end(), '\n') == 4 &&
              out.find("{\"hit\":false}\n{\"error\":\"line 5: expected 6 numbers") !=
                  std::string::npos &&
              out.find("\"index\":3") != std::string::npos,
          "--rays: 4 answers for 4 probe lines, the bad one an error in its place, exit 2");
    status = RunRay(dir, "--rays - < rays.txt", &err);
    CHECK(status == 2 && ReadOutput(dir) == out, "--rays - reads standard input the same way");

    CHECK(RunRay(dir, "--view normal --size 8", &err) == 0 &&
              FileExists(dir + "/reference_normal.png"),
          "--view normal without -o writes reference_normal.png, beside the image, not over it");
    char *first = realpath("scenes/first.scene", nullptr); // a ray from inside the red sphere
    CHECK(first && RunRay(dir, "--ray 0 0 -6 1 0 0 '" + std::string(first) + "'", &err) == 0 &&
              ReadOutput(dir).find("\"normal\":[-1,0,0]") != std::string::npos,
          "probe from inside a sphere: normal [-1,0,0], no negative zeros");
    free(first);
    CHECK(RunRay(dir, "--pixel 110 330", &err) == 0 &&
              ReadOutput(dir).find("\"kind\":\"shadow\"") != std::string::npos,
          "--pixel 110 330 prints a tree with a shadow ray");
    CHECK(RunRay(dir, "--pixel 512 0", &err) == 2 && err.find("outside") != std::string::npos,
          "--pixel outside the image: exit 2");
}

// An error is one line, even where it quotes a name with a newline in it: the newline is
// written as \n. (The name is single-quoted for the shell, which keeps the newline.)
static void TestOneLineErrors(const std::string &dir) {
    std::string err;
    CHECK(RunRay(dir, "'no\nsuch.scene' -o x.png", &err) == 2 &&
              err.find("no\\nsuch.scene") != std::string::npos &&
              std::count(err.begin(), err.end(), '\n') == 1,
          "a missing scene named with a newline: one line, the newline as \\n (" + err + ")");
    std::ofstream(dir + "/two\nlines.scene") << "size 8 8\nsphere 0 0 -3\n";
    CHECK(RunRay(dir, "'two\nlines.scene' -o x.png", &err) == 2 &&
              err.find("two\\nlines.scene:2:") != std::string::npos &&
              std::count(err.begin(), err.end(), '\n') == 1,
          "a bad line in a scene named with a newline: one line, FILE:LINE (" + err + ")");
}

// What PrintableLine keeps and what it escapes: printable ASCII and UTF-8 characters stay; C0
// and C1 controls, DEL, the line and paragraph separators, the bidirectional controls and bytes
// that are not UTF-8 become \xHH (a newline \n).
static void TestPrintableLine() {
    const char *cases[][2] = {
        {"plain.scene:3: fine", "plain.scene:3: fine"},
        {"r\xc3\xb8"
         "d \xe2\x82\xac \xf0\x9f\x99\x82",
         "r\xc3\xb8"
         "d \xe2\x82\xac \xf0\x9f\x99\x82"},
        {"a\nb\tc\rd\x1b"
         "e\x7f",
         "a\\nb\\x09c\\x0dd\\x1be\\x7f"},
        {"nel\xc2\x85 ls\xe2\x80\xa8 ps\xe2\x80\xa9",
         "nel\\xc2\\x85 ls\\xe2\\x80\\xa8 ps\\xe2\\x80\\xa9"},
        {"csi\x9b lone\xc3 overlong\xc0\xaf surrogate\xed\xa0\x80",
         "csi\\x9b lone\\xc3 overlong\\xc0\\xaf surrogate\\xed\\xa0\\x80"},
        // a right-to-left override (U+202E) and isolate (U+2067)
        {"rlo\xe2\x80\xae rli\xe2\x81\xa7", "rlo\\xe2\\x80\\xae rli\\xe2\\x81\\xa7"}};
    for (auto &c : cases)
        CHECK(PrintableLine(c[0]) == c[1],
              std::string("PrintableLine: ") + c[1] + ", got " + PrintableLine(c[0]));
}

// --layout plain: the plain loop over the shapes, no accelerator installed, draws the same bytes
// as the default (blocks, the BVH, packets) for every bundled scene, one sample a pixel and four
// jittered ones; path-traced scenes with the journal's estimator too.
static void TestPlainLayoutSameBytes(const std::string &dir) {
    const char *scenes[] = {"reference", "test",    "first",           "handout2", "effects",
                            "mesh",      "cornell", "assignment_path", "weekend"};
    std::string err;
    int differ = 0, runs = 0;
    for (const char *name : scenes) {
        char *path = realpath((std::string("scenes/") + name + ".scene").c_str(), nullptr);
        std::string scene = path ? std::string("'") + path + "'" : name;
        free(path);
        bool traced = std::string(name) == "cornell" || std::string(name) == "assignment_path" ||
                      std::string(name) == "weekend";
        std::string size = std::string(name) == "handout2" ? " --size 32x24" : " --size 32";
        std::vector<std::string> settings = {"", " --spp 4 --aa jitter"};
        if (traced)
            settings.push_back(" --spp 2 --estimator journal");
        for (const std::string &more : settings) {
            int a = RunRay(dir, scene + size + more + " -o fast.ppm", &err);
            int b = RunRay(dir, scene + size + more + " --layout plain -o plain.ppm", &err);
            std::string fast = ReadFile(dir + "/fast.ppm"), plain = ReadFile(dir + "/plain.ppm");
            differ += a != 0 || b != 0 || fast.empty() || fast != plain;
            runs++;
        }
    }
    CHECK(differ == 0, "--layout plain and the default: the same bytes in " +
                           std::to_string(runs - differ) + " of " + std::to_string(runs) +
                           " renders of the bundled scenes");
}

void TestProgram() {
    TestPrintableLine();
    std::string dir = MakeTestDir("test");
    if (dir.empty())
        return;
    TestDefaultRun(dir);
    TestBadInput(dir);
    TestScreenCameraSizes(dir);
    TestHiddenWarnings(dir);
    TestSceneFilesInProgram(dir);
    TestPlainLayoutSameBytes(dir);
    TestProbesInProgram(dir);
    TestCompare(dir);
    TestOneLineErrors(dir);
    RemoveTestDir(dir);
}
