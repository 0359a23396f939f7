// Downscaling by two in each direction, second stage of the image pipeline: mono8 in and out.
// Each output pixel is the rounded mean (a + b + c + d + 2) >> 2 of an even-aligned 2x2 block;
// an odd last row or column is dropped. The structs come from Downscale_messages.h (generated).
#include "Downscale_messages.h"

#define MAX_WIDTH 1920

void Downscale(full_t full, hls::stream<char> &full_header_frame_id,
               hls::stream<uint8_t> &full_data, small_t *small,
               hls::stream<char> &small_header_frame_id, hls::stream<uint8_t> &small_data) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
#pragma HLS DISAGGREGATE variable=full
#pragma HLS DISAGGREGATE variable=small
#pragma HLS INTERFACE mode=ap_vld port=small
#pragma HLS INTERFACE mode=ap_fifo port=full_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=full_data
#pragma HLS INTERFACE mode=ap_fifo port=small_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=small_data
    small->header.stamp.sec = full.header.stamp.sec;
    small->header.stamp.nanosec = full.header.stamp.nanosec;
    small->header.frame_id_length = full.header.frame_id_length;
    for (uint32_t i = 0; i < full.header.frame_id_length; ++i) {
        small_header_frame_id.write(full_header_frame_id.read());
    }
    const uint32_t width = full.width / 2, height = full.height / 2;
    small->width = width;
    small->height = height;
    small->data_length = width * height;
    uint16_t pairs[MAX_WIDTH / 2];  // the sums of the even row's pairs
    for (uint32_t y = 0; y < full.height; ++y) {
        uint16_t pair = 0;
        for (uint32_t x = 0; x < full.width; ++x) {
#pragma HLS PIPELINE II=1
            const uint8_t pixel = full_data.read();
            if (y >= 2 * height || x >= 2 * width) continue;  // odd last row or column
            pair = (x % 2 == 0) ? pixel : pair + pixel;
            if (x % 2 == 0) continue;
            if (y % 2 == 0) {
                pairs[x / 2] = pair;
            } else {
                small_data.write(static_cast<uint8_t>((pairs[x / 2] + pair + 2) >> 2));
            }
        }
    }
}
