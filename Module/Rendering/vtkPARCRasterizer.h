/**
 * @class   vtkPARCRasterizer
 * @brief   The PARC passes in VTK's OpenGL context: near/far depths and plane bit sets.
 *
 * The one class of the module that calls OpenGL. Inside the render window's own context
 * it projects a polygon model (parcPolygonModel.h) into an offscreen framebuffer at the
 * ray image's resolution with the ray caster's camera, and reads the result back:
 *
 * - RenderDepth: the depth model into one RG32F buffer with MIN blending, cleared to
 *   DepthBufferSource::Empty, each fragment writing (near, -far): the smallest and the
 *   largest view depth of its face. One pass gives both the "less" near buffer and the
 *   "greater" far buffer of the paper.
 * - RenderPlanes: the colour model into up to 8 GL_RGBA32UI attachments (1024 planes a
 *   pass) with glLogicOp(GL_OR); each fragment sets the bit of its face's plane. Only as
 *   many attachments as the planes need are attached, and up to 64 planes one of one or
 *   two channels (GL_R32UI, GL_RG32UI: fewer bytes to blend and read back); more than 1024
 *   planes take several passes.
 *
 * Conservative by construction (DESIGN.md section 2): the vertex shader (each of a quad's
 * four vertices carries the whole quad) clips each quad to the part in front of the eye
 * (half the near distance, perspective only) and replaces it by the screen-space bounding
 * box of its projection, dilated by 3/4 of a pixel, so every
 * pixel whose centre ray touches the quad, including grazing rays and sub-pixel quads, gets
 * a fragment. The fragment shader then tests whether the ray through the pixel centre
 * meets the face, within a rounding margin that grows as the ray grazes it (the face
 * coordinates and the depth of the hit are ratios of affine functions of the pixel's NDC,
 * set up per quad). When it surely does not, the fragment writes the neutral value (Empty,
 * or no bit); otherwise the depth pass writes the depth of the hit, widened by the margin
 * and clamped to the quad's depth range, and the plane pass the face's bit. So near is never
 * too far, far never too near and no plane is missed. Depth clamping keeps faces beyond the
 * near/far planes.
 *
 * Every piece of GL state it changes is saved and restored (through vtkOpenGLState where
 * VTK tracks it), so the rest of the scene renders unchanged. Programs, framebuffers and
 * vertex buffers are kept between frames; a model is uploaded again only when its version
 * changes. When the context lacks OpenGL 3.3, a program fails to build or a framebuffer is
 * incomplete, the passes return false with a message in GetLastError().
 *
 * Not wrapped (it speaks the core's types); used by vtkPARCVolumeMapper.
 */
#ifndef vtkPARCRasterizer_h
#define vtkPARCRasterizer_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "parcPassView.h"     // For PassView
#include "parcLightFrusta.h"  // For LightFrame, LightBufferSource
#include "parcPolygonModel.h"  // For PolygonModel

#include <cstdint> // For std::uint32_t
#include <memory>  // For std::unique_ptr
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkRenderWindow;
class vtkRenderer;
class vtkWindow;

class PARCRENDERING_EXPORT vtkPARCRasterizer : public vtkObject
{
public:
  static vtkPARCRasterizer* New();
  vtkTypeMacro(vtkPARCRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The view the passes are drawn with (parcPassView.h).
  using View = parc::vtk::PassView;

  /// The passes, each with a GPU model and a render target of its own.
  enum class Pass
  {
    Depth = 0,
    Planes = 1
  };

  /// Near/far view depths of the depth model (2 floats per pixel, see class comment).
  bool RenderDepth(vtkRenderWindow* window, const parc::PolygonModel& model,
    std::uint64_t modelVersion, const parc::Matrix4& indexToWorld, const View& view,
    std::vector<float>& nearFar);

  /// The passes of a light over a volume for its shadow rays (parcLightFrusta.h): for each
  /// camera of parc::LightCameras at resolution x resolution pixels, a depth pass (model
  /// a depth model) or the plane passes (model a colour model), drawn in the light's frame
  /// with every face's whole depth range and every face of the planes (conservative for any
  /// line), into source's buffers (grid locates rays that start in the model); source.Offset
  /// takes a ray from the frame of light.Eye's caller into the light's. False (source left
  /// without buffers) when a pass fails.
  bool RenderLight(vtkRenderWindow* window, const parc::PolygonModel& model,
    std::uint64_t modelVersion, const parc::LightFrame& light, int resolution,
    const parc::SupercellGrid* grid, parc::LightBufferSource& source);

  /// Plane bit sets of the colour model (wordsPerPixel 32-bit words per pixel). raySign is
  /// parc::RayAxisSign for the view: when not 0, the faces across the axis that face along
  /// the rays (+raySign * axis) are left out.
  bool RenderPlanes(vtkRenderWindow* window, const parc::PolygonModel& model,
    std::uint64_t modelVersion, const parc::Matrix4& indexToWorld, const View& view, int raySign,
    std::vector<std::uint32_t>& bits, int& wordsPerPixel, int& passes);

  /// Whether the model of version (of the pass) is on window's GPU already: the
  /// passes then need none of its vertices.
  bool HasModel(vtkRenderWindow* window, Pass pass, std::uint64_t modelVersion) const;

  const std::string& GetLastError() const { return this->LastError; }
  /// How many times a model was uploaded to the GPU (statistics).
  std::uint64_t GetUploadCount() const { return this->UploadCount; }
  /// How many times ReleasePass freed a pass's model or render target (statistics).
  std::uint64_t GetReleaseCount() const { return this->ReleaseCount; }
  /// Seconds the passes spent so far setting up rather than drawing: making the context
  /// current, compiling the programs, uploading models, allocating render targets.
  double GetSetUpTime() const;
  /// Bytes of the uploaded models, the render targets and the read-back buffer (on
  /// software GL all of it is main memory).
  std::size_t GetMemorySize() const;
  /// Bytes the GL implementation holds for this rasterizer's calls beyond its copies of
  /// the models and targets (GetMemorySize): compiled shaders, binned triangles, the
  /// compiler's pages. Measured (parc::vtk::DriverMemory), not asked of GL.
  std::size_t GetDriverMemorySize() const;

  /// Frees the model and render target of one pass when window is the context they belong
  /// to: a pass the view no longer uses holds no memory.
  void ReleasePass(vtkRenderWindow* window, Pass pass);
  /// Frees the GL objects when window is the context they belong to (or null).
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkPARCRasterizer();
  ~vtkPARCRasterizer() override;

private:
  vtkPARCRasterizer(const vtkPARCRasterizer&) = delete;
  void operator=(const vtkPARCRasterizer&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  std::string LastError;
  std::uint64_t UploadCount = 0;
  std::uint64_t ReleaseCount = 0;
};

#endif
