// SPDX-License-Identifier: Apache-2.0
// The error map (error_map.hpp): sample states, the model run directly at them, the lookup's
// interpolation of the written table there, and the per-region statistics.
#include "generate/error_map.hpp"

#include <fmt/format.h>

#include <railtab/lookup.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <nlohmann/json.hpp>

#include "core/check.hpp"
#include "engine/parallel_for.hpp"
#include "kernel/contact_kernel.hpp"

namespace railtab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Roberts' additive sequence in 6 dimensions (y, load, xi, eta, phi, roll): alpha_k = g^-k with
// g the real root of x^7 = x + 1. Evenly spread for any count, and a pure function of the index.
double sequence(std::size_t n, int k) {
  constexpr double g = 1.1127756842787055;
  const double alpha = std::pow(g, -(k + 1));
  const double v = 0.5 + alpha * static_cast<double>(n + 1);  // n = 0 would be every range's centre
  return v - std::floor(v);
}

// A seventh dimension, yaw (scenes with a yaw axis only, so the other samples do not change): the
// golden ratio's additive sequence, independent of the six (sqrt 5 is not in the degree-7 field
// of g).
double yaw_sequence(std::size_t n) {
  const double v = 0.5 + 0.6180339887498949 * static_cast<double>(n + 1);
  return v - std::floor(v);
}

double range_value(const std::vector<double>& grid, double u) {
  return grid.size() < 2 ? grid.front() : grid.front() + u * (grid.back() - grid.front());
}

// A copy of `scene` whose grids are the one state of `sample`, over physical creepages (the
// kernel then solves exactly that state) with the normal model `model`.
Scene one_state_scene(const Scene& scene, const ErrorSample& sample, NormalModel model) {
  Scene one = scene;
  one.grids.y = {sample.y};
  one.grids.roll = {sample.roll};
  if (!scene.grids.yaw.empty()) one.grids.yaw = {sample.yaw};
  one.grids.load = {sample.load};
  one.grids.xi = {sample.creepage[0]};
  one.grids.eta = {sample.creepage[1]};
  one.grids.phi = {sample.creepage[2]};
  one.creep_normalised = false;
  one.normal.model = model;
  one.accuracy.models.clear();
  one.accuracy.model_by_y.clear();
  return one;
}

std::size_t output_index(const PartSpec& part, const std::string& name) {
  for (std::size_t o = 0; o < part.outputs.size(); ++o)
    if (part.outputs[o].name == name) return o;
  throw Error(fmt::format("error map: the contact kernel's {} part has no output {}", part.name, name));
}

// Running sums of one region and quantity.
struct Stat {
  double sum_squares = 0.0, max = 0.0;
  std::size_t count = 0;
  void add(double e) {
    if (std::isnan(e)) return;
    sum_squares += e * e;
    max = std::max(max, e);
    ++count;
  }
  double rms() const { return count ? std::sqrt(sum_squares / static_cast<double>(count)) : kNaN; }
  double maximum() const { return count ? max : kNaN; }
};

struct RegionStats {
  std::vector<std::array<Stat, kErrorQuantities>> stat;  // [band * 2 + slot][quantity]
  std::vector<double> samples;                           // [band * 2 + slot]
};

void add_sample(RegionStats& r, std::size_t band, const SampleValues& value, const SampleValues& reference,
                double friction, double load, unsigned wheels = 3u) {
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t s = 0; s < 2 && (wheels >> w & 1u); ++s) {
      const std::vector<double> e = slot_errors(value[w][s], reference[w][s], friction, load);
      if (e.empty()) continue;
      const std::size_t region = band * 2 + s;
      for (std::size_t q = 0; q < kErrorQuantities; ++q) r.stat[region][q].add(e[q]);
      r.samples[region] += 1.0;
    }
}

