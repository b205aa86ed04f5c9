// SPDX-License-Identifier: Apache-2.0
// Piecewise-linear curvature and cant along the centreline, plus the lateral irregularity.
#include "vehicle/track_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/check.hpp"

namespace railtab::vehicle {
namespace {

// Which rail the cant at each end raises: +1 the right rail (left curve), -1 the left rail. An end
// without curvature takes the other end's side; cant with no curvature at all has no outer rail.
struct CantSides {
  double start = 1.0, end = 1.0;
};
CantSides cant_sides(const TrackSection& t, std::size_t i) {
  auto side = [](double curvature) { return curvature > 0.0 ? 1.0 : -1.0; };
  CantSides sides;
  if (t.curvature_start == 0.0 && t.curvature_end == 0.0) {
    RAILTAB_CHECK(t.cant_start == 0.0 && t.cant_end == 0.0,
                  "track section {}: cant {} -> {} m on a section without curvature: no outer "
                  "rail to raise",
                  i, t.cant_start, t.cant_end);
    return sides;
  }
  sides.start = side(t.curvature_start != 0.0 ? t.curvature_start : t.curvature_end);
  sides.end = side(t.curvature_end != 0.0 ? t.curvature_end : t.curvature_start);
  return sides;
}

}  // namespace

TrackLayout::TrackLayout(std::vector<TrackSection> sections, Irregularity irregularity,
                         double rail_centre_distance)
    : sections_(std::move(sections)),
      irregularity_(irregularity),
      rail_centre_distance_(rail_centre_distance) {
  RAILTAB_CHECK(!sections_.empty(), "track layout: empty route (no sections)");
  RAILTAB_CHECK(std::isfinite(rail_centre_distance_) && rail_centre_distance_ > 0.0,
                "track layout: rail_centre_distance = {} m, must be finite and > 0",
                rail_centre_distance_);
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const TrackSection& t = sections_[i];
    RAILTAB_CHECK(std::isfinite(t.length) && t.length > 0.0,
                  "track section {}: length = {} m, must be finite and > 0", i, t.length);
    RAILTAB_CHECK(std::isfinite(t.curvature_start) && std::isfinite(t.curvature_end),
                  "track section {}: curvature {} -> {} 1/m is not finite", i, t.curvature_start,
                  t.curvature_end);
    RAILTAB_CHECK(std::isfinite(t.cant_start) && std::isfinite(t.cant_end),
                  "track section {}: cant {} -> {} m is not finite", i, t.cant_start, t.cant_end);
    RAILTAB_CHECK(std::abs(t.cant_start) < rail_centre_distance_ &&
                      std::abs(t.cant_end) < rail_centre_distance_,
                  "track section {}: cant {} -> {} m, must be smaller than the rail centre "
                  "distance {} m",
                  i, t.cant_start, t.cant_end, rail_centre_distance_);
    const CantSides sides = cant_sides(t, i);
    signed_cant_start_.push_back(sides.start * t.cant_start);
    signed_cant_end_.push_back(sides.end * t.cant_end);
    section_start_.push_back(length_);
    length_ += t.length;
  }

  const Irregularity& irr = irregularity_;
  RAILTAB_CHECK(std::isfinite(irr.amplitude) && irr.amplitude >= 0.0,
                "irregularity: amplitude = {} m, must be finite and >= 0", irr.amplitude);
  if (irr.amplitude == 0.0) return;
  RAILTAB_CHECK(irr.components >= 1, "irregularity: components = {}, must be >= 1",
                irr.components);
  RAILTAB_CHECK(std::isfinite(irr.wavelength_min) && std::isfinite(irr.wavelength_max) &&
                    irr.wavelength_min > 0.0 && irr.wavelength_min <= irr.wavelength_max,
                "irregularity: wavelengths [{}, {}] m, need 0 < wavelength_min <= wavelength_max",
                irr.wavelength_min, irr.wavelength_max);
  std::mt19937 random(irr.seed);  // the engine (not the distributions) is portable
  const double two_pi = 2.0 * std::numbers::pi;
  for (int k = 0; k < irr.components; ++k) {
    const double f = irr.components > 1 ? double(k) / (irr.components - 1) : 0.0;
    const double wavelength =
        irr.wavelength_min * std::pow(irr.wavelength_max / irr.wavelength_min, f);
    wavenumber_.push_back(two_pi / wavelength);
    phase_.push_back(two_pi * double(random()) / 4294967296.0);
    weight_.push_back(std::sqrt(wavelength));
  }
  double largest = 0.0;
  const auto samples = static_cast<long>(std::ceil(length_ / 0.25));
  for (long i = 0; i <= samples; ++i) {
    largest = std::max(largest, std::abs(irregularity_at(std::min(0.25 * double(i), length_))));
  }
  // A sum of sines cannot vanish at every sample of a route of a few metres; guard anyway.
  const double scale = largest > 0.0 ? irr.amplitude / largest : 0.0;
  for (double& w : weight_) w *= scale;
}

double TrackLayout::irregularity_at(double s) const {
  double y = 0.0;
  for (std::size_t k = 0; k < weight_.size(); ++k) {
    y += weight_[k] * std::sin(wavenumber_[k] * s + phase_[k]);
  }
  return y;
}

TrackPoint TrackLayout::at(double s) const {
  s = std::isnan(s) ? 0.0 : std::clamp(s, 0.0, length_);  // std::clamp would keep a NaN
  const auto next = std::upper_bound(section_start_.begin(), section_start_.end(), s);
  const auto i = static_cast<std::size_t>(next - section_start_.begin()) - 1;  // start_[0] = 0
  const TrackSection& t = sections_[i];
  const double f = std::clamp((s - section_start_[i]) / t.length, 0.0, 1.0);
  TrackPoint p;
  p.curvature = t.curvature_start + f * (t.curvature_end - t.curvature_start);
  p.curvature_rate = (t.curvature_end - t.curvature_start) / t.length;
  const double cant = signed_cant_start_[i] + f * (signed_cant_end_[i] - signed_cant_start_[i]);
  p.cant_angle = std::asin(cant / rail_centre_distance_);
  p.lateral_irregularity = irregularity_at(s);
  return p;
}

double TrackLayout::length() const { return length_; }

const std::vector<TrackSection>& TrackLayout::sections() const { return sections_; }

}  // namespace railtab::vehicle
