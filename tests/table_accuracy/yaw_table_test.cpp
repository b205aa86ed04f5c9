// SPDX-License-Identifier: Apache-2.0
// The yaw axis of a table (format 2.4, docs/table-format.md): the STRIPES scene's models over a
// small grid with five yaw nodes, swept with the generator API and read through the lookup.
// The yaw = 0 node against the same scene without yaw, the lookup off the yaw nodes against the
// contact kernel run directly, mirror symmetry (y, yaw) -> (-y, -yaw) between the wheels, outputs
// even in yaw, continuity in yaw, derivatives along yaw, and a yaw query on a table without yaw.
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "accuracy_util.hpp"
#include "railtab_lookup.h"
#include "table/storage_precision.hpp"

namespace railtab::accuracy {
namespace {

constexpr double kYawNodes[] = {-0.01, -0.005, 0.0, 0.005, 0.01};  // the scene's list [rad]
constexpr std::size_t kNyaw = 5;
// The list is symmetric about 0: the table stores its non-negative half (yaw_symmetry = "even").
constexpr double kStoredYaw[] = {0.0, 0.005, 0.01};
constexpr std::size_t kNstored = 3;

// The STRIPES scene's profiles, track and models with a small grid: y symmetric about 0 (the
// mirror test needs -y for every y), tread and flange contact, two loads, three nodes per creepage.
std::string scene_text(bool with_yaw) {
  std::ifstream in(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s = s.substr(0, s.find("[grid]"));
  s += "[grid]\n"
       "y = [-0.009, -0.0075, -0.006, -0.0045, -0.003, -0.0015, 0.0, 0.0015, 0.003, 0.0045, 0.006, 0.0075, 0.009]\n"
       "equilibrium_roll = true\n";
  if (with_yaw) s += "yaw = [-0.01, -0.005, 0.0, 0.005, 0.01]\n";
  s += "load = [60e3, 100e3]\n"
       "xi = [-0.004, 0.0, 0.004]\n"
       "eta = [-0.004, 0.0, 0.004]\n"
       "phi = [-0.3, 0.0, 0.3]\n"
       "creep_coordinates = \"normalised\"\n"
       "creep_knee = [1.0, 3.0, 4.0]\n";
  return s;
}

struct YawFixture {
  Scene scene, free_scene;  // with the yaw axis; the same without yaw
  Table table, free_table;  // their sweeps
  std::optional<lk::Table> lookup, free_lookup;
  // The yaw table with double records (RAILTAB_LOOKUP_NO_FLOAT_RECORDS=1): the same interpolant
  // summed in double. The linear lookup sums float records in float (lookup/src/weighted_sum.hpp),
  // within a float rounding (~1e-7) of it: the symmetry and difference tests below, whose
  // tolerances are double roundings, run on this one, and bound the float sums against it.
  std::optional<lk::Table> lookup_doubles;
  // The yaw table without the fused query and the generic path's shortcuts
  // (RAILTAB_LOOKUP_NO_FAST_PATH=1): no skip of the cells where the creep block is zero
  // (fast_path.hpp, FastPath::empty_creep).
  std::optional<lk::Table> lookup_no_skip;
  // The fused query with the SSE2 kernels (RAILTAB_LOOKUP_NO_AVX2=1).
  std::optional<lk::Table> lookup_sse2;
};

const YawFixture& fixture() {
  static const YawFixture f = [] {
    YawFixture x;
    x.scene = parse_scene(scene_text(true), "yaw scene");
    x.free_scene = parse_scene(scene_text(false), "yaw-free scene");
    SweepResult r = run_sweep(x.scene, make_contact_kernel(x.scene), SweepOptions{});
    SweepResult rf = run_sweep(x.free_scene, make_contact_kernel(x.free_scene), SweepOptions{});
    if (r.summary.failures || rf.summary.failures) throw std::runtime_error("yaw table: " + r.summary.first_failure);
    x.table = std::move(r.table);
    x.free_table = std::move(rf.table);
    const std::filesystem::path path = temp_table_path("yaw"), free_path = temp_table_path("yaw_free");
    write_for_lookup(x.table, path);
    write_for_lookup(x.free_table, free_path);
    x.lookup.emplace(lk::Table::load(path.string()));
    x.free_lookup.emplace(lk::Table::load(free_path.string()));
    ::setenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS", "1", 1);
    x.lookup_doubles.emplace(lk::Table::load(path.string()));
    ::unsetenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS");
    ::setenv("RAILTAB_LOOKUP_NO_FAST_PATH", "1", 1);
    x.lookup_no_skip.emplace(lk::Table::load(path.string()));
    ::unsetenv("RAILTAB_LOOKUP_NO_FAST_PATH");
    ::setenv("RAILTAB_LOOKUP_NO_AVX2", "1", 1);
    x.lookup_sse2.emplace(lk::Table::load(path.string()));
    ::unsetenv("RAILTAB_LOOKUP_NO_AVX2");
    std::filesystem::remove(path);
    std::filesystem::remove(free_path);
    return x;
  }();
  return f;
}

lk::State state_at(const lk::Table& t, double y, double yaw, double load, double xi = 0.0, double eta = 0.0,
                   double phi = 0.0) {
  lk::State s = t.default_state();
  s.y = y;
  s.yaw = yaw;
  s.load = load;
  s.xi = xi;
  s.eta = eta;
  s.phi = phi;
  return s;
}

std::string label(int o) { return lk::output_name(static_cast<lk::Output>(o)); }

// The core's own resolution of an output, relative to its scale: 1e-4 (load iteration), but 1e-3
// for the patch's area and semi-axes, which step when STRIPES' strips enter or leave the patch
// (measured by ContinuousInYaw's sweep: up to 7e-4 of the area per 0.5 mrad step at y = 0, five
// times the median step, with unchanged statuses).
double core_floor(int o) { return o == lk::kArea || o == lk::kSemiAxisA || o == lk::kSemiAxisB ? 1e-3 : 1e-4; }

// Every wheel group's dataset at the yaw = 0 node is the yaw-free table's, bit for bit: the sweep
// passes yaw 0 to the geometry, which then takes the yaw-free path. The symmetric list is stored
// as its non-negative half.
TEST(YawTable, ZeroYawNodeIsTheYawFreeTable) {
  const YawFixture& f = fixture();
  EXPECT_EQ(*f.table.attribute("format_version"), "2.4");
  EXPECT_EQ(*f.free_table.attribute("format_version"), "2.3");
  ASSERT_TRUE(f.table.attribute("yaw_symmetry"));
  EXPECT_EQ(*f.table.attribute("yaw_symmetry"), "even");
  EXPECT_FALSE(f.free_table.attribute("yaw_symmetry"));
  const TableAxis* yaw = f.table.axis("yaw");
  ASSERT_NE(yaw, nullptr);
  EXPECT_EQ(yaw->units, "rad");
  EXPECT_EQ(yaw->values, std::vector<double>(std::begin(kStoredYaw), std::end(kStoredYaw)));
  EXPECT_EQ(f.free_table.axis("yaw"), nullptr);
  std::size_t compared = 0, differ_at_edge = 0;
  for (const TableGroup& free_group : f.free_table.groups) {
    if (free_group.path.empty()) continue;  // /equilibrium_roll: over y only, checked below
    const TableGroup* group = f.table.group(free_group.path);
    ASSERT_NE(group, nullptr) << free_group.path;
    for (const TableDataset& free_d : free_group.datasets) {
      const TableDataset* d = group->find(free_d.name);
      ASSERT_NE(d, nullptr) << free_group.path << "/" << free_d.name;
      ASSERT_GE(d->axes.size(), 2u);
      ASSERT_EQ(d->axes[1], "yaw");
      const std::size_t ny = d->shape[0], inner = free_d.size() / ny;
      ASSERT_EQ(d->size(), ny * kNstored * inner);
      for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t k = 0; k < inner; ++k) {
          const std::size_t a = iy * kNstored * inner + k, b = iy * inner + k;
          const std::size_t edge = (iy * kNstored + kNstored - 1) * inner + k;
          if (free_d.is_status) {
            ASSERT_EQ(d->status[a], free_d.status[b]) << free_group.path << "/" << free_d.name << " y " << iy;
          } else {
            ASSERT_EQ(d->values[a], free_d.values[b]) << free_group.path << "/" << free_d.name << " y " << iy;
            differ_at_edge += d->values[edge] != free_d.values[b];
          }
          ++compared;
        }
    }
  }
  EXPECT_GT(compared, 10000u);
  // The yaw reaches the kernel: at yaw 10 mrad most values differ from the yaw-free ones.
  EXPECT_GT(differ_at_edge, compared / 4);
  EXPECT_EQ(f.table.group("")->find("equilibrium_roll")->values, f.free_table.group("")->find("equilibrium_roll")->values);
}

// The query's fixed-variable rule for yaw: a table without yaw answers yaw 0 and flags any other
// yaw out_of_range (it was computed at yaw 0); the yaw table clamps a yaw beyond its axis and
// flags it. The C API carries yaw as the last member of its state.
TEST(YawTable, YawOnATableWithoutYawIsFlagged) {
  const YawFixture& f = fixture();
  const lk::Table& free = *f.free_lookup;
  EXPECT_EQ(free.query(lk::Wheel::kLeft, state_at(free, 0.003, 0.0, 78.5e3)).status, 0u);
  const lk::Result at_zero = free.query(lk::Wheel::kLeft, state_at(free, 0.003, 0.0, 78.5e3));
  const lk::Result yawed = free.query(lk::Wheel::kLeft, state_at(free, 0.003, 0.002, 78.5e3));
  EXPECT_EQ(yawed.status, lk::status::kOutOfRange);
  EXPECT_EQ(at_zero.contact[0].value[lk::kNormalForce], yawed.contact[0].value[lk::kNormalForce]);
  EXPECT_EQ(free.query(lk::Wheel::kLeft, state_at(free, 0.003, NAN, 78.5e3)).status & lk::status::kInvalidInput,
            lk::status::kInvalidInput);
  for (const auto& [name, value] : free.fixed_axes()) EXPECT_NE(name, "yaw");  // not a fixed value of the table
  const lk::Table& t = *f.lookup;
  EXPECT_EQ(t.query(lk::Wheel::kLeft, state_at(t, 0.003, 0.004, 78.5e3)).status, 0u);
  const lk::Result beyond = t.query(lk::Wheel::kLeft, state_at(t, 0.007, 0.03, 78.5e3));
  EXPECT_EQ(beyond.status, lk::status::kOutOfRange);
  const lk::Result edge = t.query(lk::Wheel::kLeft, state_at(t, 0.007, 0.01, 78.5e3));
  EXPECT_EQ(beyond.contact[1].value[lk::kNormalForce], edge.contact[1].value[lk::kNormalForce]);
  bool yaw_axis = false;
  for (const lk::AxisInfo& a : t.axes()) yaw_axis |= a.name == "yaw" && a.units == "rad";
  EXPECT_TRUE(yaw_axis);
  // C API: the same answer as C++ at a yawed state.
  const std::filesystem::path path = temp_table_path("yaw_c");
  write_for_lookup(f.table, path);
  railtab_lookup_table* c = nullptr;
  ASSERT_EQ(railtab_lookup_open(path.string().c_str(), RAILTAB_LOOKUP_LINEAR, &c), RAILTAB_LOOKUP_OK);
  const lk::State s = state_at(t, 0.0068, -0.0071, 81e3, 0.001, -0.0007, 0.05);
  railtab_lookup_state cs = {s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
  railtab_lookup_result cr;
  ASSERT_EQ(railtab_lookup_query(c, RAILTAB_LOOKUP_RIGHT, &cs, &cr), RAILTAB_LOOKUP_OK);
  const lk::Result r = t.query(lk::Wheel::kRight, s);
  EXPECT_EQ(std::memcmp(&cr, &r, sizeof r), 0);
  EXPECT_STREQ(railtab_lookup_var_name(RAILTAB_LOOKUP_VAR_YAW), "yaw");
  // The stored half of the symmetric list: the C API says so, lists yaw from 0 and reads |yaw|.
  EXPECT_EQ(railtab_lookup_yaw_even(c), 1);
  EXPECT_EQ(railtab_lookup_yaw_even(nullptr), 0);
  const char* name = nullptr;
  std::size_t n_nodes = 0;
  const double* nodes = nullptr;
  bool listed = false;
  for (int a = 0; railtab_lookup_axis(c, a, &name, nullptr, &n_nodes, &nodes) == RAILTAB_LOOKUP_OK; ++a)
    if (std::strcmp(name, "yaw") == 0) {
      listed = true;
      EXPECT_EQ(std::vector<double>(nodes, nodes + n_nodes), std::vector<double>(std::begin(kStoredYaw), std::end(kStoredYaw)));
    }
  EXPECT_TRUE(listed);
  railtab_lookup_state mirrored = cs;
  mirrored.yaw = -cs.yaw;
  railtab_lookup_result mr;
  ASSERT_EQ(railtab_lookup_query(c, RAILTAB_LOOKUP_RIGHT, &mirrored, &mr), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(std::memcmp(&cr, &mr, sizeof mr), 0);
  railtab_lookup_close(c);
  std::filesystem::remove(path);
  // The yaw-free table: not even.
  const std::filesystem::path free_path = temp_table_path("yaw_c_free");
  write_for_lookup(f.free_table, free_path);
  ASSERT_EQ(railtab_lookup_open(free_path.string().c_str(), RAILTAB_LOOKUP_LINEAR, &c), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(railtab_lookup_yaw_even(c), 0);
  railtab_lookup_close(c);
  std::filesystem::remove(free_path);
}

// Off the yaw nodes (y, load and creepage on their nodes, so only yaw is interpolated) the lookup
// against the contact kernel run at that yaw. Tolerance as the STRIPES table's (docs/lookup.md
// "Accuracy"): 5 x the linear interpolation bound h^2/8 |f''|, |f''| from the table's second
// differences along yaw at the cell's corners, plus core_floor of the output's scale (the core's
// own resolution) and the float32 rounding of the creep part. Cells whose corners' statuses differ from
// each other or from the direct evaluation's (a contact jump along yaw) are counted, not asserted.
TEST(YawTable, LookupAgainstDirectEvaluationOffTheYawNodes) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup;
  const std::vector<double>& ys = f.scene.grids.y;
  const std::vector<double>& loads = f.scene.grids.load;
  Random rng(31);
  struct Sample {
    Point p;
    double yaw;
    std::size_t cell;
  };
  std::vector<Sample> samples;
  for (std::size_t iy = 0; iy < ys.size(); ++iy)
    for (double load : loads)
      for (int k = 0; k < 2; ++k) {
        Sample s;
        s.p.v[kY] = ys[iy];
        s.p.v[kLoad] = load;
        s.yaw = rng.uniform(kYawNodes[0], kYawNodes[kNyaw - 1]);
        s.cell = std::min<std::size_t>(kNyaw - 2, static_cast<std::size_t>((s.yaw - kYawNodes[0]) / 0.005));
        samples.push_back(s);
      }
  std::vector<Direct> direct(samples.size());
  tbb::parallel_for(std::size_t{0}, samples.size(),
                    [&](std::size_t i) { direct[i] = evaluate_direct(f.scene, samples[i].p, samples[i].yaw); });
  // The lookup at the yaw nodes of each sample's (y, load): its nodal values along yaw.
  std::size_t checked = 0, jump_cells = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    for (std::size_t w = 0; w < 2; ++w) {
      const auto wheel = static_cast<lk::Wheel>(w);
      const lk::Result r = t.query(wheel, state_at(t, s.p.v[kY], s.yaw, s.p.v[kLoad]));
      lk::Result node[kNyaw];
      for (std::size_t j = 0; j < kNyaw; ++j) node[j] = t.query(wheel, state_at(t, s.p.v[kY], kYawNodes[j], s.p.v[kLoad]));
      for (std::size_t slot = 0; slot < kSlots; ++slot) {
        bool smooth = true;
        for (int p = 0; p < lk::kNumParts; ++p) {
          const StatusBits a = node[s.cell].contact[slot].part_status[p], b = node[s.cell + 1].contact[slot].part_status[p];
          smooth &= (a & kCompared) == (b & kCompared) && (a & kCompared) == (direct[i][w].status[p][slot] & kCompared);
        }
        if (!smooth) {
          ++jump_cells;
          continue;
        }
        for (int o = 0; o < lk::kNumOutputs; ++o) {
          const bool creep = lk::output_part(static_cast<lk::Output>(o)) >= lk::kCreep || o == lk::kNormalForce;
          double scale = 0.0, second = 0.0;
          for (std::size_t j = 0; j < kNyaw; ++j) scale = std::max(scale, std::abs(node[j].contact[slot].value[o]));
          for (std::size_t j = std::max<std::size_t>(1, s.cell); j <= std::min(kNyaw - 2, s.cell + 1); ++j)
            second = std::max(second, std::abs(node[j - 1].contact[slot].value[o] - 2.0 * node[j].contact[slot].value[o] +
                                               node[j + 1].contact[slot].value[o]));
          const double tolerance = 5.0 * second / 8.0 + (core_floor(o) + (creep ? 4.0 * kStoredRounding : 0.0)) * scale;
          const double error = std::abs(r.contact[slot].value[o] - direct[i][w].value[o][slot]);
          if (scale > 0.0) worst = std::max(worst, error / scale);
          EXPECT_LE(error, tolerance) << label(o) << " wheel " << w << " slot " << slot << " y " << s.p.v[kY]
                                      << " yaw " << s.yaw << " load " << s.p.v[kLoad];
          ++checked;
        }
      }
    }
  }
  std::printf("yaw off-node: %zu outputs checked, %zu jump cells (not asserted), worst error / scale %.2e\n", checked,
              jump_cells, worst);
  EXPECT_GE(checked, samples.size() * 2 * kSlots * lk::kNumOutputs * 3 / 4);  // most cells are smooth
}

// Mirror symmetry: the left wheel at (y, yaw, eta, phi) is the right wheel at (-y, -yaw, -eta,
// -phi), with the lateral quantities' signs flipped (contact angle, fy, mz; docs/conventions.md),
// on and off the nodes. On the double-record table (the float sums of the table as loaded are
// within 1e-6 of each output's largest |value| of it, asserted here: the 6-D yaw cells too).
TEST(YawTable, MirrorSwapsTheWheels) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup_doubles;
  const lk::Table& floats = *f.lookup;
  double diff[lk::kNumOutputs] = {}, scale[lk::kNumOutputs] = {};
  Random rng(32);
  const auto flips = [](int o) { return o == lk::kContactAngle || o == lk::kFy || o == lk::kMz; };
  std::size_t flange = 0;
  for (int k = 0; k < 400; ++k) {
    const double y = rng.uniform(-0.009, 0.009), yaw = rng.uniform(-0.01, 0.01), load = rng.uniform(60e3, 100e3);
    const double xi = rng.uniform(-0.004, 0.004), eta = rng.uniform(-0.004, 0.004), phi = rng.uniform(-0.3, 0.3);
    const lk::Result l = t.query(lk::Wheel::kLeft, state_at(t, y, yaw, load, xi, eta, phi));
    const lk::Result r = t.query(lk::Wheel::kRight, state_at(t, -y, -yaw, load, xi, -eta, -phi));
    ASSERT_EQ(l.status, 0u);
    const lk::Result lf = floats.query(lk::Wheel::kLeft, state_at(t, y, yaw, load, xi, eta, phi));
    for (std::size_t slot = 0; slot < kSlots; ++slot)
      for (int o = 0; o < lk::kNumOutputs; ++o) {
        const bool force = o == lk::kFx || o == lk::kFy;
        diff[o] = std::max(diff[o], std::abs(lf.contact[slot].value[o] - l.contact[slot].value[o]));
        scale[o] = std::max(scale[o], force ? f.scene.tangential.friction * l.contact[slot].value[lk::kNormalForce]
                                            : std::abs(l.contact[slot].value[o]));
      }
    for (std::size_t slot = 0; slot < kSlots; ++slot) {
      EXPECT_EQ(l.contact[slot].status, r.contact[slot].status) << "y " << y << " yaw " << yaw << " slot " << slot;
      flange += slot == 1 && l.contact[slot].value[lk::kNormalForce] > 0.0;
      for (int o = 0; o < lk::kNumOutputs; ++o) {
        const double a = l.contact[slot].value[o], b = (flips(o) ? -1.0 : 1.0) * r.contact[slot].value[o];
        EXPECT_NEAR(a, b, 1e-9 * std::max(std::abs(a), std::abs(b)) + 1e-12)
            << label(o) << " slot " << slot << " y " << y << " yaw " << yaw;
      }
    }
  }
  EXPECT_GT(flange, 50u);  // the flange contact is among the states
  for (int o = 0; o < lk::kNumOutputs; ++o)
    EXPECT_LE(diff[o], 1e-6 * scale[o]) << label(o) << ": float sums against double sums";
}

// The yaw table takes the fused query (lookup/src/fast_path.cpp, the yaw dimension after y in
// every block), which skips the creepage cells and the sum where the creep block is zero over the
// (y, yaw, load) cell with one set of statuses (the flange slot out of contact): the same bytes as
// the generic query without the skip, for query and query_slot of every slot, both wheels, AVX2
// and SSE2 kernels, at states in range, beyond every axis (|yaw| up to 12 mrad against the
// table's 10), on the yaw nodes and with a non-finite yaw, including states that reach empty cells.
TEST(YawTable, FusedQueryAndEmptyCellSkipGiveTheGenericBytes) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup;
  const lk::Table& sse2 = *f.lookup_sse2;
  const lk::Table& plain = *f.lookup_no_skip;
  Random rng(33);
  std::size_t empty = 0, out_of_range = 0;
  for (int k = 0; k < 3000; ++k) {
    const bool beyond = k % 3 == 1;  // 5-20 % beyond the axes
    lk::State s = beyond ? state_at(t, rng.uniform(-0.0095, 0.0095), rng.uniform(-0.012, 0.012), rng.uniform(55e3, 105e3),
                                    rng.uniform(-0.005, 0.005), rng.uniform(-0.005, 0.005), rng.uniform(-0.36, 0.36))
                         : state_at(t, rng.uniform(-0.009, 0.009), rng.uniform(-0.01, 0.01), rng.uniform(60e3, 100e3),
                                    rng.uniform(-0.004, 0.004), rng.uniform(-0.004, 0.004), rng.uniform(-0.3, 0.3));
    if (k % 3 == 2) s.yaw = (k / 3) % 2 ? kStoredYaw[(k / 6) % kNstored] : -kStoredYaw[(k / 6) % kNstored];
    if (k % 97 == 0) s.yaw = std::numeric_limits<double>::quiet_NaN();
    const lk::Wheel w = static_cast<lk::Wheel>(k % 2);
    const lk::Result a = t.query(w, s), b = plain.query(w, s), c = sse2.query(w, s);
    ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "query " << k << " y " << s.y << " yaw " << s.yaw;
    ASSERT_EQ(std::memcmp(&c, &b, sizeof c), 0) << "SSE2 query " << k << " y " << s.y << " yaw " << s.yaw;
    for (int slot = 0; slot < b.n_slots; ++slot) {
      const lk::Contact one = t.query_slot(w, s, slot), one_sse2 = sse2.query_slot(w, s, slot);
      ASSERT_EQ(std::memcmp(&one, &b.contact[slot], sizeof one), 0) << "query_slot " << k << " slot " << slot;
      ASSERT_EQ(std::memcmp(&one_sse2, &b.contact[slot], sizeof one), 0) << "SSE2 query_slot " << k << " slot " << slot;
    }
    empty += a.contact[1].value[lk::kFx] == 0.0 && a.contact[1].value[lk::kFy] == 0.0 && a.contact[1].value[lk::kMz] == 0.0;
    out_of_range += (a.status & lk::status::kOutOfRange) != 0;
  }
  EXPECT_GT(empty, 300u);         // the flange slot out of contact is among the states
  EXPECT_GT(out_of_range, 500u);  // and states beyond the axes
}

// One wheel at given creepages does not see the sign of yaw: +-yaw put the contact at the same
// place on the wheel's silhouette, only its lead (not a table output) changes sign
// (docs/validation/yaw-tables.md), so the contact kernel gives every stored output even in yaw.
// What lets a symmetric yaw list be stored as its non-negative half: checked on the kernel itself
// (the table would answer -yaw with +yaw's values by construction).
TEST(YawTable, OutputsAreEvenInYaw) {
  const YawFixture& f = fixture();
  Random rng(34);
  std::vector<Point> points(100);
  std::vector<double> yaws(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    points[k].v[kY] = rng.uniform(-0.009, 0.009);
    points[k].v[kLoad] = rng.uniform(60e3, 100e3);
    points[k].v[kXi] = rng.uniform(-0.004, 0.004);
    points[k].v[kEta] = rng.uniform(-0.004, 0.004);
    points[k].v[kPhi] = rng.uniform(-0.3, 0.3);
    yaws[k] = rng.uniform(0.0, 0.01);
  }
  std::vector<Direct> plus(points.size()), minus(points.size()), zero(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t k) {
    plus[k] = evaluate_direct(f.scene, points[k], yaws[k]);
    minus[k] = evaluate_direct(f.scene, points[k], -yaws[k]);
    zero[k] = evaluate_direct(f.scene, points[k], 0.0);
  });
  std::size_t differ_from_zero = 0, compared = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
    for (std::size_t w = 0; w < 2; ++w)
      for (std::size_t slot = 0; slot < kSlots; ++slot) {
        for (int q = 0; q < lk::kNumParts; ++q) EXPECT_EQ(plus[k][w].status[q][slot], minus[k][w].status[q][slot]);
        for (int o = 0; o < lk::kNumOutputs; ++o) {
          const double a = plus[k][w].value[o][slot], b = minus[k][w].value[o][slot];
          EXPECT_NEAR(a, b, 1e-9 * std::max(std::abs(a), std::abs(b)) + 1e-12)
              << label(o) << " wheel " << w << " slot " << slot << " y " << points[k].v[kY] << " yaw " << yaws[k];
          differ_from_zero += a != zero[k][w].value[o][slot];
          ++compared;
        }
      }
  std::printf("outputs even in yaw: %zu compared, %zu differ from yaw 0\n", compared, differ_from_zero);
  EXPECT_GT(differ_from_zero, compared / 4);  // yaw changes the outputs, only not with its sign
}

