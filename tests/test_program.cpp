// tests/test_program.cpp -- the program from the outside, as SPEC.md section 2 pins it.
//
// Runs ./ray (or $RAY) in a fresh temporary directory: the default output name, the PNG's size
// and format, identical bytes for any thread count, the --stats lines, and bad input: exit
// status 2 (3 for I/O), one `ray: ` line, and no output file touched.
#include "test.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

static std::string ReadFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

static bool FileExists(const std::string &path) { return std::ifstream(path).good(); }

// Runs `ray ARGS` in dir with stderr captured; returns the exit status.
static int RunRay(const std::string &dir, const std::string &args, std::string *stderrText) {
    std::string program = RayProgram();
    if (program[0] != '/') {
        char *cwd = realpath(".", nullptr);
        program = std::string(cwd) + "/" + program;
        free(cwd);
    }
    std::string command = "cd '" + dir + "' && '" + program + "' " + args + " >out.txt 2>err.txt";
    int status = system(command.c_str());
    *stderrText = ReadFile(dir + "/err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void TestDefaultRun(const std::string &dir) {
    std::string err;
    int status = RunRay(dir, "--threads 1 --stats", &err);
    CHECK(status == 0, "`ray` with no scene exits 0");
    Image image;
    std::string readError;
    bool read = ReadPng((dir + "/reference.png").c_str(), &image, &readError);
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
              err.find(" refraction=0 total=") != std::string::npos,
          "--stats prints the SPEC's rays: line");
    CHECK(err.find("\neffects: shadows reflection\n") != std::string::npos,
          "--stats: the assignment scene uses shadows and reflection, nothing else");

    std::string oneThread = ReadFile(dir + "/reference.png");
    status = RunRay(dir, "--threads 2 -o two.png", &err);
    CHECK(status == 0 && ReadFile(dir + "/two.png") == oneThread,
          "--threads 1 and --threads 2 write identical bytes");
    status = RunRay(dir, "test --size 32x16 --spp 4 --depth 3", &err);
    Image test;
    CHECK(status == 0 && ReadPng((dir + "/test.png").c_str(), &test, &readError) &&
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
    {"--size", 2, "needs 1 value"},
    {"--size 0", 2, "between 1 and 16384"},
    {"--size 16385", 2, "between 1 and 16384"},
    {"--size 12x", 2, "not an integer"},
    {"--spp 0", 2, "between 1 and 65536"},
    {"--spp nan", 2, "not an integer"},
    {"--depth 1001", 2, "between 1 and 1000"},
    {"--threads 0", 2, "between 1 and 1024"},
    {"--threads 2.5", 2, "not an integer"},
    {"--triangle moller", 2, "watertight or cramer"},
    {"default test", 2, "more than one scene"},
    {"nosuchscene", 2, "nosuchscene"},
    {"-o missing_dir/x.png", 3, "missing_dir/x.png"},
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
    CHECK(RunRay(dir, "--spp 0 -o fresh.png", &err) == 2 && !FileExists(dir + "/fresh.png"),
          "a failed run creates no output file");
    CHECK(RunRay(dir, "--help", &err) == 0 &&
              ReadFile(dir + "/out.txt").find("--threads") != std::string::npos,
          "--help exits 0 and lists the options");
    CHECK(RunRay(dir, "--version", &err) == 0 && ReadFile(dir + "/out.txt").rfind("rt ", 0) == 0,
          "--version exits 0 and names rt");
}

void TestProgram() {
    char pattern[] = "/tmp/rt-test-XXXXXX";
    const char *dir = mkdtemp(pattern);
    CHECK(dir != nullptr, "a temporary directory for the program tests");
    if (!dir)
        return;
    TestDefaultRun(dir);
    TestBadInput(dir);
    std::string cleanup = std::string("rm -rf '") + dir + "'";
    CHECK(system(cleanup.c_str()) == 0, "temporary directory removed");
}
