// SPDX-License-Identifier: BSD-3-Clause
// volrad INPUT.vti [--scene SCENE.json] -o OUTPUT.vti [--threads N]
//
// Reads a volume and a scene file (docs/scene-format.md), solves volumetric
// radiosity and writes the input with the output arrays added. Errors go to
// stderr with a non-zero exit; the output file is written atomically.
#include "vtkVolumetricRadiosity.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace {

const char* kUsage = R"(usage: volrad INPUT.vti [--scene SCENE.json] -o OUTPUT.vti [--threads N]

Solves volumetric radiosity in the volume INPUT (VTK XML image data, .vti)
lit as the scene file says (docs/scene-format.md; without one, the defaults
and the input's arrays kappa_a, sigma_i, sigma_d, E_I, E_D, n apply) and
writes OUTPUT.vti: the input's arrays plus IncidentRadiation,
IsotropicRadiosity, DiffuseRadiosity, FrontIncidentRadiation and
AbsorbedPower, and the solve's statistics as field data.

options:
  --scene FILE   scene file (JSON, version 1)
  -o, --output   output .vti file (written only if the solve succeeds)
  --threads N    threads (default 0: all cores; 1: deterministic)
  -h, --help     this text
)";

/// Collects the error messages of VTK objects instead of printing them.
struct ErrorCollector
{
  std::string messages;
  static void callback(vtkObject*, unsigned long, void* self, void* data)
  {
    auto* c = static_cast<ErrorCollector*>(self);
    c->messages += (c->messages.empty() ? "" : "\n") + std::string(static_cast<const char*>(data));
  }
};

int fail(const std::string& message)
{
  std::cerr << "volrad: " << message << "\n";
  return 1;
}

std::string fieldValue(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  if (!a) {
    return "?";
  }
  std::string s;
  for (int c = 0; c < a->GetNumberOfComponents(); ++c) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%s%.6g", c ? " " : "", a->GetComponent(0, c));
    s += buf;
  }
  return s;
}

} // namespace

int main(int argc, char* argv[])
{
  std::string input, scene, output;
  int threads = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* what) -> std::string {
      if (i + 1 >= argc) {
        throw std::runtime_error(std::string(what) + " needs a value");
      }
      return argv[++i];
    };
    try {
      if (arg == "-h" || arg == "--help") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--scene") {
        scene = value("--scene");
      } else if (arg == "-o" || arg == "--output") {
        output = value("-o");
      } else if (arg == "--threads") {
        const std::string v = value("--threads");
        std::size_t used = 0;
        long n = -1;
        try {
          n = std::stol(v, &used);
        } catch (const std::exception&) {
        }
        if (used != v.size() || n < 0 || n > 4096) {
          return fail("--threads takes a whole number from 0 to 4096, not '" + v + "'");
        }
        threads = int(n);
      } else if (!arg.empty() && arg[0] == '-') {
        return fail("unknown option '" + arg + "'\n" + kUsage);
      } else if (input.empty()) {
        input = arg;
      } else {
        return fail("more than one input given ('" + input + "', '" + arg + "')");
      }
    } catch (const std::exception& e) {
      return fail(e.what());
    }
  }
  if (input.empty() || output.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  if (!std::ifstream(input)) {
    return fail("cannot read the input file '" + input + "'");
  }
  if (input.size() < 4 || input.substr(input.size() - 4) != ".vti") {
    return fail("'" + input + "': this version reads VTK XML image data (.vti) only");
  }

  // Fail before a long solve if the output cannot be written at all.
  const std::string partial = output + ".partial";
  {
    std::ofstream probe(partial);
    if (!probe) {
      return fail("cannot write '" + output + "'");
    }
  }
  std::remove(partial.c_str());

  ErrorCollector errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(&ErrorCollector::callback);
  onError->SetClientData(&errors);

  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(input.c_str());
  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->Update();
  if (!errors.messages.empty() || reader->GetOutput()->GetNumberOfPoints() == 0) {
    return fail("cannot read '" + input + "' as image data" +
                (errors.messages.empty() ? "" : ": " + errors.messages));
  }

  vtkNew<vtkVolumetricRadiosity> filter;
  filter->SetInputConnection(reader->GetOutputPort());
  if (!scene.empty()) {
    filter->SetSceneFileName(scene.c_str());
  }
  filter->SetNumberOfThreads(threads);
  filter->AddObserver(vtkCommand::ErrorEvent, onError);
  filter->Update();
  vtkImageData* result = filter->GetOutput();
  if (!errors.messages.empty() || !result->GetPointData()->GetArray("IncidentRadiation")) {
    return fail(errors.messages.empty() ? "the solve failed" : errors.messages);
  }

  // Write next to the target, then rename: no partial file on failure.
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(partial.c_str());
  writer->SetInputData(result);
  writer->AddObserver(vtkCommand::ErrorEvent, onError);
  if (writer->Write() != 1 || !errors.messages.empty()) {
    std::remove(partial.c_str());
    return fail("cannot write '" + output + "'" +
                (errors.messages.empty() ? "" : ": " + errors.messages));
  }
  if (std::rename(partial.c_str(), output.c_str()) != 0) {
    std::remove(partial.c_str());
    return fail("cannot write '" + output + "'");
  }
  std::cout
    << "volrad: wrote " << output << "\n"
    << "  solver "
    << result->GetFieldData()->GetAbstractArray("SolverMethod")->GetVariantValue(0).ToString()
    << ", " << fieldValue(result, "SolveSeconds") << " s, " << fieldValue(result, "Links")
    << " links\n"
    << "  energy emitted " << fieldValue(result, "EnergyEmitted") << ", absorbed "
    << fieldValue(result, "EnergyAbsorbed") << ", walls "
    << fieldValue(result, "EnergyAbsorbedWalls") << ", escaped "
    << fieldValue(result, "EnergyEscaped") << " (residual "
    << fieldValue(result, "EnergyBalanceResidual") << ")\n";
  return 0;
}
