// SPDX-License-Identifier: BSD-3-Clause
// volrad INPUT [--scene SCENE.json] -o OUTPUT.vti [--shrink N] [--threads N]
//
// Reads a volume (any image format VTK reads) and a scene file (docs/scene-format.md), solves
// volumetric radiosity and writes the input with the output arrays added. Errors go to stderr with
// a non-zero exit; the output file is written atomically.
#include "vtkVolumetricRadiosity.h"

#include "VolumeSnapshot.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMImageReader.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageChangeInformation.h"
#include "vtkImageData.h"
#include "vtkImageShrink3D.h"
#include "vtkLogger.h"
#include "vtkMetaImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkOpenVDBGridReader.h"
#include "vtkOpenVDBGridWriter.h"
#include "vtkOutputWindow.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSLCReader.h"
#include "vtkSmartPointer.h"
#include "vtkStructuredPointsReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

const char* kUsage =
  R"(usage: volrad INPUT [--scene SCENE.json] -o OUTPUT.vti|.vdb [--png PICTURE.png] [--grid NAME]
              [--shrink N] [--threads N] [--memory-budget MIB] [--skip-empty-space]

Solves volumetric radiosity in the volume INPUT lit as the scene file says
(docs/scene-format.md; without one, the defaults and the input's arrays
kappa_a, sigma_i, sigma_d, E_I, E_D, n apply; a "material" maps its scalars)
and writes OUTPUT.vti: the input's arrays plus IncidentRadiation,
IsotropicRadiosity, DiffuseRadiosity, FrontIncidentRadiation and
AbsorbedPower, and the solve's statistics as field data.

INPUT: VTK XML image data (.vti), MetaImage (.mhd, .mha), NRRD (.nrrd,
.nhdr), SLC (.slc), legacy VTK structured points (.vtk), OpenVDB (.vdb: one
grid over its active box, the scalars a material maps), or a directory of
DICOM files. OUTPUT: .vti (the input plus the fields), or .vdb (the fields
as grids: float, vec3s for RGB).

options:
  --scene FILE   scene file (JSON, version 1)
  -o, --output   output .vti file (written only if the solve succeeds)
  --png FILE     also a picture: the lit volume rendered from its RenderRGBA
                 array (needs an X display: run under xvfb-run -a without one)
  --grid NAME    the grid of a .vdb input (default: its first)
  --shrink N     solve on a grid N times coarser along each axis (averaging)
  --threads N    threads (default 0: all cores; 1: deterministic)
  --memory-budget MIB
                 refuse, before allocating, a solve whose estimate passes MIB
                 mebibytes (default: half the physical memory; dense: 4 GiB)
  --skip-empty-space
                 a sparse solve (hierarchical solver): voxels without medium
                 get no fields (0, the background of a .vdb output) and cost
                 no links or time
  -h, --help     this text
)";

