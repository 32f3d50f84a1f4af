#pragma once
// The depth scans of the last `capacity` observation updates, kept for roll-ups (paper V).
//
// A fixed ring keyed by update index: the scan of update u lives in slot u mod capacity and
// is overwritten by the scan of update u + capacity. Only valid columns are stored, in
// column order. Everything is allocated at start-up; record() never touches the heap.

#include <cstddef>
#include <cstdint>
#include <memory>

#include "stereoscout/core/messages.hpp"
#include "stereoscout/occupancy/occupancy_grid.hpp"

namespace stereoscout::occupancy {

enum class ScanLookup : std::uint8_t {
  found,
  overwritten,    // older than the ring reaches: the roll-up that needed it is incomplete
  never_recorded  // no scan was recorded for that update (nothing to insert)
};

struct ScanHistoryCounts {
  std::uint64_t recorded = 0;
  std::uint64_t columns_truncated = 0;  // valid columns beyond max_columns, dropped
  std::uint64_t out_of_order = 0;       // record() with an update index not after the newest, refused
};

class ScanHistory {
 public:
  ScanHistory(std::size_t capacity, std::size_t max_columns);

  ScanHistory(const ScanHistory&) = delete;
  ScanHistory& operator=(const ScanHistory&) = delete;

  // Stores the scan of `update_index` (strictly increasing from call to call).
  void record(std::uint32_t update_index, const core::DepthScan& scan);
  ScanLookup find(std::uint32_t update_index, ScanView& view) const;

  std::size_t capacity() const { return capacity_; }
  std::size_t max_columns() const { return max_columns_; }
  bool empty() const { return counts_.recorded == 0; }
  std::uint32_t newest_update_index() const { return newest_; }
  const ScanHistoryCounts& counts() const { return counts_; }

 private:
  struct Entry {
    std::uint32_t update_index = 0;
    bool used = false;
    double origin_x = 0.0;
    double origin_y = 0.0;
    std::size_t count = 0;
  };

  std::size_t capacity_;
  std::size_t max_columns_;
  std::unique_ptr<Entry[]> entries_;
  std::unique_ptr<ScanPoint[]> points_;
  std::uint32_t newest_ = 0;
  ScanHistoryCounts counts_;
};

}  // namespace stereoscout::occupancy
