// SPDX-License-Identifier: Apache-2.0
// MiniProf reader (docs/profiles.md "MiniProf"). The layout follows the files the instrument
// software writes and CONTACT's testbank holds; the orientation and placement rules are ours and
// documented there.
#include "profile/formats/miniprof.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace railtab::detail {
namespace {

constexpr double kMPerMm = 1e-3;
constexpr double kWheelBackToRunningCircle = 70.0;  // [mm] taping line from the flange back (EN 13715)
constexpr double kMinPointDistance = 1e-4;          // [mm] closer consecutive points are dropped
constexpr double kMaxGlitchStep = 0.05;             // [mm] smaller steps backwards are dropped

struct RawPoint {
  double x;  // file X [mm]
  double y;  // file Y [mm]
  int line;
};

// '"', '!' and '%' start a comment anywhere, '#' only at the start of a line (the keyed header
// has values such as UOF1=#title).
std::string_view miniprof_content(std::string_view line) {
  std::string_view s = trim(line);
  if (!s.empty() && s.front() == '#') return {};
  const auto cut = s.find_first_of("\"!%");
  return trim(cut == std::string_view::npos ? s : s.substr(0, cut));
}

bool contains(std::string_view s, std::string_view what) { return s.find(what) != std::string_view::npos; }

// Positions of X and Y in a ColumnDef such as "X,Y,A,C".
void parse_column_def(std::string_view value, const fs::path& file, int line, int& n_columns,
                      int& x_col, int& y_col) {
  x_col = y_col = -1;
  n_columns = 0;
  for (std::string_view name : split_fields(value)) {
    if (trim(name) == "X") x_col = n_columns;
    if (trim(name) == "Y") y_col = n_columns;
    ++n_columns;
  }
  if (x_col < 0 || y_col < 0) {
    fail(file, line, fmt::format("ColumnDef={} names no X and Y column", value));
  }
}

bool interior(std::size_t i, std::size_t n) {
  const std::size_t margin = std::max<std::size_t>(1, n / 20);
  return i >= margin && i + margin < n;
}

// +1 when file Y points up, -1 when it points down: the extreme towards the other body (a
// wheel's flange tip, a rail's top) lies inside the measured range, the other one at its ends.
double vertical_sign(const std::vector<RawPoint>& p, ProfileKind kind, const fs::path& file) {
  const auto by_y = [](const RawPoint& a, const RawPoint& b) { return a.y < b.y; };
  const auto i_min = static_cast<std::size_t>(std::min_element(p.begin(), p.end(), by_y) - p.begin());
  const auto i_max = static_cast<std::size_t>(std::max_element(p.begin(), p.end(), by_y) - p.begin());
  const bool min_in = interior(i_min, p.size());
  const bool max_in = interior(i_max, p.size());
  if (min_in == max_in) {
    fail(file, 0,
         fmt::format("cannot tell whether Y points up or down (lowest point on line {}, highest on "
                     "line {}, both {} the measured range): give mirror_z",
                     p[i_min].line, p[i_max].line, min_in ? "inside" : "at the ends of"));
  }
  const bool wheel = kind == ProfileKind::wheel;
  // Wheel: the flange tip is the interior extreme and points down; rail: the top, pointing up.
  return (wheel == min_in) ? 1.0 : -1.0;
}

// +1 when file X points to the field side, -1 when it points to the track centre.
double lateral_sign(const std::vector<RawPoint>& p, double z_sign, ProfileKind kind) {
  auto z_up = [&](const RawPoint& a) { return z_sign * a.y; };
  const auto [lo, hi] = std::minmax_element(p.begin(), p.end(), [](const RawPoint& a, const RawPoint& b) {
    return a.x < b.x;
  });
  const double x_min = lo->x, x_max = hi->x;
  if (kind == ProfileKind::wheel) {  // the flange (lowest point) lies on the track side
    const auto tip = std::min_element(p.begin(), p.end(), [&](const RawPoint& a, const RawPoint& b) {
      return z_up(a) < z_up(b);
    });
    return tip->x - x_min <= x_max - tip->x ? 1.0 : -1.0;
  }
  // Rail: the gauge face, measured deeper than the field side, lies on the track side; a head
  // measured to the same depth on both sides (within 1 mm) keeps the file's direction.
  const auto top = std::max_element(p.begin(), p.end(), [&](const RawPoint& a, const RawPoint& b) {
    return z_up(a) < z_up(b);
  });
  double depth_low_x = 0.0, depth_high_x = 0.0;
  for (const RawPoint& a : p) {
    const double depth = z_up(*top) - z_up(a);
    (a.x < top->x ? depth_low_x : depth_high_x) = std::max(a.x < top->x ? depth_low_x : depth_high_x, depth);
  }
  return depth_high_x > depth_low_x + 1.0 ? -1.0 : 1.0;
}

}  // namespace

bool looks_like_miniprof(const std::vector<std::string>& lines) {
  for (std::size_t i = 0; i < lines.size() && i < 3; ++i) {
    if (contains(lines[i], "MINIPROF") || contains(lines[i], "[FileInfo]")) return true;
  }
  for (std::size_t i = 0; i < lines.size() && i < 200; ++i) {
    const std::string_view s = miniprof_content(lines[i]);
    if (s.starts_with("ColumnDef=") || s.starts_with("XYPoints=")) return true;
  }
  return false;
}

