#include "experiments/report/sticking_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <utility>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

constexpr const char* kClasses[] = {"must", "may", "never"};
const cv::Scalar kClassBands[] = {rgb(0xd9ecd0), rgb(0xfdf0c2), rgb(0xe3e0f0)};
constexpr double kYMargin = 0.05;  // stick fractions are in [0, 1]; a little air above and below
constexpr double kNiceSteps[] = {1, 2, 2.5, 5};
constexpr int kMaxMarkerRadius = 7;  // px, the face markers'
constexpr int kLabelGap = 3;         // px between the largest marker and the counts
constexpr int kCountSpacing = 11;    // px between the rows of counts in one bin
constexpr double kCountShade = 0.6;  // counts are written in their kind's colour at this brightness

// How the markers of one atom kind look. Markers of several kinds in one bin may coincide; faces, edges and
// vertices are drawn in this order, from the largest marker to the smallest, so each stays visible inside
// the one below it.
struct KindStyle {
  cv::Scalar color;
  LegendMarker shape;
  int radius;  // px
};

const std::pair<const char*, KindStyle> kKnownKinds[] = {
    {"face", {rgb(0x0072b2), LegendMarker::kDot, kMaxMarkerRadius}},
    {"edge", {rgb(0xe69f00), LegendMarker::kSquare, 5}},
    {"vertex", {rgb(0xcc79a7), LegendMarker::kDiamond, 4}},
};
// Kinds the records name beyond these, in turn.
const cv::Scalar kOtherKindColors[] = {rgb(0x009e73), rgb(0x56b4e9), rgb(0xd55e00)};

int known_rank(const std::string& kind) {
  for (int i = 0; i < 3; ++i)
    if (kind == kKnownKinds[i].first) return i;
  return 3;
}

KindStyle kind_style(const std::string& kind, int other_index) {
  const int rank = known_rank(kind);
  if (rank < 3) return kKnownKinds[rank].second;
  return {kOtherKindColors[other_index % 3], LegendMarker::kTriangle, 5};
}

std::string plural(const std::string& kind) { return kind == "vertex" ? "vertices" : kind + "s"; }

int class_index(const nlohmann::json& record) {
  if (!record.contains("class") || !record["class"].is_string()) return -1;
  const std::string& name = record["class"].get_ref<const std::string&>();
  for (int i = 0; i < 3; ++i)
    if (name == kClasses[i]) return i;
  return -1;
}

// One record reduced to what the figure shows.
struct Trial {
  std::string kind;
  double ratio;  // alpha/phi
  int cls;       // index into kClasses, -1 when unknown
  bool stuck;
};

// The usable records; the others are counted in `skipped`.
std::vector<Trial> usable_trials(const nlohmann::json& records, int& skipped) {
  std::vector<Trial> out;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const nlohmann::json& r = records[i];
    if (!r.is_object()) throw std::invalid_argument("records[" + std::to_string(i) + "]: expected an object");
    const auto number = [&](const char* key) {
      return r.contains(key) && r[key].is_number() ? r[key].get<double>() : std::nan("");
    };
    const double alpha = number("command_angle"), phi = number("phi");
    const bool has_kind =
        r.contains("kind") && r["kind"].is_string() && !r["kind"].get_ref<const std::string&>().empty();
    if (!has_kind || !std::isfinite(alpha) || !std::isfinite(phi) || phi <= 0 ||
        !std::isfinite(alpha / phi)) {
      ++skipped;
      continue;
    }
    const bool stuck = r.contains("stuck") && r["stuck"].is_boolean() && r["stuck"].get<bool>();
    out.push_back({r["kind"].get<std::string>(), alpha / phi, class_index(r), stuck});
  }
  return out;
}

