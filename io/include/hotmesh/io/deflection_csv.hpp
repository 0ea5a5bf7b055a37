// hotmesh io: FEM deflection tables. CSV with a header line naming the columns, in any order:
//   x,y,dx,dy          2D cases                          (SampleFrame::planar)
//   x,y,z,dx,dy,dz     3D cases                          (SampleFrame::cartesian)
//   r,z,dr,dz          meridional, about the case's axis (SampleFrame::meridional)
// plus an optional "id" column (the FEM node number, used in messages). Lines starting with
// '#' (after blanks) and blank lines are skipped; a '#' after the values starts a comment.
// Windows line ends and a UTF-8 byte order mark are accepted; numbers are read with
// std::from_chars, independent of the locale. Format reference: docs/case-file.md.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "hotmesh/geometry/deflection_samples.hpp"

namespace hotmesh::io {

/// Parses a deflection table; `source` names it in messages. Throws hotmesh::InputError with
/// the line and column of the first problem (unknown or missing column, wrong field count,
/// a value that is not a finite number, negative r, no data rows).
geometry::DeflectionSamples parse_deflection_csv(std::string_view content, std::string_view source);

geometry::DeflectionSamples read_deflection_csv(const std::filesystem::path& path);

/// The table as CSV that parse_deflection_csv reads back to the same numbers: a header
/// (id first when the samples have ids) and one row per sample, each value the shortest text
/// that reads back to the same double.
std::string format_deflection_csv(const geometry::DeflectionSamples& samples);

}  // namespace hotmesh::io
