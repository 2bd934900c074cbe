// app/app.h -- the program around the render, for main (ray.cpp): the command line
// (options.cpp), the program's modes and reports (modes.cpp), scene files (scene_file.cpp,
// statements.cpp), image files (image.cpp, image_read.cpp), lines, tokens and numbers (text.cpp),
// OBJ meshes (mesh.cpp), probes and ray trees (probe.cpp), debug views (views.cpp).
#pragma once
#include "../render.h"

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

// ---- image.cpp: image files and comparing images ------------------------------------------------

// Whether `output` may be written by a run that reads `inputs`: its name ends in .png or .ppm
// (or it is a device or FIFO), it is not one of the inputs, and if it exists, it is not a
// directory or a file without write permission. False with the exit status (2 bad usage, 3 I/O)
// and *error otherwise. Checked before a render, so a mistake costs no time.
bool CheckOutputPath(const std::string &output, const std::vector<std::string> &inputs, int *status,
                     std::string *error);

// Writes *image to path as 8-bit RGB, PNG or binary PPM by the name's extension. A regular file
// is written through a temporary file renamed into place (a symbolic link is followed), so the
// path holds either its old contents or the whole new image, also when SIGINT or SIGTERM
// arrives; a device or FIFO is written to directly. False with *error on failure.
bool WriteImage(const char *path, const Image *image, std::string *error);

// How two images of the same size differ, channel values in 0..255.
// One pixel that differs: where it is (x from the left, y from the top, as --pixel counts), its
// largest channel difference, and its colour in each image.
struct PixelDifference {
    int x, y, largest;
    unsigned char a[3], b[3];
};

// The pixels of the worst differences --compare lists, so that --pixel can look at them.
const int kWorstPixels = 5;

struct ImageDifference {
    double rmse;     // root mean square difference over all channels
    double psnr;     // 20 log10(255 / rmse) in dB; infinite for identical images
    int largest;     // largest difference of one channel
    long pixelsOver; // pixels with a channel differing by more than the tolerance
    std::vector<PixelDifference> worst; // of those, the kWorstPixels that differ most, largest
                                        // first (of equal ones, the first in reading order)
};

// A heat scale for x in [0, 1]: black, red, yellow, white.
color HeatColor(real x);

// Compares a and b (same size) and draws *heatmap: black where equal, through red and yellow to
// white for the largest possible difference. Returns false if the sizes differ.
bool CompareImages(const Image *a, const Image *b, int tolerance, ImageDifference *difference,
                   Image *heatmap);

// ---- image_read.cpp: reading images ---------------------------------------------------------

// Reads a PNG or a PPM, binary (P6) or plain text (P3, what many a first ray tracer writes: Ray
// Tracing in One Weekend prints one), into *image as 8-bit RGB, for --compare. False with *error
// ("PATH: why") for a file that is neither, or is cut short.
bool ReadImage(const char *path, Image *image, std::string *error);

// ---- text.cpp: lines, tokens and numbers (scene files, probe lines, the command line) --------

// The longest line a scene file or probe file may have: a statement is a keyword and a few dozen
// words at most (a camera's fifteen numbers, a mesh's transform words), so this leaves room for
// any comment, and a one-line file of 250 MB is refused at once instead of being held in memory.
const size_t kMaxLineLength = 65536;

enum LineStatus {
    LINE_READ,     // *line holds the next line, without its ending (\n, \r\n or \r alone)
    LINE_END,      // no more lines
    LINE_TOO_LONG, // the line was longer than kMaxLineLength (and has been skipped)
    LINE_BAD       // a NUL byte (not a text file) or a read error: stop reading
};

// Reads line number `lineNumber` (from 1) of a text file, without its comment (from `#` on); on
// line 1 a UTF-8 byte-order mark is skipped. Sets *error for LINE_TOO_LONG and LINE_BAD (a NUL
// byte, UTF-16 text).
LineStatus ReadTextLine(FILE *file, int lineNumber, std::string *line, std::string *error);

