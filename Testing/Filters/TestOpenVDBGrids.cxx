// SPDX-License-Identifier: BSD-3-Clause
// vtkOpenVDBGridReader and vtkOpenVDBGridWriter (issue 6): a .vdb grid as
// vtkImageData with its values, voxel size and placement, the grid chosen by
// name; point arrays written back as grids that read back the same; clear
// errors.
#include "vtkOpenVDBGridReader.h"
#include "vtkOpenVDBGridWriter.h"

#include "CollectErrors.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include "volrad/VdbVolume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <string>

using volrad::test::updateCollectingErrors;

namespace {

const std::string kOut = VOLRAD_TEST_OUTPUT_DIR;

/// A box of `components` values with a known pattern, nothing zero (the
/// writer leaves zeros inactive, which would shrink the active box).
volrad::DenseVolume pattern(const std::string& name, int components)
{
  volrad::DenseVolume v;
  v.name = name;
  v.dims = { 5, 4, 3 };
  v.spacing = volrad::Vec3(0.5, 0.5, 0.5);
  v.origin = volrad::Vec3(-1.0, 2.25, 0.75);
  v.components = components;
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 5; ++i) {
        for (int c = 0; c < components; ++c) {
          v.values.push_back(float(1 + i + 10 * j + 100 * k + 1000 * c));
        }
      }
    }
  }
  return v;
}

bool skipWithoutVdb()
{
  return !volrad::vdbSupported();
}

} // namespace

TEST(OpenVDBGridReader, ReadsAGridWithItsValuesVoxelSizeAndPlacement)
{
  if (skipWithoutVdb()) {
    GTEST_SKIP() << "VolRad was built without OpenVDB";
  }
  const std::string path = kOut + "/reader-pattern.vdb";
  const volrad::DenseVolume density = pattern("density", 1), velocity = pattern("velocity", 3);
  volrad::writeVdbGrids(path, { density, velocity });
  EXPECT_TRUE(vtkOpenVDBGridReader::CanReadFile(path.c_str()));

  for (const volrad::DenseVolume* expected : { &density, &velocity }) {
    vtkNew<vtkOpenVDBGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetGridName(expected->name.c_str());
    EXPECT_EQ(updateCollectingErrors(reader), "");
    vtkImageData* image = reader->GetOutput();
    int dims[3];
    image->GetDimensions(dims);
    double spacing[3], origin[3];
    image->GetSpacing(spacing);
    image->GetOrigin(origin);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(dims[a], expected->dims[a]);
      EXPECT_DOUBLE_EQ(spacing[a], expected->spacing[a]);
      EXPECT_NEAR(origin[a], expected->origin[a], 1e-12);
    }
    vtkDataArray* values = image->GetPointData()->GetScalars();
    ASSERT_NE(values, nullptr);
    EXPECT_EQ(std::string(values->GetName()), expected->name);
    ASSERT_EQ(values->GetNumberOfComponents(), expected->components);
    ASSERT_EQ(values->GetNumberOfTuples(), image->GetNumberOfPoints());
    for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p) {
      for (int c = 0; c < expected->components; ++c) {
        ASSERT_EQ(values->GetComponent(p, c),
                  expected->values[std::size_t(p) * expected->components + c]);
      }
    }
    // The point at the first voxel's centre is the first value.
    double first[3] = { expected->origin[0], expected->origin[1], expected->origin[2] };
    EXPECT_EQ(image->FindPoint(first), 0);
  }

  // No grid named: the first one.
  vtkNew<vtkOpenVDBGridReader> first;
  first->SetFileName(path.c_str());
  EXPECT_EQ(updateCollectingErrors(first), "");
  EXPECT_EQ(std::string(first->GetOutput()->GetPointData()->GetScalars()->GetName()), "density");
}

