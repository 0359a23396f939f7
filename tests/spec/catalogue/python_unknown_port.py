# error: python_unknown_port.py:10:1: block 'QuatToEuler_acc' has no input 'q'; its inputs are in0
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc["q"] >> pub
