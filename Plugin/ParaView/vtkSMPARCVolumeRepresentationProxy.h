/**
 * @class   vtkSMPARCVolumeRepresentationProxy
 * @brief   The proxy of "PARC Volume": its statistics come from the rendering ranks.
 *
 * ParaView pulls a representation's information properties from the client's own copy of
 * the representation when there is one, and a client connected to pvserver renders
 * nothing. This proxy fills the PARCLast* properties from a vtkPARCStatisticsInformation
 * gathered from the rendering processes instead, so that the GUI, pvpython, pvbatch and a
 * client of pvserver show the same: counts summed over the ranks, times of the slowest.
 *
 * @sa vtkPARCStatisticsInformation vtkPARCVolumeRepresentation
 */
#ifndef vtkSMPARCVolumeRepresentationProxy_h
#define vtkSMPARCVolumeRepresentationProxy_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkSMRepresentationProxy.h"

class PARCPARAVIEW_EXPORT vtkSMPARCVolumeRepresentationProxy : public vtkSMRepresentationProxy
{
public:
  static vtkSMPARCVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSMPARCVolumeRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSMPARCVolumeRepresentationProxy();
  ~vtkSMPARCVolumeRepresentationProxy() override;

  /** The superclass's pull, then the PARCLast* properties from the rendering ranks. */
  void UpdatePropertyInformationInternal(vtkSMProperty* property = nullptr) override;

private:
  vtkSMPARCVolumeRepresentationProxy(const vtkSMPARCVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSMPARCVolumeRepresentationProxy&) = delete;
};

#endif
