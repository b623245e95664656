#include "parcVolumeIO.h"

#include <vtkCallbackCommand.h>
#include <vtkColorTransferFunction.h>
#include <vtkContourValues.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkMetaImageReader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkOutputWindow.h>
#include <vtkPiecewiseFunction.h>
#include <vtkAlgorithm.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkSLCReader.h>
#include <vtkStructuredPoints.h>
#include <vtkStructuredPointsReader.h>
#include <vtkVolumeProperty.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>
#include <sys/stat.h>
#include <vector>

namespace parcio
{
namespace
{
bool EndsWith(const std::string& s, const std::string& suffix)
{
  if (s.size() < suffix.size())
  {
    return false;
  }
  std::string tail = s.substr(s.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), ::tolower);
  return tail == suffix;
}

bool FileExists(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

long long FileSize(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0 ? static_cast<long long>(st.st_size) : -1;
}

template <class Reader>
vtkSmartPointer<vtkAlgorithm> MakeReader(const std::string& path)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

/// Updates reader and returns the first error it or its executive reported (a truncated
/// file, a missing data file), or the first warning that names an error (VTK's legacy
/// reader only warns "Error reading binary data!" on a short file), or an empty string.
std::string UpdateAndCatchErrors(vtkAlgorithm* reader)
{
  std::string first;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&first);
  onError->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
    auto* message = static_cast<std::string*>(client);
    const std::string text = data ? static_cast<const char*>(data) : "an unnamed error";
    if (message->empty() &&
      (event == vtkCommand::ErrorEvent || text.find("rror") != std::string::npos))
    {
      *message = text;
    }
  });
  vtkOutputWindow* messages = vtkOutputWindow::GetInstance(); // generic warnings and errors
  const unsigned long tags[] = { reader->AddObserver(vtkCommand::ErrorEvent, onError),
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, onError),
    messages->AddObserver(vtkCommand::ErrorEvent, onError),
    messages->AddObserver(vtkCommand::WarningEvent, onError) };
  reader->Update();
  reader->RemoveObserver(tags[0]);
  reader->GetExecutive()->RemoveObserver(tags[1]);
  messages->RemoveObserver(tags[2]);
  messages->RemoveObserver(tags[3]);
  // VTK's messages are "ERROR: In file, line n\nclass (address): text" and "Generic
  // Warning: In file, line n\ntext": keep the text's first line.
  std::string text = first.substr(first.rfind(", line ", first.find('\n')) == std::string::npos
      ? 0
      : first.find('\n') + 1);
  const std::size_t from = text.find("): ");
  text = from == std::string::npos ? text : text.substr(from + 3);
  const std::string line = text.substr(0, text.find('\n'));
  const std::size_t end = line.find_last_not_of(' ');
  return line.substr(0, end == std::string::npos ? 0 : end + 1);
}

/// Copies the image reader produced into out; false with error naming path when reading
/// reported an error, or the image holds no point scalars for each of its points (the
/// header promises more than the file holds).
bool TakeVolume(vtkAlgorithm* reader, const std::string& path, vtkImageData* out,
  std::string& error)
{
  const std::string failure = UpdateAndCatchErrors(reader);
  if (!failure.empty())
  {
    error = "could not read " + path + ": " + failure;
    return false;
  }
  vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || image->GetNumberOfPoints() == 0 ||
    scalars->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = "could not read a volume with scalars from " + path +
      (scalars ? " (its header names more points than it holds scalars for)" : "");
    return false;
  }
  out->ShallowCopy(image);
  return true;
}

