# error: python_duplicate_block.py:9:7: duplicate block name 'Quaternion_sub' (first defined at python_duplicate_block.py:7:7)
# hint: none
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Quaternion_sub", "geometry_msgs/Point")
sub >> acc >> pub
