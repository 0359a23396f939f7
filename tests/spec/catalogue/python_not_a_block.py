# error: python_not_a_block.py:6:2: @rfc.accelerator expects a MyHDL @block function, but got function 'QuaternionToEuler'
# hint: put @block (from myhdl) between @rfc.accelerator and the function
import rfc


@rfc.accelerator(inputs={"q": "geometry_msgs/Quaternion"}, outputs={"euler": "geometry_msgs/Point"})
def QuaternionToEuler(clk, q_x, euler_x):
    return ()


project = rfc.Project("Catalogue")
