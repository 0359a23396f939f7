# error: python_type_mismatch.py:11:1: type mismatch: 'QuatToEuler_acc.out0' sends geometry_msgs/msg/Point, but 'Euler_pub.in0' takes geometry_msgs/msg/Pose
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Pose")
sub >> acc
acc >> pub
