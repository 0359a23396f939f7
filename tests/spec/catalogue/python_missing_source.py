# error: python_missing_source.py:5:21: source file './QuaternionToEuler.cpp' does not exist
# hint: paths are relative to the folder of the spec
import rfc

QuaternionToEuler = rfc.external_accelerator(
    "QuaternionToEuler",
    kind="HLS",
    sources="./QuaternionToEuler.cpp",
    inputs="geometry_msgs/Quaternion",
    outputs="geometry_msgs/Point",
)
project = rfc.Project("Catalogue")
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
