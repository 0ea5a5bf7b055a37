// hotmesh serve (internal): what the geometry service keeps between requests: loaded CAD
// models, built curves and surfaces, each in a store that hands out shared pointers under a
// short lock and drops the least recently used item when full; the root folder and the private
// upload folder; the limits. Also the readers of request fields that several routes share.
#pragma once

#include <cstdint>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/setup/curve_fit.hpp"
#include "hotmesh/setup/face_fit.hpp"
#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/geometry/deformed_face.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "service/api_error.hpp"
#include "service/private_folder.hpp"
#include "service/root_folder.hpp"
#include "service/service.hpp"

namespace hotmesh::app::serve {

struct StoredModel {
  std::string id;
  std::string name;    ///< the file name the client gave (upload) or its path below the root
  std::string source;  ///< "upload" or "root"
  geometry::CadModel cad;
  Json faces;          ///< faces_json(cad), made once
  Json edges;          ///< edges_json(cad), made once
  std::mutex mutex;    ///< a CadModel is for one thread at a time
};

/// A curve clients built: a meridional curve of CAD faces, or a deflected curve reconstructed
/// through FEM nodes. Immutable once stored.
struct StoredCurve {
  std::string id;
  bool deflected = false;
  setup::CurveRun run;
  std::unique_ptr<geometry::CurveProjector> projector;  ///< for points in the curve's plane
  std::unique_ptr<geometry::BoundaryShape> shape;       ///< for points in space
  std::string body;  ///< the answer to GET /api/curves/{id}, JSON text
  std::string frame; ///< "rz" or "xy"
};

/// Deflection fields d(t, s) clients reconstructed on CAD faces, with the deformed faces S + d
/// for download. Immutable once stored.
struct StoredSurface {
  std::string id;
  setup::SurfaceRun run;
  std::vector<geometry::DeformedFace> deformed;  ///< in the order of run.faces
  std::string body;  ///< the answer to GET /api/surfaces/{id}, JSON text
};

/// Items by id ("m1", "m2", ... with prefix "m"), at most `capacity` of them and `budget`
/// bytes (as the inserter reckons them); inserting into a full store drops the items used
/// least recently.
template <class T>
class Store {
 public:
  Store(char prefix, std::size_t capacity, std::size_t budget = SIZE_MAX)
      : prefix_(prefix), capacity_(capacity), budget_(budget) {}

  /// A fresh id for an item about to be inserted.
  std::string next_id() {
    std::lock_guard lock(mutex_);
    return fmt::format("{}{}", prefix_, ++issued_);
  }

  void insert(std::shared_ptr<T> item, const std::string& id, std::size_t bytes = 0) {
    std::lock_guard lock(mutex_);
    while (!items_.empty() && (items_.size() >= capacity_ || bytes_ + bytes > budget_)) {
      auto oldest = items_.begin();
      for (auto it = items_.begin(); it != items_.end(); ++it) {
        if (it->second.last_used < oldest->second.last_used) oldest = it;
      }
      bytes_ -= oldest->second.bytes;
      items_.erase(oldest);
    }
    items_[id] = {std::move(item), ++clock_, bytes};
    bytes_ += bytes;
  }

  /// The item, or ApiError 404 saying what `kind` was not found.
  std::shared_ptr<T> get(std::string_view id, const char* kind) {
    std::lock_guard lock(mutex_);
    const auto it = items_.find(id);
    if (it == items_.end()) {
      throw ApiError::not_found(fmt::format("no {} '{}' (never made, deleted, or dropped as the least recently used "
                                            "of {})",
                                            kind, id, capacity_));
    }
    it->second.last_used = ++clock_;
    return it->second.item;
  }

  void erase(std::string_view id, const char* kind) {
    std::lock_guard lock(mutex_);
    const auto it = items_.find(id);
    if (it == items_.end()) throw ApiError::not_found(fmt::format("no {} '{}'", kind, id));
    bytes_ -= it->second.bytes;
    items_.erase(it);
  }

  /// How many items are kept, and their bytes as the inserters reckoned them.
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  std::size_t bytes() const {
    std::lock_guard lock(mutex_);
    return bytes_;
  }

  std::vector<std::shared_ptr<T>> all() const {
    std::lock_guard lock(mutex_);
    std::vector<std::shared_ptr<T>> list;
    for (const auto& [id, entry] : items_) list.push_back(entry.item);
    return list;
  }

 private:
  struct Entry {
    std::shared_ptr<T> item;
    std::uint64_t last_used = 0;
    std::size_t bytes = 0;
  };
  mutable std::mutex mutex_;
  std::map<std::string, Entry, std::less<>> items_;
  char prefix_;
  std::size_t capacity_;
  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::uint64_t issued_ = 0;
  std::uint64_t clock_ = 0;
};

struct GeometryService::State {
  State(const std::optional<std::filesystem::path>& root_path, ServiceLimits service_limits)
      : limits(service_limits),
        models('m', service_limits.max_models),
        curves('c', service_limits.max_curves, service_limits.max_curve_bytes),
        surfaces('s', service_limits.max_surfaces, service_limits.max_surface_bytes) {
    if (root_path) root.emplace(*root_path);
  }

  ServiceLimits limits;
  std::optional<RootFolder> root;
  PrivateFolder uploads;
  Store<StoredModel> models;
  Store<const StoredCurve> curves;
  Store<const StoredSurface> surfaces;
};

/// The face ids of request[key] (face_list_field), each checked to be a face of `model`.
std::vector<int> model_faces_field(const Json& request, const char* key, const StoredModel& model, std::size_t max_faces);
/// The edge ids of request[key], each checked to be an edge of `model` (2D walls).
std::vector<int> model_edges_field(const Json& request, const char* key, const StoredModel& model, std::size_t max_edges);

/// The FEM table of a request: "csv", CSV text as in a deflection file, named "csv_name"; at
/// most limits.max_nodes nodes.
geometry::DeflectionSamples table_field(const Json& request, const ServiceLimits& limits);

/// "degree", "form", "tolerance" and "drop_far_nodes" as the reconstruction's options.
geometry::ReconstructionOptions reconstruction_field(const Json& request);

/// `text` with every occurrence of `from` replaced by `to` (a private copy's path by the name
/// the client knows the file by).
std::string replaced(std::string text, const std::string& from, const std::string& to);

/// Stores a curve made of `run` and returns the answer about it (see curve_json.hpp).
Json store_curve(GeometryService::State& state, setup::CurveRun run, bool deflected, std::size_t samples, Json extra);

}  // namespace hotmesh::app::serve