bool ReadRaw(const std::string& path, vtkImageData* out, std::string& error)
{
  static const std::regex pattern(
    R"(_(\d+)x(\d+)x(\d+)_(u?int8|u?int16(le|be)?|u?int32(le|be)?|float32|float64)\.raw$)",
    std::regex::icase);
  std::smatch m;
  if (!std::regex_search(path, m, pattern))
  {
    error = "raw file names must end in _XxYxZ_TYPE.raw (TYPE uint8, int16le, float32, ...): " +
      path;
    return false;
  }
  const int dims[3] = { std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]) };
  std::string type = m[4];
  std::transform(type.begin(), type.end(), type.begin(), ::tolower);
  const bool bigEndian = EndsWith(type, "be");
  int vtkType = VTK_UNSIGNED_CHAR, bytes = 1;
  if (type == "int8") { vtkType = VTK_SIGNED_CHAR; }
  else if (type.rfind("uint16", 0) == 0) { vtkType = VTK_UNSIGNED_SHORT; bytes = 2; }
  else if (type.rfind("int16", 0) == 0) { vtkType = VTK_SHORT; bytes = 2; }
  else if (type.rfind("uint32", 0) == 0) { vtkType = VTK_UNSIGNED_INT; bytes = 4; }
  else if (type.rfind("int32", 0) == 0) { vtkType = VTK_INT; bytes = 4; }
  else if (type == "float32") { vtkType = VTK_FLOAT; bytes = 4; }
  else if (type == "float64") { vtkType = VTK_DOUBLE; bytes = 8; }
  const long long expected = static_cast<long long>(dims[0]) * dims[1] * dims[2] * bytes;
  if (FileSize(path) != expected)
  {
    error = "raw file " + path + " has " + std::to_string(FileSize(path)) + " bytes, expected " +
      std::to_string(expected) + " for its name's dimensions and type";
    return false;
  }
  vtkNew<vtkImageReader2> reader;
  reader->SetFileName(path.c_str());
  reader->SetFileDimensionality(3);
  reader->SetDataExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1);
  reader->SetDataScalarType(vtkType);
  reader->SetNumberOfScalarComponents(1);
  if (bigEndian)
  {
    reader->SetDataByteOrderToBigEndian();
  }
  else
  {
    reader->SetDataByteOrderToLittleEndian();
  }
  return TakeVolume(reader, path, out, error);
}
}

bool ReadVolume(const std::string& path, vtkImageData* out, std::string& error)
{
  if (!FileExists(path))
  {
    error = "no such file: " + path;
    return false;
  }
  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(path, ".raw"))
  {
    return ReadRaw(path, out, error);
  }
  else if (EndsWith(path, ".vti"))
  {
    reader = MakeReader<vtkXMLImageDataReader>(path);
  }
  else if (EndsWith(path, ".mha") || EndsWith(path, ".mhd"))
  {
    reader = MakeReader<vtkMetaImageReader>(path);
  }
  else if (EndsWith(path, ".nii") || EndsWith(path, ".nii.gz"))
  {
    reader = MakeReader<vtkNIFTIImageReader>(path);
  }
  else if (EndsWith(path, ".nrrd") || EndsWith(path, ".nhdr"))
  {
    reader = MakeReader<vtkNrrdReader>(path);
  }
  else if (EndsWith(path, ".slc"))
  {
    reader = MakeReader<vtkSLCReader>(path);
  }
  else if (EndsWith(path, ".vtk"))
  {
    reader = MakeReader<vtkStructuredPointsReader>(path);
  }
  else
  {
    error = "unknown volume file type: " + path +
      " (use .vti, .mha, .mhd, .nii, .nii.gz, .nrrd, .nhdr, .vtk, .slc or _XxYxZ_TYPE.raw)";
    return false;
  }
  return TakeVolume(reader, path, out, error);
}

namespace
{
struct Node
{
  double X, Opacity, R, G, B;
};

/// Presets in fractions of the scalar range.
bool Preset(const std::string& name, std::vector<Node>& nodes)
{
  if (name == "ramp")
  {
    nodes = { { 0.0, 0.0, 0.0, 0.0, 0.0 }, { 0.15, 0.0, 0.3, 0.3, 0.3 },
      { 1.0, 0.6, 1.0, 1.0, 1.0 } };
  }
  else if (name == "mri")
  {
    nodes = { { 0.0, 0.0, 0.0, 0.0, 0.0 }, { 0.15, 0.0, 0.55, 0.25, 0.15 },
      { 0.35, 0.04, 0.85, 0.55, 0.45 }, { 0.6, 0.12, 0.95, 0.85, 0.75 },
      { 1.0, 0.5, 1.0, 1.0, 0.95 } };
  }
  else if (name == "ct-skin-bone")
  {
    nodes = { { 0.0, 0.0, 0.0, 0.0, 0.0 }, { 0.2, 0.0, 0.8, 0.5, 0.4 },
      { 0.28, 0.06, 0.9, 0.6, 0.45 }, { 0.45, 0.0, 0.9, 0.7, 0.6 },
      { 0.6, 0.0, 1.0, 1.0, 0.9 }, { 0.75, 0.7, 1.0, 1.0, 0.95 }, { 1.0, 0.9, 1.0, 1.0, 1.0 } };
  }
  else if (name == "ct-bone")
  {
    nodes = { { 0.0, 0.0, 0.0, 0.0, 0.0 }, { 0.5, 0.0, 0.9, 0.8, 0.7 },
      { 0.7, 0.6, 1.0, 1.0, 0.9 }, { 1.0, 0.9, 1.0, 1.0, 1.0 } };
  }
  else if (name == "mip")
  {
    nodes = { { 0.0, 0.0, 0.0, 0.0, 0.0 }, { 0.1, 0.0, 0.0, 0.0, 0.0 },
      { 0.5, 0.5, 0.9, 0.4, 0.1 }, { 1.0, 1.0, 1.0, 1.0, 0.8 } };
  }
  else
  {
    return false;
  }
  return true;
}
}