std::vector<std::string> ordered_kinds(const std::vector<Trial>& trials) {
  std::vector<std::string> kinds;
  for (const Trial& t : trials)
    if (std::find(kinds.begin(), kinds.end(), t.kind) == kinds.end()) kinds.push_back(t.kind);
  std::sort(kinds.begin(), kinds.end(), [](const std::string& a, const std::string& b) {
    return std::make_pair(known_rank(a), a) < std::make_pair(known_rank(b), b);
  });
  return kinds;
}

// Per bin index, which predicted classes occur in it (over all kinds).
std::map<int, std::array<bool, 3>> classes_per_bin(const StickBinning& binning) {
  std::map<int, std::array<bool, 3>> out;
  for (const StickBin& b : binning.bins)
    for (int c = 0; c < 3; ++c) out[b.index][c] = out[b.index][c] || b.classes[c] > 0;
  return out;
}

// Each bin's height [0, 1] split evenly among the classes occurring in it, must at the bottom.
void draw_class_bands(PlotCanvas& canvas, const StickBinning& binning) {
  for (const auto& [index, present] : classes_per_bin(binning)) {
    const int count = present[0] + present[1] + present[2];
    const double lo = binning.origin + index * binning.width;
    double y = 0;
    for (int c = 0; c < 3; ++c) {
      if (!present[c]) continue;
      canvas.rectangle({lo, y}, {lo + binning.width, y + 1.0 / count}, kClassBands[c]);
      y += 1.0 / count;
    }
  }
}

std::vector<KindStyle> kind_styles(const std::vector<std::string>& kinds) {
  std::vector<KindStyle> styles;
  int others = 0;
  for (const std::string& k : kinds) styles.push_back(kind_style(k, known_rank(k) < 3 ? 0 : others++));
  return styles;
}

// A drawn marker: its bin and its kind's style.
struct Marker {
  const StickBin* bin;
  const KindStyle* style;
};

// The counts of one bin's markers, right of them in their kind's darker colour: each at its marker's height,
// pushed down where it would overlap the count above it, so the counts of markers that (nearly) coincide stay
// readable.
void draw_counts(PlotCanvas& canvas, std::vector<Marker> markers) {
  const auto higher = [](const Marker& a, const Marker& b) { return a.bin->fraction() > b.bin->fraction(); };
  std::sort(markers.begin(), markers.end(), higher);  // top down
  double free_from = -1e9;                            // px: the highest pixel row the next count may use
  for (const Marker& m : markers) {
    const DataPoint p(m.bin->centre(), m.bin->fraction());
    const double y = canvas.to_image(p).y;
    const double label_y = std::max(y, free_from);
    free_from = label_y + kCountSpacing;
    canvas.text(p, std::to_string(m.bin->trials),
                {kMaxMarkerRadius + kLabelGap, static_cast<int>(label_y - y)}, TextAnchor::kLeft,
                darker(m.style->color, kCountShade));
  }
}

void draw_markers(PlotCanvas& canvas, const StickBinning& binning, const std::vector<KindStyle>& styles) {
  std::map<int, std::vector<Marker>> per_bin;  // bin index -> its markers
  for (const StickBin& b : binning.bins) {     // by kind: the larger markers first
    const auto slot = std::find(binning.kinds.begin(), binning.kinds.end(), b.kind) - binning.kinds.begin();
    const KindStyle& style = styles[static_cast<std::size_t>(slot)];
    canvas.marker({b.centre(), b.fraction()}, style.shape, style.radius, style.color);
    per_bin[b.index].push_back({&b, &style});
  }
  for (const auto& entry : per_bin) draw_counts(canvas, entry.second);
}

std::string width_text(double width) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", width);
  return buf;
}

