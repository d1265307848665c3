// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the scene-file parser (docs/scene-format.md). Any text
// must either parse or be refused with volrad::Error; anything else (a crash,
// a sanitizer report, another exception, a parsed scene that fails its own
// checks) is a finding.
#include "volrad/Error.h"
#include "volrad/SceneDescription.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const volrad::SceneDescription d = volrad::parseSceneDescription(text);
    // What the parser accepts, it has checked.
    if ((d.channels != 1 && d.channels != 3) || !(d.solver.epsilon > 0.0) ||
        !std::isfinite(d.solver.epsilon)) {
      std::abort();
    }
  } catch (const volrad::Error&) {
    // Refused with a message: the expected answer to bad text.
  }
  return 0;
}
