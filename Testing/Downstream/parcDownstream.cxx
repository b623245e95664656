// Renders a ball of density with vtkPARCVolumeMapper from an installed PARC, and checks
// that the volume shows: exit 0 when the centre pixel is lit and a corner is not.
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPARCVolumeMapper.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <iostream>

int main()
{
  constexpr int size = 64;
  vtkNew<vtkImageData> image;
  image->SetDimensions(32, 32, 32);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* values = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int k = 0; k < 32; ++k)
  {
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        const double r2 = (i - 15.5) * (i - 15.5) + (j - 15.5) * (j - 15.5) + (k - 15.5) * (k - 15.5);
        *values++ = r2 < 100.0 ? 200 : 0;
      }
    }
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(255.0, 1.0);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  color->AddRGBPoint(255.0, 1.0, 1.0, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(color);

  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->ResetCamera();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  window->Render();

  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, size - 1, size - 1, 0, pixels);
  const unsigned char* centre = pixels->GetPointer(3 * (size / 2 * size + size / 2));
  const unsigned char* corner = pixels->GetPointer(0);
  const bool lit = centre[0] > 100 && corner[0] == 0;
  std::cout << mapper->GetClassName() << ": centre " << int(centre[0]) << ", corner "
            << int(corner[0]) << (lit ? ", the volume shows" : ", the volume does not show")
            << std::endl;
  return lit ? 0 : 1;
}
