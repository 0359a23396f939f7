// Sums of FrankaState's joint angles and transforms, taking the message as one struct.
#include "Sums_messages.h"

void Sums(state_t state, hls::stream<char> &state_header_frame_id, sums_t *sums,
          hls::stream<char> &sums_header_frame_id) {
    sums->header.seq = state.header.seq;
    sums->header.stamp.sec = state.header.stamp.sec;
    sums->header.stamp.nanosec = state.header.stamp.nanosec;
    sums->header.frame_id_length = state.header.frame_id_length;
    for (uint32_t i = 0; i < state.header.frame_id_length; ++i) {
        sums_header_frame_id.write(state_header_frame_id.read());
    }
    double q = 0, q_d = 0, transforms = 0;
    for (int i = 0; i < 7; ++i) {
        q += state.q[i];
        q_d += state.q_d[i];
    }
    for (int i = 0; i < 16; ++i) {
        transforms += state.O_T_EE[i] - state.O_T_EE_d[i] + state.F_T_EE[i];
    }
    sums->point.x = q;
    sums->point.y = q_d;
    sums->point.z = transforms;
}