// The table of a symmetric yaw list answers -yaw with +yaw's values, bytes and status (it stores
// |yaw|); a list that is not symmetric keeps every node.
TEST(YawTable, SymmetricListIsStoredAsItsNonNegativeHalf) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup;
  Random rng(35);
  for (int k = 0; k < 50; ++k) {
    const double y = rng.uniform(-0.009, 0.009), yaw = rng.uniform(0.0, 0.012), load = rng.uniform(60e3, 100e3);
    for (int w = 0; w < 2; ++w) {
      const auto wheel = static_cast<lk::Wheel>(w);
      const lk::Result a = t.query(wheel, state_at(t, y, yaw, load, 0.001, -0.002, 0.1));
      const lk::Result b = t.query(wheel, state_at(t, y, -yaw, load, 0.001, -0.002, 0.1));
      EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "y " << y << " yaw " << yaw;
    }
  }
  Scene asymmetric = parse_scene([] {
    std::string s = scene_text(true);
    s.replace(s.find("yaw = ["), std::string("yaw = [-0.01, -0.005, 0.0, 0.005, 0.01]").size(), "yaw = [-0.01, 0.0, 0.005]");
    return s;
  }(), "asymmetric yaw scene");
  EXPECT_FALSE(asymmetric.grids.yaw_even);
  EXPECT_EQ(asymmetric.grids.yaw, (std::vector<double>{-0.01, 0.0, 0.005}));
  EXPECT_TRUE(f.scene.grids.yaw_even);
  EXPECT_EQ(f.scene.grids.yaw, std::vector<double>(std::begin(kStoredYaw), std::end(kStoredYaw)));
}