TEST(OpenVDBGridReader, ReportsAbsentGridsFilesAndLimitsWithAnEmptyOutput)
{
  if (skipWithoutVdb()) {
    GTEST_SKIP() << "VolRad was built without OpenVDB";
  }
  const std::string path = kOut + "/reader-errors.vdb";
  volrad::writeVdbGrids(path, { pattern("density", 1) });
  const std::string garbage = kOut + "/reader-garbage.vdb";
  std::ofstream(garbage) << "not a vdb file";
  EXPECT_FALSE(vtkOpenVDBGridReader::CanReadFile(garbage.c_str()));

  struct Case
  {
    std::string file, grid;
    vtkTypeInt64 maxVoxels;
    std::string expected;
  };
  for (const Case& c : { Case{ path, "temperature", 1 << 20, "its grids: density" },
                         Case{ kOut + "/absent.vdb", "", 1 << 20, "cannot read the file" },
                         Case{ garbage, "", 1 << 20, "not a readable OpenVDB file" },
                         Case{ path, "density", 10, "over the limit of 10 voxels" },
                         Case{ "", "", 1 << 20, "no file name" } }) {
    vtkNew<vtkOpenVDBGridReader> reader;
    reader->SetFileName(c.file.c_str());
    reader->SetGridName(c.grid.c_str());
    reader->SetMaximumVoxels(c.maxVoxels);
    const std::string errors = updateCollectingErrors(reader);
    EXPECT_NE(errors.find(c.expected), std::string::npos) << c.file << ": " << errors;
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0) << c.file;
  }

  // One reader: a good grid, then an absent one (no trace of the first
  // left in the output), then the good one again.
  vtkNew<vtkOpenVDBGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetGridName("density");
  EXPECT_EQ(updateCollectingErrors(reader), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 5 * 4 * 3);
  reader->SetGridName("temperature");
  EXPECT_NE(updateCollectingErrors(reader), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetScalars(), nullptr);
  reader->SetGridName("density");
  EXPECT_EQ(updateCollectingErrors(reader), "");
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 5 * 4 * 3);
}

TEST(OpenVDBGridWriter, ImagesRoundTripThroughTheWriterAndTheReader)
{
  if (skipWithoutVdb()) {
    GTEST_SKIP() << "VolRad was built without OpenVDB";
  }
  // An image with a shifted extent (the origin is not the first point),
  // a scalar array, a vector array and one the writer is told to leave out.
  vtkNew<vtkImageData> image;
  image->SetExtent(2, 7, -1, 3, 0, 4);
  image->SetSpacing(0.25, 0.25, 0.25);
  image->SetOrigin(1.0, -0.5, 2.0);
  vtkNew<vtkDoubleArray> g;
  g->SetName("IncidentRadiation");
  vtkNew<vtkFloatArray> rgb;
  rgb->SetName("Colour");
  rgb->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> skipped;
  skipped->SetName("Skipped");
  for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p) {
    g->InsertNextValue(p % 7 == 0 ? 0.0 : 0.5 + p); // some background voxels
    rgb->InsertNextTuple3(p + 1.0, 2.0 * p + 1.0, 3.0);
    skipped->InsertNextValue(1.0);
  }
  image->GetPointData()->AddArray(g);
  image->GetPointData()->AddArray(rgb);
  image->GetPointData()->AddArray(skipped);

  const std::string path = kOut + "/writer-roundtrip.vdb";
  vtkNew<vtkOpenVDBGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  writer->AddArrayName("IncidentRadiation");
  writer->AddArrayName("Colour");
  ASSERT_EQ(writer->Write(), 1);

  std::set<std::string> names;
  for (const auto& grid : volrad::listVdbGrids(path)) {
    names.insert(grid.first);
  }
  EXPECT_EQ(names, (std::set<std::string>{ "IncidentRadiation", "Colour" }));

  for (vtkDataArray* original :
       { static_cast<vtkDataArray*>(g), static_cast<vtkDataArray*>(rgb) }) {
    vtkNew<vtkOpenVDBGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetGridName(original->GetName());
    EXPECT_EQ(updateCollectingErrors(reader), "");
    vtkImageData* back = reader->GetOutput();
    // The reader gives the active box: here every point but background
    // corners could be inactive, so compare point by point in world space.
    vtkDataArray* values = back->GetPointData()->GetScalars();
    ASSERT_NE(values, nullptr);
    EXPECT_EQ(values->GetNumberOfComponents(), original->GetNumberOfComponents());
    double spacing[3];
    back->GetSpacing(spacing);
    for (int a = 0; a < 3; ++a) {
      EXPECT_DOUBLE_EQ(spacing[a], 0.25);
    }
    int compared = 0;
    for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p) {
      double x[3];
      image->GetPoint(p, x);
      int ijk[3];
      double pcoords[3];
      const bool inside = back->ComputeStructuredCoordinates(x, ijk, pcoords) == 1;
      const vtkIdType q = inside ? back->FindPoint(x) : -1;
      for (int c = 0; c < original->GetNumberOfComponents(); ++c) {
        const double expected = float(original->GetComponent(p, c));
        if (q >= 0) {
          ASSERT_EQ(values->GetComponent(q, c), expected) << original->GetName() << " " << p;
          ++compared;
        } else {
          ASSERT_EQ(expected, 0.0) << "an active voxel outside the box read back";
        }
      }
    }
    EXPECT_GT(compared, 0);
  }

  // Without names, every point array with 1 or 3 components.
  vtkNew<vtkOpenVDBGridWriter> all;
  const std::string allPath = kOut + "/writer-all.vdb";
  all->SetFileName(allPath.c_str());
  all->SetInputData(image);
  ASSERT_EQ(all->Write(), 1);
  EXPECT_EQ(volrad::listVdbGrids(allPath).size(), 3u);
}

