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
