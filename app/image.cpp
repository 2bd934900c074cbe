// app/image.cpp -- writing image files (PNG through libpng's simplified API, binary PPM) and
// comparing images. Reading them (--compare) is image_read.cpp.
//
// An image is written to a temporary file beside the target and renamed over it only when the
// whole file is on disk, so a failed or interrupted run never leaves a broken or half-written
// image, and an existing file stays exactly as it was. What the output path may be is checked
// before any work is done (CheckOutputPath): never an input of the same run, never a file made
// read-only; devices and FIFOs are written to directly.
#include "app.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <png.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

// Compression: PNG_IMAGE_FLAG_FAST (no row filters, zlib level 3 in libpng 1.6) instead of the
// default (adaptive filters, zlib level 6): the default's search for the best filter can cost as
// much as rendering a small scene, and a rendered image's flat colours compress well without it.
static const png_uint_32 kPngFlags = PNG_IMAGE_FLAG_FAST;

// The image as PNG on an open file. Where the file could not be written, the system's reason (a
// full disk, a pipe whose reader has gone) rather than libpng's "Write Error".
static bool EncodePng(FILE *file, const Image *image, std::string *error) {
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = (png_uint_32)image->width;
    png.height = (png_uint_32)image->height;
    png.format = PNG_FORMAT_RGB;
    png.flags = kPngFlags;
    errno = 0;
    bool written = png_image_write_to_stdio(&png, file, 0, image->pixels.data(), 0, nullptr) != 0;
    if (!written)
        *error = ferror(file) && errno != 0 ? strerror(errno) : png.message;
    png_image_free(&png);
    return written;
}

// The image as binary PPM (P6): a text header, then the RGB bytes, rows from the top. The format
// Ray Tracing in One Weekend starts from, readable by almost any image program.
static bool EncodePpm(FILE *file, const Image *image, std::string *error) {
    bool written =
        fprintf(file, "P6\n%d %d\n255\n", image->width, image->height) > 0 &&
        fwrite(image->pixels.data(), 1, image->pixels.size(), file) == image->pixels.size();
    if (!written)
        *error = strerror(errno);
    return written;
}

static bool EndsWith(const std::string &s, const char *suffix) {
    size_t n = strlen(suffix);
    if (s.size() < n)
        return false;
    for (size_t k = 0; k < n; k++)
        if (tolower((unsigned char)s[s.size() - n + k]) != suffix[k])
            return false;
    return true;
}

// Written to directly, never replaced: what is not a regular file (/dev/null, a FIFO), and the
// names of the program's own streams (/dev/stdout is a link to the file standard output goes to,
// which replacing would not reach).
static bool IsSpecial(const std::string &path, const struct stat *info) {
    return !S_ISREG(info->st_mode) || path.compare(0, 8, "/dev/std") == 0 ||
           path.compare(0, 8, "/dev/fd/") == 0 || path.compare(0, 14, "/proc/self/fd/") == 0;
}

// The file a path names (*file), following symbolic links, also one whose target does not exist
// yet (a dangling link is followed to where its target will be made). False after 40 links, the
// system's own limit: a loop of links (a -> b -> a), which names no file at all.
static bool LinkTarget(std::string path, std::string *file) {
    for (int depth = 0; depth <= 40; depth++) {
        char target[PATH_MAX];
        ssize_t n = readlink(path.c_str(), target, sizeof target - 1);
        if (n < 0) {
            *file = path;
            return true;
        }
        target[n] = 0;
        std::string next = target;
        size_t slash = path.find_last_of('/');
        path =
            next[0] == '/' || slash == std::string::npos ? next : path.substr(0, slash + 1) + next;
    }
    return false;
}

// The folder that holds `file` ("dir/" of "dir/a.png", "./" of "a.png"), where the image's
// temporary file is made.
static std::string FolderOf(const std::string &file) {
    size_t slash = file.find_last_of('/');
    return slash == std::string::npos ? "./" : file.substr(0, slash + 1);
}

// Why the image cannot be made in `folder` and renamed over `file`, as an errno value, or 0 when
// it can: the folder is missing, not a folder, or may not be written; or it is a sticky folder
// (as /tmp is) and the file someone else's, which only its owner, the folder's or root may
// replace. (Other limits, such as Linux's append-only attribute, show only when the rename is
// refused, after the render.)
static int FolderProblem(const std::string &folder, const std::string &file) {
    struct stat info, existing;
    if (stat(folder.c_str(), &info) != 0)
        return errno;
    if (!S_ISDIR(info.st_mode))
        return ENOTDIR;
    if (access(folder.c_str(), W_OK | X_OK) != 0)
        return errno;
    uid_t me = geteuid();
    bool sticky = (info.st_mode & S_ISVTX) != 0 && me != 0 && info.st_uid != me;
    return sticky && stat(file.c_str(), &existing) == 0 && existing.st_uid != me ? EPERM : 0;
}

