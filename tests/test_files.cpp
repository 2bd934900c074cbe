// tests/test_files.cpp -- files are never lost by mistake, and no input hurts the program.
//
// The ordinary slips of a new user: an output named like an input, a read-only image, a device
// or a FIFO or a symbolic link as the output, Ctrl-C during the write, a directory or /dev/zero
// given as a file of rays, a one-line file of many megabytes, a byte-order mark from Notepad.
// Each runs the program (RayProgram) in a fresh temporary directory.
#include "test.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

static void Write(const std::string &path, const std::string &text) {
    std::ofstream(path, std::ios::binary) << text;
}

static const char *kSmallScene = "size 16 16\nmaterial red diffuse 1 0 0\nlight 0 4 0\n"
                                 "sphere 0 0 -3 1 red\n";

// No temporary file (.ray-XXXXXX) left in dir.
static bool NoTemporaryFiles(const std::string &dir) {
    DIR *folder = opendir(dir.c_str());
    int temporary = 0;
    while (dirent *entry = folder ? readdir(folder) : nullptr) {
        std::string name = entry->d_name;
        temporary += name.compare(0, 5, ".ray-") == 0;
    }
    if (folder)
        closedir(folder);
    return folder && temporary == 0;
}

// The program under test as an absolute path, for a child that changes its directory.
static std::string AbsoluteRayProgram() {
    std::string program = RayProgram();
    char *cwd = program[0] == '/' ? nullptr : realpath(".", nullptr);
    if (cwd)
        program = std::string(cwd) + "/" + program;
    free(cwd);
    return program;
}

// An output that is also an input of the same run is refused, and the input left untouched.
static void TestOutputIsAnInput(const std::string &dir) {
    Write(dir + "/my.scene", kSmallScene);
    Write(dir + "/scene.png", kSmallScene); // a scene file with an image's name
    std::string err;
    CHECK(RunRay(dir, "my.scene -o my.scene", &err) == 2 &&
              ReadFile(dir + "/my.scene") == kSmallScene,
          "`ray my.scene -o my.scene`: exit 2, the scene file untouched (" + err + ")");
    CHECK(RunRay(dir, "scene.png -o scene.png", &err) == 2 &&
              err.find("is also an input") != std::string::npos &&
              ReadFile(dir + "/scene.png") == kSmallScene,
          "a scene file named scene.png as its own output: exit 2, untouched (" + err + ")");
    RunRay(dir, "my.scene -o a.png", &err);
    RunRay(dir, "my.scene --size 8 -o b.png", &err);
    std::string before = ReadFile(dir + "/b.png");
    CHECK(RunRay(dir, "--compare a.png b.png -o b.png", &err) == 2 &&
              ReadFile(dir + "/b.png") == before,
          "`--compare a.png b.png -o b.png`: exit 2, the image compared against untouched");
}

// A file nobody may write is refused with exit 3 and kept, even when the system would allow
// it (as root); an existing writable file is replaced and keeps its permissions.
static void TestReadOnlyOutput(const std::string &dir) {
    std::string err, path = dir + "/kept.png";
    Write(path, "not yet an image");
    chmod(path.c_str(), 0444);
    CHECK(RunRay(dir, "my.scene -o kept.png", &err) == 3 &&
              err.find("Permission denied") != std::string::npos &&
              ReadFile(path) == "not yet an image",
          "a read-only output: exit 3, `Permission denied`, the file untouched (" + err + ")");
    chmod(path.c_str(), 0640);
    struct stat info;
    CHECK(RunRay(dir, "my.scene -o kept.png", &err) == 0 && stat(path.c_str(), &info) == 0 &&
              (info.st_mode & 0777) == 0640,
          "a writable output is replaced and keeps its mode 0640");
}

