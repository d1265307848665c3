// SPDX-License-Identifier: BSD-3-Clause
// A picture of a lit volume straight from its RenderRGBA array: the
// fixed-point ray caster with dependent components (colour = RGB, an
// identity opacity ramp over one spacing on A), quarter-voxel samples, off
// the screen. Debian's VTK renders through X11 only: it needs a display
// (xvfb-run for none).
#pragma once

#include "vtkSmartPointer.h"

class vtkImageData;

namespace volrad {

struct SnapshotView
{
  int width = 400, height = 400;
  double elevation = 25.0, azimuth = 30.0, zoom = 1.4; ///< from the camera reset
};

/// The picture as RGB image data; throws std::runtime_error when the volume
/// has no RenderRGBA array or there is no display to render on.
vtkSmartPointer<vtkImageData> renderSnapshot(vtkImageData* lit, const SnapshotView& view = {});

} // namespace volrad
