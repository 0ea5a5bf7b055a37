// hotmesh fuzz: the JSON bodies of `hotmesh serve`'s POST routes, parsed (parse_object) and
// handed to the route's GeometryService method as the HTTP layer does; the route is the one
// whose keys the body has:
//   "path"   -> POST /api/models (load_path; the root holds a few small CAD files)
//   "points" -> POST /api/curves/{id}/project (on a curve made at start-up)
//   "grid"   -> POST /api/surfaces (create_surface; "model": "m1" is the stator-well sample)
//   "csv"    -> POST /api/curves (create_curve; "model": "m1" is the stator-well sample)
//   "mode"   -> POST /api/models/m1/mode (faces_mode)
//   else     -> POST /api/models/m1/meridional
// A request may fail only with ApiError (4xx) or hotmesh::InputError (422), anything else
// would be the server's 500, and leaves no file behind in the service's upload folder. What a
// request makes is deleted again, so every input meets the same service.
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "service/api_error.hpp"
#include "service/service.hpp"

namespace {

namespace fs = std::filesystem;
namespace serve = hotmesh::app::serve;
using hotmesh::fuzz::source_file;

struct Fixture {
  Fixture()
      : temporary(hotmesh::fuzz::use_private_temporary_folder()), root(make_root()),
        service(root, serve::ServiceLimits{}) {
    model = service.load_path({{"path", "stator_well.step"}})["model"].get<std::string>();
    const std::string csv = hotmesh::io::read_file(source_file("samples/ramp2d/ramp.csv"));
    curve = service.create_curve({{"csv", csv}})["curve"].get<std::string>();
  }

  static fs::path make_root() {
    const fs::path folder = hotmesh::fuzz::work_folder() / "root";
    fs::create_directories(folder / "tables");
    fs::copy_file(source_file("samples/stator_well/stator_well.step"), folder / "stator_well.step");
    fs::copy_file(source_file("tests/data/cad/bug3883_xr2-ct-214_bolt.stp"), folder / "bolt.stp");
    fs::copy_file(source_file("tests/data/cad/OCC8842_cone_CATIA.igs"), folder / "cone.igs");
    fs::copy_file(source_file("samples/ramp2d/ramp.csv"), folder / "tables" / "ramp.csv");
    return folder;
  }

  fs::path temporary;  ///< where the service keeps its uploads (and files read below the root)
  fs::path root;
  serve::GeometryService service;
  std::string model;
  std::string curve;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Fixture fixture = [] {
    const hotmesh::fuzz::OcctLeaksIgnored occt_leaks;  // the first CAD file fills OpenCASCADE's registries
    return Fixture();
  }();
  serve::GeometryService& service = fixture.service;
  try {
    const serve::Json request = serve::parse_object(hotmesh::fuzz::as_text(data, size));
    if (request.contains("path")) {
      const hotmesh::fuzz::OcctLeaksIgnored occt_leaks;  // the file is read as a STEP or IGES file
      service.delete_model(service.load_path(request)["model"].get<std::string>());
    } else if (request.contains("points")) {
      service.project(fixture.curve, request);
    } else if (request.contains("grid")) {
      service.delete_surface(service.create_surface(request)["surface"].get<std::string>());
    } else if (request.contains("csv")) {
      service.delete_curve(service.create_curve(request)["curve"].get<std::string>());
    } else if (request.contains("mode")) {
      service.faces_mode(fixture.model, request);
    } else {
      service.delete_curve(service.meridional(fixture.model, request)["curve"].get<std::string>());
    }
  } catch (const serve::ApiError&) {
  } catch (const hotmesh::InputError&) {
  }
  hotmesh::fuzz::require_no_files_left(fixture.temporary);
  return 0;
}
