/**
 * @class   vtkPARCVolumeMapper
 * @brief   Exact CPU volume ray casting, accelerated by Polygon Assisted Ray Casting (PARC).
 *
 * vtkPARCVolumeMapper renders a vtkImageData with one scalar component by casting one ray
 * per ray-image pixel on the CPU (in parallel with vtkSMPTools over image tiles) and
 * composites the result over the renderer's image. It follows Sobierajski & Avila, "A
 * Hardware Acceleration Method for Volumetric Ray Tracing" (1995): OpenGL passes project a
 * polygon model of the possibly contributing cells so that each ray samples only where
 * something can show (section 3: depth buffers, section 4: colour bit planes).
 *
 * Exactness contract: every acceleration mode gives a ray-cast image (see
 * GetLastRayCastImage) that is bit-identical, as float RGBA, to the one with acceleration
 * off. Rays sample a global lattice t_k = k * SampleDistance from the eye (perspective) or
 * from the plane through the camera position (parallel), whatever part of the ray is cast.
 *
 * In every acceleration mode, composite rays (one component, linear interpolation) also
 * leave out the samples of cells that cannot contribute without interpolating them: a bit
 * per cell, classified from the cell-range pyramid with the transfer functions (0.125
 * bytes a voxel, again only after an edit; GetCellClassificationCount,
 * GetLastEmptyCellSampleCount). Their opacity is 0, so the image is the same.
 *
 * Supported: scalar types (unsigned) char, short, int, float and double (point data, or
 * cell data as one voxel per cell at the cell's centre, as VTK's GPU mapper renders it;
 * up to 4 independent components, vtkVolumeProperty::IndependentComponentsOn, each with
 * its own colour, scalar and gradient opacity functions, shading and component weight,
 * combined per sample as VTK's ray cast mappers combine them, with composite, maximum and
 * minimum intensity blending (the quantized normals fall back to exact shading, and no
 * shadows are cast); dependent components,
 * vtkVolumeProperty::IndependentComponentsOff, as VTK defines them: 2 components give
 * colour through the colour function from the first and opacity and gradient from the
 * second, 4 unsigned char components give RGB directly from the first three and opacity
 * and gradient from the fourth); any origin, spacing
 * (non-zero), direction matrix and vtkVolume transform; scalar colour (gray or RGB) and
 * scalar opacity functions, opacity unit distance, gradient opacity, nearest and linear
 * interpolation (cubic is cast as linear), shading with the renderer's lights; blend modes
 * composite, maximum, minimum and average intensity, additive and isosurface (the iso values
 * of the property); parallel and perspective cameras with the eye anywhere; opaque geometry
 * of the same renderer (rays end at its depth).
 *
 * Documented results and limits:
 * - NaN scalars count as the smallest finite value, -inf as the smallest and +inf as the
 *   largest (a warning gives the number replaced), so a colour function's NaN colour does
 *   not apply. double and 32-bit integers are cast through float (24-bit mantissa).
 * - Transfer functions are sampled through their own GetColor and GetValue, so clamping,
 *   midpoints and sharpness, colour spaces and below- and above-range colours hold; a
 *   colour function into a table of 1024 entries over the data range (or its own range,
 *   ColorRangeType NATIVE), an opacity segment with a midpoint or sharpness into 32 linear
 *   pieces (classification needs piecewise-linear opacity).
 * - An image with fewer than 2 samples (cell scalars: cells) along an axis, zero spacing,
 *   no scalars or an unsupported type draws nothing and reports an error; so does an input
 *   that is not a vtkImageData (a vtkRectilinearGrid, say), with vtkResampleToImage named
 *   as the way out. A 2-D transfer function (vtkVolumeProperty TF_2D) warns once: the 1-D
 *   functions are used.
 * - The colour function is sampled into a 1024-entry table over the data range (or its
 *   own range: SetColorRangeType); opacity functions are evaluated from their nodes, no
 *   table (segments with a non-default midpoint or sharpness are subdivided into 32 linear
 *   pieces).
 * - Additive and average-intensity blending give grey images, as VTK defines them (see
 *   vtkVolumeMapper::SetBlendMode) and its GPU mapper draws them: each sample adds its value,
 *   normalised to the scalars' range, times its opacity (corrected for the sample
 *   distance); additive shows the sum, average the mean over the samples whose value lies
 *   in AverageIPScalarRange, clamped to [0, 1] and opaque. An additive ray that meets the
 *   volume is opaque even where nothing contributes (black); an average ray without a
 *   sample in the range draws nothing.
 * - Slice blending draws, for each ray, the one sample where it crosses the plane of the
 *   property's SliceFunction (a vtkPlane in world coordinates; anything else is an error
 *   and draws nothing) inside the volume: its colour, shaded when shading is on (without
 *   shadows), and its scalar opacity, uncorrected. No PARC pass is run for it (one sample
 *   a ray leaves nothing to skip); masks are not applied.
 * - Clipping planes (world coordinates) keep the side their normal points to; cropping keeps
 *   the regions of CroppingRegionFlags between CroppingRegionPlanes, given in the image's
 *   physical coordinates along its axes (origin and spacing; a direction matrix is not
 *   applied to them). A clipped or cropped ray is a shorter ray: no sample outside is taken,
 *   in every acceleration mode alike.
 * - Depth peeling: with the renderer's UseDepthPeelingForVolumes (ParaView's default), VTK's
 *   dual depth peeling renders volumes inside its peels through shader code only
 *   vtkGPUVolumeRayCastMapper provides; this mapper then draws its image when the renderer
 *   has finished, over the peeled translucent geometry, as VTK draws volumes when they are
 *   not peeled (the same pixels as with UseDepthPeelingForVolumes off). Translucent
 *   geometry in front of the volume is therefore not blended over it.
 * - Several windows: a mapper may move between windows; each PARC pass starts from the
 *   state its context really has, and a GL error other code left pending does not switch
 *   the passes off.
 * - Ghost cells (a piece of a distributed volume, as ParaView splits one across MPI ranks):
 *   when the image's cell ghost array marks cells as DUPLICATECELL, rays are cut to the box
 *   of the other cells, the piece's own, while interpolation and gradients at its border
 *   read the ghost layer. The pieces' ray-cast images, composited front to back, are the
 *   whole volume's up to float rounding when the pieces hold one ghost layer for point
 *   scalars and two for cell scalars (their gradients reach one cell further), no ray
 *   terminates early, and the colour tables do not follow each piece's own data range
 *   (ColorRangeType NATIVE). A piece may instead hold its border layers as ordinary cells
 *   and name the point extent it owns (SetOwnedExtent): the same rays, with no ghost array
 *   the size of the piece (ParaView's "PARC Volume" reads pieces this way).
 * - Transfer-function nodes with NaN are left out, opacities and colours are clamped to
 *   [0, 1] (one warning per property change); a scalar array shorter than the image, an
 *   unusable SampleDistance or ImageSampleDistance, and an isosurface without a finite iso
 *   value are errors. Supercells that would be too many for the volume are enlarged
 *   uniformly, with a warning.
 * - Positional lights use their attenuation and spot cone; shading is Blinn-Phong, two-sided,
 *   with each light's diffuse colour for the diffuse and its specular colour for the
 *   specular term (both times its intensity). The ambient term is the property's Ambient
 *   times the sample's colour, as vtkGPUVolumeRayCastMapper has it.
 *   vtkFixedPointVolumeRayCastMapper differs: it multiplies Ambient by each light's
 *   intensity and ambient colour, which is black for vtkLight's default, so that its shaded
 *   images lack the ambient term (an MRI head with Ambient 0.6: about 16 grey levels darker
 *   than this mapper's and the GPU mapper's). SetAmbientModelToLights follows FixedPoint.
 * - Gradient opacity functions map the gradient magnitude in scalar units per mean voxel
 *   spacing (the world gradient's magnitude times the mean of the image's spacing), as
 *   vtkFixedPointVolumeRayCastMapper and vtkGPUVolumeRayCastMapper measure it; with unit
 *   spacing, per world unit.
 *
 * Shadows (paper section 5): when the renderer uses shadows (vtkRenderer::UseShadowsOn, or
 * ShadowMode On) and a light has a ShadowAttenuation > 0 (vtkLight's default is 1), every
 * shaded contribution (a composite sample with non-zero opacity, an isosurface crossing)
 * that the light lights is lit only as far as the light gets through the volumes: the
 * light's diffuse and specular terms are scaled by 1 - ShadowAttenuation (1 - T), where T
 * is the transmittance towards the light along a shadow ray through all the rendered
 * volumes (composite volumes absorb with their corrected opacity, isosurfaces block with
 * the opacity of their iso value; maximum, minimum, average and additive volumes cast no
 * shadow). Each volume samples a shadow ray on its own lattice from the shaded point
 * (k dt, k >= 1), whatever the acceleration, so the shadowed image is as exact as the
 * unshadowed one. Opaque geometry of the renderer casts no shadow on the volumes. Without
 * both switches (shadows on, a shadow-casting light) no shadow ray is cast
 * (GetLastShadowRayCount is 0).
 *
 * Several volumes: with a vtkPARCMultiVolume prop, the mapper renders one volume per
 * input port (SetInputConnection(port, ...), ports 0 to MaxInputPorts - 1), each with the
 * property and transform of the vtkVolume the prop holds for that port
 * (vtkMultiVolume::SetVolume(volume, port)) and its own ray function (SetInputBlendMode),
 * scalar type, classification, PARC passes and Auto choice. Every ray meets every volume:
 * composite samples and isosurface crossings of all volumes are composited front to back
 * in depth order (at equal depth, the lower port first); a maximum, minimum or average
 * intensity or additive volume contributes its whole-ray result (its colour and opacity
 * as it would show alone) at one depth, that of its first sample with the extreme value,
 * its first averaged sample or its first contributing sample. A ray stops where the
 * composited opacity reaches TerminationOpacity, and at the latest where one composite or
 * isosurface volume's own opacity reaches it: nothing behind an opaque surface is sampled.
 * Each volume samples its own lattice (the common SampleDistance, or half its own smallest
 * voxel edge). With a plain vtkVolume, only port 0 is rendered.
 *
 * Events: each render that casts emits VolumeMapperRenderStartEvent, then after every band
 * of image rows VolumeMapperRenderProgressEvent (call data: a double*, the fraction cast)
 * and ProgressEvent (GetProgress), then VolumeMapperRenderEndEvent. SetAbortExecute(1) from
 * an observer, or the render window's abort check, stops the cast after the band.
 *
 * Thread safety: like every VTK mapper, use it from the rendering thread; it parallelizes
 * internally and the image is the same for any number of threads.
 *
 * @sa vtkFixedPointVolumeRayCastMapper vtkVolumeProperty
 */
