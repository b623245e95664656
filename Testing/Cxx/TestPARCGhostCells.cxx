// Ghost cells, as a piece of a distributed volume holds them (ParaView's pvbatch and
// pvserver with MPI): a volume split along z into two pieces, each with one layer of its
// neighbour's cells marked in the cell ghost array, renders each piece's own cells only,
// with gradients and interpolation at the border reading the ghost layer. The two pieces'
// float ray-cast images, composited front to back, match the whole volume's to the float
// rounding of their sample points (point and cell scalars, shaded; the colour table over
// the colour function's own range, ColorRangeType NATIVE, as the pieces' data ranges
// differ), and each piece's image is bit-identical with and without acceleration. A piece
// that names its owned extent (vtkPARCVolumeMapper::SetOwnedExtent) instead of holding a
// ghost array draws the same float image bit for bit. With shadows, pieces holding the
// whole volume in their ghost layers cast the whole volume's shadows.
#include "parcTestScene.h"

#include <vtkCellData.h>
#include <vtkImageClip.h>
#include <vtkLight.h>
#include <vtkPointDataToCellData.h>
#include <vtkRendererCollection.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
/// The whole volume's point z index where the pieces meet.
constexpr int SplitZ = 24;
/// Largest difference, per float RGBA channel, between the whole image and its pieces
/// composited: the same samples, summed in another order, each at its ray point in the
/// piece's own index coordinates, computed in float from where the ray passes the piece
/// (parc::RayLattice: the pieces' points differ by float rounding, ~1e-5 voxel). About
/// 1e-5 here; with ColorRangeType SCALAR, the colour tables over each piece's data range,
/// about 3e-5.
constexpr double CompositeTolerance = 3e-5;
/// Ghost layers that give each piece the whole volume.
constexpr int WholeVolumeLayers = 1000;

/// How a piece tells the cells it owns from its border layers.
enum class Border
{
  GhostArray,
  OwnedExtent
};

/// The part of image between point z indices z0 and z1 (its own extent), plus layers of
/// its neighbours' cells on each side that has a neighbour, marked as border.
vtkSmartPointer<vtkImageData> Piece(
  vtkImageData* image, int z0, int z1, int layers, Border border = Border::GhostArray)
{
  int whole[6];
  image->GetExtent(whole);
  int owned[6] = { whole[0], whole[1], whole[2], whole[3], z0, z1 };
  vtkNew<vtkImageClip> clip;
  clip->SetInputData(image);
  clip->SetOutputWholeExtent(whole[0], whole[1], whole[2], whole[3],
    std::max(z0 - layers, whole[4]), std::min(z1 + layers, whole[5]));
  clip->ClipDataOn();
  clip->Update();
  auto piece = vtkSmartPointer<vtkImageData>::New();
  piece->DeepCopy(clip->GetOutput());
  if (border == Border::GhostArray)
  {
    piece->GenerateGhostArray(owned);
  }
  else
  {
    vtkPARCVolumeMapper::SetOwnedExtent(piece, owned);
  }
  return piece;
}

/// The float ray-cast image of image under the scene's fixed camera.
std::vector<float> Render(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper,
  vtkImageData* image, int mode)
{
  mapper->SetInputData(image);
  mapper->SetAccelerationMode(mode);
  window->Render();
  return parctest::RayImage(mapper);
}

/// front over back, premultiplied RGBA.
std::vector<float> Over(const std::vector<float>& front, const std::vector<float>& back)
{
  std::vector<float> out(front.size());
  for (std::size_t p = 0; p + 3 < front.size(); p += 4)
  {
    const float t = 1.f - front[p + 3];
    for (int c = 0; c < 4; ++c)
    {
      out[p + c] = front[p + c] + t * back[p + c];
    }
  }
  return out;
}