// Where a line's comment begins: its first `#`, but for one inside a number as old Windows
// programs printed NaN and infinity (1.#QNAN, -1.#IND, 1.#INF), which is refused as a number
// with a message that says so; line.size() if it has none.
size_t CommentStart(const std::string &line);

// Splits a line into tokens at spaces and tabs, up to its comment (CommentStart).
void Tokenize(const std::string &line, std::vector<std::string> *tokens);

// A token as it may be shown in a message: quoted, at most 40 code points; UTF-8 text as written,
// each byte of a control character or of bytes that are not UTF-8 as ?.
std::string Shown(const std::string &token);

// A message as one printable line: control characters (C0, DEL and C1, the Unicode line and
// paragraph separators, the bidirectional controls) and bytes that are not UTF-8 written as
// escapes, \n or \xHH a byte.
std::string PrintableLine(const std::string &text);

// Whether text is UTF-8 without control characters (PrintableLine leaves it as it is): what a
// line of a text file holds, and a line of a PNG file does not.
bool IsPrintableText(const std::string &text);

// Whether text is UTF-8 (Unicode 15, table 3-7), control characters or not.
bool IsUtf8(const std::string &text);

// Where in `known` (null-terminated) is the word that `word` is the fewest slips of the keyboard
// away from, for a "did you mean" hint: a slip is a letter added, dropped or changed, or two
// swapped, and a word may be one slip away (two for words of six letters or more). -1 where
// none is, `word` is one of them, or it has fewer than three letters.
int NearWord(const std::string &word, const char *const *known);

// Whether a token is written as ParseReal reads numbers, whatever its size: an optional sign,
// decimal digits with an optional point, an optional exponent (-2, +0.5, 1e-3, .5, 5., 1e999).
bool LooksDecimal(const std::string &token);

// Reads a number token: decimal digits with an optional sign, point and exponent, finite.
// Returns false and sets *error for anything else (inf, nan, hexadecimal, trailing characters).
bool ParseReal(const std::string &token, real *value, std::string *error);

// Whether a token is a decimal number too small to be anything but 0 in `real` (1e-400; in float
// 1e-50), which ParseReal refuses.
bool TooSmallForNumber(const std::string &token);

// Whether a token is written as a whole number: an optional sign, then decimal digits, of any
// length.
bool IsWholeNumber(const std::string &token);

// Reads a whole number token (IsWholeNumber) in [lo, hi]; false with *error otherwise. Shared by
// the scene reader and the command line.
bool ParseWholeNumber(const std::string &token, int lo, int hi, int *value, std::string *error);

// ---- mesh.cpp: Wavefront OBJ meshes (docs/scene-format.md) --------------------------------------

// One transform word of a `mesh` statement; the words move every vertex in the order written.
enum MeshStepKind { MESH_SCALE, MESH_SCALE_AXES, MESH_ROTATE, MESH_TRANSLATE };
struct MeshStep {
    MeshStepKind kind;
    real factor;       // MESH_SCALE: the uniform factor, > 0
    vec3 factors;      // MESH_SCALE_AXES: a factor for each axis, none 0; a negative one mirrors
    int axis;          // MESH_ROTATE: 0, 1, 2 for x, y, z
    real cosine, sine; // MESH_ROTATE: of the angle (exactly 0 and +-1 for multiples of 90)
    vec3 offset;       // MESH_TRANSLATE
};

// Which normals a mesh's triangles are shaded with: the file's own (`vn`, where a face's corners
// name them), none (`flat`), or averaged over the faces around each vertex (`smooth`).
enum MeshNormals { MESH_NORMALS_FROM_FILE, MESH_FLAT, MESH_SMOOTH };

// Every word of a mesh statement after its material.
struct MeshWords {
    std::vector<MeshStep> steps; // the transform words, in order
    MeshNormals normals;
    real fit; // `fit S` (> 0): scaled and centred so that its longest side is S, first; 0: none
};

