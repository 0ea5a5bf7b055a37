// hotmesh parallel: what the physics exchanges with the other processes of a job, and nothing
// of how. Items handed out to ranks (sliding nodes to project, cells to partition) go in
// contiguous, balanced shares of a list; a rank computes its share and gather_shares() gives
// every rank the whole list again. The solver is given a RankExchange: one_process() for a job
// of one process, where every call is trivial, or the job's exchange over MPI
// (hotmesh/parallel/processes.hpp).
#pragma once

#include <cstddef>
#include <span>
#include <type_traits>

namespace hotmesh::parallel {

struct Share {
  std::size_t begin = 0, end = 0;  ///< the items [begin, end) of a list
  bool contains(std::size_t k) const { return k >= begin && k < end; }
};
/// The share of `count` items of rank `rank` of `ranks`: counts differ by at most one.
Share share_of(std::size_t count, int rank, int ranks);

class RankExchange {
 public:
  virtual ~RankExchange() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  bool alone() const { return ranks() == 1; }
  /// This rank's share of a list of `count` items.
  Share my_share(std::size_t count) const { return share_of(count, rank(), ranks()); }

  /// Each rank has filled its share of `items`; after the call every rank holds every share,
  /// bit for bit as its rank wrote it.
  template <class Item>
  void gather_shares(std::span<Item> items) const {
    static_assert(std::is_trivially_copyable_v<Item>);
    if (!alone()) gather_share_bytes(std::as_writable_bytes(items), sizeof(Item));
  }
  /// Every rank's `values` replaced by their sum over the ranks.
  virtual void sum(std::span<double> values) const = 0;
  virtual double max(double value) const = 0;

 protected:
  /// gather_shares() of items of `item_size` bytes each.
  virtual void gather_share_bytes(std::span<std::byte> items, std::size_t item_size) const = 0;
};

/// The exchange of a job of one process: it has every share, and its sums and maxima are its own.
const RankExchange& one_process();

}  // namespace hotmesh::parallel
