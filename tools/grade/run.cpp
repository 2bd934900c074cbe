// tools/grade/run.cpp -- running a program of a student's: in a folder of its own, for a limited
// time, writing files of a limited size, in a process group of its own that is killed whole at
// the end, so that a program that hangs, forks or fills the disk stops with a verdict instead of
// stopping the grader. (POSIX: fork, setpgid, setrlimit, execve, poll; Linux and macOS alike.)
#include "grade.h"

#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

// The program's path as the child will exec it: a name without `/` looked for in PATH, as a
// shell does, and any path made absolute (the child runs in another folder). "" if none.
static std::string ProgramPath(const std::string &name) {
    char resolved[PATH_MAX];
    if (name.find('/') != std::string::npos)
        return realpath(name.c_str(), resolved) ? resolved : "";
    const char *path = getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    for (size_t at = 0; at <= dirs.size();) {
        size_t end = dirs.find(':', at);
        if (end == std::string::npos)
            end = dirs.size();
        std::string candidate = (end > at ? dirs.substr(at, end - at) : ".") + "/" + name;
        if (access(candidate.c_str(), X_OK) == 0 && realpath(candidate.c_str(), resolved))
            return resolved;
        at = end + 1;
    }
    return "";
}

// In the child, between fork and exec (async-signal-safe calls only): its own process group,
// its folder, its limits, /dev/null for input, the pipe for output, default signal handling.
static void StartChild(const char *path, char *const argv[], const char *dir, const Limits *limits,
                       int output, int failure) {
    setpgid(0, 0);
    struct rlimit size = {(rlim_t)limits->outputBytes, (rlim_t)limits->outputBytes};
    struct rlimit none = {0, 0};
    rlim_t seconds = (rlim_t)limits->seconds + 1; // (CPU time: a backstop to the wall clock)
    struct rlimit cpu = {seconds, seconds};
    setrlimit(RLIMIT_FSIZE, &size);
    setrlimit(RLIMIT_CORE, &none);
    setrlimit(RLIMIT_CPU, &cpu);
    if (limits->memoryBytes > 0) {
        struct rlimit memory = {(rlim_t)limits->memoryBytes, (rlim_t)limits->memoryBytes};
        setrlimit(RLIMIT_AS, &memory);
    }
    struct sigaction standard;
    memset(&standard, 0, sizeof standard);
    standard.sa_handler = SIG_DFL;
    sigaction(SIGPIPE, &standard, nullptr);
    int in = open("/dev/null", O_RDONLY);
    if (chdir(dir) == 0 && in >= 0 && dup2(in, 0) >= 0 && dup2(output, 1) >= 0 && dup2(output, 2) >= 0)
        execve(path, argv, environ);
    int why = errno;
    if (write(failure, &why, sizeof why) < 0) {
    }
    _exit(127);
}

// Reads what is ready on fd into *kept, keeping the last `cap` bytes. False at the end of it.
static bool Drain(int fd, std::string *kept, size_t cap) {
    char chunk[4096];
    ssize_t n = read(fd, chunk, sizeof chunk);
    if (n > 0) {
        kept->append(chunk, (size_t)n);
        if (kept->size() > cap)
            kept->erase(0, kept->size() - cap);
    }
    return n > 0 || (n < 0 && (errno == EAGAIN || errno == EINTR));
}

// Waits for the child, reading its output, until it ends or its time is up (then the whole group
// is killed). Returns its wait status; *timedOut says which.
static int Wait(pid_t child, int output, double limit, std::string *kept, bool *timedOut) {
    auto start = std::chrono::steady_clock::now();
    int status = 0;
    bool open = true;
    *timedOut = false;
    for (;;) {
        pid_t done = waitpid(child, &status, WNOHANG);
        if (done == child)
            break;
        double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (spent >= limit) {
            *timedOut = true;
            kill(-child, SIGKILL);
            waitpid(child, &status, 0);
            break;
        }
        struct pollfd p = {output, POLLIN, 0};
        if (open && poll(&p, 1, 10) > 0)
            open = Drain(output, kept, 4096);
        else if (!open) // (its output ended a moment before its exit can be waited for: a short nap)
            usleep(1000);
    }
    kill(-child, SIGKILL); // (anything it left running in its group)
    while (open && Drain(output, kept, 4096)) {
    }
    return status;
}

