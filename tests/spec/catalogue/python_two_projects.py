# error: python_two_projects.py:1:1: 'python_two_projects.py' defines 2 projects ('Catalogue', 'Other'); rfc builds one per file
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
other = rfc.Project("Other")
sub >> acc >> pub