// The group of one comparison: per quantity its RMS and max over each region's samples, and the
// sample count.
TableGroup stats_group(const std::string& path, const RegionStats& r, std::size_t bands, const std::string& what) {
  TableGroup g{path, {}};
  const std::vector<std::string> axes{kBandDimension, "slot"};
  const std::vector<std::size_t> shape{bands, 2};
  for (std::size_t q = 0; q < kErrorQuantities; ++q)
    for (int stat = 0; stat < 2; ++stat) {
      TableDataset d;
      d.name = fmt::format("{}_{}", kErrorQuantityNames[q], stat == 0 ? "rms" : "max");
      d.units = kErrorQuantityUnits[q];
      d.description = fmt::format("{} error of {}, {} over the region's samples (NaN: no sample)",
                                  kErrorQuantityNames[q], what, stat == 0 ? "RMS" : "maximum");
      d.axes = axes;
      d.shape = shape;
      for (const auto& region : r.stat) d.values.push_back(stat == 0 ? region[q].rms() : region[q].maximum());
      g.datasets.push_back(std::move(d));
    }
  TableDataset n;
  n.name = "samples";
  n.units = "1";
  n.description = "wheel-sample pairs with the slot loaded on either side (both wheels pooled)";
  n.axes = axes;
  n.shape = shape;
  n.values = r.samples;
  g.datasets.push_back(std::move(n));
  return g;
}

}  // namespace

std::vector<ErrorSample> error_samples(const Scene& scene, const std::vector<double>& y_nodes,
                                       std::size_t samples_per_band, std::size_t sequence_offset) {
  std::vector<ErrorSample> out;
  if (y_nodes.size() < 2) return out;
  const std::size_t cells = y_nodes.size() - 1, bands = (cells + kCellsPerBand - 1) / kCellsPerBand;
  for (std::size_t b = 0; b < bands; ++b) {
    const std::size_t first = b * kCellsPerBand, count = std::min(kCellsPerBand, cells - first);
    for (std::size_t j = 0; j < samples_per_band; ++j) {
      const std::size_t n = sequence_offset + b * samples_per_band + j;
      ErrorSample s;
      s.band = b;
      // The band's cells in turn, at a fraction inside the cell kept off its nodes.
      const double u = sequence(n, 0) * static_cast<double>(count);
      s.cell = first + std::min(count - 1, static_cast<std::size_t>(u));
      const double f = std::clamp(u - std::floor(u), 0.02, 0.98);
      s.y = y_nodes[s.cell] + f * (y_nodes[s.cell + 1] - y_nodes[s.cell]);
      s.load = range_value(scene.grids.load, sequence(n, 1));
      s.creepage = {range_value(scene.grids.xi, sequence(n, 2)), range_value(scene.grids.eta, sequence(n, 3)),
                    range_value(scene.grids.phi, sequence(n, 4))};
      s.roll = range_value(scene.grids.roll, sequence(n, 5));
      if (!scene.grids.yaw.empty()) s.yaw = range_value(scene.grids.yaw, yaw_sequence(n));
      out.push_back(s);
    }
  }
  return out;
}

std::vector<double> slot_errors(const SlotValues& value, const SlotValues& reference, double friction, double load) {
  const double n = std::max(value.normal_force, reference.normal_force);
  const double floor = 1e-6 * load;  // a slot "loaded" carries more than a micro-share of the load
  if (!(n > floor)) return {};
  const bool both = value.normal_force > floor && reference.normal_force > floor;
  const double mun = friction * n, c = std::sqrt(std::max(value.area, reference.area) / std::numbers::pi);
  std::vector<double> e(kErrorQuantities, kNaN);
  e[0] = 100.0 * std::abs(value.fx - reference.fx) / mun;
  e[1] = 100.0 * std::abs(value.fy - reference.fy) / mun;
  e[2] = c > 0.0 ? 100.0 * std::abs(value.mz - reference.mz) / (mun * c) : kNaN;
  e[3] = 100.0 * std::abs(value.normal_force - reference.normal_force) / n;
  if (both) e[4] = std::abs(value.contact_angle - reference.contact_angle);
  return e;
}

NormalModel model_of_cell(const Scene& scene, std::size_t cell) {
  if (scene.accuracy.model_by_y.empty()) return scene.normal.model;
  return scene.accuracy.models.at(scene.accuracy.model_by_y.at(cell));
}

