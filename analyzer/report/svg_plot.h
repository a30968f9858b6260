#pragma once
// A plot frame for the HTML report's SVG charts: axis titles with units, ticks at round
// values (1, 2 or 5 times a power of ten), grid lines; the caller draws the data inside
// with x() and y().
#include <string>
#include <vector>

namespace busdecode {

// Round tick values covering [lo, hi], about `target` of them.
std::vector<double> niceTicks(double lo, double hi, int target = 6);
// A tick value with the decimals its step needs ("0.25", "1500", "-3").
std::string tickText(double v, double step);

// The unit a span of time reads best in: "ns", "us", "ms" or "s", and its length in ns.
struct TimeUnit {
    const char* name;
    double ns;
};
TimeUnit timeUnitFor(double span_ns);

struct PlotAxis {
    double lo = 0, hi = 1;
    std::string title;  // "time (ms)", "position (counts)"
};

class SvgPlot {
public:
    // `css_class` names the chart for the page and its tests; the box is W x H pixels.
    SvgPlot(std::string css_class, double width, double height, std::string title, PlotAxis x,
            PlotAxis y);
    double x(double v) const;
    double y(double v) const;
    double left() const { return L_; }
    double right() const { return W_ - R_; }
    double top() const { return T_; }
    double bottom() const { return H_ - B_; }
    // Tick labels on the right-hand side: the y ticks times `scale`, under `title`.
    void secondYAxis(double scale, std::string title);
    // Ticks on x at these values instead of round ones (integer bins).
    void xTicksAt(std::vector<double> ticks) { x_ticks_ = std::move(ticks); }
    // No y ticks or grid (a waveform's rows are lines, not values).
    void hideYTicks() { y_ticks_ = false; }
    std::string& body() { return body_; }
    // The whole <svg> element: frame, grid, ticks and titles under the body.
    std::string svg() const;

private:
    std::string css_class_, title_;
    PlotAxis xa_, ya_;
    double W_, H_, L_ = 78, R_ = 16, T_ = 26, B_ = 44;
    double second_scale_ = 0;
    std::string second_title_;
    std::vector<double> x_ticks_;
    bool y_ticks_ = true;
    std::string body_;
};

}  // namespace busdecode
