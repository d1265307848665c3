// SPDX-License-Identifier: BSD-3-Clause
#include "volrad/Memory.h"

#include <unistd.h>

namespace volrad {

std::size_t physicalMemoryBytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && size > 0) {
    return std::size_t(pages) * std::size_t(size);
  }
  return std::size_t(8) << 30;
}

} // namespace volrad
