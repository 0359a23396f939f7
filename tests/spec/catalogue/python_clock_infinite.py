# error: python_clock_infinite.py:6:11: clock must be from 1 to 1000 MHz, not inf
# hint: Zynq logic typically runs at 50 to 250 MHz; the default is 100
import rfc
from parts import QuaternionToEuler

project = rfc.Project("Catalogue", clock_mhz=float("inf"))
sub = project.subscriber("Quaternion_sub", "geometry_msgs/Quaternion")
acc = project.accelerator("QuatToEuler_acc", QuaternionToEuler)
pub = project.publisher("Euler_pub", "geometry_msgs/Point")
sub >> acc >> pub