std::string lowerExtension(const std::string& path)
{
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

/// The reader for a path: by its extension, or DICOM for a directory.
/// Null (and `error` set) for a format volrad does not read.
vtkSmartPointer<vtkAlgorithm> makeReader(const std::string& path,
                                         const std::string& grid,
                                         std::string& error)
{
  if (std::filesystem::is_directory(path)) {
    auto r = vtkSmartPointer<vtkDICOMImageReader>::New();
    r->SetDirectoryName(path.c_str());
    return r;
  }
  const std::string e = lowerExtension(path);
  if (e == ".vdb") {
    auto r = vtkSmartPointer<vtkOpenVDBGridReader>::New();
    r->SetFileName(path.c_str());
    r->SetGridName(grid.c_str());
    return r;
  }
  if (e == ".vti") {
    auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (e == ".mhd" || e == ".mha") {
    auto r = vtkSmartPointer<vtkMetaImageReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (e == ".nrrd" || e == ".nhdr") {
    auto r = vtkSmartPointer<vtkNrrdReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (e == ".slc") {
    auto r = vtkSmartPointer<vtkSLCReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (e == ".vtk") {
    auto r = vtkSmartPointer<vtkStructuredPointsReader>::New();
    r->SetFileName(path.c_str());
    // Every array of the file, not only its first SCALARS (kappa_a, E_I, ...).
    r->ReadAllScalarsOn();
    r->ReadAllVectorsOn();
    r->ReadAllFieldsOn();
    return r;
  }
  error = "'" + path + "': unknown volume format '" + e +
          "' (volrad reads .vti, .mhd, .mha, .nrrd, .nhdr, .slc, .vtk, .vdb and DICOM directories)";
  return nullptr;
}

/// A progress bar on stderr when it is a terminal.
void showProgress(vtkObject*, unsigned long, void*, void* data)
{
  const double f = *static_cast<double*>(data);
  const int width = 40, done = int(f * width + 0.5);
  std::fprintf(stderr,
               "\rvolrad: solving [%s%s] %3d%%",
               std::string(done, '#').c_str(),
               std::string(width - done, ' ').c_str(),
               int(100.0 * f + 0.5));
  std::fflush(stderr);
}

/// Collects the error messages of VTK objects instead of printing them.
struct ErrorCollector
{
  std::string messages;
  static void callback(vtkObject*, unsigned long, void* self, void* data)
  {
    auto* c = static_cast<ErrorCollector*>(self);
    c->messages += (c->messages.empty() ? "" : "\n") + plain(static_cast<const char*>(data));
  }
  /// VTK's "ERROR: In FILE, line N\nCLASS (0x...): message" (or
  /// "Warning: In ...") as "message".
  static std::string plain(std::string text)
  {
    const std::size_t line = text.find('\n');
    if ((text.rfind("ERROR: In ", 0) == 0 || text.rfind("Warning: In ", 0) == 0) &&
        line != std::string::npos) {
      text = text.substr(line + 1);
      const std::size_t open = text.find(" (0x"), close = text.find("): ");
      if (open != std::string::npos && close != std::string::npos && open < close &&
          text.find('\n') > close) {
        text = text.substr(close + 3);
      }
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
      text.pop_back();
    }
    return text;
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
  std::string input, scene, output, png, grid;
  int threads = 0, shrink = 1;
  double memoryBudget = 0.0;
  bool skipEmptySpace = false;
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
      } else if (arg == "--png") {
        png = value("--png");
      } else if (arg == "--grid") {
        grid = value("--grid");
      } else if (arg == "--threads" || arg == "--shrink") {
        const std::string v = value(arg.c_str());
        std::size_t used = 0;
        long n = -1;
        try {
          n = std::stol(v, &used);
        } catch (const std::exception&) {
        }
        const long lo = arg == "--threads" ? 0 : 1;
        if (used != v.size() || n < lo || n > 4096) {
          return fail(arg + " takes a whole number from " + std::to_string(lo) + " to 4096, not '" +
                      v + "'");
        }
        (arg == "--threads" ? threads : shrink) = int(n);
      } else if (arg == "--memory-budget") {
        const std::string v = value("--memory-budget");
        std::size_t used = 0;
        double mib = -1.0;
        try {
          mib = std::stod(v, &used);
        } catch (const std::exception&) {
        }
        if (used != v.size() || !(mib > 0.0) || mib > 1e12) {
          return fail("--memory-budget takes a positive number of MiB, not '" + v + "'");
        }
        memoryBudget = mib;
      } else if (arg == "--skip-empty-space") {
        skipEmptySpace = true;
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
  if (!std::filesystem::exists(input) ||
      (!std::filesystem::is_directory(input) && !std::ifstream(input))) {
    return fail("cannot read the input file '" + input + "'");
  }
  std::string formatError;
  vtkSmartPointer<vtkAlgorithm> reader = makeReader(input, grid, formatError);
  if (!reader) {
    return fail(formatError);
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
  // VTK's own reports (its output window and logger) would repeat each error
  // with pipeline details: volrad prints errors (collected above) and
  // warnings (below) itself, one line each.
  vtkOutputWindow::GetInstance()->SetDisplayMode(vtkOutputWindow::NEVER);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkNew<vtkCallbackCommand> onWarning;
  onWarning->SetCallback([](vtkObject*, unsigned long, void*, void* data) {
    std::cerr << "volrad: warning: " << ErrorCollector::plain(static_cast<const char*>(data))
              << "\n";
  });

  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->Update();
  vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!errors.messages.empty() && vtkOpenVDBGridReader::SafeDownCast(reader)) {
    return fail(errors.messages); // it names the file and what is wrong with it
  }
  if (!errors.messages.empty() || !image) {
    return fail("cannot read '" + input + "' as image data" +
                (errors.messages.empty() ? "" : ": " + errors.messages));
  }
  if (image->GetNumberOfPoints() == 0) {
    return fail("'" + input + "': the input image is empty (no points)");
  }
  vtkNew<vtkImageShrink3D> shrinker;
  vtkNew<vtkImageChangeInformation> centred;
  vtkAlgorithm* source = reader;
  if (shrink > 1) {
    shrinker->SetShrinkFactors(shrink, shrink, shrink);
    shrinker->AveragingOn();
    shrinker->SetInputConnection(reader->GetOutputPort());
    // The shrinker keeps the origin, but the mean of fine voxels Ni..Ni+N-1
    // belongs at their centre, (N-1)/2 fine voxels further.
    double spacing[3];
    image->GetSpacing(spacing);
    centred->SetInputConnection(shrinker->GetOutputPort());
    centred->SetOriginTranslation((shrink - 1) / 2.0 * spacing[0],
                                  (shrink - 1) / 2.0 * spacing[1],
                                  (shrink - 1) / 2.0 * spacing[2]);
    source = centred;
  }

  vtkNew<vtkVolumetricRadiosity> filter;
  filter->SetInputConnection(source->GetOutputPort());
  if (!scene.empty()) {
    filter->SetSceneFileName(scene.c_str());
  }
  filter->SetNumberOfThreads(threads);
  filter->SetMemoryBudget(memoryBudget);
  filter->SetSkipEmptySpace(skipEmptySpace);
  filter->AddObserver(vtkCommand::ErrorEvent, onError);
  filter->AddObserver(vtkCommand::WarningEvent, onWarning);
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetCallback(&showProgress);
  const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) {
    filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
  }
  filter->Update();
  if (terminal) {
    std::fprintf(stderr, "\n");
  }
  vtkImageData* result = filter->GetOutput();
  if (!errors.messages.empty() || !result->GetPointData()->GetArray("IncidentRadiation")) {
    return fail(errors.messages.empty() ? "the solve failed" : errors.messages);
  }

  // The picture first, in memory: a failed rendering leaves no output at all.
  vtkSmartPointer<vtkImageData> picture;
  if (!png.empty()) {
    try {
      picture = volrad::renderSnapshot(result);
    } catch (const std::exception& e) {
      return fail(std::string("cannot render --png: ") + e.what());
    }
  }

  if (lowerExtension(output) == ".vdb") {
    // The output fields as OpenVDB grids (float, vec3s in RGB).
    vtkNew<vtkOpenVDBGridWriter> writer;
    writer->SetFileName(output.c_str());
    writer->SetInputData(result);
    for (const char* name : { "IncidentRadiation",
                              "IsotropicRadiosity",
                              "DiffuseRadiosity",
                              "FrontIncidentRadiation",
                              "AbsorbedPower" }) {
      if (result->GetPointData()->GetArray(name)) {
        writer->AddArrayName(name);
      }
    }
    writer->AddObserver(vtkCommand::ErrorEvent, onError);
    if (writer->Write() != 1 || !errors.messages.empty()) {
      return fail(errors.messages.empty() ? "cannot write '" + output + "'" : errors.messages);
    }
  } else {
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
  }
  if (picture) {
    const std::string partialPng = png + ".partial.png";
    vtkNew<vtkPNGWriter> pngWriter;
    pngWriter->SetFileName(partialPng.c_str());
    pngWriter->SetInputData(picture);
    pngWriter->AddObserver(vtkCommand::ErrorEvent, onError);
    pngWriter->Write();
    if (!errors.messages.empty() || std::rename(partialPng.c_str(), png.c_str()) != 0) {
      std::remove(partialPng.c_str());
      return fail("wrote " + output + " but cannot write '" + png + "'" +
                  (errors.messages.empty() ? "" : ": " + errors.messages));
    }
    std::cout << "volrad: wrote " << png << "\n";
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
