// hotmesh io: reading, validating and writing mesh files chosen by extension.
#include "hotmesh/io/mesh_files.hpp"

#include <algorithm>
#include <cctype>

#include <spdlog/spdlog.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace hotmesh::io {

MeshFormat mesh_format(const std::filesystem::path& path) {
  if (is_foam_path(path)) return MeshFormat::foam;
  const std::string ext = ascii_lower(path.extension().string());
  if (ext == ".msh") return MeshFormat::gmsh;
  if (ext == ".vtu") return MeshFormat::vtu;
  if (ext == ".cgns" || ext == ".hdf" || ext == ".adf") return MeshFormat::cgns;
  throw InputError::in(path.string(), "unknown mesh format '" + ext +
                                          "': hotmesh reads Gmsh .msh and CGNS .cgns files and OpenFOAM polyMesh "
                                          "folders, and writes .msh, .cgns, .vtu and polyMesh folders");
}

LoadedMesh read_mesh(const std::filesystem::path& path) {
  LoadedMesh loaded;
  switch (mesh_format(path)) {
    case MeshFormat::gmsh: loaded.mesh = read_gmsh(path); break;
    case MeshFormat::cgns: {
      CgnsMesh cgns = read_cgns(path);
      loaded.mesh = std::move(cgns.mesh);
      loaded.write_back = std::move(cgns.write_back);
      break;
    }
    case MeshFormat::foam: {
      FoamMesh foam = read_foam(path);
      loaded.mesh = std::move(foam.mesh);
      loaded.write_back = std::move(foam.write_back);
      loaded.layer = foam.layer;
      break;
    }
    case MeshFormat::vtu: throw InputError::in(path.string(), "hotmesh writes .vtu files but does not read them");
  }
  try {
    loaded.validation = mesh::validate_mesh(loaded.mesh);
  } catch (const InputError& e) {
    throw InputError::in(path.string(), e.what());
  }
  for (const auto& note : loaded.validation.notes) spdlog::warn("{}: {}", path.string(), note);
  return loaded;
}

std::vector<std::filesystem::path> mesh_input_files(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return {path};
  // The polyMesh folder's files: those read and those the write-back copies.
  const fs::path folder = foam_mesh_folder(path);
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (e.is_regular_file(ec)) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void write_mesh(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                const VtuFields& fields) {
  switch (mesh_format(path)) {
    case MeshFormat::gmsh: {
      if (points.data() == mesh.points.data()) {
        write_gmsh(path, mesh);
      } else {
        mesh::Mesh moved = mesh;
        moved.points.assign(points.begin(), points.end());
        write_gmsh(path, moved);
      }
      return;
    }
    case MeshFormat::vtu: write_vtu(path, mesh, points, fields); return;
    case MeshFormat::cgns: write_cgns(path, mesh, points); return;
    case MeshFormat::foam: write_foam(path, mesh, points); return;
  }
}

}  // namespace hotmesh::io