/// Checks one scalar association (point or cell scalars) and camera with pieces of the
/// given ghost layers; false on failure.
bool CheckSplit(vtkRenderWindow* window, vtkRenderer* renderer, vtkPARCVolumeMapper* mapper,
  vtkImageData* whole, int layers, const char* name)
{
  const int last = whole->GetExtent()[5];
  vtkSmartPointer<vtkImageData> low = Piece(whole, 0, SplitZ, layers);
  vtkSmartPointer<vtkImageData> high = Piece(whole, SplitZ, last, layers);
  const std::vector<float> reference =
    Render(window, mapper, whole, vtkPARCVolumeMapper::ACCELERATION_NONE);
  const std::vector<float> lowImage =
    Render(window, mapper, low, vtkPARCVolumeMapper::ACCELERATION_NONE);
  const std::vector<float> highImage =
    Render(window, mapper, high, vtkPARCVolumeMapper::ACCELERATION_NONE);
  bool ok = true;
  if (Render(window, mapper, Piece(whole, 0, SplitZ, layers, Border::OwnedExtent),
        vtkPARCVolumeMapper::ACCELERATION_NONE) != lowImage ||
    Render(window, mapper, Piece(whole, SplitZ, last, layers, Border::OwnedExtent),
      vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER) != highImage)
  {
    std::cerr << name << ": a piece that names its owned extent draws another image than "
              << "the piece with a ghost array\n";
    ok = false;
  }
  for (int mode : { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
         vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER })
  {
    if (Render(window, mapper, low, mode) != lowImage ||
      Render(window, mapper, high, mode) != highImage)
    {
      std::cerr << name << ": a piece's image with acceleration "
                << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode)
                << " differs from the one without\n";
      ok = false;
    }
  }
  // The eye on the low side of the split sees the low piece in front.
  const double* eye = renderer->GetActiveCamera()->GetPosition();
  const double splitZ = whole->GetOrigin()[2] + SplitZ * whole->GetSpacing()[2];
  const bool lowInFront = eye[2] < splitZ;
  const std::vector<float> composited =
    lowInFront ? Over(lowImage, highImage) : Over(highImage, lowImage);
  if (reference.empty() || composited.size() != reference.size())
  {
    std::cerr << name << ": no ray-cast image, or images of different sizes\n";
    return false;
  }
  double worst = 0.0, alpha = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i)
  {
    worst = std::max(worst, static_cast<double>(std::fabs(composited[i] - reference[i])));
    alpha = i % 4 == 3 ? std::max(alpha, static_cast<double>(reference[i])) : alpha;
  }
  std::cout << name << ": largest difference of the composited pieces " << worst
            << " (largest alpha " << alpha << ")\n";
  if (!(worst <= CompositeTolerance) || !(alpha > 0.5))
  {
    std::cerr << name << ": the composited pieces differ from the whole by " << worst
              << " > " << CompositeTolerance << ", or the scene is empty\n";
    ok = false;
  }
  return ok;
}
}

int TestPARCGhostCells(int argc, char* argv[])
{
  (void)argc;
  (void)argv;
  vtkSmartPointer<vtkImageData> points = parctest::MakeBlobs(48);
  vtkNew<vtkPointDataToCellData> toCells;
  toCells->SetInputData(points);
  toCells->Update();
  vtkNew<vtkImageData> cells;
  cells->DeepCopy(toCells->GetOutput());
  cells->GetCellData()->SetActiveScalars("density");

  vtkNew<vtkRenderWindow> window;
  window->SetSize(96, 80);
  window->SetMultiSamples(0);
  const double viewport[4] = { 0, 0, 1, 1 };
  vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(true);
  vtkSmartPointer<vtkPARCVolumeMapper> mapper = parctest::AddVolume(
    window, viewport, points, property, vtkVolumeMapper::COMPOSITE_BLEND);
  mapper->SetTerminationOpacity(1.0); // no early termination: each piece sees every sample
  mapper->SetColorRangeType(vtkPARCVolumeMapper::NATIVE);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  vtkCamera* camera = renderer->GetActiveCamera();

  bool ok = true;
  for (const bool turned : { false, true })
  {
    if (turned) // the other piece in front
    {
      camera->Azimuth(180);
      renderer->ResetCameraClippingRange();
    }
    mapper->SetScalarModeToUsePointData();
    ok = CheckSplit(window, renderer, mapper, points, 1, "point scalars") && ok;
    mapper->SetScalarModeToUseCellData();
    ok = CheckSplit(window, renderer, mapper, cells, 2, "cell scalars") && ok;
  }

  // Shadows: a shadow ray leaves its piece, so a piece whose ghost layers cover the whole
  // volume (ParaView's representation asks for them with shadows on several ranks) casts
  // the whole volume's shadows, and the pieces composited are again the whole image.
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(0.4, 0.3, -1.0); // across the split
  light->SetShadowAttenuation(1.0);
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  renderer->AddLight(light);
  mapper->SetShadowModeToOn();
  mapper->SetScalarModeToUsePointData();
  ok = CheckSplit(window, renderer, mapper, points, WholeVolumeLayers, "point scalars, shadows") &&
    ok;
  if (mapper->GetLastShadowRayCount() == 0)
  {
    std::cerr << "shadows: no shadow ray was cast\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
