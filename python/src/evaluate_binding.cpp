// SPDX-License-Identifier: Apache-2.0
// railtab.evaluate: one wheelset state of a scene through the direct models, the very code of
// `railtab eval --json` (eval/state_eval.hpp), returned as its JSON text (railtab/_evaluate.py
// parses it), so Python and the command line cannot drift apart.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "scene/scene.hpp"
#include "eval/state_eval.hpp"
#include "eval/state_json.hpp"

namespace railtab::python {
namespace {

namespace py = pybind11;

// A scene loaded once (profiles, grids, models), evaluated many times.
struct PyScene {
  std::shared_ptr<const Scene> scene;
};

}  // namespace

void bind_evaluate(py::module_& m) {
  py::class_<PyScene>(m, "Scene")
      .def_static(
          "load", [](const std::filesystem::path& path) { return PyScene{std::make_shared<const Scene>(load_scene(path))}; },
          py::arg("path"))
      .def_property_readonly("name", [](const PyScene& s) { return s.scene->name; })
      .def_property_readonly("path", [](const PyScene& s) { return s.scene->path; });

  m.def(
      "_evaluate_json",
      [](const PyScene& s, double y, std::optional<double> roll, bool equilibrium_roll, std::optional<double> load,
         const std::string& model, const std::vector<double>& creepage, std::optional<double> mu,
         std::optional<double> yaw) {
        StateEvalRequest request;
        request.y = y;
        request.roll = roll;
        request.yaw = yaw;
        request.equilibrium_roll = equilibrium_roll;
        request.load = load;
        request.model = model;
        request.creepage = creepage;
        request.mu = mu;
        std::string text;
        {
          py::gil_scoped_release release;  // pure C++: other Python threads may run
          text = state_json(evaluate_state(*s.scene, request)).dump();
        }
        return text;
      },
      py::arg("scene"), py::arg("y"), py::arg("roll"), py::arg("equilibrium_roll"), py::arg("load"),
      py::arg("model"), py::arg("creepage"), py::arg("mu"), py::arg("yaw") = py::none());
}

}  // namespace railtab::python
