// SPDX-License-Identifier: Apache-2.0
// Reading profile files (profile_io.hpp): SIMPACK, MiniProf and two-column text into a Profile.
#include "profile/formats/profile_io.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "profile/formats/miniprof.hpp"
#include "profile/curves/parametric_profile.hpp"
#include "profile/formats/parse_util.hpp"
#include "profile/formats/profile_checks.hpp"
#include "profile/curves/spline_profile.hpp"
#include "profile/formats/text_file.hpp"

namespace railtab {
namespace {

using namespace detail;  // the readers' shared helpers (parse_util.hpp, text_file.hpp, miniprof.hpp)

// A key = value option of a SIMPACK header or spline block.
struct Option {
  std::string value;  // text after '=', trimmed
  int line;           // where it was set
};

double option_number(const std::map<std::string, Option>& options, const std::string& key,
                     double fallback, const fs::path& file) {
  const auto it = options.find(key);
  if (it == options.end()) return fallback;
  return parse_number(it->second.value, file, it->second.line, key);
}

// SIMPACK .prw/.prr: blocks "name.begin ... name.end"; options in header and spline, points in
// spline/point. Returns the points after SIMPACK's processing, in metres, z down.
std::vector<FilePoint> read_simpack(const std::vector<std::string>& lines, const fs::path& file,
                                    ProfileKind kind) {
  std::vector<std::string> blocks;  // open blocks, innermost last
  std::map<std::string, Option> header;
  std::map<std::string, Option> spline;
  std::vector<FilePoint> points;
  bool saw_points = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    const std::string_view s = trim(strip_comment(lines[i], "!"));
    if (s.empty()) continue;
    constexpr std::string_view kBegin = ".begin";
    constexpr std::string_view kEnd = ".end";
    if (s.size() > kBegin.size() && s.ends_with(kBegin) && s.find('=') == std::string_view::npos) {
      blocks.emplace_back(s.substr(0, s.size() - kBegin.size()));
      saw_points = saw_points || blocks.back() == "point";
      continue;
    }
    if (s.size() > kEnd.size() && s.ends_with(kEnd) && s.find('=') == std::string_view::npos) {
      const std::string_view name = s.substr(0, s.size() - kEnd.size());
      if (blocks.empty() || blocks.back() != name) {
        fail(file, line, fmt::format("'{}' does not close the open block '{}'", s,
                                     blocks.empty() ? std::string("(none)") : blocks.back()));
      }
      blocks.pop_back();
      continue;
    }
    const std::string current = blocks.empty() ? std::string() : blocks.back();
    if (current == "point") {
      const auto fields = split_fields(s);
      if (fields.size() < 2 || fields.size() > 3) {
        fail(file, line, fmt::format("expected 2 or 3 columns (y z [weight]), found {}", fields.size()));
      }
      points.push_back({parse_number(fields[0], file, line, "y"),
                        parse_number(fields[1], file, line, "z"), line});
      check_point_count(points.size(), file, line);
      if (fields.size() == 3) parse_number(fields[2], file, line, "weight");
      continue;
    }
    const auto eq = s.find('=');
    if (eq == std::string_view::npos || (current != "header" && current != "spline")) {
      fail(file, line, fmt::format("unexpected text '{}' in block '{}'", s, current));
    }
    Option option{std::string(trim(s.substr(eq + 1))), line};
    (current == "header" ? header : spline)[std::string(trim(s.substr(0, eq)))] = std::move(option);
  }
  const int last_line = static_cast<int>(lines.size());
  if (!blocks.empty()) fail(file, last_line, fmt::format("block '{}' is not closed", blocks.back()));
  if (!saw_points) fail(file, last_line, "no point.begin ... point.end block");

  if (const auto it = header.find("type"); it != header.end()) {
    const double type = parse_number(it->second.value, file, it->second.line, "type");
    const double expected = kind == ProfileKind::wheel ? 1.0 : 0.0;
    if (type != expected) {
      fail(file, it->second.line,
           fmt::format("header type = {} ({}), but a {} profile was asked for", it->second.value,
                       type == 1.0 ? "wheel" : type == 0.0 ? "rail" : "unknown",
                       kind == ProfileKind::wheel ? "wheel" : "rail"));
    }
  }

