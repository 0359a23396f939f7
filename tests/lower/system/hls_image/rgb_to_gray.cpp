// RGB to grayscale, first stage of the image pipeline: rgb8 in, mono8 out, same size.
// gray = (4899 R + 9617 G + 1868 B + 8192) >> 14, OpenCV's integer BT.601 luma.
// The structs and the top function's declaration come from RgbToGray_messages.h, which rfc
// generates from the ports' messages (`rfc stub ImagePipeline.yaml RgbToGray --lang hls`).
#include "RgbToGray_messages.h"

void RgbToGray(rgb_t rgb, hls::stream<char> &rgb_header_frame_id, hls::stream<uint8_t> &rgb_data,
               gray_t *gray, hls::stream<char> &gray_header_frame_id,
               hls::stream<uint8_t> &gray_data) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
#pragma HLS DISAGGREGATE variable=rgb
#pragma HLS DISAGGREGATE variable=gray
#pragma HLS INTERFACE mode=ap_vld port=gray
#pragma HLS INTERFACE mode=ap_fifo port=rgb_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=rgb_data
#pragma HLS INTERFACE mode=ap_fifo port=gray_header_frame_id
#pragma HLS INTERFACE mode=ap_fifo port=gray_data
    gray->header.stamp.sec = rgb.header.stamp.sec;
    gray->header.stamp.nanosec = rgb.header.stamp.nanosec;
    gray->header.frame_id_length = rgb.header.frame_id_length;
    for (uint32_t i = 0; i < rgb.header.frame_id_length; ++i) {
        gray_header_frame_id.write(rgb_header_frame_id.read());
    }
    gray->height = rgb.height;
    gray->width = rgb.width;
    const uint32_t pixels = rgb.data_length / 3;
    gray->data_length = pixels;
    for (uint32_t pixel = 0; pixel < pixels; ++pixel) {
#pragma HLS PIPELINE II=3
        const uint32_t r = rgb_data.read(), g = rgb_data.read(), b = rgb_data.read();
        gray_data.write(static_cast<uint8_t>((4899 * r + 9617 * g + 1868 * b + 8192) >> 14));
    }
}
