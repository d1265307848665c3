// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBGridReader.h"

#include "volrad/Error.h"
#include "volrad/VdbVolume.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <fstream>

vtkStandardNewMacro(vtkOpenVDBGridReader);

vtkOpenVDBGridReader::vtkOpenVDBGridReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkOpenVDBGridReader::~vtkOpenVDBGridReader()
{
  this->SetFileName(nullptr);
  this->SetGridName(nullptr);
}

int vtkOpenVDBGridReader::CanReadFile(const char* fileName)
{
  if (!fileName || !volrad::vdbSupported()) {
    return 0;
  }
  // Every .vdb file starts with the magic number 0x56444220 ("VDB ").
  std::ifstream in(fileName, std::ios::binary);
  unsigned char magic[4] = {};
  in.read(reinterpret_cast<char*>(magic), 4);
  return in && magic[0] == 0x20 && magic[1] == 0x42 && magic[2] == 0x44 && magic[3] == 0x56;
}

bool vtkOpenVDBGridReader::ReadGrid()
{
  if (this->Volume && this->ReadTime > this->GetMTime()) {
    return true;
  }
  this->Volume.reset();
  if (!this->FileName || !*this->FileName) {
    vtkErrorMacro(<< "no file name: set FileName to a .vdb file");
    return false;
  }
  try {
    this->Volume = std::make_unique<volrad::DenseVolume>(volrad::readVdbGrid(
      this->FileName, this->GridName ? this->GridName : "", std::size_t(this->MaximumVoxels)));
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return false;
  }
  this->ReadTime.Modified();
  return true;
}

int vtkOpenVDBGridReader::RequestInformation(vtkInformation*,
                                             vtkInformationVector**,
                                             vtkInformationVector* outputVector)
{
  vtkInformation* out = outputVector->GetInformationObject(0);
  if (!this->ReadGrid()) {
    // The pipeline stops here: the last good read must not stay behind.
    vtkImageData::GetData(out)->Initialize();
    return 0;
  }
  const volrad::DenseVolume& v = *this->Volume;
  const int extent[6] = { 0, v.dims[0] - 1, 0, v.dims[1] - 1, 0, v.dims[2] - 1 };
  out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  out->Set(vtkDataObject::SPACING(), v.spacing[0], v.spacing[1], v.spacing[2]);
  out->Set(vtkDataObject::ORIGIN(), v.origin[0], v.origin[1], v.origin[2]);
  vtkDataObject::SetPointDataActiveScalarInfo(out, VTK_FLOAT, v.components);
  return 1;
}

int vtkOpenVDBGridReader::RequestData(vtkInformation*,
                                      vtkInformationVector**,
                                      vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  if (!this->ReadGrid()) {
    return 0;
  }
  const volrad::DenseVolume& v = *this->Volume;
  image->SetDimensions(v.dims[0], v.dims[1], v.dims[2]);
  image->SetSpacing(v.spacing[0], v.spacing[1], v.spacing[2]);
  image->SetOrigin(v.origin[0], v.origin[1], v.origin[2]);
  vtkNew<vtkFloatArray> values;
  values->SetName(v.name.c_str());
  values->SetNumberOfComponents(v.components);
  if (!values->Allocate(vtkIdType(v.values.size())) ||
      vtkIdType(v.values.size()) != image->GetNumberOfPoints() * v.components) {
    vtkErrorMacro(<< "cannot hold grid '" << v.name << "' in memory");
    image->Initialize();
    this->Volume.reset();
    return 0;
  }
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  std::copy(v.values.begin(), v.values.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  // The image holds the values now: no second copy while it lives.
  this->Volume.reset();
  return 1;
}

void vtkOpenVDBGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "GridName: " << (this->GridName ? this->GridName : "(first)") << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}
