"""PARC for VTK: exact volume ray casting accelerated by polygon projection.

    from parc import vtkPARCVolumeMapper

Importing the package also loads VTK's OpenGL rendering modules, so the
render window and volume display classes have their OpenGL implementations.
"""
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (factory overrides)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

from .PARCRendering import *  # noqa: F401,F403
