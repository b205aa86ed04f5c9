// SPDX-License-Identifier: Apache-2.0
// Profiles and geometry solver of a scene: built-in analytic profiles or measured profile files.
#include <fmt/format.h>

#include "core/check.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "scene/scene.hpp"
#if __has_include("profile/formats/profile_io.hpp")
#include "profile/formats/profile_io.hpp"
#define RAILTAB_HAVE_PROFILE_IO 1
#endif

namespace railtab {
namespace {

ProfilePtr make_profile(const ProfileSource& source, ProfileKind kind) {
  if (source.file.empty()) {
    if (kind == ProfileKind::wheel && source.name == "s1002") return make_s1002_profile();
    if (kind == ProfileKind::rail && source.name == "uic60") return make_uic60_profile();
    throw Error(fmt::format("unknown built-in profile '{}'", source.name));
  }
#ifdef RAILTAB_HAVE_PROFILE_IO
  ProfileReadOptions options;
  options.smoothing_length = source.smoothing_length;
  options.mirror_y = source.mirror_y;
  options.mirror_z = source.mirror_z;
  options.lateral_shift = source.lateral_shift;
  return read_profile(source.file, kind, options);
#else
  throw Error(fmt::format("{}: reading profile files is not available in this build", source.file.string()));
#endif
}

}  // namespace

ContactGeometrySolver make_geometry_solver(const Scene& scene) {
  ProfilePtr wheel = make_profile(scene.wheel, ProfileKind::wheel);
  ProfilePtr rail = make_profile(scene.rail, ProfileKind::rail);
  // Both sides share the profile objects: the right pair is the mirror image of the left one.
  return ContactGeometrySolver(wheel, rail, wheel, rail, scene.track, scene.wheelset, scene.geometry);
}

}  // namespace railtab
