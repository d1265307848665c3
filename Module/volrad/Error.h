// SPDX-License-Identifier: BSD-3-Clause
/// @file Error.h
/// @brief Exceptions of the core. Library code never exits the process: it
/// throws, and the filter or the command turns the message into an error.
#pragma once

#include <stdexcept>
#include <string>

namespace volrad {

/// Bad input or a request the core refuses (the message says which value).
class Error : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The progress callback asked the solve to stop.
class Aborted : public Error
{
public:
  Aborted()
    : Error("the solve was aborted")
  {
  }
};

} // namespace volrad
