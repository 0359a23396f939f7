# error: python_publisher_sends.py:17:1: publisher 'Euler_pub' sends to 'QuatToEuler_acc', but a publisher's messages go to ROS
# hint: connect the block that feeds the publisher instead
import rfc

QuaternionToEuler = rfc.external_accelerator(
    "QuaternionToEuler",
    kind="HLS",
    sources="./accel.cpp",
    inputs="geometry_msgs/Quaternion",
    outputs="geometry_msgs/Point",
)
project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
pub >> acc
