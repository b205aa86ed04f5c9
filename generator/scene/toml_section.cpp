// SPDX-License-Identifier: Apache-2.0
// Checked TOML reading: typed values, units and unknown-key errors naming file and key.
#include "scene/toml_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "profile/formats/text_file.hpp"

namespace railtab::scene_toml {

namespace {
// A scene lists its grids explicitly at most; 4 MiB is thousands of times the shipped ones.
constexpr std::size_t kMaxSceneFileBytes = 4u << 20;
}  // namespace

void fail(const Context& ctx, const toml::source_region& where, const std::string& key,
          const std::string& message) {
  if (where.begin.line > 0) {
    throw Error(fmt::format("{}:{}: {}: {}", ctx.file, where.begin.line, key, message));
  }
  throw Error(fmt::format("{}: {}: {}", ctx.file, key, message));
}

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

bool positive(double v) { return v > 0.0; }
bool non_negative(double v) { return v >= 0.0; }

Section::Section(const Context& ctx, std::string name, const toml::table* table,
                 std::vector<std::string> allowed)
    : ctx_(ctx), name_(std::move(name)), table_(table), allowed_(std::move(allowed)) {
  if (!table_) return;
  for (auto&& [key, node] : *table_) {
    if (std::find(allowed_.begin(), allowed_.end(), key.str()) == allowed_.end()) {
      fail(ctx_, key.source(), dotted(std::string(key.str())),
           fmt::format("unknown key (known keys: {})", join(allowed_)));
    }
  }
}

const toml::node& Section::required(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) {
    fail(ctx_, table_ ? table_->source() : toml::source_region{}, dotted(key),
         table_ ? "missing required key" : fmt::format("missing required key (no [{}] section)", name_));
  }
  return *n;
}

double Section::number(const toml::node& n, const std::string& key) const {
  double value = 0.0;
  if (auto i = n.as_integer()) {
    value = static_cast<double>(i->get());
  } else if (auto f = n.as_floating_point()) {
    value = f->get();
  } else {
    fail(ctx_, n.source(), dotted(key), fmt::format("expected a number, got {}", type_name(n)));
  }
  if (!std::isfinite(value)) fail(ctx_, n.source(), dotted(key), "value is not finite");
  return value;
}

double Section::number(const std::string& key, double fallback, bool (*check)(double),
                       const char* requirement, bool is_required) const {
  const toml::node* n = is_required ? &required(key) : node(key);
  if (!n) return fallback;
  const double value = number(*n, key);
  if (check && !check(value)) {
    fail(ctx_, n->source(), dotted(key), fmt::format("must be {}, got {}", requirement, value));
  }
  return value;
}

int Section::integer(const std::string& key, int fallback, int min_value, int max_value) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  auto i = n->as_integer();
  if (!i) fail(ctx_, n->source(), dotted(key), fmt::format("expected an integer, got {}", type_name(*n)));
  if (i->get() < min_value || i->get() > max_value) {
    fail(ctx_, n->source(), dotted(key),
         fmt::format("must be an integer in [{}, {}], got {}", min_value, max_value, i->get()));
  }
  return static_cast<int>(i->get());
}

bool Section::boolean(const std::string& key, bool fallback) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  auto b = n->as_boolean();
  if (!b) fail(ctx_, n->source(), dotted(key), fmt::format("expected true or false, got {}", type_name(*n)));
  return b->get();
}

std::string Section::string(const toml::node& n, const std::string& key) const {
  auto s = n.as_string();
  if (!s) fail(ctx_, n.source(), dotted(key), fmt::format("expected a string, got {}", type_name(n)));
  return s->get();
}

std::optional<std::string> Section::string(const std::string& key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  return string(*n, key);
}

const toml::table* table_at(const Context& ctx, const toml::table& parent, const std::string& key,
                            const std::string& dotted_name) {
  const toml::node* n = parent.get(key);
  if (!n) return nullptr;
  if (!n->is_table()) {
    fail(ctx, n->source(), dotted_name, fmt::format("expected a table [{}], got {}", dotted_name, type_name(*n)));
  }
  return n->as_table();
}

std::string read_text(const std::filesystem::path& path, const char* what) {
  // Regular files only, size-limited, without blocking on a FIFO (src/profile/formats/text_file.hpp).
  try {
    return read_regular_file(path, kMaxSceneFileBytes);
  } catch (const Error& e) {
    throw Error(fmt::format("{} ({})", e.what(), what));
  }
}

toml::table parse(std::string_view text, const std::string& source_name) {
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}:{}: TOML syntax error: {}", source_name, e.source().begin.line,
                            e.source().begin.column, e.description()));
  }
}

Section section(const Context& ctx, const toml::table& root, const std::string& name,
                std::vector<std::string> allowed) {
  return Section(ctx, name, table_at(ctx, root, name, name), std::move(allowed));
}

}  // namespace railtab::scene_toml
