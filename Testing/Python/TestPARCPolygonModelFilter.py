"""vtkPARCPolygonModelFilter from Python: the depth model of the wavelet is a closed
surface whose statistics match its polygons, merging keeps the area with fewer quads, the
colour model numbers its planes from 0, a transfer-function change re-executes the
filter, with LabelMap the labels' opacities classify the cells as the mapper's with a
label-map mask, a bad supercell size gives an error and an empty model, and the model
renders through vtkPolyDataMapper."""
import unittest

from parc import vtkPARCPolygonModelFilter, vtkPARCVolumeMapper
from vtkmodules.vtkCommonCore import VTK_UNSIGNED_CHAR, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkFeatureEdges
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkVolumeProperty,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkVolumeMapper

from parctesthelpers import offscreen_window, offscreen_window_showing


def statistic(poly, name):
    return poly.GetFieldData().GetArray(name).GetValue(0)


def total_area(poly):
    sizes = vtkCellSizeFilter()
    sizes.SetInputData(poly)
    sizes.ComputeSumOn()
    sizes.Update()
    return sizes.GetOutput().GetFieldData().GetArray("Area").GetValue(0)


class ErrorObserver:
    def __init__(self):
        self.messages = []

    def __call__(self, caller, event, data=None):
        self.messages.append(event)