SampleValues model_at(const Scene& scene, const ContactGeometrySolver& geometry, const ErrorSample& sample,
                      NormalModel model, unsigned wheels) {
  const Scene one = one_state_scene(scene, sample, model);
  // The map compares no creep coefficient: not computed (with the exact model, 85 % of a state's CPU).
  const SweepKernel kernel = make_contact_kernel(one, geometry, false);
  // The column buffers as the sweep lays them out: one value per slot for every part here.
  std::vector<std::size_t> first{0};
  for (const PartSpec& p : kernel.parts) first.push_back(first.back() + p.outputs.size());
  std::vector<std::vector<double>> values(2 * first.back(), std::vector<double>(kSlots, 0.0));
  std::vector<std::vector<StatusBits>> status(2 * kernel.parts.size(), std::vector<StatusBits>(kSlots, 0u));
  std::vector<double*> vp;
  std::vector<StatusBits*> sp;
  for (auto& v : values) vp.push_back(v.data());
  for (auto& s : status) sp.push_back(s.data());
  ColumnOutput out(vp, sp, first, kernel.parts.size());
  ColumnState state;
  state.y = sample.y;
  state.roll = one.equilibrium_roll ? kernel.equilibrium_roll(sample.y) : sample.roll;
  state.yaw = sample.yaw;
  state.wheels = wheels;
  kernel.compute(state, out);
  auto at = [&](const std::string& part, const std::string& name, std::size_t w, std::size_t s) {
    for (std::size_t p = 0; p < kernel.parts.size(); ++p)
      if (kernel.parts[p].name == part) return values[w * first.back() + first[p] + output_index(kernel.parts[p], name)][s];
    throw Error(fmt::format("error map: the contact kernel has no {} part", part));
  };
  SampleValues r;
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t s = 0; s < 2; ++s) {
      SlotValues& v = r[w][s];
      v.fx = at("creep", "fx", w, s);
      v.fy = at("creep", "fy", w, s);
      v.mz = at("creep", "mz", w, s);
      v.normal_force = at("creep", "normal_force", w, s);
      v.area = at("normal", "area", w, s);
      v.contact_angle = at("geometry", "contact_angle", w, s);
    }
  return r;
}

ErrorMap compute_error_map(const Scene& scene, const std::filesystem::path& written, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  lookup::LoadOptions load_options;
  load_options.require_checksums = true;
  const lookup::Table table = lookup::Table::load(written.string(), load_options);
  std::vector<double> y_nodes;
  for (const lookup::AxisInfo& a : table.axes())
    if (a.name == "y") y_nodes = a.nodes;
  if (y_nodes.size() < 2) return {};  // y fixed: no y bands (such a table has no map)
  const std::vector<ErrorSample> samples = error_samples(scene, y_nodes);
  const std::size_t bands = samples.empty() ? 0 : samples.back().band + 1;
  const bool exact_is_own = scene.normal.model == NormalModel::halfspace && scene.accuracy.models.empty();
  // Per sample: the table, the model, and (the band's first kExactSamplesPerBand) the exact model.
  std::vector<SampleValues> tab(samples.size()), own(samples.size()), exact(samples.size());
  auto exact_sample = [&](std::size_t i) { return !exact_is_own && i % kModelSamplesPerBand < kExactSamplesPerBand; };
  // The exact model on the left wheel only (it costs 0.05-0.1 s CPU per wheel): the right wheel at
  // y mirrors the left one at -y, which the band at -y samples, so the left wheel over all bands
  // covers every wheel position once.
  auto exact_wheels = [](std::size_t) { return 1u; };
  const ContactGeometrySolver geometry = make_geometry_solver(scene);
  // The exact states first, one task each (they cost 100 times a fast-model state), then the rest.
  std::vector<std::size_t> exact_index;
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (exact_sample(i)) exact_index.push_back(i);
  parallel_for_index(threads, exact_index.size(), [&](std::size_t k) {
    const std::size_t i = exact_index[k];
    exact[i] = model_at(scene, geometry, samples[i], NormalModel::halfspace, exact_wheels(i));
  });
  const auto t1 = std::chrono::steady_clock::now();
  parallel_for_index(threads, samples.size(), [&](std::size_t i) {
    const ErrorSample& s = samples[i];
    own[i] = model_at(scene, geometry, s, model_of_cell(scene, s.cell));
    lookup::State state = table.default_state();
    state.y = s.y;
    for (const lookup::AxisInfo& a : table.axes()) {
      if (a.name == "load") state.load = s.load;
      if (a.name == "roll") state.roll = s.roll;
      if (a.name == "yaw") state.yaw = s.yaw;
      if (a.name == "xi") state.xi = s.creepage[0];
      if (a.name == "eta") state.eta = s.creepage[1];
      if (a.name == "phi") state.phi = s.creepage[2];
    }
    for (std::size_t w = 0; w < 2; ++w) {
      const lookup::Result r = table.query(w == 0 ? lookup::Wheel::kLeft : lookup::Wheel::kRight, state);
      for (std::size_t slot = 0; slot < 2; ++slot) {
        const double* v = r.contact[slot].value;
        tab[i][w][slot] = {v[lookup::kFx],          v[lookup::kFy],   v[lookup::kMz],
                           v[lookup::kNormalForce], v[lookup::kArea], v[lookup::kContactAngle]};
      }
    }
  });
  RegionStats table_model{std::vector<std::array<Stat, kErrorQuantities>>(bands * 2), std::vector<double>(bands * 2)};
  RegionStats model_exact = table_model;
  std::size_t exact_states = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    add_sample(table_model, samples[i].band, tab[i], own[i], scene.tangential.friction, samples[i].load);
    if (exact_sample(i)) {
      add_sample(model_exact, samples[i].band, own[i], exact[i], scene.tangential.friction, samples[i].load,
                 exact_wheels(i));
      ++exact_states;
    }
  }
  ErrorMap map;
  // Band edges: the y of each band's first and last node.
  TableGroup root{kErrorMapGroup, {}};
  for (int end = 0; end < 2; ++end) {
    TableDataset d;
    d.name = end == 0 ? "y_band_start" : "y_band_end";
    d.units = "m";
    d.description = end == 0 ? "lateral displacement where the band starts (a y node)"
                             : "lateral displacement where the band ends (a y node)";
    d.axes = {kBandDimension};
    d.shape = {bands};
    for (std::size_t b = 0; b < bands; ++b)
      d.values.push_back(y_nodes[std::min(y_nodes.size() - 1, (b + end) * kCellsPerBand)]);
    root.datasets.push_back(std::move(d));
  }
  map.groups.push_back(std::move(root));
  map.groups.push_back(stats_group(std::string(kErrorMapGroup) + "/table_vs_model", table_model, bands,
                                   "the table (lookup, linear) against its own model run directly"));
  if (!exact_is_own)
    map.groups.push_back(stats_group(std::string(kErrorMapGroup) + "/model_vs_exact", model_exact, bands,
                                     "the table's model against the exact half-space model"));
  nlohmann::json j = {{"cells_per_band", kCellsPerBand},
                      {"samples_per_band", kModelSamplesPerBand},
                      {"exact_samples_per_band", exact_is_own ? 0 : kExactSamplesPerBand},
                      {"model_vs_exact", exact_is_own ? "same model" : "halfspace"},
                      {"exact_wheel", exact_is_own ? "none" : "left"},
                      {"states", "Roberts additive sequence, fixed by index; y inside the band's cells, load and "
                                 "creepages uniform over the scene's ranges"},
                      {"interpolation", "linear"},
                      {"mz_scale", "mu N c, c = sqrt(area / pi)"}};
  map.sampling = j.dump();
  map.model_states = samples.size();
  map.exact_states = exact_states;
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  map.exact_seconds = std::chrono::duration<double>(t1 - t0).count();
  return map;
}

