// SPDX-License-Identifier: Apache-2.0
// The states file of `railtab query --states` (query_states.hpp).
#include "cli/query_states.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string_view>
#include <vector>

#include "core/check.hpp"
#include "core/number_input.hpp"
#include "scene/state_rules.hpp"

namespace railtab {
namespace {

constexpr std::size_t kMaxLine = 4096;  // characters per line: a state needs fewer than 200
constexpr const char* kNames[] = {"y", "roll", "load", "xi", "eta", "phi", "yaw"};
constexpr NumberRule kRules[] = {kLateralShiftRule, kRollRule,     kWheelLoadRule,    kCreepageRule,
                                 kCreepageRule,     kSpinCreepageRule, kYawRule};
constexpr int kColumns = 7;

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  while (true) {
    const std::size_t comma = line.find(',');
    out.push_back(trimmed(line.substr(0, comma)));
    if (comma == std::string_view::npos) return out;
    line.remove_prefix(comma + 1);
  }
}

double& variable(lookup::State& s, int k) {
  double* v[] = {&s.y, &s.roll, &s.load, &s.xi, &s.eta, &s.phi, &s.yaw};
  return *v[k];
}

}  // namespace

StateReader::StateReader(const std::string& path) : path_(path), in_(&std::cin) {
  column_.fill(-1);
  if (path != "-") {
    std::error_code ec;
    RAILTAB_CHECK(!std::filesystem::is_directory(path, ec), "{}: is a directory, not a states file", path);
    file_.open(path);
    const int error = errno;
    RAILTAB_CHECK(file_.is_open(), "{}: cannot open the states file ({})", path, std::strerror(error));
    in_ = &file_;
  }
  std::string header;
  RAILTAB_CHECK(read_line(header), "{}: empty: expected a header naming the columns (y and any of roll, load, xi, "
                "eta, phi, yaw)", path_);
  const std::vector<std::string_view> names = fields(header);
  columns_ = static_cast<int>(names.size());
  for (int c = 0; c < columns_; ++c) {
    int k = 0;
    while (k < kColumns && names[c] != kNames[k]) ++k;
    RAILTAB_CHECK(k < kColumns, "{}:{}: header: unknown column '{}' (known: y, roll, load, xi, eta, phi, yaw)", path_,
                  line_number_, names[c].substr(0, 40));
    RAILTAB_CHECK(column_[k] < 0, "{}:{}: header: column {} named twice", path_, line_number_, kNames[k]);
    column_[k] = c;
  }
  RAILTAB_CHECK(column_[0] >= 0, "{}:{}: header: no column y", path_, line_number_);
}

bool StateReader::has(const char* name) const {
  for (int k = 0; k < kColumns; ++k)
    if (std::string_view(name) == kNames[k]) return column_[k] >= 0;
  return false;
}

bool StateReader::read_line(std::string& line) {
  char buffer[kMaxLine + 2];
  while (true) {
    in_->getline(buffer, sizeof buffer);
    const std::streamsize n = in_->gcount();
    if (n == 0 && in_->eof()) return false;
    ++line_number_;
    RAILTAB_CHECK(!in_->fail() || in_->eof(), "{}:{}: line longer than {} characters", path_, line_number_, kMaxLine);
    RAILTAB_CHECK(!in_->bad(), "{}:{}: read error", path_, line_number_);
    // gcount counts the line end when it was read; a NUL inside the line is kept (and refused).
    line.assign(buffer, static_cast<std::size_t>(in_->eof() ? n : n - 1));
    const std::string_view text = trimmed(line);
    if (!text.empty() && text.front() != '#') return true;
    if (in_->eof()) return false;
  }
}

bool StateReader::next(lookup::State& state) {
  std::string line;
  if (!read_line(line)) return false;
  const std::vector<std::string_view> values = fields(line);
  RAILTAB_CHECK(static_cast<int>(values.size()) == columns_, "{}:{}: {} values, the header names {} columns", path_,
                line_number_, values.size(), columns_);
  for (int k = 0; k < kColumns; ++k) {
    if (column_[k] < 0) continue;
    double v = 0.0;
    const std::string problem = number_problem(values[column_[k]], kRules[k], v);
    RAILTAB_CHECK(problem.empty(), "{}:{}: column {}: {}", path_, line_number_, kNames[k], problem);
    variable(state, k) = v;
  }
  return true;
}

}  // namespace railtab