  // Processing options, in SIMPACK's order (as CONTACT's read_simpack applies them).
  const double dist_min = option_number(spline, "point.dist.min", 0.0, file);
  if (dist_min > 0.0 && !points.empty()) {
    std::vector<FilePoint> kept{points.front()};
    for (const FilePoint& p : points) {
      if (std::fabs(p.y - kept.back().y) > dist_min) kept.push_back(p);
    }
    points = std::move(kept);
  }
  const double shift_y = option_number(spline, "shift.y", 0.0, file);
  const double shift_z = option_number(spline, "shift.z", 0.0, file);
  const double angle_factor = option_number(spline, "units.ang.f", 1.0, file);
  const double rotate = option_number(spline, "rotate", 0.0, file) / angle_factor;
  const double c = std::cos(rotate);
  const double s = std::sin(rotate);
  for (FilePoint& p : points) {
    const double y = p.y + shift_y;
    const double z = p.z + shift_z;
    p.y = c * y - s * z;
    p.z = s * y + c * z;
  }
  const double y_min = option_number(spline, "bound.y.min", 1.0, file);
  const double y_max = option_number(spline, "bound.y.max", 0.0, file);
  if (y_min < y_max) {
    std::erase_if(points, [&](const FilePoint& p) { return p.y < y_min || p.y > y_max; });
  }
  const double z_min = option_number(spline, "bound.z.min", 1.0, file);
  const double z_max = option_number(spline, "bound.z.max", 0.0, file);
  if (z_min < z_max) {
    for (FilePoint& p : points) p.z = std::clamp(p.z, z_min, z_max);
  }
  const bool mirror_y = option_number(spline, "mirror.y", 0.0, file) == 1.0;
  const bool mirror_z = option_number(spline, "mirror.z", 0.0, file) == 1.0;
  if (option_number(spline, "inversion", 0.0, file) == 1.0) std::reverse(points.begin(), points.end());
  // units.len.f = file length unit per metre (1000 for mm); CONTACT assumes mm when absent.
  const double length_factor = option_number(spline, "units.len.f", 1000.0, file);
  if (!(length_factor > 0.0)) {
    fail(file, spline.at("units.len.f").line, "units.len.f must be positive");
  }
  for (FilePoint& p : points) {
    p.y = (mirror_y ? -p.y : p.y) / length_factor;
    p.z = (mirror_z ? -p.z : p.z) / length_factor;
  }
  return points;
}

// Two columns "lateral vertical" in mm, lateral towards the field side, vertical downwards.
std::vector<FilePoint> read_two_column(const std::vector<std::string>& lines, const fs::path& file) {
  constexpr double kMPerMm = 1e-3;
  std::vector<FilePoint> points;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    const auto fields = split_fields(trim(strip_comment(lines[i], "#%!")));
    if (fields.empty()) continue;
    if (fields.size() != 2) {
      fail(file, line, fmt::format("expected 2 columns (lateral vertical, mm), found {}", fields.size()));
    }
    points.push_back({parse_number(fields[0], file, line, "lateral coordinate") * kMPerMm,
                      parse_number(fields[1], file, line, "vertical coordinate") * kMPerMm, line});
    check_point_count(points.size(), file, line);
  }
  return points;
}

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool is_simpack(const fs::path& file, const std::vector<std::string>& lines) {
  const std::string ext = lower_extension(file);
  if (ext == ".prw" || ext == ".prr") return true;
  for (const std::string& l : lines) {
    const std::string_view s = trim(strip_comment(l, "!"));
    if (s == "header.begin" || s == "spline.begin") return true;
  }
  return false;
}

bool is_miniprof(const fs::path& file, const std::vector<std::string>& lines) {
  const std::string ext = lower_extension(file);
  return ext == ".whl" || ext == ".ban" || ext == ".mpt" || looks_like_miniprof(lines);
}

