// SPDX-License-Identifier: BSD-3-Clause
// Regression image in C++: a small cloud lit by the filter and
// volume-rendered straight from its RenderRGBA array
// (vtkFixedPointVolumeRayCastMapper, dependent components, an identity
// opacity ramp over one spacing), compared with Testing/Baseline/ by
// vtkImageDifference as VTK's regression tests do. Runs off-screen under
// xvfb-run (Debian's VTK renders through X11 only). With
// VOLRAD_UPDATE_BASELINES=1 in the environment it writes the baseline
// instead (look at it first).
#include "vtkVolumetricRadiosity.h"

#include "DensityImage.h"
#include "VolumeSnapshot.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

namespace {

/// Per channel difference that costs nothing, and the largest thresholded
/// error (in fully wrong pixels) a picture may have. A soft cloud changes
/// its pixels by little: turning the sun by 23 degrees changes none by more
/// than 30 of 255, and costs 50 pixels at 10 (a re-render: 0).
constexpr int kPixelThreshold = 10;
constexpr double kErrorLimit = 2.0;

void writePng(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> w;
  w->SetFileName(path.c_str());
  w->SetInputData(image);
  w->Write();
}

/// Two overlapping blobs of density (the active scalars), 16^3.
vtkSmartPointer<vtkImageData> blobs()
{
  return volrad::test::densityImage({ 16, 16, 16 }, 1.0 / 16, [](const double* x) {
    return std::max(volrad::test::blob(x, 0.35, 0.45, 0.45, 0.3),
                    volrad::test::blob(x, 0.65, 0.55, 0.55, 0.25));
  });
}

} // namespace

TEST(RenderingRegression, RenderRGBAOfALitCloud)
{
  // The cloud preset, a warm sun from the side and a blue sky above: the
  // picture shows the lit side, the shadow one blob casts on the other and
  // the bluish underside. The dense solver takes seconds here.
  vtkNew<vtkVolumetricRadiosity> radiosity;
  radiosity->SetInputData(blobs());
  radiosity->SetSceneJSON(R"({"version": 1, "channels": 3, "material": {"preset": "cloud"},
    "lights": [{"type": "directional", "direction": [1, 0.3, -0.4], "irradiance": [1, 0.9, 0.7]}],
    "boundary": {"zmax": {"type": "open", "radiance": [0.02, 0.04, 0.08]}},
    "solver": {"method": "dense"}})");
  radiosity->SetNumberOfThreads(1);
  radiosity->Update();
  vtkImageData* lit = radiosity->GetOutput();
  ASSERT_NE(lit->GetPointData()->GetArray("RenderRGBA"), nullptr);
  // volrad --png's picture, at 300 x 300.
  volrad::SnapshotView view;
  view.width = view.height = 300;
  const vtkSmartPointer<vtkImageData> picture = volrad::renderSnapshot(lit, view);

  const std::string baseline = VOLRAD_BASELINE_DIR "/cloud_rgba.png";
  const std::string out = VOLRAD_TEST_OUTPUT_DIR "/cloud_rgba.png";
  writePng(picture, out);
  const char* update = std::getenv("VOLRAD_UPDATE_BASELINES");
  if (update && std::string(update) == "1") {
    writePng(picture, baseline);
    GTEST_SKIP() << "wrote the baseline " << baseline;
  }
  ASSERT_TRUE(std::ifstream(baseline).good()) << "no baseline " << baseline;
  vtkNew<vtkPNGReader> valid;
  valid->SetFileName(baseline.c_str());
  valid->Update();
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(picture);
  diff->SetImageData(valid->GetOutput());
  diff->SetThreshold(kPixelThreshold);
  diff->Update();
  const double error = diff->GetThresholdedError();
  std::printf(
    "[measured] cloud RenderRGBA picture: thresholded error %.3f (limit %g)\n", error, kErrorLimit);
  if (error > kErrorLimit) {
    writePng(diff->GetOutput(), VOLRAD_TEST_OUTPUT_DIR "/cloud_rgba.diff.png");
  }
  EXPECT_LE(error, kErrorLimit) << "see " << VOLRAD_TEST_OUTPUT_DIR << "/cloud_rgba.diff.png";
}
