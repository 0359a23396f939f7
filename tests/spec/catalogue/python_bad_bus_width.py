# error: python_bad_bus_width.py:6:11: bus width must be 8, 32 or 64 bits, not 16
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue", bus_width=16)
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
