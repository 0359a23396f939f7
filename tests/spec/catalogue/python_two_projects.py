# error: python_two_projects.py:1:1: 'python_two_projects.py' defines 2 projects ('Catalogue', 'Other'); rfc builds one per file
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
other = rfc.Project("Other")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
