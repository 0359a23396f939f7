// The integral image, last stage of the image pipeline: mono8 in, 32SC1 out (a little-endian
// uint32 per pixel, step = 4 width), out(y, x) = the sum of in over rows <= y and columns <= x.
// The structs come from IntegralImage_messages.h (generated).
#include "IntegralImage_messages.h"

#define MAX_WIDTH 1920

void IntegralImage(image_t image, hls::stream<char> &image_header_frame_id,
                   hls::stream<uint8_t> &image_data, integral_t *integral,
                   hls::stream<char> &integral_header_frame_id,
                   hls::stream<char> &integral_encoding, hls::stream<uint8_t> &integral_data) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
#pragma HLS DISAGGREGATE variable=image
#pragma HLS DISAGGREGATE variable=integral
#pragma HLS INTERFACE mode=ap_vld port=integral
#pragma HLS INTERFACE mode=ap_fifo port=image_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=image_data
#pragma HLS INTERFACE mode=ap_fifo port=integral_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=integral_encoding
#pragma HLS INTERFACE mode=ap_fifo port=integral_data
    integral->header.stamp.sec = image.header.stamp.sec;
    integral->header.stamp.nanosec = image.header.stamp.nanosec;
    integral->header.frame_id_length = image.header.frame_id_length;
    for (uint32_t i = 0; i < image.header.frame_id_length; ++i) {
        integral_header_frame_id.write(image_header_frame_id.read());
    }
    static const char encoding[] = "32SC1";
    integral->encoding_length = sizeof encoding - 1;
    for (uint32_t i = 0; i + 1 < sizeof encoding; ++i) integral_encoding.write(encoding[i]);
    integral->height = image.height;
    integral->width = image.width;
    integral->step = 4 * image.width;
    integral->data_length = 4 * image.width * image.height;
    uint32_t above[MAX_WIDTH];  // the integral of the row above
    for (uint32_t y = 0; y < image.height; ++y) {
        uint32_t row = 0;
        for (uint32_t x = 0; x < image.width; ++x) {
#pragma HLS PIPELINE II=4
            row += image_data.read();
            const uint32_t sum = row + (y == 0 ? 0 : above[x]);
            above[x] = sum;
            for (int byte = 0; byte < 4; ++byte) {
                integral_data.write(static_cast<uint8_t>(sum >> (8 * byte)));
            }
        }
    }
}
