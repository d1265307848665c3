// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBGridWriter.h"

#include "volrad/VdbVolume.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

vtkStandardNewMacro(vtkOpenVDBGridWriter);

vtkOpenVDBGridWriter::vtkOpenVDBGridWriter() = default;

vtkOpenVDBGridWriter::~vtkOpenVDBGridWriter()
{
  this->SetFileName(nullptr);
}

void vtkOpenVDBGridWriter::AddArrayName(const char* name)
{
  if (name) {
    this->ArrayNames.emplace_back(name);
    this->Modified();
  }
}

void vtkOpenVDBGridWriter::ClearArrayNames()
{
  if (!this->ArrayNames.empty()) {
    this->ArrayNames.clear();
    this->Modified();
  }
}

vtkImageData* vtkOpenVDBGridWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkOpenVDBGridWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkOpenVDBGridWriter::WriteData()
{
  vtkImageData* image = this->GetInput();
  if (!this->FileName || !*this->FileName) {
    vtkErrorMacro(<< "no file name: set FileName to a .vdb path");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  if (!image || image->GetNumberOfPoints() == 0) {
    vtkErrorMacro(<< "no input image to write to '" << this->FileName << "'");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  vtkPointData* pd = image->GetPointData();
  std::vector<vtkDataArray*> arrays;
  if (this->ArrayNames.empty()) {
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i) {
      vtkDataArray* a = pd->GetArray(i);
      if (a && a->GetName() &&
          (a->GetNumberOfComponents() == 1 || a->GetNumberOfComponents() == 3)) {
        arrays.push_back(a);
      }
    }
  }
  for (const std::string& name : this->ArrayNames) {
    vtkDataArray* a = pd->GetArray(name.c_str());
    if (!a || (a->GetNumberOfComponents() != 1 && a->GetNumberOfComponents() != 3)) {
      vtkErrorMacro(<< "the input has no numeric point array '" << name
                    << "' with 1 or 3 components to write as a grid");
      this->SetErrorCode(vtkErrorCode::UnknownError);
      return;
    }
    arrays.push_back(a);
  }
  if (arrays.empty()) {
    vtkErrorMacro(<< "the input has no point array with 1 or 3 components to write");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  if (!image->GetDirectionMatrix()->IsIdentity()) {
    vtkErrorMacro(<< "'" << this->FileName
                  << "': OpenVDB grids are written axis-aligned, and this image is rotated "
                     "(its direction matrix is not the identity)");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  int extent[6];
  image->GetExtent(extent);
  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  std::vector<volrad::DenseVolume> grids;
  for (vtkDataArray* a : arrays) {
    volrad::DenseVolume v;
    v.name = a->GetName();
    image->GetDimensions(v.dims.data());
    for (int k = 0; k < 3; ++k) {
      v.spacing[k] = spacing[k];
      v.origin[k] = origin[k] + extent[2 * k] * spacing[k];
    }
    v.components = a->GetNumberOfComponents();
    v.values.resize(std::size_t(a->GetNumberOfTuples()) * v.components);
    bool active = false;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
      for (int c = 0; c < v.components; ++c) {
        const float x = float(a->GetComponent(i, c));
        v.values[std::size_t(i) * v.components + c] = x;
        active = active || x != this->Background;
      }
    }
    if (!active) {
      vtkWarningMacro(<< "array '" << v.name << "' holds only the background value "
                      << this->Background << ": its grid has no active voxels");
    }
    grids.push_back(std::move(v));
  }

  try {
    volrad::writeVdbGrids(this->FileName, grids, this->Background);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkOpenVDBGridWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayNames:";
  for (const auto& n : this->ArrayNames) {
    os << " " << n;
  }
  os << (this->ArrayNames.empty() ? " (all with 1 or 3 components)\n" : "\n");
  os << indent << "Background: " << this->Background << "\n";
}