TEST(OpenVDBGridWriter, ReportsAbsentArraysAndUnwritablePathsWithoutAFile)
{
  if (skipWithoutVdb()) {
    GTEST_SKIP() << "VolRad was built without OpenVDB";
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(3, 3, 3);
  vtkNew<vtkFloatArray> a;
  a->SetName("G");
  a->SetNumberOfTuples(27);
  a->Fill(1.0);
  image->GetPointData()->AddArray(a);
  struct Case
  {
    std::string path, array, expected;
  };
  vtkNew<vtkImageData> rotated;
  rotated->DeepCopy(image);
  rotated->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  for (const Case& c :
       { Case{ kOut + "/writer-absent.vdb", "Missing", "no numeric point array 'Missing'" },
         Case{ "/nonexistent-dir/out.vdb", "G", "cannot write '/nonexistent-dir/out.vdb'" },
         Case{ kOut + "/writer-rotated.vdb", "G", "rotated" } }) {
    vtkNew<vtkOpenVDBGridWriter> writer;
    writer->SetFileName(c.path.c_str());
    writer->SetInputData(c.expected == "rotated" ? rotated.Get() : image.Get());
    writer->AddArrayName(c.array.c_str());
    volrad::test::MessageCollector errors;
    errors.observe(writer);
    writer->Write();
    EXPECT_NE(errors.text.find(c.expected), std::string::npos) << errors.text;
    EXPECT_NE(writer->GetErrorCode(), 0);
    EXPECT_FALSE(std::ifstream(c.path)) << c.path;
    EXPECT_FALSE(std::ifstream(c.path + ".partial.vdb")) << c.path;
  }
}

TEST(OpenVDBGridWriter, AnArrayOfBackgroundOnlyIsAWarning)
{
  if (skipWithoutVdb()) {
    GTEST_SKIP() << "VolRad was built without OpenVDB";
  }
  vtkNew<vtkImageData> image;
  image->SetDimensions(3, 3, 3);
  vtkNew<vtkFloatArray> a;
  a->SetName("AbsorbedPower");
  a->SetNumberOfTuples(27);
  a->Fill(0.0);
  image->GetPointData()->AddArray(a);
  const std::string path = kOut + "/writer-background.vdb";
  vtkNew<vtkOpenVDBGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  volrad::test::MessageCollector warnings;
  warnings.observe(writer, vtkCommand::WarningEvent);
  EXPECT_EQ(writer->Write(), 1);
  EXPECT_NE(warnings.text.find("'AbsorbedPower' holds only the background"), std::string::npos)
    << warnings.text;
}
