// Renderer::Gl: the renderer's GL pipeline (gl_pipeline.hpp), shared by the canvas's sources
// (render.cpp, render_shapes.cpp). Internal.
#pragma once

#include "fixstep/render/render.hpp"
#include "gl_pipeline.hpp"  // GL through OSMesa only, never libGL: see gl_api.hpp

namespace fixstep {

struct Renderer::Gl : gl::Pipeline {
  using Pipeline::Pipeline;
};

}  // namespace fixstep
