// bench/svg.h -- what the bench's hand-written SVG plots share: axes fitted to the data (a log
// axis snapped to decades, half-decades or 1-2-5 steps, whichever leaves no large empty band),
// and labels placed beside their markers so that they overlap neither each other nor a marker.
#pragma once

#include <string>
#include <vector>

// One axis: its ends in data units, the pixels they map to, and the values to label.
struct SvgAxis {
    double lo, hi;
    bool log;
    double p0, p1; // the pixels of lo and hi (p1 < p0 for a y axis)
    std::vector<double> ticks;
};

// An axis over the data [lo, hi] drawn from pixel `from` to pixel `to`; the data keep a margin
// of a few pixels from both ends.
SvgAxis FitAxis(double lo, double hi, bool log, double from, double to);
double AxisPixel(const SvgAxis &axis, double value);

struct SvgBox {
    double x0, y0, x1, y1;
};
// The frame of a plot: the axes' pixels and their margins.
SvgBox FrameBox(const SvgAxis &x, const SvgAxis &y);
// The frame of a plot drawn, its ticks, tick labels, grid lines and axis titles, as SVG elements.
std::string SvgFrame(const SvgAxis &x, const SvgAxis &y, const char *xTitle, const char *yTitle);

struct SvgCircle {
    double x, y, r;
};
struct SvgSegment {
    double x0, y0, x1, y1;
};

// What labels must avoid: the area they stay in, the labels placed so far, the markers and the
// bars (such as whiskers from min to max); the plotted lines are avoided where possible.
struct SvgLabels {
    SvgBox area;
    std::vector<SvgBox> placed;
    std::vector<SvgCircle> markers;
    std::vector<SvgSegment> lines, bars;
    std::vector<std::string> legend, legendFill; // "X  text" for each label that had no room
};

void AddMarker(SvgLabels *labels, double x, double y, double r);
// A line labels avoid where they can, or (`hard`) a bar they always avoid.
void AddLine(SvgLabels *labels, double x0, double y0, double x1, double y1, bool hard);

// A <text> element for `text` beside the marker of radius r at (x, y), in a free place among
// right, left, above, below (centred, or starting or ending at the marker) and the diagonals,
// the one nearest the fewest other markers. With none free, the label becomes a letter there
// (or a little away, a line leading to it), and "letter  text" goes to labels->legend.
std::string PlaceLabel(SvgLabels *labels, double x, double y, double r, const std::string &text,
                       const char *fill, int fontSize);

// Labels for several markers (each already added with AddMarker), the most crowded first: a
// marker with others near it has the fewest free places.
struct SvgMark {
    double x, y, r;
    std::string text;
    const char *fill;
    int fontSize;
};
std::string PlaceLabels(SvgLabels *labels, const std::vector<SvgMark> &marks);

// The lettered labels' legend as <text> lines from (x, y) down, one every `step` pixels.
std::string SvgLegend(const SvgLabels &labels, double x, double y, double step);

// printf into a std::string, of any length.
#if defined(__GNUC__) || defined(__clang__) // (so that -Wformat checks the calls)
std::string Format(const char *format, ...) __attribute__((format(printf, 1, 2)));
#else
std::string Format(const char *format, ...);
#endif

// A time measured several times, as the plots draw it (whiskers) and the sentences compare it.
struct Spread {
    double median, min, max;
};
Spread SpreadOf(std::vector<double> times);
// Whether two times' [min, max] ranges overlap: then no difference between them is claimed.
bool WithinNoise(const Spread &a, const Spread &b);
// "median (min-max)", each number printed with `format` (such as "%.1f").
std::string SpreadText(const Spread &s, const char *format);
