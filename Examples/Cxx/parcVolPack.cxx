#include "parcVolPack.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkTimerLog.h>
#include <vtkVolume.h>
#include <vtkVolumeMapper.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>

#ifdef PARC_HAVE_VOLPACK
#include <volpack.h>
#endif

namespace parcvolpack
{
#ifndef PARC_HAVE_VOLPACK
struct Renderer::Internals
{
};

std::string Renderer::Unsupported(int, vtkVolume*, vtkImageData*, vtkCamera*)
{
  return "VolPack (Debian libvolpack1-dev) is not in this build";
}

Renderer::Renderer(vtkVolume*, vtkImageData*)
{
  throw std::logic_error(Unsupported(0, nullptr, nullptr, nullptr));
}

Renderer::~Renderer() = default;

double Renderer::ClassificationTime() const
{
  return 0.0;
}

std::vector<unsigned char> Renderer::Render(vtkCamera*, int, int, double&)
{
  return {};
}
#else
namespace
{
/// A voxel as VolPack reads it: the encoded normal and the density shade it, the density
/// classifies it.
struct Voxel
{
  std::uint16_t Normal;
  std::uint8_t Density;
  std::uint8_t Gradient;
};

constexpr int NormalField = 0;
constexpr int DensityField = 1;
constexpr int GradientField = 2;
constexpr int Densities = 256;
constexpr int Normals = VP_NORM_MAX + 1;
/// Voxels more transparent than this are left out of VolPack's run-length encoding (its
/// opacities have 8 bits).
constexpr double MinimumVoxelOpacity = 1.0 / 255.0;
/// VolPack's colours run from 0 to 255.
constexpr double MaxIntensity = 255.0;
/// The rays' early termination, as this project's mapper stops its rays.
constexpr double MaximumRayOpacity = 0.99;

void Check(vpContext* vpc, vpResult result, const char* what)
{
  if (result != VP_OK)
  {
    throw std::runtime_error(std::string("VolPack: ") + what + ": " +
      vpGetErrorString(vpGetError(vpc)));
  }
}

/// Sets VolPack's matrix `which` (VP_MODEL, VP_VIEW or VP_PROJECT) to matrix.
void SetMatrix(vpContext* vpc, int which, vtkMatrix4x4* matrix)
{
  vpMatrix4 m;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[r][c] = matrix->GetElement(r, c);
    }
  }
  Check(vpc, vpCurrentMatrix(vpc, which), "matrix");
  Check(vpc, vpSetMatrix(vpc, m), "matrix");
}
}

