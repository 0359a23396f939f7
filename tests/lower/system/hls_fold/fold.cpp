// Folds FrankaState's joint and transform arrays into three 64-bit words (each element's bit
// pattern rotated left by its index, then exclusive-ored), and passes the stamp on.
#include <cstring>

#include "Fold_messages.h"

static uint64_t bits(double value) {
    uint64_t word;
    std::memcpy(&word, &value, sizeof word);
    return word;
}

static double value(uint64_t word) {
    double result;
    std::memcpy(&result, &word, sizeof result);
    return result;
}

static uint64_t rotated(double element, int index) {
    const uint64_t word = bits(element);
    return index == 0 ? word : (word << index) | (word >> (64 - index));
}

void Fold(state_t state, folded_t *folded) {
    folded->header.stamp.sec = state.header.stamp.sec;
    folded->header.stamp.nanosec = state.header.stamp.nanosec;
    uint64_t joints = 0, targets = 0, transforms = 0;
    for (int i = 0; i < 7; ++i) {
        joints ^= rotated(state.q[i], i);
        targets ^= rotated(state.q_d[i], i);
    }
    for (int i = 0; i < 16; ++i) {
        transforms ^= rotated(state.O_T_EE[i], i) ^ rotated(state.O_T_EE_d[i], 16 + i);
        transforms ^= rotated(state.F_T_EE[i], 32 + i);
    }
    folded->point.x = value(joints);
    folded->point.y = value(targets);
    folded->point.z = value(transforms);
}
