#include "stereoscout/occupancy/scan_history.hpp"

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {

ScanHistory::ScanHistory(std::size_t capacity, std::size_t max_columns)
    : capacity_(capacity),
      max_columns_(max_columns),
      entries_(new Entry[capacity]()),
      points_(new ScanPoint[capacity * max_columns]()) {
  STEREOSCOUT_CHECK(capacity > 0, "scan history needs at least one slot");
}

void ScanHistory::record(std::uint32_t update_index, const core::DepthScan& scan) {
  if (counts_.recorded > 0 && update_index <= newest_) {
    ++counts_.out_of_order;
    return;
  }
  Entry& entry = entries_[update_index % capacity_];
  ScanPoint* points = points_.get() + (update_index % capacity_) * max_columns_;
  entry.update_index = update_index;
  entry.used = true;
  entry.origin_x = scan.origin_robot.x();
  entry.origin_y = scan.origin_robot.y();
  entry.count = 0;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind == core::DepthScanColumn::Kind::invalid) continue;
    if (entry.count == max_columns_) {
      ++counts_.columns_truncated;
      continue;
    }
    points[entry.count++] = ScanPoint::from_column(column);
  }
  newest_ = update_index;
  ++counts_.recorded;
}

ScanLookup ScanHistory::find(std::uint32_t update_index, ScanView& view) const {
  if (counts_.recorded == 0 || update_index > newest_) return ScanLookup::never_recorded;
  if (static_cast<std::size_t>(newest_ - update_index) >= capacity_) return ScanLookup::overwritten;
  const Entry& entry = entries_[update_index % capacity_];
  if (!entry.used || entry.update_index != update_index) return ScanLookup::never_recorded;
  view.origin_x_robot_m = entry.origin_x;
  view.origin_y_robot_m = entry.origin_y;
  view.points = points_.get() + (update_index % capacity_) * max_columns_;
  view.count = entry.count;
  return ScanLookup::found;
}

}  // namespace stereoscout::occupancy
