// SPDX-License-Identifier: BSD-3-Clause
/// @file Progress.h
/// @brief Progress and interruption of long solves.
#pragma once

#include "volrad/Error.h"

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
