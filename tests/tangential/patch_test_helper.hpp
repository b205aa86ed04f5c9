// SPDX-License-Identifier: Apache-2.0
// Test helpers for the tangential and wear tests: elliptic ContactPatch data built by hand (the
// same strip layout the normal layer produces), ellipse recovery from a reference's area and
// approach, and a small CSV reader for ../shared/reference.
#pragma once

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "normal/normal_model.hpp"

namespace railtab::test {

// Elliptic patch (semi-axes a along x, b along s) as lateral strips. Semi-elliptic shape: Hertz
// pressure p0 sqrt(1 - x2/a2 - y2/b2), p0 = 3N/(2 pi a b); parabolic: Kalker's simplified
// 2N/(pi a b)(1 - x2/a2 - y2/b2). Planar patch in a tangent plane at contact angle gamma: the wheel
// radius varies as r - y sin(gamma) across it.
inline ContactPatch elliptic_patch(double a, double b, double normal_force, int strips,
                                   StripPressure shape = StripPressure::semi_elliptic,
                                   double contact_angle = 0.0, double radius = 0.46) {
  ContactPatch p;
  p.point_index = 0;
  p.model = NormalModel::hertz;
  p.pressure_shape = shape;
  p.normal_force = normal_force;
  p.area = std::numbers::pi * a * b;
  p.semi_axis_a = a;
  p.semi_axis_b = b;
  p.contact_angle = contact_angle;
  p.rolling_radius = radius;
  const bool parabolic = shape == StripPressure::parabolic;
  const double p0 = parabolic ? 2.0 * normal_force / (std::numbers::pi * a * b)
                              : 1.5 * normal_force / (std::numbers::pi * a * b);
  p.max_pressure = p0;
  const double dy = 2.0 * b / strips;
  for (int j = 0; j < strips; ++j) {
    const double y = -b + (j + 0.5) * dy;
    const double f = 1.0 - y * y / (b * b);
    Strip s{};
    s.s = y;
    s.width = dy;
    s.wheel_u = y * std::cos(contact_angle);
    s.rail_u = y;
    s.contact_angle = contact_angle;
    s.rolling_radius = radius - y * std::sin(contact_angle);
    s.x_lead = a * std::sqrt(f);
    s.x_trail = -s.x_lead;
    s.pressure_peak = parabolic ? p0 * f : p0 * std::sqrt(f);
    s.ellipse_a = a;
    s.ellipse_b = b;
    p.strips.push_back(s);
  }
  return p;
}

struct Ellipse {
  double major = 0.0;  // [m]
  double minor = 0.0;  // [m]
};

// Hertz ellipse with the given area, approach and normal force (delta = p0 b K(e) / E*, Johnson
// 4.2, b the minor semi-axis, e the eccentricity); a circle when no ellipse fits.
inline Ellipse ellipse_from_area_approach(double area, double approach, double normal_force,
                                          double contact_modulus) {
  const double p0 = 1.5 * normal_force / area;
  auto delta = [&](double rho) {
    const double minor = std::sqrt(area * rho / std::numbers::pi);
    return p0 * minor * std::comp_ellint_1(std::sqrt(1.0 - rho * rho)) / contact_modulus;
  };
  double lo = 1e-4, hi = 1.0;
  double rho = 1.0;
  if (delta(hi) > approach && delta(lo) < approach) {
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (delta(mid) < approach ? lo : hi) = mid;
    }
    rho = 0.5 * (lo + hi);
  }
  const double minor = std::sqrt(area * rho / std::numbers::pi);
  return {minor / rho, minor};
}

// CSV with a header line; rows as name -> text.
using CsvRow = std::map<std::string, std::string>;
inline std::vector<CsvRow> read_csv(const std::string& path) {
  std::vector<CsvRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& l) {
    std::vector<std::string> out;
    std::stringstream ss(l);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(cell);
    return out;
  };
  if (std::getline(in, line)) header = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto cells = split(line);
    CsvRow row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}
inline double num(const CsvRow& row, const std::string& key) { return std::stod(row.at(key)); }

}  // namespace railtab::test