// Reads the words tokens[first..]: the transform words `scale S`, `scale X Y Z`, `rotate x|y|z
// DEGREES`, `translate X Y Z`, any number of each, and `flat`, `smooth`, `fit S`, each at most
// once. Returns false with *error for an unknown word or a bad value.
bool ParseMeshWords(const std::vector<std::string> &tokens, size_t first, MeshWords *words,
                    std::string *error);

// The transform words alone (ParseMeshWords, the other words refused).
bool ParseMeshTransform(const std::vector<std::string> &tokens, size_t first,
                        std::vector<MeshStep> *steps, std::string *error);

// The vertex p moved by every step, in order.
vec3 TransformVertex(const std::vector<MeshStep> &steps, vec3 p);

// A normal n turned by the steps: the inverse transpose of each step, which for a uniform scale
// and a translation is nothing, for a rotation the rotation, and for `scale X Y Z` a division by
// each factor; made unit length.
vec3 TransformNormal(const std::vector<MeshStep> &steps, vec3 n);

// Whether the steps mirror the mesh (an odd number of negative factors): its faces' winding is then
// turned back, so that their outward side stays outward.
bool MirrorsMesh(const std::vector<MeshStep> &steps);

// Reads a Wavefront OBJ file, open as `file` and called meshName in messages: every face as
// triangles of `material` (a fan from its first corner), its vertices moved by `steps`,
// appended to *triangles, at most maxTriangles of them. False with *error = "MESH:LINE: message"
// for a malformed line, a file without faces, or more triangles than that; where the mesh
// statement is to blame (its transform words, the scene's limit), the message names it by
// `statement` ("SCENE:LINE").
bool ReadObj(FILE *file, const char *meshName, int material, const std::vector<MeshStep> &steps,
             size_t maxTriangles, const std::string &statement, std::vector<Triangle> *triangles,
             std::string *error);

// ReadObj with all of a mesh statement's words, into the scene: its triangles, and where the
// mesh is smooth (MeshWords::normals, a file's `vn`), their CornerNormals, each turned to its
// triangle's outward side (scene->cornerNormals grows to hold them, flat triangles before them
// getting zeros). `fit` is applied by the caller, as steps.
bool ReadObjInto(FILE *file, const char *meshName, int material, const MeshWords *words,
                 size_t maxTriangles, const std::string &statement, Scene *scene,
                 std::string *error);

// A mesh statement's PATH as rt opens it: relative to the folder of the scene file that names it
// (an absolute path as given).
std::string MeshPath(const char *sceneFile, const std::string &path);

// The statement `mesh PATH MATERIAL [transform words]` on line `line` of sceneFile, its material
// already found: reads the file into scene->triangles (at most maxTriangles) and records it in
// scene->meshFiles. False with *error: "SCENE:LINE: message" for the statement or a file that
// cannot be opened, "MESH:LINE: message" for the file's own content.
bool ReadMeshStatement(const std::vector<std::string> &tokens, const char *sceneFile, int line,
                       int material, size_t maxTriangles, Scene *scene, std::string *error);

// ---- mesh_normals.cpp: a smooth mesh's corner normals ------------------------------------------

// What a mesh file gave its triangles' corners (mesh.cpp keeps it while the file is read): for
// triangle t, vertex[3t + i] and normal[3t + i] are its corner i's places among the file's
// `vertices` positions and among its normals (-1: none).
struct MeshCorners {
    const int *vertex, *normal;
    size_t vertices;
    const vec3 *normals;
};

// The corner normals of the mesh's triangles, scene->triangles[first..], as `how` asks (the
// file's, or for `smooth` the faces' normals averaged at each vertex), each triangle's turned to
// its outward side. A triangle with a zero normal at a corner, or a corner that then leans behind
// its face (c.face <= 0), is flat. scene->cornerNormals grows to hold them (flat triangles before
// them getting zeros; nothing is added for a mesh with none). Warnings naming meshName go to
// scene->warnings: how many triangles a corner leaning behind made flat, and under `smooth`, how
// many edges join faces wound opposite ways.
void AddCornerNormals(const MeshCorners *corners, MeshNormals how, size_t first,
                      const char *meshName, Scene *scene);

