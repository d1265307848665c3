// SPDX-License-Identifier: BSD-3-Clause
// The filter tests' view of a result: its IncidentRadiation values.
#pragma once

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <vector>

namespace volrad::test {

/// All IncidentRadiation values of an output (empty when it has none).
inline std::vector<float> incidentRadiation(vtkImageData* output)
{
  std::vector<float> g;
  if (auto* a =
        vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("IncidentRadiation"))) {
    g.assign(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfValues());
  }
  return g;
}

} // namespace volrad::test
