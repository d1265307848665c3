// SPDX-License-Identifier: BSD-3-Clause
// OpenVDB files: a volume written as grids reads back with its values,
// voxel size and placement; absent grids, limits and bad files are named;
// the smoke sample's geometry as published.
#include "volrad/Error.h"
#include "volrad/VdbVolume.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

using namespace volrad;

namespace {

DenseVolume sample(const std::string& name, int components)
{
  DenseVolume v;
  v.name = name;
  v.dims = { 5, 4, 3 };
  v.indexLower = { -2, 7, 1 };
  v.spacing = Vec3(0.5, 0.5, 0.5);
  v.origin = Vec3(-1.0, 3.5, 0.5); // index (-2, 7, 1) at 0.5 spacing, no translation
  v.components = components;
  v.values.resize(std::size_t(5 * 4 * 3 * components));
  for (std::size_t i = 0; i < v.values.size(); ++i) {
    v.values[i] = (i % 7 == 0) ? 0.f : float(i) * 0.25f;
  }
  return v;
}

// One file per test: ctest runs them in parallel.
const std::string kFile = std::string(VOLRAD_TEST_TMP_DIR) + "/roundtrip.vdb";
const std::string kErrorsFile = std::string(VOLRAD_TEST_TMP_DIR) + "/errors.vdb";

} // namespace

TEST(VdbVolume, WrittenGridsReadBack)
{
  if (!vdbSupported()) {
    GTEST_SKIP() << "built without OpenVDB";
  }
  const DenseVolume g = sample("IncidentRadiation", 1), c = sample("RenderColour", 3);
  writeVdbGrids(kFile, { g, c });
  const auto names = listVdbGrids(kFile);
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0].first, "IncidentRadiation");
  EXPECT_EQ(names[0].second, "float");
  EXPECT_EQ(names[1].second, "vec3s");
  for (const DenseVolume* v : { &g, &c }) {
    const DenseVolume r = readVdbGrid(kFile, v->name);
    // The active box: voxels equal to the background (0) at its edges are
    // inactive, so compare where the box says, value by value.
    EXPECT_EQ(r.components, v->components);
    EXPECT_NEAR((r.spacing - v->spacing).norm(), 0.0, 1e-12);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(r.indexLower[a], v->indexLower[a]);
      EXPECT_LE(r.indexLower[a] + r.dims[a], v->indexLower[a] + v->dims[a]);
      EXPECT_NEAR(
        r.origin[a], v->origin[a] + (r.indexLower[a] - v->indexLower[a]) * v->spacing[a], 1e-12);
    }
    for (int z = 0; z < r.dims[2]; ++z) {
      for (int y = 0; y < r.dims[1]; ++y) {
        for (int x = 0; x < r.dims[0]; ++x) {
          const int X = x + r.indexLower[0] - v->indexLower[0],
                    Y = y + r.indexLower[1] - v->indexLower[1],
                    Z = z + r.indexLower[2] - v->indexLower[2];
          for (int k = 0; k < v->components; ++k) {
            const std::size_t i =
              (std::size_t(x) + r.dims[0] * (y + std::size_t(r.dims[1]) * z)) * v->components + k;
            const std::size_t j =
              (std::size_t(X) + v->dims[0] * (Y + std::size_t(v->dims[1]) * Z)) * v->components + k;
            EXPECT_EQ(r.values[i], v->values[j]);
          }
        }
      }
    }
  }
}

TEST(VdbVolume, ProblemsAreNamed)
{
  if (!vdbSupported()) {
    GTEST_SKIP() << "built without OpenVDB";
  }
  writeVdbGrids(kErrorsFile, { sample("density", 1) });
  auto message = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { readVdbGrid(kErrorsFile, "temperature"); }).find("its grids: density"),
            std::string::npos);
  EXPECT_NE(message([] { readVdbGrid(kErrorsFile, "density", 10); }).find("over the limit of 10"),
            std::string::npos);
  EXPECT_NE(message([] { readVdbGrid("/nonexistent/x.vdb"); }).find("cannot read"),
            std::string::npos);
  const std::string junk = std::string(VOLRAD_TEST_TMP_DIR) + "/junk.vdb";
  std::ofstream(junk) << "not a vdb file";
  EXPECT_NE(message([&] { readVdbGrid(junk); }).find("not a readable OpenVDB file"),
            std::string::npos);
}

TEST(VdbVolume, TheSmokeSampleAsPublished)
{
  const std::string smoke = VOLRAD_SHARED_DATA_DIR "/smoke/smoke.vdb";
  if (!vdbSupported() || !std::ifstream(smoke)) {
    GTEST_SKIP() << "no OpenVDB or no " << smoke;
  }
  const DenseVolume d = readVdbGrid(smoke, "density");
  // ../shared/data/README.md: active box [1,2,1] -> [111,223,112], voxel 0.476.
  EXPECT_EQ(d.indexLower[0], 1);
  EXPECT_EQ(d.indexLower[1], 2);
  EXPECT_EQ(d.indexLower[2], 1);
  EXPECT_EQ(d.dims[0], 111);
  EXPECT_EQ(d.dims[1], 222);
  EXPECT_EQ(d.dims[2], 112);
  EXPECT_NEAR(d.spacing[0], 0.47619, 1e-4);
  std::size_t active = 0;
  for (float v : d.values) {
    active += v != 0.f ? 1 : 0;
  }
  std::printf("[measured] smoke.vdb density: %zu non-zero voxels of %zu in its active box\n",
              active,
              d.values.size());
  EXPECT_GT(active, 500000u);
}
