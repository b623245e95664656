/**
 * @class   vtkPARCPVPolygonModelFilter
 * @brief   vtkPARCPolygonModelFilter with the transfer functions ParaView edits.
 *
 * ParaView's proxies hand a filter an opacity function (a "piecewise_functions" proxy)
 * rather than a vtkVolumeProperty: this subclass keeps its own volume property and sets
 * the given scalar opacity function and iso values on it. Only opacity and iso values
 * decide which cells may contribute; colour does not.
 *
 * @sa vtkPARCPolygonModelFilter vtkPARCVolumeRepresentation
 */
#ifndef vtkPARCPVPolygonModelFilter_h
#define vtkPARCPVPolygonModelFilter_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkPARCPolygonModelFilter.h"

class vtkPiecewiseFunction;

class PARCPARAVIEW_EXPORT vtkPARCPVPolygonModelFilter : public vtkPARCPolygonModelFilter
{
public:
  static vtkPARCPVPolygonModelFilter* New();
  vtkTypeMacro(vtkPARCPVPolygonModelFilter, vtkPARCPolygonModelFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The scalar opacity function of component 0 (null: VTK's default, opaque everywhere).
   */
  void SetScalarOpacityFunction(vtkPiecewiseFunction* function);

  ///@{
  /**
   * The iso values of the isosurface blend mode.
   */
  void SetNumberOfIsosurfaces(int number);
  void SetIsosurfaceValue(int i, double value);
  ///@}

protected:
  vtkPARCPVPolygonModelFilter();
  ~vtkPARCPVPolygonModelFilter() override;

private:
  vtkPARCPVPolygonModelFilter(const vtkPARCPVPolygonModelFilter&) = delete;
  void operator=(const vtkPARCPVPolygonModelFilter&) = delete;
};

#endif
