# error: python_unknown_message.py:7:7: unknown message type 'geometry_msgs/Quaternoin' for ROS 2 humble
# hint: did you mean 'geometry_msgs/Quaternion' or 'geometry_msgs/QuaternionStamped' or 'geometry_msgs/Point'?
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternoin")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
