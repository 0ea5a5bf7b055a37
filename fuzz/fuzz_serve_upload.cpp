// hotmesh fuzz: CAD uploads to `hotmesh serve` (POST /api/models, multipart/form-data), from
// the form's fields on: GeometryService::load_upload with the file's name, its content and
// the unit field. The input holds the three as the multipart parser hands them over:
//   <file name> '\n' <unit> '\n' <content>
// A request may fail only with ApiError (4xx) or hotmesh::InputError (422), and leaves no
// file behind in the service's upload folder. The model an upload makes is deleted again.
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "service/api_error.hpp"
#include "service/service.hpp"

namespace serve = hotmesh::app::serve;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path temporary = hotmesh::fuzz::use_private_temporary_folder();
  static serve::GeometryService service(std::nullopt, serve::ServiceLimits{});
  std::string_view rest = hotmesh::fuzz::as_text(data, size);
  const auto field = [&rest] {
    const auto end = std::min(rest.find('\n'), rest.size());
    const std::string_view value = rest.substr(0, end);
    rest.remove_prefix(std::min(end + 1, rest.size()));
    return value;
  };
  const std::string_view filename = field();
  const std::string_view unit = field();
  const hotmesh::fuzz::OcctLeaksIgnored occt_leaks;  // the upload is read as a STEP or IGES file
  try {
    service.delete_model(service.load_upload(filename, rest, unit)["model"].get<std::string>());
  } catch (const serve::ApiError&) {
  } catch (const hotmesh::InputError&) {
  }
  hotmesh::fuzz::require_no_files_left(temporary);
  return 0;
}