// ---- probe.cpp: probes and ray trees (docs/command-line.md) -------------------------------------

// Reads a probe line `OX OY OZ DX DY DZ`. Returns false with *error for a bad line; sets *blank
// (and returns true) for a blank or comment line.
bool ParseProbeLine(const std::string &line, Ray *ray, bool *blank, std::string *error);

// The JSON line for the nearest hit of `ray` with t > 0.
std::string ProbeRayJson(const Scene *scene, const RenderSettings *settings, const Ray *ray);

// The JSON line for a probe line that could not be read.
std::string ProbeErrorJson(const std::string &message);

// The JSON ray tree of pixel (x, y)'s centre ray.
std::string PixelTreeJson(const Scene *scene, const RenderSettings *settings, int x, int y);

// ---- views.cpp: debug views -----------------------------------------------------------------

enum ViewKind { VIEW_NORMAL, VIEW_DEPTH, VIEW_ID, VIEW_COST, VIEW_SHADOW };

// Looks up a view by its command-line name; false if there is none. ViewName is the reverse.
bool FindView(const std::string &name, ViewKind *view);
const char *ViewName(ViewKind view);

// Renders a debug view of the primary hits instead of the lit image.
void RenderView(const Scene *scene, const RenderSettings *settings, ViewKind view, Image *image,
                RayStats *stats);

// ---- scene_file.cpp: scene files (docs/scene-format.md) -----------------------------------------

// Reads a scene file. On failure returns false with *error = "FILE:LINE: message".
bool ReadSceneFile(const char *path, Scene *scene, std::string *error);

// Reads a scene from text, naming it fileName in errors.
bool ParseSceneText(const std::string &text, const char *fileName, Scene *scene,
                    std::string *error);

// What a render of the scene would hide without a word, for warnings: a point light inside a
// sphere (its shadow rays end on it, so nothing outside is lit by that light), and the eye rays'
// start (the eye, or under the slides' rays the screen's centre) inside a sphere that is not
// glass (the image shows its inside). One line each, no prefix.
std::vector<std::string> InsideWarnings(const Scene *scene, vec3 eyeRaysStart);

// ---- options.cpp: the command line -------------------------------------------------------------

// What the command line asks for; zero or empty means "not given".
struct Options {
    std::string scene = "default", output;
    int width = 0, height = 0, spp = 1, depth = 0, threads = 0;
    int sampling = 0;  // --aa: grid, jitter, adaptive, in SampleMethod's order
    int methodSet = 0; // --methods: robust, handout
    int layout = 0;    // --layout: auto, list, bvh, plain, in fast/'s LayoutChoice order
    int estimator = 0, scatter = 0, lights = 0, roulette = 0; // --estimator, --scatter,
                                                              // --lights, --roulette (shading
                                                              // path): in Estimator's,
                                                              // ScatterMethod's, LightMethod's
                                                              // order; on, off
    int seed = 0;                                             // --seed (shading path)
    int sphereLamps = 0; // --sphere-lamps (shading path): cone, area
    int sphere = -1, triangle = -1, selfHit = -1, cameraRay = -1, fresnel = -1; // -1: from the set
    real epsilon = 0; // --self-hit epsilon=E
    bool stats = false, help = false, version = false;
    bool probeRay = false, pixel = false, view = false, compare = false;
    real probe[6];
    int pixelX = 0, pixelY = 0;
    ViewKind viewKind = VIEW_NORMAL;
    std::string raysFile, compareA, compareB;
    double tolerance = 0;
};

// Options::layout for `--layout plain` (LAYOUT_PLAIN: main checks that they agree).
const int kPlainLayout = 3;

