// SPDX-License-Identifier: BSD-3-Clause
// The bad-input table (README "Bad input: what volrad says"), run through the
// volrad command: every case exits non-zero with one line that names the
// problem and leaves no output file; the cases that are warnings solve, say
// so, and write their output.
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkXMLImageDataWriter.h"

#include "VolradCommand.h"
#include "volrad/VdbVolume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kOut = VOLRAD_TEST_OUTPUT_DIR;

/// A file of this test's own: ctest runs this file's tests in parallel, and a
/// shared name let one test rewrite a volume another was reading.
std::string testFile(const std::string& name, const char* extension)
{
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  return kOut + "/bad-" + (test ? test->name() : "none") + "-" + name + extension;
}

struct Array
{
  std::string name;
  int components;
  std::function<std::string(int)> value; ///< of point i (text, so "nan" can be written)
};

/// A legacy-format volume (human-readable, any spacing, NaN as text).
std::string legacyVolume(const std::string& name,
                         std::array<int, 3> dims,
                         std::array<double, 3> spacing,
                         const std::vector<Array>& arrays)
{
  const std::string path = testFile(name, ".vtk");
  std::ofstream f(path);
  f << "# vtk DataFile Version 3.0\n" << name << "\nASCII\nDATASET STRUCTURED_POINTS\n"
    << "DIMENSIONS " << dims[0] << " " << dims[1] << " " << dims[2] << "\nSPACING " << spacing[0]
    << " " << spacing[1] << " " << spacing[2] << "\nORIGIN 0 0 0\n";
  const int n = dims[0] * dims[1] * dims[2];
  if (n > 0) {
    f << "POINT_DATA " << n << "\n";
  }
  for (const Array& a : arrays) {
    f << "SCALARS " << a.name << " float " << a.components << "\nLOOKUP_TABLE default\n";
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < a.components; ++c) {
        f << a.value(i) << " ";
      }
    }
    f << "\n";
  }
  return path;
}

std::string scene(const std::string& name, const std::string& json)
{
  const std::string path = testFile(name, ".json");
  std::ofstream(path) << json;
  return path;
}

Array ones(const char* name)
{
  return { name, 1, [](int) { return std::string("1"); } };
}

/// 4^3 voxels of kappa_a = 1, spacing 1.
std::string goodVolume()
{
  return legacyVolume("good", { 4, 4, 4 }, { 1, 1, 1 }, { ones("kappa_a") });
}

const char* kSun = R"({"version": 1, "lights": [{"type": "directional", "direction": [0, 0, -1]}]})";

struct Case
{
  const char* what;
  std::function<std::string()> args; ///< volrad's arguments before -o
  const char* message;               ///< a part of the one-line message
};

std::string emptyVti()
{
  const std::string path = testFile("empty", ".vti");
  vtkNew<vtkImageData> empty;
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetInputData(empty);
  w->SetFileName(path.c_str());
  w->Write();
  return path;
}

std::string vdbFile(const std::string& name, bool truncate)
{
  volrad::DenseVolume v;
  v.name = "density";
  v.dims = { 6, 5, 4 };
  v.values.assign(6 * 5 * 4, 0.5f);
  const std::string path = testFile(name, ".vdb");
  volrad::writeVdbGrids(path, { v });
  if (truncate) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  return path;
}

