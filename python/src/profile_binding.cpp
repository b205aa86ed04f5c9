// SPDX-License-Identifier: Apache-2.0
// railtab.Profile: wheel and rail profiles from files (profile/formats/profile_io.hpp), the built-in
// S1002 and UIC60, evaluation on numpy arrays, and the SIMPACK writer.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

#include "bindings.hpp"
#include "core/check.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/formats/simpack_writer.hpp"
#include "table/output_file.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab::python {
namespace {

namespace py = pybind11;

ProfileKind parse_kind(const std::string& kind) {
  if (kind == "wheel") return ProfileKind::wheel;
  if (kind == "rail") return ProfileKind::rail;
  throw py::value_error("kind must be 'wheel' or 'rail', got '" + kind + "'");
}

// A const profile shared with the core (ProfilePtr is shared_ptr<const Profile>).
struct PyProfile {
  ProfilePtr profile;
};

// z, dz/du, d2z/du2 at every u (any shape); u outside [u_min, u_max] raises ValueError.
py::tuple evaluate(const PyProfile& p, const py::array_t<double, py::array::forcecast>& u) {
  py::array_t<double> z(u.request().shape), dz(u.request().shape), d2z(u.request().shape);
  const py::ssize_t n = u.size();
  // A C-contiguous copy only when u is a strided view.
  const auto flat = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(u);
  const double* x = flat.data();
  double* zo = z.mutable_data();
  double* dzo = dz.mutable_data();
  double* d2zo = d2z.mutable_data();
  for (py::ssize_t k = 0; k < n; ++k) {
    const ProfileSample s = p.profile->eval(x[k]);
    zo[k] = s.z;
    dzo[k] = s.dz;
    d2zo[k] = s.d2z;
  }
  return py::make_tuple(z, dz, d2z);
}

}  // namespace

void bind_profile(py::module_& m) {
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  py::class_<PyProfile>(m, "Profile")
      .def_static(
          "read",
          [](const std::filesystem::path& path, const std::string& kind, double smoothing_length) {
            return PyProfile{read_profile(path, parse_kind(kind), smoothing_length)};
          },
          py::arg("path"), py::arg("kind"), py::arg("smoothing_length") = 0.0)
      .def_static("s1002", [] { return PyProfile{make_s1002_profile()}; })
      .def_static("uic60", [] { return PyProfile{make_uic60_profile()}; })
      .def_property_readonly("name", [](const PyProfile& p) { return p.profile->name(); })
      .def_property_readonly("kind", [](const PyProfile& p) {
        return p.profile->kind() == ProfileKind::wheel ? "wheel" : "rail";
      })
      .def_property_readonly("u_min", [](const PyProfile& p) { return p.profile->u_min(); })
      .def_property_readonly("u_max", [](const PyProfile& p) { return p.profile->u_max(); })
      .def("_eval", &evaluate, py::arg("u"));

  m.def(
      "_write_simpack",
      [](const std::filesystem::path& path, const std::string& kind, const std::vector<double>& u,
         const std::vector<double>& z, const std::string& comment) {
        // src/ writes no file: the text is written through the generator's safe output file.
        check_simpack_file_name(path, parse_kind(kind));
        write_text_file(path, simpack_profile_text(parse_kind(kind), u, z, comment));
      },
      py::arg("path"), py::arg("kind"), py::arg("u"), py::arg("z"), py::arg("comment") = "");
}

}  // namespace railtab::python
