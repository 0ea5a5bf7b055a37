// hotmesh geometry: FEM deflection samples (deflection_samples.hpp): how a sample is named in
// messages (node id, table line) and the names of the tables' coordinate frames.
#include "hotmesh/geometry/deflection_samples.hpp"

namespace hotmesh::geometry {

std::string sample_label(std::span<const std::int64_t> ids, std::span<const std::size_t> lines, std::size_t j) {
  const bool has_id = j < ids.size();
  const bool has_line = j < lines.size() && lines[j] > 0;
  if (has_id && has_line) return "node " + std::to_string(ids[j]) + " (line " + std::to_string(lines[j]) + ")";
  if (has_id) return "node " + std::to_string(ids[j]);
  if (has_line) return "line " + std::to_string(lines[j]);
  return "sample " + std::to_string(j + 1);
}

std::string DeflectionSamples::label(std::size_t j) const { return sample_label(ids, lines, j); }

const char* to_string(SampleFrame frame) {
  switch (frame) {
    case SampleFrame::planar: return "planar (x, y)";
    case SampleFrame::cartesian: return "cartesian (x, y, z)";
    case SampleFrame::meridional: return "meridional (r, z)";
  }
  return "?";
}

}  // namespace hotmesh::geometry