extern const char *kVersion;

// --help's text.
std::string UsageText();

// Reads the command line into *opt; false with *error (one line) for anything not allowed:
// unknown options, missing or bad values, an option given twice, modes that do not go together.
bool ParseOptions(int argc, char **argv, Options *opt, std::string *error);

// The methods the options choose: the set (--methods), then each single-method option given.
Methods ChosenMethods(const Options *opt);

// The render settings the scene and the options choose, planned for the scene (PlanRender), with
// a progress line on standard error when it is a terminal.
RenderSettings ChosenSettings(const Options *opt, const Scene *scene);

// ---- modes.cpp: the program's modes, and what it reports ---------------------------------------

// An error or warning, as one line `ray: MESSAGE` on standard error, whatever it quotes: a
// control character (a newline in a file's name) is written as an escape (PrintableLine).
void Complain(const std::string &message);

// --compare: prints the difference, writes the heat map if -o was given. Returns the exit code.
int CompareMode(const Options *opt);

// --ray or --rays: one JSON line per ray. Returns the exit code.
int ProbeMode(const Options *opt, const Scene *scene, const RenderSettings *settings);

// --pixel X Y: the pixel's ray tree as JSON. Returns the exit code.
int PixelTreeMode(const Options *opt, const Scene *scene, const RenderSettings *settings);

// --size refused (false, *error), or the scene's own size warned of (true, *warning), when the
// pixels of a screen camera would not be square; the message names a size that fits.
bool CheckScreenCameraSize(const Options *opt, const Scene *scene, std::string *error,
                           std::string *warning);

// Why a lit render of this scene can only be one flat colour, for a warning: it has no shapes
// (every pixel is the background), or nothing gives light (no light, a black background, and
// ambient 0, or under `shading path` no material that emits): every pixel is black. Empty if
// neither. (A warning, not an error: a test scene may mean it.)
std::string OneColourWarning(const Scene *scene);

// The file a render (or --view) writes: -o, or the scene's default name (a debug view's beside
// the image: reference_normal.png), checked (CheckOutputPath) against the run's inputs: the
// scene file, if `sceneIsFile`, and its meshes. False, said, and the exit status, if refused.
bool ChooseOutput(const Options *opt, const Scene *scene, bool sceneIsFile,
                  const std::string &defaultOutput, std::string *output, int *status);

// The warnings of a render (not of a debug view): a scene that can only be one flat colour
// (OneColourWarning), and what it would hide without a word (InsideWarnings).
void WarnOfRender(const Options *opt, const Scene *scene, const RenderSettings *settings);

// --stats: each mesh statement's triangles and their bounding box (where the model is, and how big,
// after its words: to frame it with the camera, or to choose `fit`).
void PrintMeshes(const Scene *scene);

// --stats: the image, the time, the rays by kind, the speed and the effects used (`threads`: the
// threads the render ran on, which may be fewer than --threads asked for).
void PrintStats(const RayStats *s, const RenderSettings *settings, int threads,
                double renderSeconds, double totalSeconds);

// Whether a `camera screen` can make a ray through every pixel: h and v non-zero and not parallel,
// and the eye off the screen's plane (else every ray lies in that plane). False with *error.
bool ScreenCameraIsValid(const Camera *camera, std::string *error);

// A screen camera's edges fix its shape, so its image must keep it, or the pixels would not be
// square: whether a W x H image does, for edges of lengths h and v (to within 1 part in 256).
bool SquarePixels(double W, double H, double h, double v);

// The size nearest `width` wide whose pixels are square for edges h and v (SquarePixels); false
// if none up to 16384 x 16384 is.
bool SquareSize(int width, double h, double v, int *W, int *H);

// Whether a screen camera's edges are not at right angles, to the same 1 part in 256 (the cosine
// of their angle): its pixels are then parallelograms, which a size can make equal-sided but not
// square.
bool ScreenIsSheared(const Camera *camera);
