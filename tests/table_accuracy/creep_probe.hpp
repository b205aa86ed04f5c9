// SPDX-License-Identifier: Apache-2.0
// What the creepage probes (tread_probe.cpp, flange_probe.cpp) share: the exact scene reduced to
// 0.5 mm elements, random creepages per y inside the scene's ranges, their direct evaluations
// cached in a file (they do not depend on the table being probed), and settings from the
// environment. Diagnostics built on request, not tests.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "accuracy_util.hpp"

namespace railtab::accuracy::probe {

// A number from the environment variable `name`, or `fallback` when it is not set.
inline double env_number(const char* name, double fallback) {
  const char* s = std::getenv(name);
  return s ? std::atof(s) : fallback;
}

// n nodes evenly from lo to hi (the last exactly hi).
inline std::vector<double> even_nodes(double lo, double hi, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = lo + (hi - lo) * double(i) / double(n - 1);
  v.back() = hi;
  return v;
}

// tables/default.toml with 0.5 mm elements (table and direct evaluation alike).
inline Scene probe_scene() {
  Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
  scene.halfspace.element_size = 0.5e-3;
  return scene;
}

// `per_y` random creepages inside the scene's ranges at each of `ys`, one load, y by y.
inline std::vector<Point> probe_states(const Scene& scene, const std::vector<double>& ys, double load,
                                       std::size_t per_y, std::uint64_t seed) {
  std::vector<Point> pts;
  Random rng(seed);
  for (double y : ys)
    for (std::size_t i = 0; i < per_y; ++i) {
      Point p;
      p.v[kY] = y;
      p.v[kLoad] = load;
      p.v[kXi] = rng.uniform(scene.grids.xi.front(), scene.grids.xi.back());
      p.v[kEta] = rng.uniform(scene.grids.eta.front(), scene.grids.eta.back());
      p.v[kPhi] = rng.uniform(scene.grids.phi.front(), scene.grids.phi.back());
      pts.push_back(p);
    }
  return pts;
}

// The direct evaluations of `pts`, read from `cache` when it holds them, else computed and written there.
inline std::vector<Direct> cached_direct(const Scene& scene, const std::vector<Point>& pts, const std::string& cache) {
  std::vector<Direct> direct(pts.size());
  const std::streamsize bytes = std::streamsize(direct.size() * sizeof(Direct));
  std::ifstream in(cache, std::ios::binary);
  if (!(in && in.read(reinterpret_cast<char*>(direct.data()), bytes))) {
    direct = evaluate_direct(scene, pts);
    std::ofstream(cache, std::ios::binary).write(reinterpret_cast<const char*>(direct.data()), bytes);
    std::printf("direct computed\n");
  }
  return direct;
}

}  // namespace railtab::accuracy::probe
