#include "vtkPARCOverrides.h"

#include "vtkObjectFactory.h"
#include "vtkPARCGPUVolumeRayCastMapper.h"
#include "vtkPARCVolumeMapper.h"
#include "vtkSmartPointer.h"
#include "vtkSmartVolumeMapper.h"
#include "vtkVersion.h"

#include <cstdlib>
#include <cstring>

vtkStandardNewMacro(vtkPARCOverrides);

namespace
{
constexpr const char* Overridden = "vtkGPUVolumeRayCastMapper";
constexpr const char* Ours = "vtkPARCGPUVolumeRayCastMapper";
/// VTK's own override of the GPU mapper (module RenderingVolumeOpenGL2).
constexpr const char* VTKs = "vtkOpenGLGPUVolumeRayCastMapper";

VTK_CREATE_CREATE_FUNCTION(vtkPARCGPUVolumeRayCastMapper);

/// The factory that makes vtkPARCGPUVolumeRayCastMapper for vtkGPUVolumeRayCastMapper.
class vtkPARCObjectFactory : public vtkObjectFactory
{
public:
  static vtkPARCObjectFactory* New();
  vtkTypeMacro(vtkPARCObjectFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override
  {
    return "PARC: vtkGPUVolumeRayCastMapper rendered by vtkPARCVolumeMapper";
  }

protected:
  vtkPARCObjectFactory()
  {
    this->RegisterOverride(Overridden, Ours, "PARC CPU ray casting", 1,
      vtkObjectFactoryCreatevtkPARCGPUVolumeRayCastMapper);
  }

private:
  vtkPARCObjectFactory(const vtkPARCObjectFactory&) = delete;
  void operator=(const vtkPARCObjectFactory&) = delete;
};
vtkStandardNewMacro(vtkPARCObjectFactory);

/// The factory, registered on the first Enable and kept for the program's life (VTK's
/// registry holds it too), as module factories are.
vtkPARCObjectFactory* Factory(bool create)
{
  static vtkSmartPointer<vtkPARCObjectFactory> factory;
  if (!factory && create)
  {
    factory = vtkSmartPointer<vtkPARCObjectFactory>::New();
    vtkObjectFactory::RegisterFactory(factory);
  }
  return factory;
}

/// vtkSmartVolumeMapper's GPU mapper (a protected getter, reached through a pointer to
/// member formed in a derived class, as C++ allows).
struct SmartVolumeMapperAccess : vtkSmartVolumeMapper
{
  static vtkGPUVolumeRayCastMapper* GPUMapperOf(vtkSmartVolumeMapper* smart)
  {
    vtkGPUVolumeRayCastMapper* (vtkSmartVolumeMapper::*get)() =
      &SmartVolumeMapperAccess::GetGPUMapper;
    return (smart->*get)();
  }
};

/// Enables the override when the library loads and PARC_OVERRIDE_GPU_MAPPER is 1.
struct EnvironmentSwitch
{
  EnvironmentSwitch() { vtkPARCOverrides::EnableFromEnvironment(); }
} const environmentSwitch;
}

//------------------------------------------------------------------------------
void vtkPARCOverrides::Enable()
{
  Factory(true);
  vtkObjectFactory::SetAllEnableFlags(0, Overridden);
  vtkObjectFactory::SetAllEnableFlags(1, Overridden, Ours);
}

//------------------------------------------------------------------------------
void vtkPARCOverrides::Disable()
{
  vtkObjectFactory::SetAllEnableFlags(0, Overridden, Ours);
  vtkObjectFactory::SetAllEnableFlags(1, Overridden, VTKs);
}

//------------------------------------------------------------------------------
bool vtkPARCOverrides::IsEnabled()
{
  vtkPARCObjectFactory* factory = Factory(false);
  return factory && factory->GetEnableFlag(Overridden, Ours);
}

//------------------------------------------------------------------------------
bool vtkPARCOverrides::EnableFromEnvironment()
{
  const char* value = std::getenv("PARC_OVERRIDE_GPU_MAPPER");
  if (!value || std::strcmp(value, "1") != 0)
  {
    return false;
  }
  vtkPARCOverrides::Enable();
  return true;
}

//------------------------------------------------------------------------------
vtkPARCVolumeMapper* vtkPARCOverrides::GetPARCMapper(vtkVolumeMapper* mapper)
{
  if (auto* parc = vtkPARCVolumeMapper::SafeDownCast(mapper))
  {
    return parc;
  }
  if (auto* smart = vtkSmartVolumeMapper::SafeDownCast(mapper))
  {
    mapper = SmartVolumeMapperAccess::GPUMapperOf(smart);
  }
  auto* gpu = vtkPARCGPUVolumeRayCastMapper::SafeDownCast(mapper);
  return gpu ? gpu->GetPARCMapper() : nullptr;
}

//------------------------------------------------------------------------------
void vtkPARCOverrides::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Enabled: " << vtkPARCOverrides::IsEnabled() << "\n";
}
