# error: python_duplicate_block.py:15:7: duplicate block name 'Quaternion_sub' (first defined at python_duplicate_block.py:13:7)
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
pub = project.publisher("Quaternion_sub", "geometry_msgs/Point")
sub >> acc >> pub