bool LoadTransferFunction(const std::string& nameOrFile, const double range[2],
  vtkVolumeProperty* property, std::string& error)
{
  std::vector<Node> nodes;
  bool relative = true;
  if (!Preset(nameOrFile, nodes))
  {
    std::ifstream in(nameOrFile);
    if (!in)
    {
      error = "unknown transfer function preset or file: " + nameOrFile +
        " (presets: ramp, mri, ct-skin-bone, ct-bone, mip)";
      return false;
    }
    relative = false;
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line))
    {
      ++lineNumber;
      line = line.substr(0, line.find('#'));
      if (line.find_first_not_of(" \t\r") == std::string::npos)
      {
        continue;
      }
      std::istringstream fields(line);
      Node n;
      if (!(fields >> n.X >> n.Opacity >> n.R >> n.G >> n.B))
      {
        error = nameOrFile + ":" + std::to_string(lineNumber) +
          ": expected 'scalar opacity red green blue'";
        return false;
      }
      nodes.push_back(n);
    }
    if (nodes.empty())
    {
      error = "transfer function file has no nodes: " + nameOrFile;
      return false;
    }
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkNew<vtkColorTransferFunction> color;
  for (const Node& n : nodes)
  {
    const double x = relative ? range[0] + n.X * (range[1] - range[0]) : n.X;
    opacity->AddPoint(x, n.Opacity);
    color->AddRGBPoint(x, n.R, n.G, n.B);
  }
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  return true;
}

//------------------------------------------------------------------------------
void MakeFloor(const double objectBounds[6], vtkImageData* out)
{
  constexpr double WidthPerObjectWidth = 1.2; // the paper's: 228 units under a 306-unit cell
  constexpr double RampSamples = 2.0;        // the density's fall across a face
  constexpr double SlabSamples = 6.0;        // the slab's thickness below its top surface
  const int* n = FloorSamples;
  const double width = WidthPerObjectWidth *
    std::max(objectBounds[1] - objectBounds[0], objectBounds[5] - objectBounds[4]);
  const double spacing = width / (n[0] - 1);
  // The slab in sample units: x and z inside the box by RampSamples, y from the bottom
  // (kept RampSamples inside) up to the top surface.
  const double top = (n[1] - 1) - RampSamples - 1.0;
  const double bottom = top - SlabSamples;
  out->SetDimensions(n[0], n[1], n[2]);
  out->SetSpacing(spacing, spacing, spacing);
  out->SetOrigin(0.5 * (objectBounds[0] + objectBounds[1]) - 0.5 * width,
    objectBounds[2] - top * spacing, 0.5 * (objectBounds[4] + objectBounds[5]) - 0.5 * width);
  out->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* density = static_cast<unsigned char*>(out->GetScalarPointer());
  // Signed distance in samples inside the slab (positive inside), by the nearest face.
  const auto inside = [&](int i, int j, int k) {
    const double x = std::min(i - RampSamples, (n[0] - 1) - RampSamples - i);
    const double z = std::min(k - RampSamples, (n[2] - 1) - RampSamples - k);
    const double y = std::min(j - bottom, top - j);
    return std::min({ x, y, z });
  };
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        const double d = std::clamp(0.5 + inside(i, j, k) / RampSamples, 0.0, 1.0);
        *density++ = static_cast<unsigned char>(std::lround(255.0 * d));
      }
    }
  }
}

//------------------------------------------------------------------------------
void SetUpSurfaceProperty(double iso, const double rgb[3], vtkVolumeProperty* property)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 1.0);
  opacity->AddPoint(255.0, 1.0);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, rgb[0], rgb[1], rgb[2]);
  color->AddRGBPoint(255.0, rgb[0], rgb[1], rgb[2]);
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetInterpolationTypeToLinear();
  property->GetIsoSurfaceValues()->SetValue(0, iso);
  property->ShadeOn();
}
}