void add_legend(PlotCanvas& canvas, const StickBinning& binning, const std::vector<KindStyle>& styles) {
  for (std::size_t k = 0; k < binning.kinds.size(); ++k)
    canvas.add_legend({"observed, " + plural(binning.kinds[k]), styles[k].color, styles[k].shape});
  canvas.add_legend({"numbers: trials per bin", kInk, LegendMarker::kNone});  // in the kind's colour
  canvas.add_legend({"bin width: " + width_text(binning.width) + " alpha/phi", kInk, LegendMarker::kNone});
  for (int c = 0; c < 3; ++c)
    canvas.add_legend(
        {std::string("predicted ") + kClasses[c] + " stick", kClassBands[c], LegendMarker::kFill});
  canvas.add_legend({"alpha = phi", rgb(0x606060), LegendMarker::kLine});
}

}  // namespace

double stick_bin_width(double lo, double hi) {
  const double span = hi - lo;
  if (!std::isfinite(span) || span <= 0) return kStickMinBinWidth;
  const auto bins = [&](double w) { return std::floor(hi / w) - std::floor(lo / w) + 1; };
  for (double decade = std::pow(10.0, std::floor(std::log10(span / kStickMaxBins))); std::isfinite(decade);
       decade *= 10)
    for (double step : kNiceSteps) {
      const double w = std::max(step * decade, kStickMinBinWidth);
      if (bins(w) <= kStickMaxBins) return w;
    }
  return span;  // not reached for finite lo and hi
}

StickBinning bin_sticking_records(const nlohmann::json& sticking) {
  StickBinning out;
  if (!sticking.is_object() || !sticking.contains("records")) return out;
  const nlohmann::json& records = sticking["records"];
  if (!records.is_array()) throw std::invalid_argument("records: expected a list");
  const std::vector<Trial> trials = usable_trials(records, out.skipped);
  if (trials.empty()) return out;
  const auto [lo, hi] = std::minmax_element(trials.begin(), trials.end(),
                                            [](const Trial& a, const Trial& b) { return a.ratio < b.ratio; });
  out.width = stick_bin_width(lo->ratio, hi->ratio);
  const double first = std::floor(lo->ratio / out.width);
  out.origin = first * out.width;
  out.count = static_cast<int>(std::floor(hi->ratio / out.width) - first) + 1;
  out.kinds = ordered_kinds(trials);
  std::map<std::pair<std::size_t, int>, StickBin> bins;  // (kind's place, bin index)
  for (const Trial& t : trials) {
    const int index =
        static_cast<int>(std::clamp(std::floor(t.ratio / out.width) - first, 0.0, out.count - 1.0));
    const auto place =
        static_cast<std::size_t>(std::find(out.kinds.begin(), out.kinds.end(), t.kind) - out.kinds.begin());
    StickBin& b = bins[{place, index}];
    b.kind = t.kind;
    b.index = index;
    b.lo = out.origin + index * out.width;
    b.hi = b.lo + out.width;
    ++b.trials;
    b.stuck += t.stuck;
    if (t.cls >= 0) ++b.classes[t.cls];
  }
  for (auto& entry : bins) out.bins.push_back(std::move(entry.second));
  return out;
}

std::optional<PlotCanvas> draw_sticking_figure(const nlohmann::json& sticking, const std::string& title,
                                               const FigureSize& size) {
  const StickBinning binning = bin_sticking_records(sticking);
  if (binning.bins.empty()) return std::nullopt;
  PlotCanvas canvas(size, title + ": stick fraction vs command angle",
                    "alpha/phi (command angle / friction angle, 1)", "stick fraction (stuck / trials, 1)");
  const double x_lo = std::min(0.0, binning.origin);
  const double x_hi = binning.origin + (binning.count + 1) * binning.width;  // a bin of air on the right
  canvas.set_ranges({x_lo, x_hi}, {-kYMargin, 1 + kYMargin}, false);
  draw_class_bands(canvas, binning);
  canvas.grid();
  // alpha = phi: where a face's friction cone ends.
  canvas.dashed_line({1, -kYMargin}, {1, 1 + kYMargin}, rgb(0x606060), 1);
  const std::vector<KindStyle> styles = kind_styles(binning.kinds);
  draw_markers(canvas, binning, styles);
  add_legend(canvas, binning, styles);
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report