// Continuity in yaw: the kernel at a yaw of 1e-9 rad either side of the yaw = 0 node gives that
// node (the yawed path meets the yaw-free one), and along a fine yaw sweep (0.5 mrad steps over the
// table's range) in flange and tread contact no output steps by more than 3 x its median step plus
// core_floor of its scale where the statuses do not change.
TEST(YawTable, ContinuousInYaw) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup;
  for (const double y : {-0.0075, 0.0, 0.0075}) {
    Point p;
    p.v[kY] = y;
    p.v[kLoad] = 60e3;
    for (const double tiny : {1e-9, -1e-9}) {
      const Direct d = evaluate_direct(f.scene, p, tiny);
      for (std::size_t w = 0; w < 2; ++w) {
        const lk::Result node = t.query(static_cast<lk::Wheel>(w), state_at(t, y, 0.0, 60e3));
        for (std::size_t slot = 0; slot < kSlots; ++slot)
          for (int o = 0; o < lk::kNumOutputs; ++o) {
            const double a = node.contact[slot].value[o], b = d[w].value[o][slot];
            const bool creep = lk::output_part(static_cast<lk::Output>(o)) >= lk::kCreep || o == lk::kNormalForce;
            EXPECT_NEAR(a, b, (1e-6 + (creep ? 2.0 * kStoredRounding : 0.0)) * std::max(std::abs(a), 1e-3) + 1e-9)
                << label(o) << " y " << y << " yaw " << tiny << " wheel " << w << " slot " << slot;
          }
      }
    }
    std::vector<double> yaws;
    for (int k = -20; k <= 20; ++k) yaws.push_back(0.0005 * k);
    std::vector<Direct> sweep(yaws.size());
    tbb::parallel_for(std::size_t{0}, yaws.size(), [&](std::size_t i) { sweep[i] = evaluate_direct(f.scene, p, yaws[i]); });
    for (std::size_t w = 0; w < 2; ++w)
      for (std::size_t slot = 0; slot < kSlots; ++slot)
        for (int o = 0; o < lk::kNumOutputs; ++o) {
          std::vector<double> steps;
          double scale = 0.0;
          for (std::size_t i = 0; i + 1 < yaws.size(); ++i) {
            steps.push_back(std::abs(sweep[i + 1][w].value[o][slot] - sweep[i][w].value[o][slot]));
            scale = std::max(scale, std::abs(sweep[i][w].value[o][slot]));
          }
          std::vector<double> sorted = steps;
          std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
          const double median = sorted[sorted.size() / 2];
          for (std::size_t i = 0; i < steps.size(); ++i) {
            bool same = true;
            for (int q = 0; q < lk::kNumParts; ++q) same &= sweep[i][w].status[q][slot] == sweep[i + 1][w].status[q][slot];
            if (!same) continue;
            EXPECT_LE(steps[i], 3.0 * median + core_floor(o) * scale)
                << label(o) << " y " << y << " wheel " << w << " slot " << slot << " yaw " << yaws[i] << " .. " << yaws[i + 1];
          }
        }
  }
}

