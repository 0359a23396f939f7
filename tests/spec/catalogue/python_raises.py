# error: python_raises.py:16:15: the spec raised NameError: name 'publisher' is not defined
# hint: none
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
sub >> acc >> publisher
