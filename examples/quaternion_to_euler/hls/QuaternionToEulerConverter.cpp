// Quaternion -> Euler angles for the Vitis HLS path; see QuaternionToEulerConverter.h.
#include "QuaternionToEulerConverter.h"

#include <limits>

#if defined(__SYNTHESIS__) || defined(__VITIS_HLS__)
#include "hls_math.h"
namespace math = hls;
#else
#include <cmath>
namespace math = std;
#endif

namespace {

// The MyHDL core's component range, Q2.53: [-2, 2).
bool in_domain(double c) { return c >= -2.0 && c < 2.0; }

double clamp_unit(double v) { return v > 1.0 ? 1.0 : (v < -1.0 ? -1.0 : v); }

}  // namespace

void QuaternionToEulerConverter(double x, double y, double z, double w, double *roll,
                                double *pitch, double *yaw) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
#pragma HLS INTERFACE mode=ap_none port=x
#pragma HLS INTERFACE mode=ap_none port=y
#pragma HLS INTERFACE mode=ap_none port=z
#pragma HLS INTERFACE mode=ap_none port=w
#pragma HLS INTERFACE mode=ap_vld port=roll
#pragma HLS INTERFACE mode=ap_vld port=pitch
#pragma HLS INTERFACE mode=ap_vld port=yaw
    // NaN compares false, so NaN components fail the range test too.
    if (!(in_domain(x) && in_domain(y) && in_domain(z) && in_domain(w))) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        *roll = nan;
        *pitch = nan;
        *yaw = nan;
        return;
    }
    *roll = math::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
    *pitch = math::asin(clamp_unit(2.0 * (w * y - z * x)));
    *yaw = math::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}
