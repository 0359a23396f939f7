// Quaternion -> Euler angles for the Vitis HLS path (paper use case 7.1.1).
//
// Point x = roll, y = pitch, z = yaw: intrinsic Z-Y-X angles by the usual formulas
//   roll  = atan2(2(wx + yz), 1 - 2(x^2 + y^2))
//   pitch = asin(clamp(2(wy - zx), -1, 1))
//   yaw   = atan2(2(wz + xy), 1 - 2(y^2 + z^2))
// in double precision. Interface: ap_ctrl_hs block protocol (ap_start, ap_done, ap_idle,
// ap_ready); x, y, z, w are ap_none inputs read after ap_start; roll, pitch, yaw are ap_vld
// outputs. As in the MyHDL core, a component that is NaN, infinite or outside [-2, 2) makes all
// three angles a quiet NaN. Plain C++17: g++ compiles it for testing (pragmas are ignored).
#ifndef QUATERNION_TO_EULER_CONVERTER_H
#define QUATERNION_TO_EULER_CONVERTER_H

void QuaternionToEulerConverter(double x, double y, double z, double w, double *roll,
                                double *pitch, double *yaw);

#endif
