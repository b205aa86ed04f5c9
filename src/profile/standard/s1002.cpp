// SPDX-License-Identifier: Apache-2.0
// The S1002 wheel profile from its piecewise analytic definition (s1002.hpp).
#include "profile/standard/s1002.hpp"

#include <cmath>
#include <memory>

namespace railtab {
namespace {

// The standard writes F(S) in millimetres; sections are evaluated in mm and scaled once.
constexpr double kMmPerM = 1000.0;

// F, F', F'' of one section at S [mm, mm/mm, 1/mm].
struct SectionValue {
  double f;    // radius increase F [mm]
  double df;   // dF/dS [-]
  double d2f;  // d2F/dS2 [1/mm]
};

enum class SectionShape {
  polynomial,  // F = sum c[k] S^k
  arc,         // F = a + sign * sqrt(radius^2 - (S + offset)^2)
};

struct Section {
  double s_low;          // lower end of the section in S [mm]; the section reaches up to the previous one
  SectionShape shape;    // polynomial or circular arc
  int degree;            // polynomial degree (polynomial only)
  std::array<double, 9> c;  // polynomial coefficients c[0..degree] of S^k (polynomial only) [mm^(1-k)]
  double a;              // arc: vertical offset [mm]
  double radius;         // arc: radius [mm]
  double offset;         // arc: centre at S = -offset [mm]
  double sign;           // arc: +1 convex part (upper half of the circle in F), -1 concave part
};

constexpr Section polynomial(double s_low, int degree, std::array<double, 9> c) {
  return Section{s_low, SectionShape::polynomial, degree, c, 0.0, 0.0, 0.0, 0.0};
}

constexpr Section arc(double s_low, double a, double radius, double offset, double sign) {
  return Section{s_low, SectionShape::arc, 0, {}, a, radius, offset, sign};
}

// Sections A..H from the field side (S = +60) to the flange back, coefficients as printed in
// UIC 510-2 (signs of the printed formulas folded into c[k]).
constexpr double kSMin = kS1002UMin * kMmPerM;
constexpr std::array<Section, 8> kSections = {
    // A: field-side cone 1:15, F = AA - BA S
    polynomial(32.15796, 1, {1.364323640, -0.066666667}),
    // B: tread, F = AB - BB S + CB S^2 - DB S^3 + EB S^4 - FB S^5 + GB S^6 - HB S^7 + IB S^8
    polynomial(-26.0, 8,
               {0.0, -3.358537058e-2, 1.565681624e-3, -2.810427944e-5, 5.844240864e-8,
                -1.562379023e-8, 5.309217349e-15, -5.957839843e-12, 2.646656573e-13}),
    // C: flange root, F = -AC - BC S - CC S^2 - ... - HC S^7
    polynomial(-35.0, 7,
               {-4.320221063e3, -1.038384026e3, -1.065501873e2, -6.051367875, -2.054332446e-1,
                -4.169739389e-3, -4.687195829e-5, -2.252755540e-7}),
    // D: R13 concave arc, F = AD - sqrt(BD^2 - (S + CD)^2)
    arc(-38.426669071, 16.446, 13.0, 26.210665, -1.0),
    // E: flank line, F = -AE - BE S
    polynomial(-39.764473993, 1, {-93.576667419, -2.747477419}),
    // F: R20 convex arc
    arc(-49.662510381, 8.834924130, 20.0, 58.558326413, 1.0),
    // G: R12 flange tip
    arc(-62.764705882, 16.0, 12.0, 55.0, 1.0),
    // H: R20.5 back of the flange
    arc(kSMin, 9.519259302, 20.5, 49.5, 1.0),
};

SectionValue eval_polynomial(const Section& sec, double s) {
  // Horner for F, F', F'' together.
  double f = sec.c[static_cast<std::size_t>(sec.degree)];
  double df = 0.0;
  double d2f = 0.0;
  for (int k = sec.degree - 1; k >= 0; --k) {
    d2f = d2f * s + 2.0 * df;
    df = df * s + f;
    f = f * s + sec.c[static_cast<std::size_t>(k)];
  }
  return {f, df, d2f};
}

SectionValue eval_arc(const Section& sec, double s) {
  const double w = s + sec.offset;
  const double q = std::sqrt(sec.radius * sec.radius - w * w);
  return {sec.a + sec.sign * q, -sec.sign * w / q, -sec.sign * sec.radius * sec.radius / (q * q * q)};
}

SectionValue eval_s1002(double s) {
  // Sections are ordered by descending S; the first whose lower end is below s holds it.
  const Section* sec = &kSections.back();
  for (const Section& candidate : kSections) {
    if (s >= candidate.s_low) {
      sec = &candidate;
      break;
    }
  }
  return sec->shape == SectionShape::polynomial ? eval_polynomial(*sec, s) : eval_arc(*sec, s);
}

class S1002Profile final : public Profile {
 public:
  S1002Profile() : Profile("S1002", ProfileKind::wheel, kS1002UMin, kS1002UMax) {}

 protected:
  ProfileSample eval_unchecked(double u) const override {
    const SectionValue v = eval_s1002(u * kMmPerM);
    // z = -F: millimetres to metres for z, slope unchanged, curvature from 1/mm to 1/m.
    return {-v.f / kMmPerM, -v.df, -v.d2f * kMmPerM};
  }
};

}  // namespace

std::array<double, 7> s1002_joints() {
  std::array<double, 7> joints{};
  for (std::size_t i = 0; i < joints.size(); ++i) joints[i] = kSections[i].s_low / kMmPerM;
  return joints;
}

ProfilePtr make_s1002_profile() { return std::make_shared<const S1002Profile>(); }

}  // namespace railtab
