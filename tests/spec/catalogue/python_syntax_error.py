# error: python_syntax_error.py:10:18: Python syntax error: unmatched ')'
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub)
