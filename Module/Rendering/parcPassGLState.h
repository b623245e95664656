// PARC for VTK: the GL state of vtkPARCRasterizer's passes, set for a pass and restored
// after it (part of the rasterizer, the one class that calls OpenGL).
#ifndef parcPassGLState_h
#define parcPassGLState_h

#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

namespace parc
{
namespace vtk
{
/// What both passes set: no scissor, depth test, culling or depth writes; all colour
/// channels; depth clamping (faces beyond the near/far planes still count); tight rows.
inline void SetCommonPassState(vtkOpenGLState* state)
{
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 4);
  glEnable(GL_DEPTH_CLAMP);
}

/// Saves the GL state the passes change and restores it when destroyed.
class ScopedPassState
{
public:
  explicit ScopedPassState(vtkOpenGLState* state)
    : State(state)
    , Viewport(state)
    , ClearColor(state)
    , ColorMask(state)
    , DepthMask(state)
    , BlendFunc(state)
    , Scissor(state, GL_SCISSOR_TEST)
    , DepthTest(state, GL_DEPTH_TEST)
    , Blend(state, GL_BLEND)
    , Cull(state, GL_CULL_FACE)
  {
    this->State->PushFramebufferBindings();
    this->DepthClamp = glIsEnabled(GL_DEPTH_CLAMP);
    this->LogicOp = glIsEnabled(GL_COLOR_LOGIC_OP);
    glGetIntegerv(GL_LOGIC_OP_MODE, &this->LogicOpMode);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &this->VertexArray);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &this->ArrayBuffer);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &this->Renderbuffer);
    glGetIntegerv(GL_PACK_ALIGNMENT, &this->PackAlignment);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &this->BlendEquation[0]);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &this->BlendEquation[1]);
  }
  ~ScopedPassState()
  {
    glBindVertexArray(static_cast<GLuint>(this->VertexArray));
    glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(this->ArrayBuffer));
    glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(this->Renderbuffer));
    glLogicOp(static_cast<GLenum>(this->LogicOpMode));
    (this->LogicOp ? glEnable : glDisable)(GL_COLOR_LOGIC_OP);
    (this->DepthClamp ? glEnable : glDisable)(GL_DEPTH_CLAMP);
    this->State->vtkglPixelStorei(GL_PACK_ALIGNMENT, this->PackAlignment);
    this->State->vtkglBlendEquationSeparate(
      static_cast<GLenum>(this->BlendEquation[0]), static_cast<GLenum>(this->BlendEquation[1]));
    this->State->GetShaderCache()->ReleaseCurrentShader();
    this->State->PopFramebufferBindings();
  }

private:
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglClearColor ClearColor;
  vtkOpenGLState::ScopedglColorMask ColorMask;
  vtkOpenGLState::ScopedglDepthMask DepthMask;
  vtkOpenGLState::ScopedglBlendFuncSeparate BlendFunc;
  vtkOpenGLState::ScopedglEnableDisable Scissor, DepthTest, Blend, Cull;
  GLboolean DepthClamp = GL_FALSE;
  GLboolean LogicOp = GL_FALSE;
  GLint LogicOpMode = GL_COPY;
  GLint VertexArray = 0, ArrayBuffer = 0, Renderbuffer = 0;
  GLint PackAlignment = 4;
  GLint BlendEquation[2] = { GL_FUNC_ADD, GL_FUNC_ADD };
};
}
}

#endif