class TestPolygonModelFilter(unittest.TestCase):
    def setUp(self):
        self.source = vtkRTAnalyticSource()  # the wavelet, values about 37..277
        self.source.SetWholeExtent(-16, 16, -16, 16, -16, 16)
        self.opacity = vtkPiecewiseFunction()
        self.opacity.AddPoint(200, 0.0)
        self.opacity.AddPoint(260, 0.5)
        self.property = vtkVolumeProperty()
        self.property.SetScalarOpacity(self.opacity)
        self.filter = vtkPARCPolygonModelFilter()
        self.filter.SetInputConnection(self.source.GetOutputPort())
        self.filter.SetVolumeProperty(self.property)
        self.filter.SetBlendMode(vtkVolumeMapper.COMPOSITE_BLEND)
        self.filter.SetSupercellSize(2, 2, 2)

    def model(self):
        self.filter.Update()
        out = vtkCleanPolyData()
        out.SetInputData(self.filter.GetOutput())
        out.Update()
        return self.filter.GetOutput(), out.GetOutput()

    def test_depth_model_is_closed_and_counted(self):
        poly, cleaned = self.model()
        self.assertGreater(poly.GetNumberOfCells(), 0)
        self.assertEqual(statistic(poly, "Polygons"), poly.GetNumberOfCells())
        self.assertEqual(statistic(poly, "Cells"), 32 ** 3)
        self.assertEqual(statistic(poly, "Supercells"), 16 ** 3)
        pc = statistic(poly, "ContributingSupercells")
        self.assertTrue(0 < pc < 16 ** 3)
        self.assertAlmostEqual(statistic(poly, "ContributingPercent"), 100.0 * pc / 16 ** 3)
        edges = vtkFeatureEdges()
        edges.SetInputData(cleaned)
        edges.BoundaryEdgesOn()
        edges.FeatureEdgesOff()
        edges.ManifoldEdgesOff()
        edges.NonManifoldEdgesOff()
        edges.Update()
        self.assertEqual(edges.GetOutput().GetNumberOfCells(), 0, "no boundary edge")

    def test_merging_keeps_the_area(self):
        poly, _ = self.model()
        area, quads = total_area(poly), poly.GetNumberOfCells()
        self.filter.MergeFacesOn()
        merged, _ = self.model()
        self.assertLess(merged.GetNumberOfCells(), quads)
        self.assertAlmostEqual(total_area(merged), area, delta=1e-9 * area)

    def test_color_model_planes(self):
        self.filter.SetModelToColor()
        self.filter.SetMajorAxis(0)
        poly, _ = self.model()
        planes = poly.GetCellData().GetArray("PlaneIndex")
        self.assertIsNotNone(planes)
        lo, hi = planes.GetRange()
        self.assertEqual(lo, 0)
        self.assertGreater(hi, 0)
        self.assertLess(hi, 16)

    def test_transfer_function_change_reexecutes(self):
        poly, _ = self.model()
        before = statistic(poly, "ContributingSupercells")
        self.opacity.AddPoint(120, 0.0)
        self.opacity.AddPoint(140, 0.2)
        self.opacity.AddPoint(160, 0.0)
        poly, _ = self.model()
        self.assertGreater(statistic(poly, "ContributingSupercells"), before)

    def test_classifies_only_when_its_inputs_change(self):
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 1)
        self.assertEqual(statistic(poly, "PyramidBuilds"), 1)
        # Another model, axis or face merging of the same classification: none new.
        self.filter.SetModelToColor()
        for axis in range(3):
            self.filter.SetMajorAxis(axis)
            poly, _ = self.model()
        self.filter.MergeFacesOn()
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 1)
        # A transfer function, blend mode or supercell size: a new one, on the same pyramid.
        self.opacity.AddPoint(230, 0.1)
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 2)
        self.filter.SetBlendMode(vtkVolumeMapper.MAXIMUM_INTENSITY_BLEND)
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 3)
        self.filter.SetSupercellSize(4, 4, 4)
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 4)
        self.assertEqual(statistic(poly, "PyramidBuilds"), 1)
        # New scalars: a new pyramid.
        self.source.SetMaximum(300.0)
        poly, _ = self.model()
        self.assertEqual(statistic(poly, "Classifications"), 5)
        self.assertEqual(statistic(poly, "PyramidBuilds"), 2)

    def test_isosurface_and_progress(self):
        self.property.GetIsoSurfaceValues().SetValue(0, 150.0)
        self.filter.SetBlendMode(vtkVolumeMapper.ISOSURFACE_BLEND)
        progress = []
        self.filter.AddObserver(vtkCommand.ProgressEvent,
                                lambda caller, event: progress.append(caller.GetProgress()))
        poly, _ = self.model()
        self.assertGreater(poly.GetNumberOfCells(), 0)
        self.assertEqual(progress, sorted(progress))
        self.assertEqual(progress[-1], 1.0)

    def test_bad_supercell_size(self):
        errors = ErrorObserver()
        self.filter.AddObserver(vtkCommand.ErrorEvent, errors)
        self.filter.SetSupercellSize(0, 1, 1)
        self.filter.Update()
        self.assertEqual(self.filter.GetOutput().GetNumberOfCells(), 0)
        self.assertEqual(len(errors.messages), 1)

    def label_map_counts(self):
        """The filter's contributing supercells, and vtkPARCVolumeMapper's with a label map
        (every voxel of label 1) at the same supercell size."""
        poly, _ = self.model()
        labels = vtkImageData()
        labels.CopyStructure(self.source.GetOutput())
        labels.AllocateScalars(VTK_UNSIGNED_CHAR, 1)
        labels.GetPointData().GetScalars().Fill(1)
        mapper = vtkPARCVolumeMapper()
        mapper.SetInputConnection(self.source.GetOutputPort())
        mapper.SetMaskInput(labels)
        mapper.SetMaskTypeToLabelMap()
        mapper.SetMaskBlendFactor(1.0)
        mapper.SetAccelerationModeToDepthBuffer()
        mapper.SetSupercellSize(2, 2, 2)
        window = offscreen_window(mapper, self.property, 64)
        window.Render()
        return statistic(poly, "ContributingSupercells"), mapper.GetLastContributingSupercellCount()

    def test_label_map_classifies_as_the_mapper(self):
        default_only = statistic(self.model()[0], "ContributingSupercells")
        label = vtkPiecewiseFunction()  # a band below the default opacity's
        label.AddPoint(100, 0.0)
        label.AddPoint(120, 0.3)
        label.AddPoint(140, 0.0)
        self.property.SetLabelScalarOpacity(1, label)
        self.assertEqual(statistic(self.model()[0], "ContributingSupercells"), default_only,
                         "without LabelMap the labels' functions are not read")
        self.filter.LabelMapOn()
        filtered, mapped = self.label_map_counts()
        self.assertGreater(filtered, default_only)
        self.assertEqual(filtered, mapped)
        label.RemoveAllPoints()  # a label function edit re-executes the filter
        label.AddPoint(0, 0.0)
        filtered, mapped = self.label_map_counts()
        self.assertEqual(filtered, default_only)
        self.assertEqual(filtered, mapped)
        errors = ErrorObserver()
        self.filter.AddObserver(vtkCommand.ErrorEvent, errors)
        self.filter.SetBlendMode(vtkVolumeMapper.MAXIMUM_INTENSITY_BLEND)
        self.filter.Update()
        self.assertEqual(self.filter.GetOutput().GetNumberOfCells(), 0)
        self.assertEqual(len(errors.messages), 1)

    def test_renders_through_a_polydata_mapper(self):
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(self.filter.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        window = offscreen_window_showing(actor, 100)
        window.Render()
        grab = vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.Update()
        pixels = grab.GetOutput().GetPointData().GetScalars()
        lit = sum(1 for i in range(pixels.GetNumberOfTuples()) if pixels.GetTuple3(i) != (0, 0, 0))
        self.assertGreater(lit, 100)


if __name__ == "__main__":
    unittest.main()
