// Masks (vtkGPUVolumeRayCastMapper::SetMaskInput): a binary mask that keeps the wavelet
// inside an ellipsoid, and a label map (SetMaskTypeToLabelMap) of two ellipsoids labelled
// 1 and 2 over the wavelet, each label with its own colour and opacity
// functions (vtkVolumeProperty::SetLabelColor, SetLabelScalarOpacity), label 0 with the
// default ones; blended fully (mask blend factor 1) and half-way (0.5). Compared with
// vtkGPUVolumeRayCastMapper. The two mappers disagree on the label of some samples within
// about half a voxel of a label's boundary (this mapper takes the nearest voxel's label;
// VTK's reads a label texture): a thin rim along label 2's edge, so this comparison allows
// 0.5% of the values beyond 24 levels, where the others allow 0.1%. VTK 9.1's GPU mapper
// needs the mask to hold every label that has functions (it scales the mask's values by
// their range).
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageEllipsoidSource.h>
#include <vtkImageMathematics.h>

namespace
{
/// An ellipsoid of the given label (0 outside) on the wavelet's voxels.
vtkSmartPointer<vtkImageEllipsoidSource> Ellipsoid(double x, double y, double z, int label)
{
  auto ellipsoid = vtkSmartPointer<vtkImageEllipsoidSource>::New();
  parcexample::SetVolumeExtent(ellipsoid.Get());
  ellipsoid->SetCenter(x, y, z);
  ellipsoid->SetRadius(14, 10, 18);
  ellipsoid->SetInValue(label);
  ellipsoid->SetOutValue(0);
  ellipsoid->SetOutputScalarTypeToUnsignedChar();
  return ellipsoid;
}

/// A binary mask: the wavelet inside an ellipsoid.
auto BinaryMaskScene()
{
  return [](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetMaskInput(parcexample::ZeroBased(Ellipsoid(-6, 0, 0, 1)));
    mapper->SetMaskTypeToBinary();
    parcexample::SampleAlike(mapper);
    parcexample::AddVolume(renderer, mapper, parcexample::MakeWaveletProperty());
  };
}

auto LabelScene(float blendFactor)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkImageMathematics> labels; // label 1 on the left, 2 on the right
    labels->SetOperationToMax();
    labels->SetInputConnection(0, Ellipsoid(-14, 0, 0, 1)->GetOutputPort());
    labels->SetInputConnection(1, Ellipsoid(14, 4, 0, 2)->GetOutputPort());
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetMaskInput(parcexample::ZeroBased(labels));
    mapper->SetMaskTypeToLabelMap();
    mapper->SetMaskBlendFactor(blendFactor);
    parcexample::SampleAlike(mapper);

    auto property = parcexample::MakeWaveletProperty();
    vtkNew<vtkColorTransferFunction> red;
    red->AddRGBPoint(0, 0.6, 0.0, 0.0);
    red->AddRGBPoint(254, 1.0, 0.3, 0.3);
    vtkNew<vtkPiecewiseFunction> dense;
    dense->AddPoint(60, 0.0);
    dense->AddPoint(254, 0.8);
    property->SetLabelColor(1, red);
    property->SetLabelScalarOpacity(1, dense);
    vtkNew<vtkColorTransferFunction> green;
    green->AddRGBPoint(0, 0.0, 0.5, 0.0);
    green->AddRGBPoint(254, 0.4, 1.0, 0.4);
    vtkNew<vtkPiecewiseFunction> faint;
    faint->AddPoint(100, 0.0);
    faint->AddPoint(254, 0.15);
    property->SetLabelColor(2, green);
    property->SetLabelScalarOpacity(2, faint);
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using parcexample::CompareWithVTK;
  parcexample::Tolerance labelRim = parcexample::AgainstGPU;
  labelRim.FarFraction = 0.005;
  return CompareWithVTK<vtkGPUVolumeRayCastMapper>(
           argc, argv, "BinaryMask", BinaryMaskScene(), parcexample::AgainstGPU) |
    CompareWithVTK<vtkGPUVolumeRayCastMapper>(argc, argv, "LabelMap", LabelScene(1.f), labelRim) |
    CompareWithVTK<vtkGPUVolumeRayCastMapper>(
      argc, argv, "LabelMapHalfBlend", LabelScene(0.5f), labelRim);
}