// Where a regular file's image will go (WriteImage): the file its links lead to, and a new file in
// that file's folder. False with *error (exit 3) where either cannot be.
static bool CanReplace(const std::string &output, std::string *error) {
    std::string file;
    if (!LinkTarget(output, &file)) {
        *error = output + ": " + strerror(ELOOP);
        return false;
    }
    std::string folder = FolderOf(file);
    int why = FolderProblem(folder, file);
    if (why == 0)
        return true;
    *error = output + ": " + strerror(why);
    if (why == EPERM) // (the file itself may be writable)
        *error += " (" + folder + " is a sticky folder: only the file's owner may replace it)";
    else if (why == EACCES || why == EROFS)
        *error +=
            " (in " + folder + ", where the image is written before it is renamed into place)";
    else if (file != output) // (say where the link leads: the link itself exists)
        *error += " (the link leads to " + file + ")";
    return false;
}

bool CheckOutputPath(const std::string &output, const std::vector<std::string> &inputs, int *status,
                     std::string *error) {
    struct stat out;
    errno = 0;
    bool exists = stat(output.c_str(), &out) == 0;
    *status = 2;
    // Not there (ENOENT) is what a new output is; anything else names no file that can be made: a
    // loop of links (ELOOP: no file to write, and none to make), a name too long, a folder on the
    // way that is a file or may not be searched
    if (!exists && errno != ENOENT) {
        *status = 3;
        *error = output + ": " + strerror(errno);
        return false;
    }
    if (exists && S_ISDIR(out.st_mode)) {
        *status = 3;
        *error = output + ": Is a directory";
        return false;
    }
    bool special = exists && IsSpecial(output, &out);
    if (!special && !EndsWith(output, ".png") && !EndsWith(output, ".ppm")) {
        *error = output + ": unknown image format (the name must end in .png or .ppm)";
        return false;
    }
    for (const std::string &input : inputs) {
        struct stat in;
        if (exists && stat(input.c_str(), &in) == 0 && in.st_dev == out.st_dev &&
            in.st_ino == out.st_ino) {
            *error = output + ": is also an input of this run (" + input +
                     "); choose another output with -o";
            return false;
        }
    }
    // A file nobody may write is refused even when the system would let us (root): it was made
    // read-only on purpose, and replacing it would lose it
    if (exists && !special && (access(output.c_str(), W_OK) != 0 || (out.st_mode & 0222) == 0)) {
        *status = 3; // (the system's reason: a file system mounted read-only says so)
        *error = output + ": " + strerror((out.st_mode & 0222) == 0 ? EACCES : errno);
        return false;
    }
    if (!special && !CanReplace(output, error)) {
        *status = 3;
        return false;
    }
    return true;
}

// Signals whose default is to stop the program. They are held while a temporary file exists, so
// that an interrupted run cannot leave one behind: a signal that arrives meanwhile is delivered
// once the temporary file is gone, and the output path is left as it was. (SIGKILL cannot be
// held; nothing can clean up after it.)
static const int kStopSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGQUIT, SIGPIPE,
                                   SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGVTALRM};

static void HoldStopSignals(sigset_t *previous) {
    sigset_t stops;
    sigemptyset(&stops);
    for (int signal : kStopSignals)
        sigaddset(&stops, signal);
    pthread_sigmask(SIG_BLOCK, &stops, previous);
}

// A stop signal is waiting to be delivered. One the process ignores (a shell starts background
// jobs with SIGINT ignored) is still reported pending while held, but stops nothing.
static bool StopSignalPending() {
    sigset_t pending;
    sigpending(&pending);
    for (int signal : kStopSignals) {
        struct sigaction action;
        if (sigismember(&pending, signal) && sigaction(signal, nullptr, &action) == 0 &&
            action.sa_handler != SIG_IGN)
            return true;
    }
    return false;
}

static bool Encode(FILE *file, const std::string &path, const Image *image, std::string *error) {
    bool ppm = EndsWith(path, ".ppm");
    return ppm ? EncodePpm(file, image, error) : EncodePng(file, image, error);
}

// Writes straight into a special output (IsSpecial): it cannot be replaced, and replacing a
// device would be wrong.
static bool WriteSpecial(const std::string &path, const Image *image, std::string *error) {
    FILE *file = fopen(path.c_str(), "wb");
    std::string why;
    bool written = file && Encode(file, path, image, &why);
    if (!file)
        why = strerror(errno);
    if (file && fclose(file) != 0 && written) {
        why = strerror(errno);
        written = false;
    }
    if (!written)
        *error = path + ": " + why;
    return written;
}

