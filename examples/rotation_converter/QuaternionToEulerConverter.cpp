// Quaternion to Euler angles (roll, pitch, yaw), the accelerator of the paper's Listing 1.
// Vitis HLS top function: the generated wrapper feeds the fields of geometry_msgs/Quaternion
// and collects those of geometry_msgs/Point (x = roll, y = pitch, z = yaw, in radians).
#include <cmath>

void QuaternionToEuler(double q_x, double q_y, double q_z, double q_w,
                       double *euler_x, double *euler_y, double *euler_z) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
    // roll: rotation about x
    double sinr_cosp = 2.0 * (q_w * q_x + q_y * q_z);
    double cosr_cosp = 1.0 - 2.0 * (q_x * q_x + q_y * q_y);
    *euler_x = std::atan2(sinr_cosp, cosr_cosp);
    // pitch: rotation about y, clamped at +-90 degrees when out of range
    double sinp = 2.0 * (q_w * q_y - q_z * q_x);
    *euler_y = std::fabs(sinp) >= 1.0 ? std::copysign(M_PI / 2.0, sinp) : std::asin(sinp);
    // yaw: rotation about z
    double siny_cosp = 2.0 * (q_w * q_z + q_x * q_y);
    double cosy_cosp = 1.0 - 2.0 * (q_y * q_y + q_z * q_z);
    *euler_z = std::atan2(siny_cosp, cosy_cosp);
}
