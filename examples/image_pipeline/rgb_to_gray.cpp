// RGB to grayscale (ITU-R BT.601 luma in 8-bit fixed point), first stage of the image pipeline.
// Vitis HLS top function: rgb8 pixels stream in as bytes, one gray byte per pixel streams out.
#include <ap_int.h>
#include <hls_stream.h>

void RgbToGray(ap_uint<32> height, ap_uint<32> width, hls::stream<ap_uint<8>> &data,
               hls::stream<ap_uint<8>> &gray) {
#pragma HLS INTERFACE mode=axis port=data
#pragma HLS INTERFACE mode=axis port=gray
    for (ap_uint<64> pixel = 0; pixel < (ap_uint<64>)height * width; ++pixel) {
#pragma HLS PIPELINE II=3
        ap_uint<8> r = data.read(), g = data.read(), b = data.read();
        ap_uint<16> luma = 77 * r + 150 * g + 29 * b;  // weights sum to 256
        gray.write(luma >> 8);
    }
}
