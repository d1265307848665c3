// SPDX-License-Identifier: BSD-3-Clause
// The volrad command end to end: bundled data in, the documented arrays out;
// errors give a message, a non-zero exit and no output file.
#include "vtkAbstractArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkVariant.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>

namespace {

struct CommandRun
{
  int code;
  std::string output;
};

CommandRun run(const std::string& args)
{
  const std::string log = std::string(VOLRAD_TEST_OUTPUT_DIR) + "/volrad.log";
  const int status =
    std::system((std::string(VOLRAD_COMMAND) + " " + args + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return { WEXITSTATUS(status), text };
}

bool exists(const std::string& path)
{
  return bool(std::ifstream(path));
}

const std::string kData = VOLRAD_DATA_DIR;
const std::string kOut = VOLRAD_TEST_OUTPUT_DIR;

} // namespace

TEST(VolradCommand, SolvesTheBundledSceneAndWritesTheDocumentedArrays)
{
  const std::string out = kOut + "/neghip16-lit.vti";
  std::remove(out.c_str());
  const CommandRun r =
    run(kData + "/neghip16.vti --scene " + kData + "/neghip16.scene.json -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(out.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  ASSERT_EQ(image->GetNumberOfPoints(), 16 * 16 * 16);
  for (const char* name : { "IncidentRadiation",
                            "IsotropicRadiosity",
                            "DiffuseRadiosity",
                            "FrontIncidentRadiation",
                            "AbsorbedPower",
                            "density" }) {
    EXPECT_NE(image->GetPointData()->GetArray(name), nullptr) << name;
  }
  EXPECT_EQ(image->GetPointData()->GetArray("IncidentRadiation")->GetDataType(), VTK_FLOAT);
  const double residual =
    image->GetFieldData()->GetArray("EnergyBalanceResidual")->GetComponent(0, 0);
  // The bundled scene uses the default, hierarchical solver: energy
  // balanced within its 0.5% (physics.md 5.2).
  EXPECT_LT(residual, 5e-3);
  auto* method = image->GetFieldData()->GetAbstractArray("SolverMethod");
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(method->GetVariantValue(0).ToString(), "hierarchical");
}

TEST(VolradCommand, ErrorsExitNonZeroWithAMessageAndNoOutput)
{
  const std::string out = kOut + "/should-not-exist.vti";
  std::remove(out.c_str());
  const std::string bad = kOut + "/bad-scene.json";
  std::ofstream(bad) << R"({"version": 1, "lights": [{"type": "directional", "colour": 1}]})";
  CommandRun r = run(kData + "/neghip16.vti --scene " + bad + " -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("lights[0].colour"), std::string::npos) << r.output;
  EXPECT_FALSE(exists(out));

  r = run(kData + "/missing.vti -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("missing.vti"), std::string::npos) << r.output;
  EXPECT_FALSE(exists(out));

  const std::string garbage = kOut + "/garbage.vti";
  std::ofstream(garbage) << "<VTKFile this is not";
  r = run(garbage + " -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_FALSE(exists(out));

  r = run(kData + "/neghip16.vti -o /nonexistent-dir/out.vti");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("cannot write"), std::string::npos) << r.output;

  r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("usage: volrad"), std::string::npos);
}