void RunLimited(const std::vector<std::string> &argv, const std::string &dir, const Limits *limits,
                RunResult *result) {
    *result = {RUN_NOT_STARTED, 0, "", "", 0};
    std::string path = ProgramPath(argv.empty() ? "" : argv[0]);
    if (path.empty()) {
        result->why = std::string(strerror(ENOENT)) + ": " + (argv.empty() ? "" : argv[0]);
        return;
    }
    std::vector<char *> args;
    for (const std::string &a : argv)
        args.push_back(const_cast<char *>(a.c_str()));
    args.push_back(nullptr);
    int output[2], failure[2];
    if (pipe(output) != 0 || pipe(failure) != 0) {
        result->why = strerror(errno);
        return;
    }
    fcntl(failure[1], F_SETFD, FD_CLOEXEC);
    fcntl(output[0], F_SETFD, FD_CLOEXEC);
    auto start = std::chrono::steady_clock::now();
    pid_t child = fork();
    if (child == 0)
        StartChild(path.c_str(), args.data(), dir.c_str(), limits, output[1], failure[1]);
    close(output[1]);
    close(failure[1]);
    int why = 0;
    bool failed = child > 0 && read(failure[0], &why, sizeof why) == (ssize_t)sizeof why;
    close(failure[0]);
    if (child < 0 || failed) {
        result->why = strerror(child < 0 ? errno : why);
        if (child > 0)
            waitpid(child, nullptr, 0);
        close(output[0]);
        return;
    }
    setpgid(child, child); // (also here: the kill below must not find it still in ours)
    fcntl(output[0], F_SETFL, O_NONBLOCK);
    bool timedOut;
    int status = Wait(child, output[0], limits->seconds, &result->output, &timedOut);
    close(output[0]);
    result->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (timedOut)
        result->end = RUN_TIMED_OUT, result->seconds = limits->seconds;
    else if (WIFSIGNALED(status))
        result->end = RUN_SIGNALED, result->status = WTERMSIG(status);
    else
        result->end = RUN_EXITED, result->status = WEXITSTATUS(status);
}

std::string SignalName(int signal) {
    static const struct {
        int number;
        const char *name;
    } kNames[] = {{SIGSEGV, "SIGSEGV"}, {SIGABRT, "SIGABRT"}, {SIGFPE, "SIGFPE"},
                  {SIGBUS, "SIGBUS"},   {SIGILL, "SIGILL"},   {SIGKILL, "SIGKILL"},
                  {SIGTERM, "SIGTERM"}, {SIGXCPU, "SIGXCPU"}, {SIGXFSZ, "SIGXFSZ"},
                  {SIGPIPE, "SIGPIPE"}, {SIGINT, "SIGINT"},   {SIGTRAP, "SIGTRAP"}};
    for (const auto &n : kNames)
        if (n.number == signal)
            return n.name;
    return "signal " + std::to_string(signal);
}

bool MakeScratch(const char *prefix, std::string *dir, std::string *error) {
    const char *tmp = getenv("TMPDIR");
    std::string name = std::string(tmp && *tmp ? tmp : "/tmp") + "/" + prefix + "XXXXXX";
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back(0);
    if (!mkdtemp(buffer.data())) {
        *error = name + ": " + strerror(errno);
        return false;
    }
    *dir = buffer.data();
    return true;
}

// Removes dir and all it holds, a program's leavings included: a folder it made unreadable is
// opened up first, and a link is removed, never followed.
void RemoveTree(const std::string &dir) {
    chmod(dir.c_str(), 0700);
    if (DIR *d = opendir(dir.c_str())) {
        while (struct dirent *e = readdir(d)) {
            std::string name = e->d_name;
            if (name == "." || name == "..")
                continue;
            std::string path = dir + "/" + name;
            struct stat info;
            if (lstat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
                RemoveTree(path);
            else
                unlink(path.c_str());
        }
        closedir(d);
    }
    rmdir(dir.c_str());
}
