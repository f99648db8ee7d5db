// GripperLift's picture: the shared gripper scene (gripper_scene_render.hpp) from its default
// camera, the cube red, green once it is lifted and held.
#include <stdexcept>

#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/gripper_scene_render.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/rasterizer.hpp"

namespace rlrun {

bool GripperLift::render(Frame& frame) const {
  if (!world_) throw std::logic_error(id() + ": call reset() before render()");
  Rasterizer raster(frame);
  draw_gripper_scene(raster, frame, *world_, GripperCamera{},
                     success_ ? Rgb{40, 180, 70} : Rgb{200, 40, 40});
  return true;
}

}  // namespace rlrun
