// Downscaling by two in each direction (mean of 2x2 blocks), second stage of the pipeline.
// Vitis HLS top function: gray bytes stream in row by row, one byte per output pixel out.
#include <ap_int.h>
#include <hls_stream.h>

#define MAX_WIDTH 1920

void Downscale(ap_uint<32> height, ap_uint<32> width, hls::stream<ap_uint<8>> &data,
               hls::stream<ap_uint<8>> &small) {
#pragma HLS INTERFACE mode=axis port=data
#pragma HLS INTERFACE mode=axis port=small
    ap_uint<10> row_sums[MAX_WIDTH / 2];
    for (ap_uint<32> y = 0; y < height; ++y) {
        for (ap_uint<32> x = 0; x < width; x += 2) {
#pragma HLS PIPELINE II=2
            ap_uint<10> pair = data.read() + data.read();
            if (y % 2 == 0) {
                row_sums[x / 2] = pair;
            } else {
                small.write((row_sums[x / 2] + pair) >> 2);
            }
        }
    }
}