// Writes the image into a new temporary file (*temporary, made from its pattern) with the mode
// the file it will replace has (`mode`); false with *why. mkstemp makes a file readable by its
// owner only, hence the chmod.
static bool WriteTemporary(std::string *temporary, const std::string &target, mode_t mode,
                           const Image *image, std::string *why) {
    int fd = mkstemp(&(*temporary)[0]);
    FILE *file = fd >= 0 ? fdopen(fd, "wb") : nullptr;
    if (!file) {
        *why = strerror(errno);
        if (fd >= 0) {
            close(fd);
            unlink(temporary->c_str());
        }
        temporary->clear();
        return false;
    }
    bool written = Encode(file, target, image, why);
    if (fclose(file) != 0 && written) { // fclose flushes: a full disk shows up here
        *why = strerror(errno);
        written = false;
    }
    if (written && chmod(temporary->c_str(), mode) != 0) {
        *why = strerror(errno);
        written = false;
    }
    return written;
}

bool WriteImage(const char *path, const Image *image, std::string *error) {
    struct stat info;
    bool exists = stat(path, &info) == 0;
    if (exists && IsSpecial(path, &info))
        return WriteSpecial(path, image, error);

    // A symbolic link is followed: the file it points to is replaced (or made), the link stays
    std::string target, why;
    if (!LinkTarget(path, &target)) {
        *error = std::string(path) + ": " + strerror(ELOOP);
        return false;
    }
    std::string temporary = FolderOf(target) + ".ray-XXXXXX"; // short: if the name fits, this does
    mode_t mask = umask(0);
    umask(mask);
    sigset_t previous;
    struct sigaction fileSize, ignore = {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGXFSZ, &ignore, &fileSize); // over a file-size limit: EFBIG, not a dead process
    HoldStopSignals(&previous);
    bool written = WriteTemporary(&temporary, target, exists ? info.st_mode & 07777 : 0666 & ~mask,
                                  image, &why);
    if (written && StopSignalPending())
        why = "interrupted", written = false;
    if (written && rename(temporary.c_str(), target.c_str()) != 0)
        why = strerror(errno), written = false;
    if (!written && !temporary.empty())
        unlink(temporary.c_str());
    pthread_sigmask(SIG_SETMASK, &previous, nullptr); // a held signal is delivered here
    sigaction(SIGXFSZ, &fileSize, nullptr);
    if (!written)
        *error = std::string(path) + ": " + why;
    return written;
}

// A heat scale for x in [0, 1]: black, red, yellow, white, each channel rising in turn.
color HeatColor(real x) {
    x = std::fmin(real(1), std::fmax(real(0), x)) * 3;
    return {std::fmin(x, real(1)), std::fmin(std::fmax(x - 1, real(0)), real(1)),
            std::fmin(std::fmax(x - 2, real(0)), real(1))};
}

bool CompareImages(const Image *a, const Image *b, int tolerance, ImageDifference *difference,
                   Image *heatmap) {
    if (a->width != b->width || a->height != b->height)
        return false;
    size_t pixels = (size_t)a->width * a->height;
    heatmap->width = a->width;
    heatmap->height = a->height;
    heatmap->pixels.assign(pixels * 3, 0);
    double sumSquares = 0;
    *difference = ImageDifference{0, 0, 0, 0, {}};
    auto worse = [](const PixelDifference &u, const PixelDifference &v) {
        return u.largest > v.largest ||
               (u.largest == v.largest && (u.y < v.y || (u.y == v.y && u.x < v.x)));
    };
    for (size_t p = 0; p < pixels; p++) {
        int largest = 0;
        for (int c = 0; c < 3; c++) {
            int d = std::abs((int)a->pixels[3 * p + c] - (int)b->pixels[3 * p + c]);
            sumSquares += (double)d * d;
            largest = std::max(largest, d);
        }
        difference->largest = std::max(difference->largest, largest);
        difference->pixelsOver += largest > tolerance;
        std::vector<PixelDifference> *worst = &difference->worst;
        if (largest > tolerance &&
            ((int)worst->size() < kWorstPixels || largest > worst->back().largest)) {
            PixelDifference d = {(int)(p % a->width), (int)(p / a->width), largest, {}, {}};
            memcpy(d.a, &a->pixels[3 * p], 3), memcpy(d.b, &b->pixels[3 * p], 3);
            worst->insert(std::upper_bound(worst->begin(), worst->end(), d, worse), d);
            if ((int)worst->size() > kWorstPixels)
                worst->pop_back();
        }
        color heat = HeatColor(real(largest) / 255);
        heatmap->pixels[3 * p + 0] = ToByte(heat.x);
        heatmap->pixels[3 * p + 1] = ToByte(heat.y);
        heatmap->pixels[3 * p + 2] = ToByte(heat.z);
    }
    difference->rmse = std::sqrt(sumSquares / (3.0 * (double)std::max(pixels, (size_t)1)));
    difference->psnr = difference->rmse > 0 ? 20 * std::log10(255 / difference->rmse) : INFINITY;
    return true;
}