// d/d yaw of the interpolant against central differences of the query inside the cells (the
// derivative code is generic over the axes; the normalised creep part's scales depend on yaw).
// The derivatives of the table as loaded (float records) are the double-record table's to the byte
// (the chain reads double sums), differenced on that one.
TEST(YawTable, DerivativeAlongYaw) {
  const YawFixture& f = fixture();
  const lk::Table& t = *f.lookup_doubles;
  const lk::Table& floats = *f.lookup;
  Random rng(33);
  std::size_t nonzero = 0;
  for (int k = 0; k < 100; ++k) {
    const lk::State s = state_at(t, rng.uniform(-0.009, 0.009), rng.uniform(-0.01, 0.01), rng.uniform(60e3, 100e3),
                                 rng.uniform(-0.004, 0.004), rng.uniform(-0.004, 0.004), rng.uniform(-0.3, 0.3));
    for (int w = 0; w < 2; ++w) {
      const auto wheel = static_cast<lk::Wheel>(w);
      lk::Result r, rp, rm;
      lk::Derivatives d;
      ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
      lk::Result rf;
      lk::Derivatives df;
      ASSERT_TRUE(floats.query_derivatives(wheel, s, rf, df));
      ASSERT_EQ(std::memcmp(&d, &df, sizeof d), 0) << "float and double records' derivatives";
      const double h = 1e-9;
      lk::State plus = s, minus = s;
      plus.yaw += h;
      minus.yaw -= h;
      t.query(wheel, plus, rp);
      t.query(wheel, minus, rm);
      for (std::size_t slot = 0; slot < kSlots; ++slot)
        for (int o = 0; o < lk::kNumOutputs; ++o) {
          const double fd = (rp.contact[slot].value[o] - rm.contact[slot].value[o]) / (2.0 * h);
          const double dv = d.d[slot][o][lk::kYaw];
          nonzero += dv != 0.0;
          const double scale = std::abs(r.contact[slot].value[o]) / 0.005 + std::abs(fd);  // per cell width
          EXPECT_NEAR(dv, fd, 1e-5 * scale + 1e-12) << label(o) << " wheel " << w << " slot " << slot;
        }
    }
  }
  EXPECT_GT(nonzero, 1000u);
}

