// PARC for VTK examples: parc-render's studies, each a measurement printed as a markdown
// table (acceleration modes side by side, the paper's Table 3, against FixedPoint, budgets,
// sample and edit costs, Auto's trial frames, thread scaling, supercell sizes).
#ifndef parcRenderStudies_h
#define parcRenderStudies_h

#include <vector> // For std::vector

class vtkImageData;
class vtkPARCVolumeMapper;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

namespace parcstudies
{
/// Every acceleration mode side by side in one run (markdown table).
void CompareAccelerationModes(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, int repeat);

/// The paper's Table 3: rounds interleaved frames without and with shadows, for
/// acceleration none and PARC (depth buffers, colour buffers, Auto) on primary and shadow
/// rays, each with its own mapper (markdown tables: the paper's columns, then the ratios
/// beside the paper's). "Total with shadows" is a shadowed frame plus its light passes, as
/// when the lights move every frame (the passes are otherwise cached).
void ShadowTable(vtkRenderWindow* window, vtkRenderer* renderer, vtkVolume* prop,
  vtkPARCVolumeMapper* parc, int rounds);

/// rounds x (this mapper without acceleration, with Auto, for each shading model when the
/// scene is shaded, then vtkFixedPointVolumeRayCastMapper), interleaved after a warm-up of
/// each (markdown table of wall times per frame).
void VersusFixedPoint(vtkRenderWindow* window, vtkVolume* volume, vtkPARCVolumeMapper* parc,
  vtkImageData* image, int rounds);

/// Interaction under a render-time budget: for each mapper in turn (PARC with Auto warmed
/// up, vtkFixedPointVolumeRayCastMapper), twice (A B A B), a still frame, 30 frames of a
/// rotation at the desired update rate and a still frame again (markdown table of frame
/// times against the budget). A mapper's budget control reads the renderer's last frame,
/// so the mappers take turns by whole rotations, not frame by frame.
void BudgetRotation(vtkRenderWindow* window, vtkRenderer* renderer, vtkVolume* volume,
  vtkPARCVolumeMapper* parc, vtkImageData* image, double rate);

/// Casting cost per sample (unshaded) and per contributing shaded sample (the shaded cast
/// minus the unshaded one) for each shading model, acceleration none, rounds interleaved
/// (markdown table).
void SampleCost(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property,
  int rounds);

/// Transfer-function edits: rounds times, a small change of the scalar opacity (a node
/// moved back and forth, so that the classification changes), then the frame right after it
/// and the next, warm one (markdown table of wall times and the ratio of medians).
void EditCost(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property,
  int rounds);

/// Auto's trial frames: rounds times a fresh mapper like mapper in Auto renders until it has
/// settled (its first frame also builds everything), then 3 more frames. Per round: the
/// modes and wall times of the frames, and the slowest frame after the first against the
/// median settled frame (markdown table).
void AutoTrialFrames(vtkRenderWindow* window, vtkVolume* volume, vtkPARCVolumeMapper* mapper,
  int rounds);

/// Scaling with threads: per acceleration mode, rounds frames with one thread interleaved
/// with frames with all threads (markdown table of the medians of the frame, of the
/// mapper's casting and of its GL passes, and the frame's and the casting's ratios).
void ThreadScaling(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, int rounds);

/// Polygons against ray steps: cubic supercells of each size (markdown table).
void SweepSupercells(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper,
  const std::vector<double>& sizes, int repeat);
}

#endif