// A cut file: its last line holds data but no line end, so its last number may be incomplete.
void check_not_cut(const TextFile& text, const fs::path& file) {
  if (text.ends_with_newline || text.lines.empty()) return;
  const std::string_view last = trim(strip_comment(text.lines.back(), "#%!\""));
  if (!last.empty() && (std::isdigit(static_cast<unsigned char>(last.front())) ||
                        last.front() == '-' || last.front() == '+' || last.front() == '.')) {
    fail(file, static_cast<int>(text.lines.size()),
         "the last line has no line end: the file looks cut off (its last number may be incomplete)");
  }
}

void check_coordinates(const std::vector<FilePoint>& points, const fs::path& file) {
  for (const FilePoint& p : points) {
    if (!(std::abs(p.y) <= limits::kMaxProfileCoordinate && std::abs(p.z) <= limits::kMaxProfileCoordinate)) {
      fail(file, p.line,
           fmt::format("point ({:.6g}, {:.6g}) m is beyond the coordinate limit of {} m (wrong "
                       "length unit?)",
                       p.y, p.z, limits::kMaxProfileCoordinate));
    }
  }
}

}  // namespace

ProfilePtr read_profile(const fs::path& file, ProfileKind kind, double smoothing_length) {
  ProfileReadOptions options;
  options.smoothing_length = smoothing_length;
  return read_profile(file, kind, options);
}

ProfilePtr read_profile(const fs::path& file, ProfileKind kind, const ProfileReadOptions& options) {
  const TextFile text = read_text_file(file);
  const std::vector<std::string>& lines = text.lines;
  check_not_cut(text, file);
  std::vector<FilePoint> points;
  if (is_simpack(file, lines)) {
    points = read_simpack(lines, file, kind);
  } else if (is_miniprof(file, lines)) {
    points = read_miniprof(lines, file, kind, {options.mirror_y, options.mirror_z});
  } else {
    points = read_two_column(lines, file);
  }
  if (!is_miniprof(file, lines) &&
      (options.mirror_y != AxisMirror::automatic || options.mirror_z != AxisMirror::automatic)) {
    fail(file, 0, "mirror_y / mirror_z apply to MiniProf files only (SIMPACK files carry mirror.y / "
                  "mirror.z, two-column files have a fixed orientation)");
  }
  const int last_line = static_cast<int>(lines.size());
  if (points.size() < 4) {
    fail(file, last_line, fmt::format("too few profile points: {} (a spline needs at least 4)", points.size()));
  }
  check_coordinates(points, file);
  // Our frames: u = lateral (towards the field side), z = -vertical (up); ascending u at the ends.
  if (points.back().y < points.front().y) std::reverse(points.begin(), points.end());
  std::vector<double> u;
  std::vector<double> z;
  u.reserve(points.size());
  z.reserve(points.size());
  bool single_valued = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const FilePoint& p = points[i];
    if (i > 0) {
      const FilePoint& q = points[i - 1];
      if (p.y == q.y && p.z == q.z) {
        fail(file, p.line, fmt::format("duplicate point ({} mm, {} mm), same as on line {}",
                                       p.y * 1e3, p.z * 1e3, q.line));
      }
      single_valued = single_valued && p.y > q.y;
    }
    u.push_back(p.y + options.lateral_shift);
    z.push_back(-p.z);
  }
  RAILTAB_CHECK(std::isfinite(options.lateral_shift) && std::abs(options.lateral_shift) <= limits::kMaxProfileCoordinate,
                "{}: lateral shift {} m must be finite and at most {} m", file.string(), options.lateral_shift,
                limits::kMaxProfileCoordinate);
  RAILTAB_CHECK(std::isfinite(options.smoothing_length) && options.smoothing_length >= 0.0,
                "{}: smoothing length {} m must be finite and >= 0", file.string(), options.smoothing_length);
  // Overhangs, undercuts and vertical faces make a curve that is not a function z(u): parametric.
  ProfilePtr profile =
      single_valued ? ProfilePtr(std::make_shared<const SplineProfile>(file.stem().string(), kind, std::move(u),
                                                                       std::move(z), options.smoothing_length))
                    : ProfilePtr(std::make_shared<const ParametricProfile>(
                          file.stem().string(), kind, std::move(u), std::move(z), options.smoothing_length));
  if (options.check_plausibility) check_plausible_profile(*profile, file.string());
  return profile;
}

}  // namespace railtab
