// The names of joint types and joint input kinds (joint.hpp).
#include "fixstep/core/joint.hpp"

namespace fixstep {

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::revolute:
      return "revolute";
    case JointType::prismatic:
      return "prismatic";
    case JointType::weld:
      return "weld";
    case JointType::distance:
      return "distance";
    case JointType::wheel:
      return "wheel";
    case JointType::motor:
      return "motor";
  }
  return "?";
}

const char* joint_input_kind_name(JointInputKind kind) {
  switch (kind) {
    case JointInputKind::motor_speed:
      return "motor_speed";
    case JointInputKind::max_motor_torque:
      return "max_motor_torque";
    case JointInputKind::max_motor_force:
      return "max_motor_force";
    case JointInputKind::enable_motor:
      return "enable_motor";
    case JointInputKind::target:
      return "target";
    case JointInputKind::target_angle:
      return "target_angle";
  }
  return "?";
}

}  // namespace fixstep
