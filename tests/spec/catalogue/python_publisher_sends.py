# error: python_publisher_sends.py:11:1: publisher 'Euler_pub' sends to 'QuatToEuler_acc', but a publisher's messages go to ROS
# hint: connect the block that feeds the publisher instead
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
pub >> acc
