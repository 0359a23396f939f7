// Integral image (summed-area table), last stage of the pipeline: each output pixel is the
// sum of every input pixel above and to the left of it, as a 32-bit little-endian word.
#include <ap_int.h>
#include <hls_stream.h>

#define MAX_WIDTH 960

void IntegralImage(ap_uint<32> height, ap_uint<32> width, hls::stream<ap_uint<8>> &data,
                   hls::stream<ap_uint<32>> &integral) {
#pragma HLS INTERFACE mode=axis port=data
#pragma HLS INTERFACE mode=axis port=integral
    ap_uint<32> column_sums[MAX_WIDTH];
    for (ap_uint<32> y = 0; y < height; ++y) {
        ap_uint<32> row_sum = 0;
        for (ap_uint<32> x = 0; x < width; ++x) {
#pragma HLS PIPELINE II=1
            row_sum += data.read();
            ap_uint<32> above = y == 0 ? ap_uint<32>(0) : column_sums[x];
            column_sums[x] = above + row_sum;
            integral.write(column_sums[x]);
        }
    }
}
