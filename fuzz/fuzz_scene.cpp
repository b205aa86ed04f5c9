// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the scene reader (generator/scene): parse_scene on arbitrary TOML text, then the
// objects the scene describes (geometry solver, model options). Profile files named in the scene
// are looked up in an empty directory. Any input must end in a Scene or a railtab::Error.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/check.hpp"
#include "scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path empty_dir = [] {
    // A fixed name (not the pid): the path ends up in error messages, and a length that changes
    // from run to run changes the code paths taken, so a seeded run would not repeat itself.
    auto d = std::filesystem::temp_directory_path() / "railtab_fuzz_scene_empty_dir";
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    railtab::Scene scene = railtab::parse_scene(text, "fuzz.toml", empty_dir);
    (void)railtab::fastsim_options(scene);
    (void)railtab::creep_conditions(scene);
    (void)railtab::wear_options(scene);
  } catch (const railtab::Error&) {
  }
  return 0;
}