struct Renderer::Internals
{
  vpContext* Context = vpCreateContext();
  std::vector<Voxel> Voxels;
  std::vector<float> Opacity = std::vector<float>(Densities);
  /// The colour function's nodes are VolPack's materials, mixed by density with linear
  /// weights.
  std::vector<float> Weights;     ///< [density][material]
  std::vector<float> ColorTable;  ///< [normal][material][rgb]
  int Dims[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing = 1.0;
  double Classification = 0.0;
  bool Shaded = false;

  ~Internals() { vpDestroyContext(this->Context); }
};

std::string Renderer::Unsupported(
  int blendMode, vtkVolume* volume, vtkImageData* image, vtkCamera* camera)
{
  const double* spacing = image->GetSpacing();
  if (!camera->GetParallelProjection())
  {
    return "VolPack 1.0 renders parallel projections only";
  }
  if (blendMode != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    return "VolPack composites only";
  }
  if (image->GetScalarType() != VTK_UNSIGNED_CHAR || image->GetNumberOfScalarComponents() != 1)
  {
    return "VolPack classifies 8-bit scalars of one component";
  }
  if (spacing[0] != spacing[1] || spacing[1] != spacing[2] || !volume->GetMatrix()->IsIdentity())
  {
    return "VolPack's voxels are cubes here: isotropic spacing, no volume transform";
  }
  return "";
}

Renderer::Renderer(vtkVolume* volume, vtkImageData* image)
  : I(new Internals)
{
  vpContext* vpc = this->I->Context;
  vtkVolumeProperty* property = volume->GetProperty();
  image->GetDimensions(this->I->Dims);
  image->GetOrigin(this->I->Origin);
  this->I->Spacing = image->GetSpacing()[0];
  const int* n = this->I->Dims;
  const std::size_t count = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  this->I->Voxels.resize(count);
  Voxel* dummy = this->I->Voxels.data();
  Check(vpc, vpSetVolumeSize(vpc, n[0], n[1], n[2]), "volume size");
  Check(vpc, vpSetVoxelSize(vpc, sizeof(Voxel), 3, 2, 1), "voxel size");
  Check(vpc, vpSetVoxelField(vpc, NormalField, sizeof(std::uint16_t),
    vpFieldOffset(dummy, Normal), VP_NORM_MAX), "normal field");
  Check(vpc, vpSetVoxelField(vpc, DensityField, sizeof(std::uint8_t),
    vpFieldOffset(dummy, Density), Densities - 1), "density field");
  Check(vpc, vpSetVoxelField(vpc, GradientField, sizeof(std::uint8_t),
    vpFieldOffset(dummy, Gradient), VP_GRAD_MAX), "gradient field");
  const int x = sizeof(Voxel);
  Check(vpc, vpSetRawVoxels(vpc, dummy, static_cast<int>(count * sizeof(Voxel)), x, x * n[0],
    x * n[0] * n[1]), "voxels");
  auto* scalars =
    static_cast<unsigned char*>(image->GetPointData()->GetScalars()->GetVoidPointer(0));
  Check(vpc, vpVolumeNormals(vpc, scalars, static_cast<int>(count), DensityField, GradientField,
    NormalField), "normals");

  // Opacity per voxel value, and the colour function's nodes as materials.
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  for (int v = 0; v < Densities; ++v)
  {
    this->I->Opacity[v] = static_cast<float>(std::min(1.0, std::max(0.0, opacity->GetValue(v))));
  }
  Check(vpc, vpSetClassifierTable(vpc, 0, DensityField, this->I->Opacity.data(),
    static_cast<int>(this->I->Opacity.size() * sizeof(float))), "opacity table");
  vtkColorTransferFunction* color = property->GetRGBTransferFunction();
  std::vector<double> nodeValues;
  std::vector<std::array<double, 3>> nodeColors;
  for (int i = 0; i < color->GetSize(); ++i)
  {
    double node[6];
    color->GetNodeValue(i, node);
    nodeValues.push_back(node[0]);
    nodeColors.push_back({ node[1], node[2], node[3] });
  }
  const int materials = static_cast<int>(nodeColors.size());
  this->I->Weights.assign(static_cast<std::size_t>(Densities) * materials, 0.f);
  for (int v = 0; v < Densities; ++v)
  {
    const auto& x0 = nodeValues;
    const auto upper = std::upper_bound(x0.begin(), x0.end(), static_cast<double>(v));
    const int hi = std::min(static_cast<int>(upper - x0.begin()), materials - 1);
    const int lo = std::max(hi - 1, 0);
    const double width = x0[hi] - x0[lo];
    const double f = width > 0.0 ? std::min(1.0, std::max(0.0, (v - x0[lo]) / width)) : 1.0;
    this->I->Weights[v * materials + lo] += static_cast<float>(1.0 - f);
    this->I->Weights[v * materials + hi] += static_cast<float>(f);
  }
  this->I->ColorTable.assign(static_cast<std::size_t>(Normals) * materials * 3, 0.f);
  Check(vpc, vpSetLookupShader(vpc, 3, materials, NormalField, this->I->ColorTable.data(),
    static_cast<int>(this->I->ColorTable.size() * sizeof(float)), DensityField,
    this->I->Weights.data(), static_cast<int>(this->I->Weights.size() * sizeof(float))),
    "shader");
  this->I->Shaded = property->GetShade() != 0;
  if (this->I->Shaded)
  {
    Check(vpc, vpEnable(vpc, VP_LIGHT_BOTH_SIDES, 1), "two-sided lighting");
    for (int m = 0; m < materials; ++m)
    {
      const auto& c = nodeColors[m];
      const double ka = property->GetAmbient(), kd = property->GetDiffuse();
      const double ks = property->GetSpecular();
      Check(vpc, vpSetMaterial(vpc, VP_MATERIAL0 + m, VP_AMBIENT, VP_BOTH_SIDES, ka * c[0],
        ka * c[1], ka * c[2]), "material");
      Check(vpc, vpSetMaterial(vpc, VP_MATERIAL0 + m, VP_DIFFUSE, VP_BOTH_SIDES, kd * c[0],
        kd * c[1], kd * c[2]), "material");
      Check(vpc, vpSetMaterial(vpc, VP_MATERIAL0 + m, VP_SPECULAR, VP_BOTH_SIDES, ks, ks, ks),
        "material");
      Check(vpc, vpSetMaterial(vpc, VP_MATERIAL0 + m, VP_SHINYNESS, VP_BOTH_SIDES,
        property->GetSpecularPower(), 0.0, 0.0), "material");
    }
    Check(vpc, vpSetLight(vpc, VP_LIGHT0, VP_COLOR, 1.0, 1.0, 1.0), "light");
    Check(vpc, vpEnable(vpc, VP_LIGHT0, 1), "light");
  }
  else
  {
    for (int normal = 0; normal < Normals; ++normal)
    {
      for (int m = 0; m < materials; ++m)
      {
        for (int c = 0; c < 3; ++c)
        {
          this->I->ColorTable[(normal * materials + m) * 3 + c] =
            static_cast<float>(MaxIntensity * nodeColors[m][c]);
        }
      }
    }
  }
  Check(vpc, vpSetd(vpc, VP_MIN_VOXEL_OPACITY, MinimumVoxelOpacity), "minimum opacity");
  Check(vpc, vpSetd(vpc, VP_MAX_RAY_OPACITY, MaximumRayOpacity), "ray opacity");
  const double start = vtkTimerLog::GetUniversalTime();
  Check(vpc, vpClassifyVolume(vpc), "classification");
  this->I->Classification = vtkTimerLog::GetUniversalTime() - start;
}

Renderer::~Renderer() = default;

double Renderer::ClassificationTime() const
{
  return this->I->Classification;
}

std::vector<unsigned char> Renderer::Render(
  vtkCamera* camera, int width, int height, double& seconds)
{
  vpContext* vpc = this->I->Context;
  const int* n = this->I->Dims;
  // VolPack's object coordinates: voxel index i at (i - n/2) / max(n) per axis.
  const double maxDim = std::max({ n[0], n[1], n[2] });
  vtkNew<vtkMatrix4x4> objectToWorld;
  for (int a = 0; a < 3; ++a)
  {
    const double h = this->I->Spacing;
    objectToWorld->SetElement(a, a, maxDim * h);
    objectToWorld->SetElement(a, 3, this->I->Origin[a] + 0.5 * n[a] * h);
  }
  // VolPack's model, view and projection matrices as VTK's: the viewer looks down -z in eye
  // coordinates in both, and VolPack shades with the view matrix's eye direction.
  vtkNew<vtkMatrix4x4> projection;
  projection->DeepCopy(
    camera->GetProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0));
  // VolPack puts pixel x at clip coordinate 2x / width - 1, VTK at (2x + 1) / width - 1:
  // half a pixel to the left and down.
  for (int c = 0; c < 4; ++c)
  {
    const double w = projection->GetElement(3, c);
    projection->SetElement(0, c, projection->GetElement(0, c) - w / width);
    projection->SetElement(1, c, projection->GetElement(1, c) - w / height);
  }
  SetMatrix(vpc, VP_MODEL, objectToWorld);
  SetMatrix(vpc, VP_VIEW, camera->GetViewTransformMatrix());
  SetMatrix(vpc, VP_PROJECT, projection);
  if (this->I->Shaded) // a headlight: the direction towards it, in world coordinates
  {
    double direction[3];
    camera->GetDirectionOfProjection(direction);
    Check(vpc, vpSetLight(vpc, VP_LIGHT0, VP_DIRECTION, -direction[0], -direction[1],
      -direction[2]), "light");
  }
  std::vector<unsigned char> rgb(static_cast<std::size_t>(width) * height * 3);
  Check(vpc, vpSetImage(vpc, rgb.data(), width, height, width * 3, VP_RGB), "image");
  const double start = vtkTimerLog::GetUniversalTime();
  if (this->I->Shaded)
  {
    Check(vpc, vpShadeTable(vpc), "shading table");
  }
  Check(vpc, vpRenderClassifiedVolume(vpc), "render");
  seconds = vtkTimerLog::GetUniversalTime() - start;
  return rgb;
}
#endif
}
