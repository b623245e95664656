"""PARC for VTK: exact volume ray casting accelerated by polygon projection.

    from parc import vtkPARCVolumeMapper

Importing the package also loads VTK's OpenGL rendering modules, so the
render window and volume display classes have their OpenGL implementations.

    import parc
    parc.enable_overrides()

makes vtkGPUVolumeRayCastMapper() (and the GPU mapper vtkSmartVolumeMapper builds)
a vtkPARCGPUVolumeRayCastMapper from then on; parc.disable_overrides() restores
VTK's own. PARC_OVERRIDE_GPU_MAPPER=1 in the environment enables it at import.
"""
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (factory overrides)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

from .PARCRendering import *  # noqa: F401,F403
from .PARCRendering import vtkPARCOverrides


def enable_overrides():
    """vtkGPUVolumeRayCastMapper() returns a PARC mapper from now on (vtkPARCOverrides)."""
    vtkPARCOverrides.Enable()


def disable_overrides():
    """vtkGPUVolumeRayCastMapper() returns VTK's OpenGL mapper again."""
    vtkPARCOverrides.Disable()


def overrides_enabled():
    """Whether vtkGPUVolumeRayCastMapper() returns a PARC mapper now."""
    return vtkPARCOverrides.IsEnabled()


# The library enabled the override when it loaded if PARC_OVERRIDE_GPU_MAPPER=1; VTK's
# OpenGL volume module, imported above, registered its factory after it: enable again so
# that it stays off (a no-op otherwise).
vtkPARCOverrides.EnableFromEnvironment()
