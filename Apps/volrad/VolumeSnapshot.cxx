// SPDX-License-Identifier: BSD-3-Clause
#include "VolumeSnapshot.h"

#include "vtkCamera.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkMultiThreader.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkThreadedImageAlgorithm.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <cstdlib>
#include <stdexcept>

namespace volrad {

vtkSmartPointer<vtkImageData> renderSnapshot(vtkImageData* lit, const SnapshotView& view)
{
  if (!lit || !lit->GetPointData()->GetArray("RenderRGBA")) {
    throw std::runtime_error("the volume has no RenderRGBA array to render");
  }
  // Without a display VTK's X11 window aborts the process: say so instead.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    throw std::runtime_error("rendering needs an X display: run under xvfb-run -a");
  }
  // A copy whose active scalars are the colours (the caller's are kept).
  vtkNew<vtkImageData> image;
  image->ShallowCopy(lit);
  image->GetPointData()->SetActiveScalars("RenderRGBA");

  // VTK 9.1's space leaping for dependent components reads the wrong voxels
  // in every piece of the volume but the first (it steps one component per
  // voxel, not four), and the caster then skips blocks that hold matter. One
  // piece avoids it: the mapper is made while imaging filters default to one
  // thread without SMP (its space-leaping filter keeps that); the rays still
  // use every core.
  const bool smp = vtkThreadedImageAlgorithm::GetGlobalDefaultEnableSMP();
  const int threads = vtkMultiThreader::GetGlobalDefaultNumberOfThreads();
  vtkThreadedImageAlgorithm::SetGlobalDefaultEnableSMP(false);
  vtkMultiThreader::SetGlobalDefaultNumberOfThreads(1);
  vtkNew<vtkFixedPointVolumeRayCastMapper> mapper;
  vtkThreadedImageAlgorithm::SetGlobalDefaultEnableSMP(smp);
  vtkMultiThreader::SetGlobalDefaultNumberOfThreads(threads);
  mapper->SetNumberOfThreads(threads);
  mapper->SetInputData(image);
  double spacing[3];
  image->GetSpacing(spacing);
  const double h = (spacing[0] + spacing[1] + spacing[2]) / 3.0;
  // Quarter-voxel samples (the default is one world unit, whatever the voxels).
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetSampleDistance(0.25 * h);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(255, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->IndependentComponentsOff();
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(h); // A is the opacity of one spacing
  property->SetInterpolationTypeToLinear();
  property->ShadeOff(); // the colour is the light
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.12);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(view.elevation);
  renderer->GetActiveCamera()->Azimuth(view.azimuth);
  renderer->GetActiveCamera()->Zoom(view.zoom);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(view.width, view.height);
  window->AddRenderer(renderer);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  vtkSmartPointer<vtkImageData> picture = vtkSmartPointer<vtkImageData>::New();
  picture->DeepCopy(grab->GetOutput());
  return picture;
}

} // namespace volrad
