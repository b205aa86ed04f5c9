// SPDX-License-Identifier: Apache-2.0
// The one JSON shape the lookup reads, a flat object such as the root attribute fixed_axes (flat_json.hpp).
#include "flat_json.hpp"

#include <charconv>
#include <stdexcept>

namespace railtab::lookup::detail {
namespace {

class Cursor {
 public:
  explicit Cursor(std::string_view text) : s_(text) {}

  void skip_space() {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t' || s_[p_] == '\n' || s_[p_] == '\r'))
      ++p_;
  }
  bool peek(char c) {
    skip_space();
    return p_ < s_.size() && s_[p_] == c;
  }
  void expect(char c) {
    if (!peek(c)) fail(std::string("expected '") + c + "'");
    ++p_;
  }
  bool at_end() {
    skip_space();
    return p_ == s_.size();
  }
  std::string string() {
    expect('"');
    std::string out;
    while (p_ < s_.size() && s_[p_] != '"') {
      if (s_[p_] == '\\') {
        if (++p_ == s_.size()) break;
        const char e = s_[p_];
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e;  // keys are plain names; enough
      } else {
        out += s_[p_];
      }
      ++p_;
    }
    expect('"');
    return out;
  }
  double number() {
    skip_space();
    double v = 0.0;
    const char* begin = s_.data() + p_;
    const char* end = s_.data() + s_.size();
    if (p_ < s_.size() && s_[p_] == '+') fail("expected a number");
    const auto [ptr, ec] = std::from_chars(begin, end, v);  // locale-independent
    if (ec != std::errc() || ptr == begin) fail("expected a number");
    p_ += static_cast<std::size_t>(ptr - begin);
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(what + " at offset " + std::to_string(p_) + " of '" +
                             std::string(s_) + "'");
  }

 private:
  std::string_view s_;  // whole text
  std::size_t p_ = 0;   // read position
};

}  // namespace

std::vector<FlatJsonEntry> parse_flat_json(std::string_view text) {
  Cursor c(text);
  std::vector<FlatJsonEntry> out;
  c.expect('{');
  if (!c.peek('}')) {
    do {
      FlatJsonEntry e;
      e.key = c.string();
      c.expect(':');
      if (c.peek('"')) {
        e.is_text = true;
        e.text = c.string();
      } else {
        e.number = c.number();
      }
      out.push_back(std::move(e));
    } while (c.peek(',') && (c.expect(','), true));
  }
  c.expect('}');
  if (!c.at_end()) c.fail("trailing text");
  return out;
}

std::vector<std::pair<std::string, double>> parse_flat_json_numbers(std::string_view text) {
  std::vector<std::pair<std::string, double>> out;
  for (FlatJsonEntry& e : parse_flat_json(text)) {
    if (e.is_text) throw std::runtime_error("value of '" + e.key + "' is not a number in '" + std::string(text) + "'");
    out.emplace_back(std::move(e.key), e.number);
  }
  return out;
}

}  // namespace railtab::lookup::detail