// The exact half-space model through a yaw table: at its nodes the lookup gives the kernel run at
// that yaw, the geometry and normal parts to round-off, the coupled creep part within the warm
// chain's bound (the sweep starts each creepage from its neighbour's solution, the direct
// evaluation from cold: HalfspaceDirect.AgreesWithTheTableAtAGridNode), and yaw moves it.
// The exact model's list is stored whole (not folded): how far its outputs at -yaw are from those
// at +yaw is printed (docs/validation/yaw-tables.md). A small grid at 0.5 mm elements (seconds).
TEST(YawTable, ExactModelThroughTheTable) {
  std::ifstream in(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s = s.substr(0, s.find("[grid]"));
  s.replace(s.find("element_size = 0.4e-3"), std::string("element_size = 0.4e-3").size(), "element_size = 0.5e-3");
  s += "[grid]\ny = [0.003, 0.0075]\nequilibrium_roll = true\nyaw = [-0.01, 0.0, 0.01]\nload = 78.5e3\n"
       "xi = [-0.002, 0.0, 0.002]\neta = [0.0, 0.001]\nphi = 0.1\n";
  const Scene scene = parse_scene(s, "exact yaw scene");
  ASSERT_FALSE(scene.grids.yaw_even);  // the exact model's list is kept whole
  SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const std::filesystem::path path = temp_table_path("yaw_exact");
  write_for_lookup(r.table, path);
  const lk::Table t = lk::Table::load(path.string());
  std::filesystem::remove(path);
  std::vector<Point> points;
  for (double y : scene.grids.y)
    for (double xi : scene.grids.xi)
      for (double eta : scene.grids.eta) {
        Point p;
        p.v[kY] = y, p.v[kLoad] = 78.5e3, p.v[kXi] = xi, p.v[kEta] = eta, p.v[kPhi] = 0.1;
        points.push_back(p);
      }
  const double yaws[] = {-0.01, 0.0, 0.01};
  std::vector<Direct> direct(points.size() * 3);
  tbb::parallel_for(std::size_t{0}, direct.size(),
                    [&](std::size_t i) { direct[i] = evaluate_direct(scene, points[i / 3], yaws[i % 3]); });
  std::size_t checked = 0, moved = 0;
  double odd = 0.0;  // largest |f(-yaw) - f(+yaw)| / max |f| over outputs with equal statuses
  int odd_output = 0;
  double odd_fz = 0.0;  // the same for the creep forces fx, fy over mu N
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t w = 0; w < 2; ++w) {
        const Direct& d = direct[i * 3 + j];
        const lk::Result q = t.query(static_cast<lk::Wheel>(w), state_at(t, p.v[kY], yaws[j], p.v[kLoad], p.v[kXi], p.v[kEta], 0.1));
        EXPECT_EQ(q.status, 0u);
        for (std::size_t slot = 0; slot < kSlots; ++slot) {
          // The warm chain's bound: the load split within 2e-4 F_z, the creep forces within that
          // share of mu F_z plus 1e-4 mu N, the rest of the creep and wear parts 2e-4 relative;
          // plus the float32 rounding (4 x 2^-20 of N for forces rebuilt from F / (mu N) and N).
          const double fz = 78.5e3, mun = 0.3 * std::abs(d[w].value[lk::kNormalForce][slot]);
          const double creep_tol = 2e-4 * fz * 0.3 + 1e-4 * mun;
          for (int o = 0; o < lk::kNumOutputs; ++o) {
            const double a = q.contact[slot].value[o], b = d[w].value[o][slot];
            const bool creep = lk::output_part(static_cast<lk::Output>(o)) >= lk::kCreep || o == lk::kNormalForce;
            const double warm = o == lk::kNormalForce ? 2e-4 * fz
                                : o == lk::kFx || o == lk::kFy ? creep_tol
                                : o == lk::kMz ? 0.01 * creep_tol : 0.0;
            const double bound = creep ? warm + 2e-4 * std::abs(b) + 4.0 * kStoredRounding * (std::abs(b) + mun / 0.3)
                                       : 1e-12 * std::abs(b) + 1e-15;
            EXPECT_NEAR(a, b, bound) << label(o) << " y " << p.v[kY] << " yaw " << yaws[j] << " wheel " << w << " slot " << slot;
            ++checked;
            if (j != 1) {
              const double zero = direct[i * 3 + 1][w].value[o][slot];
              moved += std::abs(b - zero) > 1e-6 * std::max(std::abs(zero), 1e-3);
            }
            if (j == 0) {
              bool same = true;
              for (int part = 0; part < lk::kNumParts; ++part)
                same &= d[w].status[part][slot] == direct[i * 3 + 2][w].status[part][slot];
              const double c = direct[i * 3 + 2][w].value[o][slot], scale = std::max(std::abs(b), std::abs(c));
              if (same && scale > 0.0 && std::abs(b - c) / scale > odd) odd = std::abs(b - c) / scale, odd_output = o;
              if (same && mun > 0.0 && (o == lk::kFx || o == lk::kFy)) odd_fz = std::max(odd_fz, std::abs(b - c) / mun);
            }
          }
        }
      }
  }
  std::printf("exact model through a yaw table: %zu outputs checked at the nodes, %zu at +-10 mrad move by > 1e-6 from "
              "yaw 0; largest |f(-yaw) - f(+yaw)| / |f| %.2e (%s), of fx and fy / (mu N) %.2e\n",
              checked, moved, odd, label(odd_output).c_str(), odd_fz);
  EXPECT_GT(moved, checked / 10);  // the yaw reaches the exact model
}

}  // namespace
}  // namespace railtab::accuracy
