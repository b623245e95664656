/**
 * @class   vtkPARCPolygonModelFilter
 * @brief   The PARC polygon model of a volume: the faces of its possibly contributing
 *          supercells, as quads.
 *
 * vtkPARCPolygonModelFilter classifies the cells of an image for a volume property and a
 * ray function (the vtkVolumeMapper blend modes), groups them into supercells of
 * m x n x p cells (positive real numbers; below 1 they are subcells) and outputs the
 * polygon model PARC projects (Sobierajski & Avila 1995, sections 2-4; Figure 9):
 *
 * - Depth model (default): the outer faces of the union of possibly contributing (PC)
 *   supercells. MergeFaces (both models) joins coplanar neighbouring faces into larger
 *   rectangles (same area, fewer polygons; the mapper merges); off by default so the counts
 *   compare with the paper's.
 * - Colour model: for MajorAxis (0, 1, 2), every face of every PC supercell except those
 *   shared with a PC supercell of the same plane, with the cell array "PlaneIndex" (0 for
 *   the first plane along +axis holding a PC supercell).
 *
 * Quads are in the image's physical coordinates (origin, spacing, direction matrix),
 * wound counter-clockwise seen from outside. The field data holds the statistics of the
 * paper's Table 4 as one-tuple arrays: "Cells", "Supercells", "ContributingSupercells",
 * "ContributingPercent" and "Polygons".
 *
 * The filter updates when the property or its transfer functions change; the data's cell
 * ranges are kept between updates, so a transfer-function change only reclassifies.
 * Bad input (fewer than 2 samples along an axis, zero spacing, unsupported scalar type,
 * invalid supercell size) gives an error and an empty output.
 *
 * @sa vtkPARCVolumeMapper
 */
#ifndef vtkPARCPolygonModelFilter_h
#define vtkPARCPolygonModelFilter_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For std::unique_ptr

class vtkVolumeProperty;

class PARCRENDERING_EXPORT vtkPARCPolygonModelFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkPARCPolygonModelFilter* New();
  vtkTypeMacro(vtkPARCPolygonModelFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Models
  {
    DEPTH_MODEL = 0,
    COLOR_MODEL = 1
  };

  ///@{
  /**
   * The volume property whose transfer functions (component 0) and iso values classify
   * the cells. Without one, a default vtkVolumeProperty is used.
   */
  void SetVolumeProperty(vtkVolumeProperty* property);
  vtkGetObjectMacro(VolumeProperty, vtkVolumeProperty);
  ///@}

  ///@{
  /**
   * The ray function, as a vtkVolumeMapper blend mode (COMPOSITE_BLEND, ...,
   * SLICE_BLEND; a slice's cells are classified as a composite volume's, by where the
   * opacity is not zero, though the mapper draws slices without a pass). Default:
   * composite.
   */
  vtkSetMacro(BlendMode, int);
  vtkGetMacro(BlendMode, int);
  ///@}

  ///@{
  /**
   * The scalar range averaged by AVERAGE_INTENSITY_BLEND (as in vtkVolumeMapper).
   */
  vtkSetVector2Macro(AverageIPScalarRange, double);
  vtkGetVectorMacro(AverageIPScalarRange, double, 2);
  ///@}

  ///@{
  /**
   * Supercell size in cells along x, y, z; positive and finite. Default 1 x 1 x 1.
   */
  vtkSetVector3Macro(SupercellSize, double);
  vtkGetVector3Macro(SupercellSize, double);
  ///@}

  ///@{
  /**
   * Which model to output. Default: depth.
   */
  vtkSetClampMacro(Model, int, DEPTH_MODEL, COLOR_MODEL);
  vtkGetMacro(Model, int);
  void SetModelToDepth() { this->SetModel(DEPTH_MODEL); }
  void SetModelToColor() { this->SetModel(COLOR_MODEL); }
  ///@}

  ///@{
  /**
   * The volume axis (0, 1, 2) whose planes number the colour model. Default 2.
   */
  vtkSetClampMacro(MajorAxis, int, 0, 2);
  vtkGetMacro(MajorAxis, int);
  ///@}

  ///@{
  /**
   * Merge coplanar neighbouring faces of the depth model. Default off.
   */
  vtkSetMacro(MergeFaces, bool);
  vtkGetMacro(MergeFaces, bool);
  vtkBooleanMacro(MergeFaces, bool);
  ///@}

  ///@{
  /**
   * Classify as vtkPARCVolumeMapper does with a label-map mask (SetMaskTypeToLabelMap and
   * a MaskBlendFactor above 0): a cell may contribute where the default scalar opacity or
   * any label's (vtkVolumeProperty::SetLabelScalarOpacity) is non-zero in its range. Label
   * maps apply to composite blending; other blend modes give an error and an empty output.
   * Default off: the default scalar opacity only, as the mapper classifies without a mask.
   */
  vtkSetMacro(LabelMap, bool);
  vtkGetMacro(LabelMap, bool);
  vtkBooleanMacro(LabelMap, bool);
  ///@}

  /**
   * Includes the property's (and its transfer functions') modification time, and with
   * LabelMap its labels' scalar opacities'.
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkPARCPolygonModelFilter();
  ~vtkPARCPolygonModelFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkVolumeProperty* VolumeProperty = nullptr;
  int BlendMode = 0;
  double AverageIPScalarRange[2] = { VTK_DOUBLE_MIN, VTK_DOUBLE_MAX };
  double SupercellSize[3] = { 1.0, 1.0, 1.0 };
  int Model = DEPTH_MODEL;
  int MajorAxis = 2;
  bool MergeFaces = false;
  bool LabelMap = false;

private:
  vtkPARCPolygonModelFilter(const vtkPARCPolygonModelFilter&) = delete;
  void operator=(const vtkPARCPolygonModelFilter&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