const std::vector<Case>& errorCases()
{
  static const std::vector<Case> cases = {
    { "an empty image", [] { return emptyVti(); }, "the input image is empty (no points)" },
    { "a flat image",
      [] { return legacyVolume("flat", { 8, 8, 1 }, { 1, 1, 1 }, { ones("kappa_a") }); },
      "8 x 8 x 1 points: volumetric radiosity needs a 3-D volume" },
    { "one voxel",
      [] { return legacyVolume("one", { 1, 1, 1 }, { 1, 1, 1 }, { ones("kappa_a") }); },
      "1 x 1 x 1 points" },
    { "a negative coefficient",
      [] {
        return legacyVolume("negative", { 4, 4, 4 }, { 1, 1, 1 },
                            { { "kappa_a", 1, [](int i) { return i == 21 ? "-2" : "1"; } } });
      },
      "kappa_a = -2 at voxel 21 (i=1, j=1, k=1), channel 0: must be finite and >= 0" },
    { "a huge coefficient",
      [] {
        return legacyVolume("huge", { 4, 4, 4 }, { 1, 1, 1 },
                            { { "kappa_a", 1, [](int i) { return i == 21 ? "1e30" : "1"; } } }) +
               " --scene " + scene("sun", kSun);
      },
      "kappa_t * spacing = 1e+30 at voxel 21" },
    { "emission beyond float32",
      [] {
        return legacyVolume("hot", { 4, 4, 4 }, { 1, 1, 1 },
                            { ones("kappa_a"),
                              { "E_I", 1, [](int) { return std::string("3e38"); } } });
      },
      "does not fit the output's float32" },
    { "zero spacing",
      [] { return legacyVolume("zero", { 4, 4, 4 }, { 0, 1, 1 }, { ones("kappa_a") }); },
      "spacing[0] = 0 must be finite and > 0" },
    { "negative spacing",
      [] { return legacyVolume("negspacing", { 4, 4, 4 }, { 1, -1, 1 }, { ones("kappa_a") }); },
      "spacing[1] = -1 must be finite and > 0" },
    { "components that do not match channels",
      [] {
        return legacyVolume("twocomp", { 4, 4, 4 }, { 1, 1, 1 },
                            { { "kappa_a", 2, [](int) { return std::string("1"); } } }) +
               " --scene " + scene("rgb", R"({"version": 1, "channels": 3})");
      },
      "'kappa_a' has 2 components; expected 1 or 3 (channels)" },
    { "an unknown scene key",
      [] { return goodVolume() + " --scene " + scene("key", R"({"version": 1, "bogus": 1})"); },
      "key 'bogus' is unknown" },
    { "a mistyped scene value",
      [] {
        return goodVolume() + " --scene " +
               scene("typed", R"({"version": 1, "solver": {"epsilon": "small"}})");
      },
      "solver.epsilon must be a number" },
    { "malformed JSON",
      [] { return goodVolume() + " --scene " + scene("malformed", R"({"version": 1, )"); },
      "malformed JSON" },
    { "epsilon <= 0",
      [] {
        return goodVolume() + " --scene " +
               scene("eps", R"({"version": 1, "solver": {"epsilon": -1e-3}})");
      },
      "solver.epsilon must be > 0" },
    { "a zero-length light direction",
      [] {
        return goodVolume() + " --scene " +
               scene("dir", R"({"version": 1, "lights": [{"type": "directional",
                                 "direction": [0, 0, 0]}]})");
      },
      "lights[0].direction must not be zero" },
    { "a missing scene file", [] { return goodVolume() + " --scene " + kOut + "/nothere.json"; },
      "cannot read the scene file" },
    { "a missing input", [] { return kOut + "/nothere.vti"; }, "cannot read the input file" },
    { "a truncated .vti",
      [] {
        const std::string path = testFile("truncated", ".vti");
        std::ofstream(path) << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">"
                               "<ImageData WholeExtent=\"0 3 0 3 0 3\"><Piece Extent=\"0 3";
        return path;
      },
      "cannot read" },
    { "a corrupt .vdb",
      [] {
        const std::string path = testFile("garbage", ".vdb");
        std::ofstream(path, std::ios::binary) << std::string(600, '\x42');
        return path;
      },
      "is not a readable OpenVDB file" },
    { "a truncated .vdb", [] { return vdbFile("truncated", true); }, "corrupt or truncated" },
    { "over the memory budget (hierarchical)",
      [] { return goodVolume() + " --scene " + scene("sun", kSun) + " --memory-budget 0.01"; },
      "over its memory budget of 0.01 MiB: raise solver.epsilon or the budget" },
    { "over the memory budget (dense)",
      [] {
        return goodVolume() + " --scene " +
               scene("densesun", R"({"version": 1, "solver": {"method": "dense"}})") +
               " --memory-budget 0.01";
      },
      "over its memory budget of 0.01 MiB: use the hierarchical solver" },
    { "a bad memory budget", [] { return goodVolume() + " --memory-budget lots"; },
      "--memory-budget takes a positive number of MiB, not 'lots'" },
  };
  return cases;
}

} // namespace

