# error: python_maxima_unknown_key.py:6:11: unknown key 'sequences' in maxima; expected one of string, sequence, frame, fields
# hint: did you mean 'sequence'?
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue", maxima={"sequences": 8})
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