// Devices and FIFOs are written to, never replaced; a symbolic link is followed.
static void TestSpecialOutputs(const std::string &dir) {
    std::string err;
    struct stat info;
    CHECK(RunRay(dir, "my.scene -o /dev/null", &err) == 0 && stat("/dev/null", &info) == 0 &&
              S_ISCHR(info.st_mode),
          "`-o /dev/null` writes into the device and leaves it a device");
    CHECK(RunRay(dir, "my.scene -o /dev/stdout", &err) == 0 &&
              ReadFile(dir + "/out.txt").compare(1, 3, "PNG") == 0,
          "`-o /dev/stdout` writes the PNG to standard output");
    std::string fifo = dir + "/pipe";
    mkfifo(fifo.c_str(), 0600);
    std::string command = "cat '" + fifo + "' > '" + dir + "/from-pipe.png' &";
    int ignored = system(command.c_str());
    (void)ignored;
    RunRay(dir, "my.scene -o plain.png", &err);
    CHECK(RunRay(dir, "my.scene -o pipe", &err) == 0 && stat(fifo.c_str(), &info) == 0 &&
              S_ISFIFO(info.st_mode),
          "a FIFO as the output is written to and stays a FIFO");
    for (int k = 0; k < 50 && ReadFile(dir + "/from-pipe.png") != ReadFile(dir + "/plain.png"); k++)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    CHECK(ReadFile(dir + "/from-pipe.png") == ReadFile(dir + "/plain.png"),
          "what came through the FIFO is the image");
    Write(dir + "/real.png", "old");
    int linked = symlink("real.png", (dir + "/link.png").c_str());
    CHECK(linked == 0 && RunRay(dir, "my.scene -o link.png", &err) == 0 &&
              lstat((dir + "/link.png").c_str(), &info) == 0 && S_ISLNK(info.st_mode) &&
              ReadFile(dir + "/real.png") == ReadFile(dir + "/plain.png"),
          "a symbolic link as the output: the file it points to is replaced, the link stays");
    int dangling = symlink("made-by-link.png", (dir + "/dangling.png").c_str());
    CHECK(dangling == 0 && RunRay(dir, "my.scene -o dangling.png", &err) == 0 &&
              lstat((dir + "/dangling.png").c_str(), &info) == 0 && S_ISLNK(info.st_mode) &&
              ReadFile(dir + "/made-by-link.png") == ReadFile(dir + "/plain.png"),
          "a dangling symbolic link as the output: its target is made, the link stays");
    std::string longName = std::string(250, 'a') + ".png"; // 254 characters: the limit is 255
    CHECK(RunRay(dir, "my.scene -o " + longName, &err) == 0 &&
              ReadFile(dir + "/" + longName) == ReadFile(dir + "/plain.png"),
          "an output name of 254 characters is written (" + err + ")");
    CHECK(RunRay(dir, "my.scene -o x.jpg", &err) == 2 && RunRay(dir, "my.scene -o x", &err) == 2,
          "an output named neither .png nor .ppm: exit 2");
    CHECK(RunRay(dir, "my.scene -o ''", &err) == 2 &&
              err.find("-o needs a file name") != std::string::npos &&
              RunRay(dir, "--compare plain.png plain.png -o ''", &err) == 2,
          "an empty output name, for a render or a comparison: exit 2, not the default name");
    CHECK(RunRay(dir, "my.scene -o x.ppm", &err) == 0 &&
              ReadFile(dir + "/x.ppm").compare(0, 13, "P6\n16 16\n255\n") == 0 &&
              ReadFile(dir + "/x.ppm").size() == 13 + 16 * 16 * 3,
          "`-o x.ppm` writes a binary PPM: the P6 header, then 16 x 16 x 3 bytes");
    CHECK(NoTemporaryFiles(dir), "no temporary file is left behind");
}