void add_error_map_of_merged(Table& table, const std::filesystem::path& written, int threads) {
  const std::string* text = table.attribute("scene");
  RAILTAB_CHECK(text, "{}: the merged table carries no scene text: its error map cannot be computed", written.string());
  Scene scene;
  try {
    scene = parse_scene(*text, "the merged table's scene");
  } catch (const Error& e) {
    throw Error(fmt::format("merge: the error map runs the table's scene again and its scene does not load here "
                            "(run merge where the scene's profile files are, as for generate): {}",
                            e.what()));
  }
  if (const TableGroup* root = table.group("")) {
    if (const TableDataset* index = root->find("normal_model_index")) {
      scene.accuracy.model_by_y.clear();
      for (double v : index->values) scene.accuracy.model_by_y.push_back(static_cast<std::size_t>(v));
    }
  }
  add_error_map(table, compute_error_map(scene, written, threads));
}

MergeFinish error_map_merge_finish(int threads) {
  return [threads](Table& merged, const std::filesystem::path& written) {
    add_error_map_of_merged(merged, written, threads);
  };
}

void add_error_map(Table& table, ErrorMap map) {
  if (map.groups.empty()) return;
  auto& groups = table.groups;
  groups.erase(std::remove_if(groups.begin(), groups.end(),
                              [](const TableGroup& g) { return g.path.rfind(kErrorMapGroup, 0) == 0; }),
               groups.end());
  for (TableGroup& g : map.groups) groups.push_back(std::move(g));
  table.remove_attribute(kErrorMapAttribute);
  table.set_attribute(kErrorMapAttribute, map.sampling);
}

}  // namespace railtab