#ifndef vtkPARCVolumeMapper_h
#define vtkPARCVolumeMapper_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkImageData;
class vtkRenderWindow;
class vtkVolumeProperty;

class PARCRENDERING_EXPORT vtkPARCVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkPARCVolumeMapper* New();
  vtkTypeMacro(vtkPARCVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum AccelerationModes
  {
    ACCELERATION_NONE = 0,
    ACCELERATION_DEPTH_BUFFER = 1,
    ACCELERATION_COLOR_BUFFER = 2,
    ACCELERATION_AUTO = 3,
    ACCELERATION_BOTH = 4,
    ACCELERATION_SUPERCELL_WALK = 5
  };

  ///@{
  /**
   * How rays are told where to sample. None casts each ray through the whole volume;
   * DepthBuffer projects the outer faces of the possibly contributing (PC) supercells into
   * near/far buffers and casts each ray only between them; ColorBuffer projects per-plane
   * faces into bit planes and casts only inside the planes a ray's bits name; Both
   * intersects the two. SupercellWalk draws nothing: each ray walks the PC supercells
   * on the CPU (blocks of 4^3 supercells, empty ones crossed several at a time) from its
   * front and its back to where it first and last may meet one, and is cast between (one
   * segment, as DepthBuffer, usually tighter); shadow rays walk the same way instead of
   * passes from the lights. It needs no GL pass, but walking costs each ray about as much
   * as tens of empty samples, so it pays on large, sparse volumes and rarely beats a depth
   * pass; Auto does not try it (Documentation/Features.md gives measurements). Auto picks
   * per volume, ray function and view: no pass when every supercell may contribute (none
   * can help), no sample when none may, and otherwise the
   * fastest of DepthBuffer, ColorBuffer, Both and None, measured: DepthBuffer first, then
   * a mode is tried on a still frame only when the measured frames predict it faster
   * (GetAutoTrialsRemaining; interactive frames of a render-time budget try none). None is
   * predicted from the samples the rays would take without acceleration and the measured
   * cost of a sample that contributes nothing, ColorBuffer from the depth pass's time and
   * samples, Both from both passes. The first still frame that needs no trial ends the
   * trials; then every frame uses the mode predicted fastest: its fastest frame for the
   * current classification or, after a transfer-function edit, its last frame with the
   * projection scaled by the number of PC supercells, and both times scaled by the
   * ray-image pixels; an edit or a new image size brings no trial frames.
   * After the view turns or moves markedly, or the image size changes, a mode's next frame
   * replaces its estimate.
   * GetLastAccelerationMode says which mode a frame used. The image is bit-identical in
   * every mode. When no OpenGL 3.3 context or framebuffer is available, the mapper warns
   * once and casts unaccelerated.
   * Default: Auto.
   */
  vtkSetClampMacro(AccelerationMode, int, ACCELERATION_NONE, ACCELERATION_SUPERCELL_WALK);
  vtkGetMacro(AccelerationMode, int);
  void SetAccelerationModeToNone() { this->SetAccelerationMode(ACCELERATION_NONE); }
  void SetAccelerationModeToDepthBuffer() { this->SetAccelerationMode(ACCELERATION_DEPTH_BUFFER); }
  void SetAccelerationModeToColorBuffer() { this->SetAccelerationMode(ACCELERATION_COLOR_BUFFER); }
  void SetAccelerationModeToAuto() { this->SetAccelerationMode(ACCELERATION_AUTO); }
  void SetAccelerationModeToBoth() { this->SetAccelerationMode(ACCELERATION_BOTH); }
  void SetAccelerationModeToSupercellWalk()
  {
    this->SetAccelerationMode(ACCELERATION_SUPERCELL_WALK);
  }
  static const char* GetAccelerationModeAsString(int mode);
  ///@}

  enum ShadingModels
  {
    SHADING_EXACT = 0,
    SHADING_QUANTIZED_NORMALS = 1
  };

  ///@{
  /**
   * How shaded samples (vtkVolumeProperty::ShadeOn) are lit. Exact, the default: the
   * gradient of the interpolated field at every sample, then Blinn-Phong with every light.
   * QuantizedNormals, as vtkFixedPointVolumeRayCastMapper shades: each voxel's gradient
   * direction is stored in 16 bits (2 bytes per voxel, made once per input), the
   * directional lights are evaluated once per render for every stored direction as seen
   * from one view direction (towards the eye from the volume's centre), and a sample
   * interpolates the results of its cell's 8 corners. Faster on shaded data, less accurate
   * (scripts/benchmark.sh compares the two against a fine reference). Scenes with a
   * positional or shadow-casting light are shaded exactly. Either model gives the same
   * image in every acceleration mode. GetLastShadingModel says which one a render used.
   */
  vtkSetClampMacro(ShadingModel, int, SHADING_EXACT, SHADING_QUANTIZED_NORMALS);
  vtkGetMacro(ShadingModel, int);
  void SetShadingModelToExact() { this->SetShadingModel(SHADING_EXACT); }
  void SetShadingModelToQuantizedNormals() { this->SetShadingModel(SHADING_QUANTIZED_NORMALS); }
  static const char* GetShadingModelAsString(int model);
  /** The shading model port 0's last render used (Exact when it was not shaded). */
  int GetLastShadingModel();
  ///@}

  enum AmbientModels
  {
    AMBIENT_MATERIAL = 0,
    AMBIENT_LIGHTS = 1
  };

  ///@{
  /**
   * Where the ambient term's light comes from. Material, the default, as
   * vtkGPUVolumeRayCastMapper under the renderer's own light: the property's Ambient times
   * the sample's colour, as under a white ambient light. Lights, as
   * vtkFixedPointVolumeRayCastMapper: Ambient times the sum of the switched-on lights'
   * ambient colours times their intensities, which is black for vtkLight's defaults, so
   * that the ambient term vanishes under VTK's default lights. A program written for
   * FixedPoint keeps its images' brightness with Lights.
   */
  vtkSetClampMacro(AmbientModel, int, AMBIENT_MATERIAL, AMBIENT_LIGHTS);
  vtkGetMacro(AmbientModel, int);
  void SetAmbientModelToMaterial() { this->SetAmbientModel(AMBIENT_MATERIAL); }
  void SetAmbientModelToLights() { this->SetAmbientModel(AMBIENT_LIGHTS); }
  static const char* GetAmbientModelAsString(int model);
  ///@}

  enum ShadowModes
  {
    SHADOWS_FROM_RENDERER = 0,
    SHADOWS_OFF = 1,
    SHADOWS_ON = 2
  };

  ///@{
  /**
   * Whether lights with a ShadowAttenuation > 0 cast shadows through the volumes (see
   * "Shadows" above): as the renderer says (vtkRenderer::UseShadows), the default; never;
   * or always, whatever the renderer says, for applications whose shadow switch does not
   * reach the renderer (ParaView's "PARC Volume" representation sets it from its
   * PARCShadows property). Only the volumes cast these shadows; UseShadows alone also turns
   * on VTK's shadow maps for opaque geometry.
   */
  vtkSetClampMacro(ShadowMode, int, SHADOWS_FROM_RENDERER, SHADOWS_ON);
  vtkGetMacro(ShadowMode, int);
  void SetShadowModeToFromRenderer() { this->SetShadowMode(SHADOWS_FROM_RENDERER); }
  void SetShadowModeToOff() { this->SetShadowMode(SHADOWS_OFF); }
  void SetShadowModeToOn() { this->SetShadowMode(SHADOWS_ON); }
  static const char* GetShadowModeAsString(int mode);
  ///@}

  enum TFRangeType
  {
    SCALAR = 0,
    NATIVE = 1
  };

  ///@{
  /**
   * The scalar range the colour function is sampled over (into its 1024-entry table), as
   * vtkGPUVolumeRayCastMapper::SetColorRangeType has it: SCALAR, the default, the data's
   * range; NATIVE, the colour function's own range (vtkColorTransferFunction::GetRange, or
   * the gray function's), values outside it taking its end colours. NATIVE makes pieces of
   * a distributed volume, whose data ranges differ, use the same table (ParaView's "PARC
   * Volume" sets it). Opacity functions are evaluated from their nodes either way.
   */
  vtkSetClampMacro(ColorRangeType, int, SCALAR, NATIVE);
  vtkGetMacro(ColorRangeType, int);
  ///@}

  ///@{
  /**
   * The point extent (in image's own extent coordinates) of the cells a piece of a
   * distributed volume owns, when image holds its neighbours' cells at its border as
   * ordinary cells: rays are cut to the owned cells as they are by a cell ghost array, and
   * interpolation and gradients read the border. Stored in image's field data (an int
   * array of 6 values named "vtkPARCOwnedExtent", kept through shallow copies); a cell
   * ghost array takes precedence. GetOwnedExtent returns false, leaving extent unchanged,
   * when image names none (it owns all its cells).
   */
  static void SetOwnedExtent(vtkImageData* image, const int extent[6]);
  static bool GetOwnedExtent(vtkImageData* image, int extent[6]);
  ///@}

  ///@{
  /**
   * Supercell size in cells along the volume's x, y and z (positive real numbers; below 1
   * they are subcells): larger supercells mean fewer polygons to project, smaller ones
   * fewer samples in empty space (paper, section 2). Default 4 x 4 x 4: composite rays
   * leave out the samples of empty cells themselves, so samples in empty space cost little
   * and the passes' polygons dominate; on large volumes (10^8 voxels and more) larger
   * supercells pay, which AutoSupercellSize finds (the benchmark's supercell sweep shows
   * the trade-off).
   * Setting a size turns AutoSupercellSize off: a size the user sets is kept.
   */
  virtual void SetSupercellSize(double x, double y, double z);
  virtual void SetSupercellSize(const double size[3]);
  vtkGetVector3Macro(SupercellSize, double);
  ///@}

  ///@{
  /**
   * In ACCELERATION_AUTO, whether Auto also chooses the supercell size (default on, off
   * once SetSupercellSize is called): it starts from the supercell size scaled by the
   * least of 1, 2, 4 and 8 at which the volume holds at most 65,536 supercells, else 8 (a
   * 7 MB head starts at 8 cells, a 434 MB volume at 32), and once it has settled on a pass it
   * times the frames of that pass at that scale, then twice it, four times, ... (or half,
   * a quarter, ... when twice is slower or out of range), two frames a scale, and keeps
   * the fastest: the paper's polygons against ray steps, from the projection and casting
   * times it measures (parc::SupercellSearch).
   * When it settled on None only because the depth pass's projection cost more than the
   * pass saved, it times the depth pass at 2, 4, ... times the size against None's frame
   * and takes the pass if a size beats None (still frames only; GetAutoTrialsRemaining
   * counts this search). The images are the same at every size. GetLastSupercellSize
   * gives the size the last render used for the first input.
   */
  vtkSetMacro(AutoSupercellSize, vtkTypeBool);
  vtkGetMacro(AutoSupercellSize, vtkTypeBool);
  vtkBooleanMacro(AutoSupercellSize, vtkTypeBool);
  double* GetLastSupercellSize() VTK_SIZEHINT(3);
  ///@}

  ///@{
  /**
   * Distance between samples along a ray, in world units. A value <= 0 (the default) means
   * half the smallest voxel edge in world units (spacing times the volume's scale).
   */
  vtkSetMacro(SampleDistance, double);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * Screen pixels per ray along each image axis (1 = one ray per pixel, the default; 2 = a
   * ray every second pixel, the image magnified with linear filtering). Used as set only
   * with AutoAdjustSampleDistances off, as in vtkFixedPointVolumeRayCastMapper; otherwise
   * each render chooses it (see AutoAdjustSampleDistances).
   */
  vtkSetClampMacro(ImageSampleDistance, double, 1.0, 64.0);
  vtkGetMacro(ImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * Accumulated opacity at which composite and isosurface rays stop (early ray
   * termination). 1 disables it in practice. Default 0.99.
   */
  vtkSetClampMacro(TerminationOpacity, double, 0.0, 1.0);
  vtkGetMacro(TerminationOpacity, double);
  ///@}

  ///@{
  /**
   * Whether the mapper keeps a copy of the rendered scalars in bricks of 64^3 cells (each
   * stored with the voxels its cells' gradients read), which the rays sample instead of
   * the input's slices (default off). On volumes much larger than the processor's caches
   * the voxels a ray reads next then lie near each other in memory, and frames take less
   * time (Documentation/Performance.md: 1.13x and 1.20x faster unshaded and shaded at
   * 429 MB; nothing to gain on a 7 MB volume). The copy costs memory: 1.15 times the
   * rendered scalars' bytes where each axis holds a whole number of bricks, up to about 1.5
   * times where it does not (1.41 times at 429 MB). It is made on the first render after
   * the scalars change (about 0.2 s at 429 MB) and freed when this is turned off.
   * Images are the same bit for bit with and without it. When the memory cannot be had,
   * or the copy would hold more than twice the values (scalars thinner than a brick along
   * some axis), the mapper warns once and samples the input. GetMemorySize counts the copy.
   */
  vtkSetMacro(BrickedCopy, vtkTypeBool);
  vtkGetMacro(BrickedCopy, vtkTypeBool);
  vtkBooleanMacro(BrickedCopy, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Brightness and contrast of the displayed image, as vtkFixedPointVolumeRayCastMapper
   * and vtkSmartVolumeMapper define them: each displayed premultiplied colour becomes
   * rgb / window + (1/2 - level / window) alpha, kept within [0, alpha]; alpha is unchanged.
   * The float ray-cast image (GetLastRayCastImage) is not adjusted. A window of 0 warns
   * once and adjusts nothing. Defaults: window 1, level 0.5 (no change).
   */
  vtkSetMacro(FinalColorWindow, float);
  vtkGetMacro(FinalColorWindow, float);
  vtkSetMacro(FinalColorLevel, float);
  vtkGetMacro(FinalColorLevel, float);
  ///@}

  ///@{
  /**
   * Render-time budgets, as vtkFixedPointVolumeRayCastMapper keeps them. With
   * AutoAdjustSampleDistances on (the default), each render picks the ImageSampleDistance
   * that should fit the volume's allocated render time (vtkProp::GetAllocatedRenderTime,
   * set by the render window's desired update rate), estimated from the last render's time
   * (a render's time grows with its number of rays and samples), within
   * [MinimumImageSampleDistance, MaximumImageSampleDistance]; an interactive render (less
   * than 1 / InteractiveUpdateRate seconds allocated) also samples every
   * InteractiveSampleDistance world units when that is coarser. A still render (a large
   * allocation, as after interaction ends) is cast at MinimumImageSampleDistance and the
   * full sample distance. Every render is exact for the settings it uses: the acceleration
   * modes agree bit for bit on it. With AutoAdjustSampleDistances off, ImageSampleDistance
   * and SampleDistance are used as set. GetLastImageSampleDistance and
   * GetLastSampleDistance give what the last render used, GetLastInteractive whether it
   * was interactive.
   * Defaults: on, 1, 10, 2.0 world units and 1 frame per second (FixedPoint's).
   */
  vtkSetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkSetClampMacro(MinimumImageSampleDistance, double, 1.0, 64.0);
  vtkGetMacro(MinimumImageSampleDistance, double);
  vtkSetClampMacro(MaximumImageSampleDistance, double, 1.0, 64.0);
  vtkGetMacro(MaximumImageSampleDistance, double);
  vtkSetMacro(InteractiveSampleDistance, double);
  vtkGetMacro(InteractiveSampleDistance, double);
  vtkSetClampMacro(InteractiveUpdateRate, double, 1e-6, 1e6);
  vtkGetMacro(InteractiveUpdateRate, double);
  vtkGetMacro(LastImageSampleDistance, double);
  vtkGetMacro(LastInteractive, vtkTypeBool);
  ///@}

  ///@{
  /**
   * As vtkSmartVolumeMapper has it: with InteractiveAdjustSampleDistances on, interactive
   * renders adjust the sample distances as with AutoAdjustSampleDistances even when that
   * is off, and still renders use ImageSampleDistance and SampleDistance as set. Default
   * off (vtkSmartVolumeMapper's default is on, with AutoAdjustSampleDistances off: set
   * both so to behave like it).
   */
  vtkSetMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Derive the sample distance from the input's spacing instead of SampleDistance: the
   * average voxel edge (world units) times min(1/2, cbrt(N) / 200) for N voxels, half the
   * average edge from 10^6 voxels on and proportionally finer for smaller volumes, as
   * vtkFixedPointVolumeRayCastMapper describes it. Default off.
   */
  vtkSetMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  vtkGetMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  vtkBooleanMacro(LockSampleDistanceToInputSpacing, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Threads that cast rays (vtkSMPTools); 0, the default, means vtkSMPTools' own number
   * (all cores unless configured otherwise). The image is the same for any number.
   * GetLastNumberOfThreads is the number the last cast could use.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  vtkGetMacro(LastNumberOfThreads, int);
  ///@}

  ///@{
  /**
   * vtkGPUVolumeRayCastMapper and vtkSmartVolumeMapper settings, for programs that swap
   * mappers. Jittering (random ray offsets against wood-grain artefacts) is not done: rays
   * sample one exact lattice; turning it on warns once and changes nothing. The requested
   * render mode may be Default or RayCast (the mapper always casts rays on the CPU, with GL
   * only to accelerate); GPU or OSPRay warn once and cast rays as well.
   * GetLastUsedRenderMode is vtkSmartVolumeMapper::RayCastRenderMode after a render, and
   * InvalidRenderMode before one.
   */
  vtkSetMacro(UseJittering, vtkTypeBool);
  vtkGetMacro(UseJittering, vtkTypeBool);
  vtkBooleanMacro(UseJittering, vtkTypeBool);
  /**
   * A mask for the volume of port 0, as vtkGPUVolumeRayCastMapper takes it: an image of
   * the volume's dimensions. A binary mask (SetMaskTypeToBinary) confines composite,
   * isosurface and additive rendering (and the shadows of those) to where the mask's
   * nearest voxel is non-zero, exactly in every acceleration mode; the other ray functions
   * report an error. A label map (the default type, as in VTK) gives composite rendering of
   * one component the functions of each sample's label L (its nearest voxel, rounded) as
   * VTK's GPU mapper does: where the property has label functions for L > 0
   * (vtkVolumeProperty::SetLabelScalarOpacity, SetLabelColor, SetLabelGradientOpacity; a
   * function not set is the default one), opacity and colour are (1 - f) times the default
   * plus f times the label's, f = MaskBlendFactor; elsewhere, and everywhere when f is 0,
   * the default functions apply. Exact in every acceleration mode.
   */
  void SetMaskInput(vtkImageData* mask);
  vtkGetObjectMacro(MaskInput, vtkImageData);
  enum MaskTypes
  {
    BinaryMaskType = 0,
    LabelMapMaskType = 1
  };
  vtkSetClampMacro(MaskType, int, BinaryMaskType, LabelMapMaskType);
  vtkGetMacro(MaskType, int);
  void SetMaskTypeToBinary() { this->SetMaskType(BinaryMaskType); }
  void SetMaskTypeToLabelMap() { this->SetMaskType(LabelMapMaskType); }
  vtkSetClampMacro(MaskBlendFactor, float, 0.0f, 1.0f);
  vtkGetMacro(MaskBlendFactor, float);
  /**
   * Whether renders emit progress events (VolumeMapperRenderProgressEvent and
   * ProgressEvent), as vtkGPUVolumeRayCastMapper's ReportProgress. Default on.
   */
  vtkSetMacro(ReportProgress, bool);
  vtkGetMacro(ReportProgress, bool);
  /**
   * vtkGPUVolumeRayCastMapper's texture memory limits and vtkSmartVolumeMapper's
   * interpolation for downsampling a volume that does not fit them: kept so that such
   * programs run, without effect (this mapper samples the input in place, whole).
   */
  vtkSetMacro(MaxMemoryInBytes, vtkIdType);
  vtkGetMacro(MaxMemoryInBytes, vtkIdType);
  vtkSetClampMacro(MaxMemoryFraction, float, 0.1f, 1.0f);
  vtkGetMacro(MaxMemoryFraction, float);
  vtkSetClampMacro(InterpolationMode, int, 0, 2);
  vtkGetMacro(InterpolationMode, int);
  // vtkImageReslice's values: nearest 0, linear 1, cubic 2.
  void SetInterpolationModeToNearestNeighbor() { this->SetInterpolationMode(0); }
  void SetInterpolationModeToLinear() { this->SetInterpolationMode(1); }
  void SetInterpolationModeToCubic() { this->SetInterpolationMode(2); }
  /**
   * vtkGPUVolumeRayCastMapper's depth pass renders a depth image of an isosurface for
   * other passes to read; it does not change the picture. Here it has no effect: the flag
   * is kept so that such programs run.
   */
  vtkSetMacro(UseDepthPass, vtkTypeBool);
  vtkGetMacro(UseDepthPass, vtkTypeBool);
  vtkBooleanMacro(UseDepthPass, vtkTypeBool);
  void SetRequestedRenderMode(int mode);
  vtkGetMacro(RequestedRenderMode, int);
  // vtkSmartVolumeMapper's values: Default 0, RayCast 1, GPU 2, OSPRay 3.
  void SetRequestedRenderModeToDefault() { this->SetRequestedRenderMode(0); }
  void SetRequestedRenderModeToRayCast() { this->SetRequestedRenderMode(1); }
  void SetRequestedRenderModeToGPU() { this->SetRequestedRenderMode(2); }
  void SetRequestedRenderModeToOSPRay() { this->SetRequestedRenderMode(3); }
  int GetLastUsedRenderMode();
  /**
   * Whether the mapper can render vol in window: 1 when the volume's input is an image it
   * supports (scalars of a supported type, at least 2 samples along each axis, non-zero
   * spacing). No GL context is needed: without one the mapper casts unaccelerated.
   */
  int IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty* property);
  ///@}

  ///@{
  /**
   * Whether rays end at the opaque geometry already drawn by the renderer (its depth
   * buffer is read once per render when the renderer holds any visible non-volume prop).
   * Default on.
   */
  vtkSetMacro(IntermixIntersectingGeometry, vtkTypeBool);
  vtkGetMacro(IntermixIntersectingGeometry, vtkTypeBool);
  vtkBooleanMacro(IntermixIntersectingGeometry, vtkTypeBool);
  ///@}

  /**
   * The sample distance of the last render in world units (SampleDistance, or the value
   * derived from the spacing when SampleDistance <= 0).
   */
  vtkGetMacro(LastSampleDistance, double);

  /**
   * Copies the ray-cast image of the last render into image: a float RGBA point array
   * "RGBA" of premultiplied colours, one point per ray, x to the right and y up.
   */
  void GetLastRayCastImage(vtkImageData* image);

  ///@{
  /**
   * Statistics of the last render. Samples are scalar samples on the lattice; contributing
   * samples had non-zero opacity (or were isosurface crossings); empty-cell samples lay
   * in cells that cannot contribute, left out by composite rays without interpolation.
   * Times are in seconds: casting (rays only), projection (PARC passes) and the whole
   * Render call.
   */
  vtkIdType GetLastSampleCount();
  vtkIdType GetLastContributingSampleCount();
  vtkIdType GetLastEmptyCellSampleCount();
  vtkIdType GetLastRayCount();
  vtkIdType GetLastGradientCount();
  /**
   * Bytes of the threads' caches of cell differences that the last render's gradients
   * used (larger where rays are closer than a voxel; in GetMemorySize).
   */
  vtkIdType GetLastGradientCacheSize();
  double GetLastCastingTime();
  double GetLastProjectionTime();
  double GetLastRenderTime();
  /** The acceleration mode the last render used (after any fallback). */
  int GetLastAccelerationMode();
  /** Auto: frames still to be rendered before the fastest pass is known (0 when settled). */
  int GetAutoTrialsRemaining();
  /** Polygons projected by the last render's PARC passes (0 without acceleration). */
  vtkIdType GetLastPolygonCount();
  /** Cells the cast ray segments crossed (the paper's "cells considered"). */
  vtkIdType GetLastCellCount();
  /**
   * Shadows (paper section 5, Table 3): shadow rays cast (one per shaded contribution and
   * shadow-casting light that lights it), the lattice samples they took and the cells
   * they crossed.
   */
  vtkIdType GetLastShadowRayCount();
  vtkIdType GetLastShadowSampleCount();
  vtkIdType GetLastShadowCellCount();
  /**
   * Seconds the last render spent in the PARC passes of the lights (shadow rays; 0 when
   * they were cached). The shadow rays of a volume use PARC buffers from each light unless
   * the acceleration mode is ACCELERATION_NONE: colour bit planes in
   * ACCELERATION_COLOR_BUFFER, depth buffers in the other modes (Auto too, so that its
   * choice of the view's pass never remakes them; the paper's Figure 13 uses depth). The
   * buffers are remade only when a light, the volume's transform, its classification or
   * the acceleration mode changes.
   */
  double GetLastLightProjectionTime();
  /**
   * Light frusta (each a near and a far depth pass) the last render drew for shadow rays:
   * 0 when the lights' buffers were cached or no light casts shadows.
   */
  int GetLastLightFrustumCount();
  /** Supercells and PC supercells of the last classification. */
  vtkIdType GetLastSupercellCount();
  vtkIdType GetLastContributingSupercellCount();
  /** Seconds the most recent classification took (with the data's pyramid cached). */
  double GetLastClassificationTime();
  /** Colour-buffer PARC: planes and passes of the last render (0 otherwise). */
  int GetLastPlaneCount();
  int GetLastPassCount();
  /**
   * How often the work that only changes with the data, the transfer functions or the
   * supercell size was done since the mapper was made: cell-range pyramids built,
   * classifications of the supercells and of the cells (for the caster, in every
   * acceleration mode), polygon models built and uploaded to the GPU.
   */
  vtkIdType GetPyramidBuildCount();
  vtkIdType GetClassificationCount();
  vtkIdType GetCellClassificationCount();
  vtkIdType GetModelBuildCount();
  vtkIdType GetModelUploadCount();
  void PrintStatistics(ostream& os);
  ///@}

  ///@{
  /**
   * Bytes the mapper holds besides its input, per structure and in total: the copy of
   * the scalars (only non-finite floating-point input is copied; other scalars are sampled
   * in place, in their own type; so is a mask), the cell-range pyramid, the supercell
   * flags, the polygon models, the read-back PARC buffers, the ray-cast and display
   * images, and what the OpenGL implementation keeps for the passes and the displayed
   * image. No GL call tells the last: it is measured as the process's heap and resident
   * growth over the GL calls that allocate (programs built, models uploaded, render
   * targets and the display texture allocated; on a software GL such as llvmpipe it
   * includes the shader compiler's pages). Another thread allocating during those calls
   * is counted with them. ReleaseGraphicsResources drops it.
   * PrintMemory writes one line per structure.
   */
  vtkIdType GetMemorySize();
  void PrintMemory(ostream& os);
  ///@}

  ///@{
  /**
   * The ray function of the volume on an input port, a vtkVolumeMapper blend mode
   * (COMPOSITE_BLEND, MAXIMUM_INTENSITY_BLEND, ...). Port 0 follows SetBlendMode; the other
   * ports default to COMPOSITE_BLEND. Ports outside [0, MaxInputPorts) are an error.
   */
  void SetInputBlendMode(int port, int blendMode);
  int GetInputBlendMode(int port);
  ///@}

  /** The most volumes (input ports) one mapper renders together. */
  static constexpr int MaxInputPorts = 10;

  /** The acceleration mode the last render used for the volume on port. */
  int GetLastInputAccelerationMode(int port);

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkPARCVolumeMapper();
  ~vtkPARCVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  class vtkVolumeState;
  /**
   * Render's first phase: prepares the volumes of vol (itself, or a multi-volume's) with
   * PrepareField and PrepareParameters; false (nothing drawn) on bad input.
   */
  bool PrepareVolumes(vtkRenderer* ren, vtkVolume* vol);
  /**
   * Updates the input of the volume's port and converts its scalars when they changed;
   * false on bad input.
   */
  bool PrepareField(vtkVolumeState& state, vtkVolume* prop);
  /** Makes or frees the copies in bricks of the volume's fields, as BrickedCopy asks. */
  void PrepareBricks(vtkVolumeState& state);
  /** Wraps the mask for port 0's volume, with a label map's functions (their fixes added
   * to fixes); false (nothing drawn) on a bad mask. */
  bool PrepareMask(vtkVolumeState& state, vtkVolumeProperty* property, std::string& fixes);
  /**
   * Converts the property and transform of prop (the vtkVolume of the volume's port) and
   * the renderer's lights into the caster's parameters.
   */
  bool PrepareParameters(vtkVolumeState& state, vtkRenderer* ren, vtkVolume* prop);
  /// The range the colour table of a component spans (ColorRangeType): range, the data's,
  /// or the colour function's own when NATIVE asks for it and it has one.
  void ColorTableRange(vtkVolumeProperty* property, int component, double range[2]) const;
  /// The parameters and casters of the independent components after the first (from the
  /// first one's, prepared), given to the first one's caster; their transfer-function
  /// fixes are added to fixes.
  bool PrepareComponents(vtkVolumeState& state, vtkVolumeProperty* property, std::string& fixes);
  /**
   * Render's middle phases for the renderer's camera: the ray image's view, the depth of
   * other geometry, each volume's PARC passes, the cast, Auto's measurements.
   */
  void RenderRayImage(vtkRenderer* ren);
  /**
   * A set-up step of this render begins (with ReportProgress): the progress text names it
   * and the progress (ProgressEvent) is `progress`; the render's casting then reports
   * from 0.5 to 1.
   */
  void ReportSetUp(const char* step, double progress);
  /** What the render's phases read of this mapper (vtkInternals::Settings). */
  void TakeSettings(vtkRenderer* ren);

  /**
   * The image sample distance of this render: ImageSampleDistance, or with
   * AutoAdjustSampleDistances the one estimated to fit the allocated render time.
   */
  double ChooseImageSampleDistance() const;

  /** Composites the ray image over the renderer's viewport. */
  void DisplayImage(vtkRenderer* ren, vtkVolume* vol);

  int AccelerationMode = ACCELERATION_AUTO;
  int ShadingModel = SHADING_EXACT;
  int AmbientModel = AMBIENT_MATERIAL;
  int ShadowMode = SHADOWS_FROM_RENDERER;
  int ColorRangeType = SCALAR;
  double SupercellSize[3] = { 4.0, 4.0, 4.0 };
  vtkTypeBool AutoSupercellSize = 1;
  double LastSupercellSize[3] = { 0.0, 0.0, 0.0 };
  double SampleDistance = 0.0;
  double ImageSampleDistance = 1.0;
  double TerminationOpacity = 0.99;
  vtkTypeBool BrickedCopy = 0;
  vtkTypeBool IntermixIntersectingGeometry = 1;
  double LastSampleDistance = 0.0;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  vtkTypeBool InteractiveAdjustSampleDistances = 0;
  double MinimumImageSampleDistance = 1.0;
  double MaximumImageSampleDistance = 10.0;
  double InteractiveSampleDistance = 2.0;
  double InteractiveUpdateRate = 1.0;
  double LastImageSampleDistance = 1.0;
  vtkTypeBool LastInteractive = 0;
  vtkTypeBool LockSampleDistanceToInputSpacing = 0;
  int NumberOfThreads = 0;
  int LastNumberOfThreads = 0;
  vtkTypeBool UseJittering = 0;
  vtkTypeBool UseDepthPass = 0;
  vtkImageData* MaskInput = nullptr;
  int MaskType = LabelMapMaskType;
  float MaskBlendFactor = 1.0f;
  bool ReportProgress = true;
  vtkIdType MaxMemoryInBytes = 0;
  float MaxMemoryFraction = 0.75f;
  int InterpolationMode = 1;
  float FinalColorWindow = 1.0f;
  float FinalColorLevel = 0.5f;
  int RequestedRenderMode = 0;
  int InputBlendModes[MaxInputPorts] = {}; ///< ports 1 and up (port 0: BlendMode)

private:
  vtkPARCVolumeMapper(const vtkPARCVolumeMapper&) = delete;
  void operator=(const vtkPARCVolumeMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
