// hotmesh io: the thin layer over the CGNS library (see cgns_library.hpp).
#include "cgns_library.hpp"

#include <cstring>

#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::io::cgns {

namespace {
std::recursive_mutex library_mutex;
}  // namespace

File::File(const std::filesystem::path& path, int mode) : lock_(library_mutex), name_(path.string()) {
  if (mode == CG_MODE_WRITE) cg_set_file_type(CG_FILE_HDF5);
  if (mode == CG_MODE_READ || mode == CG_MODE_MODIFY) {
    require_input_file(path);
    int file_type = CG_FILE_NONE;
    if (cg_is_cgns(name_.c_str(), &file_type) != CG_OK) {
      throw InputError::in(name_, "not a CGNS file (neither HDF5 nor ADF, or no CGNSLibraryVersion node)");
    }
  }
  if (cg_open(name_.c_str(), mode, &fn_) != CG_OK) {
    fn_ = -1;
    throw InputError::in(name_, std::string("cannot open the CGNS file: ") + cg_get_error());
  }
}

File::~File() {
  if (fn_ >= 0) cg_close(fn_);
}

void File::close() {
  const int fn = fn_;
  fn_ = -1;
  if (cg_close(fn) != CG_OK) throw InputError::in(name_, std::string("cannot close the CGNS file: ") + cg_get_error());
}

void File::check(int status, std::string_view what) const {
  if (status == CG_OK) return;
  std::string message(what);
  message.append(": ").append(cg_get_error());
  throw InputError::in(name_, message);
}

std::string family_name_here() {
  Label family{};
  if (cg_famname_read(family) != CG_OK) return {};  // CG_NODE_NOT_FOUND: no family
  return family;
}

std::string bc_family(const File& file, int base, int zone, int bc) {
  if (cg_goto(file.fn(), base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end") != CG_OK) return {};
  return family_name_here();
}

}  // namespace hotmesh::io::cgns
