/**
 * @class   vtkPARCStatisticsInformation
 * @brief   The statistics of the last render of a "PARC Volume", gathered from the ranks.
 *
 * Gathered from the vtkPARCVolumeRepresentation of every rendering process (pvbatch's or
 * pvserver's ranks, or the built-in server) to the client: the samples, rays and shadow
 * rays summed over the ranks, the times of the slowest rank, and the acceleration mode of
 * the first rank that rendered.
 *
 * @sa vtkSMPARCVolumeRepresentationProxy vtkPARCVolumeRepresentation
 */
#ifndef vtkPARCStatisticsInformation_h
#define vtkPARCStatisticsInformation_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkPVInformation.h"

#include <string> // For the acceleration mode

class PARCPARAVIEW_EXPORT vtkPARCStatisticsInformation : public vtkPVInformation
{
public:
  static vtkPARCStatisticsInformation* New();
  vtkTypeMacro(vtkPARCStatisticsInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Reads the statistics of a vtkPARCVolumeRepresentation on this process. */
  void CopyFromObject(vtkObject* object) override;
  /** Adds another rank's: sums of the counts, maxima of the times. */
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;

  ///@{
  /** The seconds of the slowest rank. */
  vtkGetMacro(RenderTime, double);
  vtkGetMacro(CastingTime, double);
  vtkGetMacro(ProjectionTime, double);
  ///@}
  ///@{
  /** Summed over the ranks. */
  vtkGetMacro(SampleCount, vtkIdType);
  vtkGetMacro(RayCount, vtkIdType);
  vtkGetMacro(ShadowRayCount, vtkIdType);
  ///@}
  /** The acceleration mode of the first rank that rendered ("" when none did). */
  const char* GetAccelerationMode() const { return this->AccelerationMode.c_str(); }

protected:
  vtkPARCStatisticsInformation();
  ~vtkPARCStatisticsInformation() override;

private:
  vtkPARCStatisticsInformation(const vtkPARCStatisticsInformation&) = delete;
  void operator=(const vtkPARCStatisticsInformation&) = delete;

  double RenderTime = 0.0;
  double CastingTime = 0.0;
  double ProjectionTime = 0.0;
  vtkIdType SampleCount = 0;
  vtkIdType RayCount = 0;
  vtkIdType ShadowRayCount = 0;
  std::string AccelerationMode;
};

#endif