// Where the output cannot be made, the run says so before it renders, with exit 3, and changes
// nothing: a loop of symbolic links (which names no file: replacing one link of it would lose
// it), a name too long, a folder that does not exist, a file used as a folder; and, for a user
// other than root (root may write any folder), a folder that may not be written, though the file
// in it may (the image is made beside the output and renamed over it), and someone else's file in
// a sticky folder (as in /tmp), which only its owner may replace. "Before it renders": the render
// asked for (16384 x 16384 pixels at 65536 samples) would outlast the 30 s of CPU the shell
// allows it, and a run stopped by that limit gives no exit 3.
static void TestOutputFolders(const std::string &dir) {
    std::string err, as = ""; // (as root: the last cases run as nobody)
    const std::string big = "my.scene --size 16384 --spp 65536 -o ";
    auto refused = [&](const std::string &output) {
        return RunRayAfter(dir, "ulimit -t 30 && " + as, big + output, &err) == 3;
    };
    int a = symlink("loop-b.png", (dir + "/loop-a.png").c_str());
    int b = symlink("loop-a.png", (dir + "/loop-b.png").c_str());
    int self = symlink("self.png", (dir + "/self.png").c_str());
    int lost = symlink("../no-such-folder/x.png", (dir + "/lost.png").c_str());
    struct stat info;
    CHECK(a == 0 && b == 0 && refused("loop-a.png") &&
              err.find("loop-a.png: Too many levels of symbolic links") != std::string::npos &&
              lstat((dir + "/loop-a.png").c_str(), &info) == 0 && S_ISLNK(info.st_mode) &&
              lstat((dir + "/loop-b.png").c_str(), &info) == 0 && S_ISLNK(info.st_mode),
          "a loop of two symbolic links as the output: exit 3 before the render, both links kept "
          "(" +
              err + ")");
    CHECK(self == 0 && refused("self.png") && lstat((dir + "/self.png").c_str(), &info) == 0 &&
              S_ISLNK(info.st_mode),
          "a symbolic link to itself as the output: exit 3 before the render, the link kept");
    CHECK(refused(std::string(300, 'a') + ".png") &&
              err.find("File name too long") != std::string::npos,
          "an output name of 304 characters: exit 3 before the render, `File name too long`");
    CHECK(refused("no-such-folder/x.png") &&
              err.find("no-such-folder/x.png: No such file or directory") != std::string::npos,
          "an output in a folder that does not exist: exit 3 before the render (" + err + ")");
    CHECK(lost == 0 && refused("lost.png") &&
              err.find("(the link leads to ../no-such-folder/x.png)") != std::string::npos,
          "a link into a folder that does not exist: exit 3 before the render, and where it "
          "leads (" +
              err + ")");
    CHECK(refused("my.scene/x.png") && err.find("Not a directory") != std::string::npos &&
              ReadFile(dir + "/my.scene") == kSmallScene,
          "an output 'in' a file (my.scene/x.png): exit 3 before the render, the file untouched");
    if (geteuid() == 0) { // as nobody, where the system has setpriv and nobody may run the program
        chmod(dir.c_str(), 0755);
        as = "setpriv --reuid=65534 --regid=65534 --clear-groups";
        if (RunRayAfter(dir, as, "--version", &err) != 0) {
            printf("   (as root without a way to run as another user: no unwritable folders)\n");
            chmod(dir.c_str(), 0700);
            return;
        }
    }
    std::string shut = dir + "/shut", sticky = dir + "/sticky";
    mkdir(shut.c_str(), 0755);
    Write(shut + "/open.png", "old");
    chmod((shut + "/open.png").c_str(), 0666);
    chmod(shut.c_str(), 0555);
    CHECK(refused("shut/open.png") && err.find("where the image is written") != std::string::npos &&
              ReadFile(shut + "/open.png") == "old",
          "a writable file in a folder that may not be written: exit 3 before the render, "
          "untouched, and why (" +
              err + ")");
    chmod(shut.c_str(), 0755);
    if (geteuid() == 0) { // (someone else's file in a sticky folder: root's, to nobody)
        mkdir(sticky.c_str(), 0755);
        chmod(sticky.c_str(), 01777);
        Write(sticky + "/theirs.png", "old");
        chmod((sticky + "/theirs.png").c_str(), 0666);
        CHECK(refused("sticky/theirs.png") &&
                  err.find("is a sticky folder: only the file's owner") != std::string::npos &&
                  ReadFile(sticky + "/theirs.png") == "old",
              "someone else's writable file in a sticky folder: exit 3 before the render, "
              "untouched, and why (" +
                  err + ")");
        chmod(dir.c_str(), 0700);
    }
}

// A reader that goes away early (`ray --rays many.txt | head -c 1`, an image to `-o /dev/stdout`
// piped the same way) ends the run with exit 3 and "Broken pipe", not with the signal SIGPIPE.
// Both outputs are far larger than a pipe holds (64 KB; the image about 400 KB), so the program
// is still writing when the reader has gone, however late the reader leaves.
static void TestClosedPipe(const std::string &dir) {
    std::string rays;
    for (int k = 0; k < 20000; k++) // about 2 MB of answers: far more than a pipe holds
        rays += "0 0 0 0 0 -1\n";
    Write(dir + "/many.txt", rays);
    for (const char *args : {"my.scene --rays many.txt", "my.scene --size 3000 -o /dev/stdout"}) {
        std::string command = "cd '" + dir + "' && ( '" + RayPath() + "' " + args +
                              " 2>pipe-err.txt; echo $? >pipe-status.txt ) | head -c 1 >/dev/null";
        int ignored = system(command.c_str());
        (void)ignored;
        std::string status = ReadFile(dir + "/pipe-status.txt"),
                    err = ReadFile(dir + "/pipe-err.txt");
        CHECK(status == "3\n" && err.find("Broken pipe") != std::string::npos,
              std::string("`ray ") + args + " | head -c 1`: exit 3, `Broken pipe` (exit " + status +
                  ", " + err + ")");
    }
}