TEST(BadInput, EachCaseIsOneNamedErrorAndNoOutput)
{
  const std::string out = testFile("out", ".vti");
  for (const Case& c : errorCases()) {
    if (std::string(c.what).find(".vdb") != std::string::npos && !volrad::vdbSupported()) {
      continue;
    }
    std::remove(out.c_str());
    const volrad::test::CommandRun r = volrad::test::runVolrad(c.args() + " -o " + out);
    EXPECT_NE(r.code, 0) << c.what << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos)
      << c.what << ": expected '" << c.message << "' in: " << r.output;
    EXPECT_EQ(r.output.rfind("volrad: ", 0), 0u) << c.what << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.what << ": " << r.output;
    // One readable line (a truncated .vdb once gave OpenVDB's message with a
    // gigabyte of blanks in it).
    EXPECT_LT(r.output.size(), 600u) << c.what << ": " << r.output.substr(0, 600);
    EXPECT_FALSE(volrad::test::fileExists(out)) << c.what << ": an output was written";
  }
}

TEST(BadInput, UnwritableOutputsLeaveNothingBehind)
{
  for (const std::string out : { std::string("/nonexistent-dir/out.vti"),
                                 std::string("/nonexistent-dir/out.vdb") }) {
    const volrad::test::CommandRun r = volrad::test::runVolrad(goodVolume() + " -o " + out);
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("cannot write '" + out + "'"), std::string::npos) << r.output;
  }
  // A failed solve over an existing output keeps the old file whole.
  const std::string out = testFile("keep", ".vti");
  ASSERT_EQ(volrad::test::runVolrad(goodVolume() + " -o " + out).code, 0);
  std::ifstream before(out);
  const std::string old((std::istreambuf_iterator<char>(before)), std::istreambuf_iterator<char>());
  const volrad::test::CommandRun r = volrad::test::runVolrad(
    legacyVolume("flat2", { 8, 8, 1 }, { 1, 1, 1 }, { ones("kappa_a") }) + " -o " + out);
  EXPECT_NE(r.code, 0);
  std::ifstream after(out);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(after)), std::istreambuf_iterator<char>()),
            old);
}

TEST(BadInput, LightsWallsKeepOutAndMissingArraysAreWarnings)
{
  const std::string out = testFile("warned", ".vti");
  struct Warned
  {
    std::string scene, message;
  };
  const std::vector<Warned> cases = {
    { R"({"version": 1, "boundary": {"xmin": {"type": "wall", "reflectance": 0.5}},
         "lights": [{"type": "point", "position": [-5, 1, 1], "intensity": 1}]})",
      "point light 0 at (-5.000000, 1.000000, 1.000000) is outside the volume behind walls" },
    { R"({"version": 1, "boundary": {"zmax": {"type": "wall"}},
         "lights": [{"type": "directional", "direction": [0, 0, -1]}]})",
      "directional light 0 meets only walls where it would enter" },
    { R"({"version": 1, "arrays": {"absorption": "nothere"}, "lights": [{"type": "directional",
         "direction": [0, 0, -1]}]})",
      "the input has no point-data array 'nothere': taken as zero" },
  };
  for (const Warned& w : cases) {
    std::remove(out.c_str());
    const volrad::test::CommandRun r =
      volrad::test::runVolrad(goodVolume() + " --scene " + scene("warned", w.scene) + " -o " + out);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("volrad: warning: " + w.message), std::string::npos) << r.output;
    EXPECT_TRUE(volrad::test::fileExists(out));
  }
  // A point light beside an open face is no warning.
  const volrad::test::CommandRun r = volrad::test::runVolrad(
    goodVolume() + " --scene " +
    scene("open", R"({"version": 1, "lights": [{"type": "point", "position": [-5, 1, 1]}]})") +
    " -o " + out);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}
