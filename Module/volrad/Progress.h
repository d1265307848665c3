// SPDX-License-Identifier: BSD-3-Clause
/// @file Progress.h
/// @brief Progress and interruption of long solves.
#pragma once

#include "volrad/Error.h"

#include <algorithm>
#include <chrono>
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
  /// Calls body(begin, end) on consecutive blocks of [0, n), reporting
  /// after each how far it got: a long (parallel) pass that a stop request
  /// interrupts between blocks. Blocks are sized to take about 0.1 s each,
  /// whatever an item costs, from `firstBlock` items up to `maxBlock` (the
  /// items after a run of cheap ones may be dear: maxBlock of the dearest
  /// should take a fraction of a second).
  template<class Body>
  void forBlocks(std::int64_t n, std::int64_t firstBlock, std::int64_t maxBlock, Body&& body) const
  {
    using Clock = std::chrono::steady_clock;
    constexpr double kBlockSeconds = 0.1;
    double size = double(std::max<std::int64_t>(1, firstBlock));
    for (std::int64_t b0 = 0; b0 < n;) {
      const std::int64_t b1 = std::min(n, b0 + std::int64_t(size));
      const Clock::time_point start = Clock::now();
      body(b0, b1);
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      report(double(b1) / double(n));
      // The next block: as long as this one would have needed to take
      // kBlockSeconds, growing at most 4x at a time.
      size = std::clamp(size * kBlockSeconds / std::max(seconds, 1e-9), 1.0, 4.0 * size);
      size = std::min(size, double(std::max<std::int64_t>(1, maxBlock)));
      b0 = b1;
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
