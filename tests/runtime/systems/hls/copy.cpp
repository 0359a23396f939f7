// Copies every field of rfc_kinds/Kinds, as a user writes it against Copy_messages.h.
#include "Copy_messages.h"

void Copy(kin_t kin, hls::stream<char> &kin_name, hls::stream<uint16_t> &kin_samples,
          hls::stream<kin_cloud_t> &kin_cloud, kout_t *kout, hls::stream<char> &kout_name,
          hls::stream<uint16_t> &kout_samples, hls::stream<kout_cloud_t> &kout_cloud) {
    kout->flag = kin.flag;
    kout->i8 = kin.i8;
    kout->u8 = kin.u8;
    kout->i16 = kin.i16;
    kout->u16 = kin.u16;
    kout->i32 = kin.i32;
    kout->u32 = kin.u32;
    kout->i64 = kin.i64;
    kout->u64 = kin.u64;
    kout->f32 = kin.f32;
    kout->f64 = kin.f64;
    kout->name_length = kin.name_length;
    for (uint32_t i = 0; i < kin.name_length; ++i) kout_name.write(kin_name.read());
    for (int i = 0; i < 3; ++i) kout->gains[i] = kin.gains[i];
    for (int i = 0; i < 2; ++i) {
        kout->corners[i].x = kin.corners[i].x;
        kout->corners[i].y = kin.corners[i].y;
        kout->corners[i].z = kin.corners[i].z;
    }
    kout->samples_length = kin.samples_length;
    for (uint32_t i = 0; i < kin.samples_length; ++i) kout_samples.write(kin_samples.read());
    kout->cloud_length = kin.cloud_length;
    for (uint32_t i = 0; i < kin.cloud_length; ++i) {
        const kin_cloud_t point = kin_cloud.read();
        kout_cloud_t copy;
        copy.x = point.x;
        copy.y = point.y;
        copy.z = point.z;
        kout_cloud.write(copy);
    }
}