// SIGINT at moments spread over a run that writes a large image (before, during and after the
// write): no temporary file remains, and the output is either as it was (and the run did not
// succeed) or the complete new image.
static void TestInterruptedWrites(const std::string &dir) {
    Write(dir + "/wide.scene", "size 2500 2500\nbackground 0.2 0.4 0.6\n");
    std::string err;
    auto start = std::chrono::steady_clock::now();
    RunRay(dir, "wide.scene -o whole.ppm", &err);
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string whole = ReadFile(dir + "/whole.ppm"), program = AbsoluteRayProgram();
    int kept = 0, completed = 0, broken = 0;
    for (double share : {0.3, 0.6, 0.8, 0.85, 0.9, 0.95, 1.0, 1.1}) {
        Write(dir + "/target.ppm", "the old file");
        pid_t child = fork();
        if (child == 0) {
            signal(SIGINT, SIG_DFL); // as at a terminal, whatever the test runner was started with
            int quiet = open("/dev/null", O_WRONLY); // (the scene's warning: it has no shapes)
            if (quiet >= 0)
                dup2(quiet, 2);
            if (chdir(dir.c_str()) == 0)
                execl(program.c_str(), "ray", "wide.scene", "-o", "target.ppm", (char *)nullptr);
            _exit(127);
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(share * seconds));
        kill(child, SIGINT);
        int status;
        waitpid(child, &status, 0);
        std::string now = ReadFile(dir + "/target.ppm");
        bool finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
        kept += now == "the old file" && !finished;
        completed += now == whole; // a signal after the rename stops a run whose file is complete
        broken += (now != "the old file" || finished) && now != whole;
    }
    CHECK(broken == 0 && kept + completed == 8 && NoTemporaryFiles(dir),
          "8 runs stopped by SIGINT at 30%..110% of their time: " + std::to_string(kept) +
              " left the old file, " + std::to_string(completed) +
              " wrote the whole image first, none left a broken file or a temporary one");
}

// Over a file-size limit (ulimit -f) the write fails with exit 3, and no temporary file is left:
// SIGXFSZ, which would end the program, is ignored while writing.
static void TestFileSizeLimit(const std::string &dir) {
    std::string program = AbsoluteRayProgram();
    std::string command =
        "cd '" + dir + "' && (ulimit -f 16; '" + program + "' wide.scene -o limited.ppm) 2>err.txt";
    int status = system(command.c_str());
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 3 && NoTemporaryFiles(dir),
          "over a file-size limit of 16 blocks: exit 3 and no temporary file (" +
              ReadFile(dir + "/err.txt") + ")");
}

// Inputs that are not what they should be: exit 2 with a message, never a hang or an abort.
static void TestOddInputs(const std::string &dir) {
    std::string err;
    CHECK(RunRay(dir, "my.scene --rays /tmp", &err) == 2 &&
              err.find("is a directory") != std::string::npos,
          "`--rays DIRECTORY`: exit 2 (" + err + ")");
    CHECK(RunRay(dir, "my.scene --rays /dev/zero", &err) == 2 &&
              err.find("not a text file") != std::string::npos,
          "`--rays /dev/zero`: exit 2 at its first NUL byte (" + err + ")");
    Write(dir + "/bom.scene", std::string("\xEF\xBB\xBF") + kSmallScene);
    CHECK(RunRay(dir, "bom.scene -o bom.png", &err) == 0,
          "a scene file that starts with a UTF-8 byte-order mark reads (" + err + ")");
    // 40 MB on one line: refused as a long line, never held in memory whole
    std::string line(40 << 20, '1');
    Write(dir + "/huge.scene", "ambient " + line + "\n");
    int status = RunRay(dir, "huge.scene -o huge.png", &err);
    CHECK(status == 2 && err.find("huge.scene:1: line longer than") != std::string::npos,
          "a 40 MB one-line scene file: exit 2, `line longer than` (" + err.substr(0, 80) + ")");
    unlink((dir + "/huge.scene").c_str());
}

void TestFiles() {
    std::string dir = MakeTestDir("files");
    if (dir.empty())
        return;
    TestOutputIsAnInput(dir);
    TestReadOnlyOutput(dir);
    TestSpecialOutputs(dir);
    TestOutputFolders(dir);
    TestClosedPipe(dir);
    TestInterruptedWrites(dir);
    TestFileSizeLimit(dir);
    TestOddInputs(dir);
    std::string command = "rm -rf '" + dir + "'";
    int ignored = system(command.c_str());
    (void)ignored;
}
