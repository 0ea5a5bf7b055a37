// hotmesh geometry (internal): what a CadModel holds: the transferred OpenCASCADE shape and its
// faces in id order, next to their descriptions.
#pragma once

#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <filesystem>
#include <vector>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry {

struct CadModel::Impl {
  std::filesystem::path path;
  LengthUnit unit = LengthUnit::metre;
  TopoDS_Shape shape;
  std::vector<TopoDS_Face> faces;  // faces[id - 1]
  std::vector<FaceInfo> info;      // info[id - 1]
  // Every edge: those of the faces (sewn where they came apart), then those outside any face;
  // numbered from 1 (cad_model.hpp).
  TopTools_IndexedMapOfShape edges;
  std::vector<EdgeInfo> edge_info;  // edge_info[id - 1]
};

}  // namespace hotmesh::geometry
