# error: python_include_missing_field.py:10:1: geometry_msgs/msg/Quaternion has no field 'yy'
# hint: did you mean 'y'?
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub.include("x", "yy") >> acc >> pub