std::vector<FilePoint> read_miniprof(const std::vector<std::string>& lines, const fs::path& file,
                                     ProfileKind kind, const MiniProfOptions& options) {
  bool old_style = false;
  for (std::size_t i = 0; i < lines.size() && i < 3; ++i) {
    if (contains(lines[i], "[FileInfo]")) {
      fail(file, static_cast<int>(i) + 1,
           "multi-part MiniProf files (.mpt) are not supported: export the profile as .whl or .ban");
    }
    old_style = old_style || contains(lines[i], "MINIPROF");
  }
  int n_columns = 0, x_col = 0, y_col = 1;
  bool column_def = false;
  bool in_data = !old_style;  // old style: free header text up to the first blank line
  std::vector<RawPoint> raw;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    if (!in_data) {
      in_data = trim(lines[i]).empty();
      continue;
    }
    const std::string_view s = miniprof_content(lines[i]);
    if (s.empty()) continue;
    if (const auto eq = s.find('='); eq != std::string_view::npos) {
      if (!raw.empty()) fail(file, line, fmt::format("header line '{}' after the data", s));
      if (trim(s.substr(0, eq)) == "ColumnDef") {
        parse_column_def(trim(s.substr(eq + 1)), file, line, n_columns, x_col, y_col);
        column_def = true;
      }
      continue;  // other keys describe the measurement, not the shape
    }
    const auto fields = split_fields(s);
    if (raw.empty() && !column_def) n_columns = static_cast<int>(fields.size());
    if (static_cast<int>(fields.size()) != n_columns || n_columns < 2) {
      fail(file, line,
           fmt::format("expected {} columns ({}), found {}", n_columns,
                       column_def ? "as ColumnDef says" : "as the first data line", fields.size()));
    }
    raw.push_back({parse_number(fields[static_cast<std::size_t>(x_col)], file, line, "X"),
                   parse_number(fields[static_cast<std::size_t>(y_col)], file, line, "Y"), line});
    check_point_count(raw.size(), file, line);
    if (raw.size() > 1) {
      const RawPoint& q = raw[raw.size() - 2];
      if (std::hypot(raw.back().x - q.x, raw.back().y - q.y) < kMinPointDistance) raw.pop_back();
    }
  }
  if (raw.size() < 4) {
    fail(file, static_cast<int>(lines.size()),
         fmt::format("too few profile points: {} (a spline needs at least 4)", raw.size()));
  }
  // A point that steps back against the measuring direction by less than the instrument's
  // resolution where the surface is flatter than 45 degrees is noise (avg_HR.BAN: X = 29.27 then 29.26 at the same Y); kept, it would fold the
  // curve into a tiny loop that hides the rest of the surface. A real overhang turns back over
  // many points and survives (each step is compared with the last point kept).
  const double direction = raw.back().x >= raw.front().x ? 1.0 : -1.0;
  std::vector<RawPoint> kept{raw.front()};
  for (std::size_t i = 1; i < raw.size(); ++i) {
    const double step = direction * (raw[i].x - kept.back().x);
    const bool flat = std::abs(raw[i].y - kept.back().y) < -step;  // flatter than 45 deg
    if (step < 0.0 && step > -kMaxGlitchStep && flat && i + 1 < raw.size()) continue;
    kept.push_back(raw[i]);
  }
  raw = std::move(kept);
  for (const RawPoint& p : raw) {  // before any arithmetic on them (docs/profiles.md "Limits")
    if (std::abs(p.x) * kMPerMm > limits::kMaxProfileCoordinate ||
        std::abs(p.y) * kMPerMm > limits::kMaxProfileCoordinate) {
      fail(file, p.line, fmt::format("coordinate ({}, {}) mm is beyond the limit of {} m", p.x, p.y,
                                     limits::kMaxProfileCoordinate));
    }
  }

  // z_down = -z_sign * Y, y = x_sign * X (file units mm).
  const double z_sign = options.mirror_z == Mirror::automatic ? vertical_sign(raw, kind, file)
                        : options.mirror_z == Mirror::yes     ? 1.0
                                                              : -1.0;
  const double x_sign = options.mirror_y == Mirror::automatic ? lateral_sign(raw, z_sign, kind)
                        : options.mirror_y == Mirror::yes     ? -1.0
                                                              : 1.0;
  std::vector<FilePoint> points;
  points.reserve(raw.size());
  for (const RawPoint& p : raw) points.push_back({x_sign * p.x, -z_sign * p.y, p.line});

  if (kind == ProfileKind::wheel) {
    // Flange back (innermost point) at u = -70 mm; z = 0 where the tread crosses u = 0.
    double y_back = points.front().y;
    for (const FilePoint& p : points) y_back = std::min(y_back, p.y);
    const double shift = y_back + kWheelBackToRunningCircle;
    for (FilePoint& p : points) p.y -= shift;
    bool found = false;
    double z0 = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      const FilePoint& a = points[i - 1];
      const FilePoint& b = points[i];
      if ((a.y - 0.0) * (b.y - 0.0) > 0.0 || a.y == b.y) continue;
      const double z = a.z + (b.z - a.z) * (0.0 - a.y) / (b.y - a.y);
      if (!found || z > z0) z0 = z;  // z down: the point facing the rail
      found = true;
    }
    if (!found) {
      fail(file, 0, fmt::format("the wheel does not reach u = 0, {} mm from its flange back: not a "
                                "wheel profile?", kWheelBackToRunningCircle));
    }
    for (FilePoint& p : points) p.z -= z0;
  }
  for (FilePoint& p : points) {
    p.y *= kMPerMm;
    p.z *= kMPerMm;
  }
  return points;
}

}  // namespace railtab::detail
