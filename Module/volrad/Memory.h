// SPDX-License-Identifier: BSD-3-Clause
/// @file Memory.h
/// @brief The machine's physical memory, for default memory budgets.
#pragma once

#include <cstddef>

namespace volrad {

/// Physical memory in bytes (8 GiB where the system does not say).
std::size_t physicalMemoryBytes();

} // namespace volrad
