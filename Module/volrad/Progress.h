// SPDX-License-Identifier: BSD-3-Clause
/// @file Progress.h
/// @brief Progress and interruption of long solves.
#pragma once

#include "volrad/Error.h"

#include <algorithm>
#include <cstdint>
#include <functional>

namespace volrad {

/// Called on the calling thread with the fraction done in [0, 1]; return
/// false to stop the solve (it then throws volrad::Aborted).
using ProgressCallback = std::function<bool(double fraction)>;

/// Reports a sub-range [begin, end] of the whole solve's progress.
class ProgressRange
{
public:
  /// Reports nowhere.
  ProgressRange()
    : ProgressRange(none(), 0.0, 1.0)
  {
  }
  ProgressRange(const ProgressCallback& cb, double begin, double end)
    : cb_(cb)
    , begin_(begin)
    , end_(end)
  {
  }
  /// Reports `fraction` of this range; throws Aborted when asked to stop.
  void report(double fraction) const
  {
    if (cb_ && !cb_(begin_ + (end_ - begin_) * fraction)) {
      throw Aborted();
    }
  }
  ProgressRange sub(double begin, double end) const
  {
    return ProgressRange(cb_, begin_ + (end_ - begin_) * begin, begin_ + (end_ - begin_) * end);
  }
  /// Calls body(begin, end) on consecutive blocks of [0, n), about `blocks`
  /// of them and none under `minBlock` items, reporting after each how far
  /// it got: a long (parallel) pass that a stop request interrupts between
  /// blocks.
  template<class Body>
  void forBlocks(std::int64_t n, std::int64_t minBlock, std::int64_t blocks, Body&& body) const
  {
    const std::int64_t size = std::max(minBlock, n / blocks);
    for (std::int64_t b0 = 0; b0 < n; b0 += size) {
      const std::int64_t b1 = std::min(n, b0 + size);
      body(b0, b1);
      report(double(b1) / double(n));
    }
  }

private:
  static const ProgressCallback& none()
  {
    static const ProgressCallback empty;
    return empty;
  }
  const ProgressCallback& cb_;
  double begin_, end_;
};

} // namespace volrad
