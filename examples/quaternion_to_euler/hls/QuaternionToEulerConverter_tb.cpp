// Test driver for QuaternionToEulerConverter (C simulation, or g++ in rfc's tests).
//
// Reads lines "x y z w" of float64 bit patterns in hexadecimal from standard input and writes
// "roll pitch yaw" the same way, one line per quaternion, so that a caller compares bits.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "QuaternionToEulerConverter.h"

namespace {

double from_bits(std::uint64_t bits) {
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

std::uint64_t to_bits(double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

}  // namespace

int main() {
    std::uint64_t q[4];
    while (std::scanf("%" SCNx64 " %" SCNx64 " %" SCNx64 " %" SCNx64, &q[0], &q[1], &q[2],
                      &q[3]) == 4) {
        double roll, pitch, yaw;
        QuaternionToEulerConverter(from_bits(q[0]), from_bits(q[1]), from_bits(q[2]),
                                   from_bits(q[3]), &roll, &pitch, &yaw);
        std::printf("%016" PRIx64 " %016" PRIx64 " %016" PRIx64 "\n", to_bits(roll),
                    to_bits(pitch), to_bits(yaw));
    }
    return 0;
}
