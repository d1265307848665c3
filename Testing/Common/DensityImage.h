// SPDX-License-Identifier: BSD-3-Clause
// Test volumes: image data whose active scalars, "density", are a function
// of the world position of each point.
#pragma once

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <array>

namespace volrad::test {

template<class F>
vtkSmartPointer<vtkImageData> densityImage(const std::array<int, 3>& dims, double spacing, F&& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) {
    double x[3];
    image->GetPoint(i, x);
    density->SetValue(i, static_cast<float>(f(x)));
  }
  image->GetPointData()->SetScalars(density);
  return image;
}

/// 1 at the centre (cx, cy, cz) falling to 0 at radius r.
inline double blob(const double x[3], double cx, double cy, double cz, double r)
{
  const double d2 =
    (x[0] - cx) * (x[0] - cx) + (x[1] - cy) * (x[1] - cy) + (x[2] - cz) * (x[2] - cz);
  return d2 < r * r ? 1.0 - d2 / (r * r) : 0.0;
}

} // namespace volrad::test
