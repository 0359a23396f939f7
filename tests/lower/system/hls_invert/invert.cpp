// Inverts an image's bytes (255 - value), keeping its stamp and shape.
#include "Invert_messages.h"

void Invert(image_t image, hls::stream<uint8_t> &image_data, inverted_t *inverted,
            hls::stream<uint8_t> &inverted_data) {
    inverted->header.stamp.sec = image.header.stamp.sec;
    inverted->header.stamp.nanosec = image.header.stamp.nanosec;
    inverted->height = image.height;
    inverted->width = image.width;
    inverted->step = image.step;
    for (uint32_t i = 0; i < image.data_length; ++i) {
        inverted_data.write(255 - image_data.read());
    }
    inverted->data_length = image.data_length;
}
