// hotmesh python: the `hotmesh` module, <hotmesh/hotmesh.hpp> on NumPy arrays (docs/library.md).
// Points come back as read-only views of the result's own memory (no copies); the motion runs
// without the GIL; a mistake in what the caller gave is hotmesh.InputError, a ValueError.
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <string>

#include "hotmesh/hotmesh.hpp"

namespace py = pybind11;

namespace {

/// A read-only NumPy view of `count` rows of `columns` doubles, `stride` bytes apart, kept
/// alive by `owner`.
py::array view(const double* data, std::size_t count, std::size_t columns, std::size_t stride, py::handle owner) {
  py::array a(py::dtype::of<double>(), {count, columns}, {stride, sizeof(double)}, data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// The (n, 2) or (n, 3) table of `name` as float64 in C order, or hotmesh.InputError saying
/// what is wrong with it.
py::array_t<double, py::array::c_style> table(py::handle value, const char* name, const std::string& call) {
  py::array a = py::module_::import("numpy").attr("asarray")(value);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw hotmesh::InputError(fmt::format("{}: {} has dtype {}: give real numbers (a float64 array)", call, name,
                                          py::str(a.dtype()).cast<std::string>()));
  }
  if (a.ndim() != 2 || (a.shape(1) != 2 && a.shape(1) != 3) || a.shape(0) == 0) {
    throw hotmesh::InputError(fmt::format("{}: {} has shape {}: give an (n, 2) or (n, 3) array, a row per FEM node "
                                          "(x, y; x, y, z; or r, z)",
                                          call, name, py::str(a.attr("shape")).cast<std::string>()));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

hotmesh::Frame frame_named(const std::string& name) {
  static constexpr std::array<std::pair<const char*, hotmesh::Frame>, 4> kFrames{
      {{"auto", hotmesh::Frame::automatic},
       {"planar", hotmesh::Frame::planar},
       {"cartesian", hotmesh::Frame::cartesian},
       {"meridional", hotmesh::Frame::meridional}}};
  for (const auto& [text, frame] : kFrames) {
    if (name == text) return frame;
  }
  throw hotmesh::InputError(fmt::format("set_deflection: frame '{}': give auto, planar, cartesian or meridional", name));
}

void set_deflection(hotmesh::Case& c, const std::string& patch, py::handle nodes, py::handle displacements,
                    const std::string& frame) {
  const std::string call = fmt::format("set_deflection({})", patch);
  const auto p = table(nodes, "nodes", call);
  const auto d = table(displacements, "displacements", call);
  if (p.shape(0) != d.shape(0) || p.shape(1) != d.shape(1)) {
    throw hotmesh::InputError(fmt::format("{}: nodes has shape ({}, {}) and displacements ({}, {}): give one "
                                          "displacement per node, with as many columns",
                                          call, p.shape(0), p.shape(1), d.shape(0), d.shape(1)));
  }
  const auto size = static_cast<std::size_t>(p.size());
  c.set_deflection(patch, {p.data(), size}, {d.data(), size}, static_cast<int>(p.shape(1)), frame_named(frame));
}

/// The motion without the GIL; `progress` (a callable, or None) hears of it with the GIL.
hotmesh::Result deform(hotmesh::Case& c, const hotmesh::Result* previous, const py::object& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) {
    throw hotmesh::InputError("deform: progress must be a callable taking a hotmesh.Progress, or None");
  }
  struct Reset {
    hotmesh::Case& c;
    ~Reset() { c.set_progress({}); }
  } reset{c};
  if (!progress.is_none()) {
    c.set_progress([&progress](const hotmesh::Progress& p) {
      py::gil_scoped_acquire gil;
      progress(p);
    });
  }
  py::gil_scoped_release released;
  return previous ? c.deform(*previous) : c.deform();
}

py::dict quality_dict(const hotmesh::Quality& q) {
  py::dict d;
  d["min_scaled_jacobian"] = q.min_scaled_jacobian;
  d["inverted_cells"] = q.inverted_cells;
  d["max_non_orthogonality"] = q.max_non_orthogonality;
  d["mean_non_orthogonality"] = q.mean_non_orthogonality;
  d["severely_non_orthogonal_faces"] = q.severely_non_orthogonal_faces;
  d["max_skewness"] = q.max_skewness;
  d["max_volume_ratio"] = q.max_volume_ratio;
  d["max_aspect_ratio"] = q.max_aspect_ratio;
  return d;
}

void bind_case(py::module_& m) {
  py::class_<hotmesh::Case>(m, "Case", "A case: a mesh, its patches' roles and deflections, the solver's settings.")
      .def(py::init<const std::filesystem::path&>(), py::arg("path"), "Reads and checks a case file and its tables.")
      .def_static(
          "from_mesh",
          [](const std::filesystem::path& mesh, const std::vector<std::pair<std::string, std::string>>& roles,
             int increments) { return hotmesh::Case::from_mesh(mesh, roles, increments); },
          py::arg("mesh"), py::arg("roles"), py::arg("increments") = 16,
          "A case built in code: the mesh file and [(patch, role), ...].")
      .def_property_readonly("file", &hotmesh::Case::file)
      .def_property_readonly("mesh_file", &hotmesh::Case::mesh_file)
      .def_property_readonly("patches", &hotmesh::Case::patches)
      .def("role", &hotmesh::Case::role, py::arg("patch"))
      .def("set_deflection", &set_deflection, py::arg("patch"), py::kw_only(), py::arg("nodes"),
           py::arg("displacements"), py::arg("frame") = "auto",
           "The FEM deflection of a patch's wall: nodes (n, 2 or 3) and their displacements, as a table's columns.")
      .def("set_calculix_deflection", &hotmesh::Case::set_calculix_deflection, py::arg("patch"), py::kw_only(),
           py::arg("frd"), py::arg("inp"), py::arg("set"), "The deflection of a patch from CalculiX results.")
      .def_property("threads", nullptr, &hotmesh::Case::set_threads,
                    "OpenMP threads of the motion, taken by the first deform; 0: the case's solver.threads, "
                    "else hotmesh chooses")
      .def(
          "deform", [](hotmesh::Case& c, const hotmesh::Result* previous, const py::object& progress) {
            return deform(c, previous, progress);
          },
          py::arg("previous") = nullptr, py::kw_only(), py::arg("progress") = py::none(),
          "Moves the mesh; from `previous` (a Result of this mesh) for the next coupling iteration.");
}

void bind_result(py::module_& m) {
  py::class_<hotmesh::Result>(m, "Result", "A moved mesh.")
      .def_property_readonly("success", &hotmesh::Result::success)
      .def_property_readonly("message", &hotmesh::Result::message)
      .def_property_readonly("stage", &hotmesh::Result::stage)
      .def_property_readonly("dimension", &hotmesh::Result::dimension)
      .def_property_readonly(
          "points",
          [](py::object self) {
            const auto& r = self.cast<const hotmesh::Result&>();
            const auto points = r.points();
            return view(&points.data()->x, points.size(), static_cast<std::size_t>(r.dimension()), sizeof(hotmesh::Point),
                        self);
          },
          "(n, dimension) float64, read-only, the result's own memory")
      .def_property_readonly("node_ids",
                             [](py::object self) {
                               const auto ids = self.cast<const hotmesh::Result&>().node_ids();
                               return py::array_t<std::int64_t>(static_cast<py::ssize_t>(ids.size()), ids.data(), self);
                             })
      .def_property_readonly("scaled_jacobians",
                             [](py::object self) {
                               const auto q = self.cast<const hotmesh::Result&>().scaled_jacobians();
                               return view(q.data(), q.size(), 1, sizeof(double), self).attr("reshape")(-1);
                             })
      .def_property_readonly("min_scaled_jacobian", &hotmesh::Result::min_scaled_jacobian)
      .def_property_readonly("quality", [](const hotmesh::Result& r) { return quality_dict(r.quality()); })
      .def_property_readonly(
          "report",
          [](const hotmesh::Result& r) { return py::module_::import("json").attr("loads")(r.report()); },
          "report.json as a dict")
      .def(
          "write",
          [](const hotmesh::Result& r, const std::filesystem::path& folder) {
            py::gil_scoped_release released;
            r.write(folder);
          },
          py::arg("folder"), "Writes the files `hotmesh deform` writes into the folder.");
}

void bind_check(py::module_& m) {
  py::class_<hotmesh::PatchCheck>(m, "PatchCheck")
      .def_readonly("patch", &hotmesh::PatchCheck::patch)
      .def_readonly("nodes", &hotmesh::PatchCheck::nodes)
      .def_readonly("max_distance", &hotmesh::PatchCheck::max_distance)
      .def_readonly("mean_distance", &hotmesh::PatchCheck::mean_distance)
      .def_readonly("worst_node", &hotmesh::PatchCheck::worst_node)
      .def_readonly("wall_distance", &hotmesh::PatchCheck::wall_distance)
      .def_readonly("passed", &hotmesh::PatchCheck::passed);
  py::class_<hotmesh::CheckResult>(m, "CheckResult")
      .def_readonly("passed", &hotmesh::CheckResult::passed)
      .def_readonly("tolerance", &hotmesh::CheckResult::tolerance)
      .def_readonly("patches", &hotmesh::CheckResult::patches)
      .def_readonly("text", &hotmesh::CheckResult::text)
      .def_property_readonly(
          "report", [](const hotmesh::CheckResult& r) { return py::module_::import("json").attr("loads")(r.json); })
      .def("__bool__", [](const hotmesh::CheckResult& r) { return r.passed; });
  m.def(
      "check",
      [](const std::filesystem::path& mesh, const std::filesystem::path& case_file, double tolerance,
         double wall_tolerance) {
        py::gil_scoped_release released;
        return hotmesh::check(mesh, case_file, tolerance, wall_tolerance);
      },
      py::arg("mesh"), py::kw_only(), py::arg("case"), py::arg("tolerance") = 0.0, py::arg("wall_tolerance") = 0.0,
      "hotmesh check MESH --case CASE: the mesh's walls against the case's.");
}

}  // namespace

PYBIND11_MODULE(hotmesh, m) {
  m.doc() = "hotmesh: moves a CFD mesh onto the hot running geometry computed by an FEM code (docs/library.md).";
  py::register_exception<hotmesh::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("__version__") = hotmesh::version();
  m.def("version", &hotmesh::version);
  m.def(
      "set_verbosity",
      [](const std::string& level) {
        static constexpr std::array<std::pair<const char*, hotmesh::Verbosity>, 4> kLevels{
            {{"quiet", hotmesh::Verbosity::quiet},
             {"warnings", hotmesh::Verbosity::warnings},
             {"info", hotmesh::Verbosity::info},
             {"debug", hotmesh::Verbosity::debug}}};
        for (const auto& [name, verbosity] : kLevels) {
          if (level == name) return hotmesh::set_verbosity(verbosity);
        }
        throw hotmesh::InputError(fmt::format("set_verbosity: '{}': give quiet, warnings, info or debug", level));
      },
      py::arg("level"), "How much hotmesh logs on stderr: quiet, warnings (the default), info, debug.");
  py::class_<hotmesh::Progress>(m, "Progress", "Where the motion is (deform's progress callback).")
      .def_readonly("increment", &hotmesh::Progress::increment)
      .def_readonly("increments", &hotmesh::Progress::increments)
      .def_readonly("corner_pass", &hotmesh::Progress::corner_pass)
      .def_readonly("newton_iteration", &hotmesh::Progress::newton_iteration)
      .def_readonly("residual_reduction", &hotmesh::Progress::residual_reduction)
      .def_readonly("min_scaled_jacobian", &hotmesh::Progress::min_scaled_jacobian)
      .def_readonly("accepted", &hotmesh::Progress::accepted);
  bind_case(m);
  bind_result(m);
  bind_check(m);
}
