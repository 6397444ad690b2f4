// The fixed-point coefficients of hal/v4l2/rgb_to_yuyv.cpp, shared by its C
// and SSE2 rows.
#pragma once

namespace depthkey::yuyv {

// BT.601 limited range, coefficients in Q16 (x 65536, rounded):
//   Y  = 16  + 219/255 (0.299 R + 0.587 G + 0.114 B)
//        219/255 = 0.858824: R 0.256788 -> 16829, G 0.504129 -> 33039, B 0.097906 -> 6416
//   Cb = 128 + 224/255 (-0.168736 R - 0.331264 G + 0.5 B)
//        224/255 = 0.878431: R -0.148223 -> -9714, G -0.290993 -> -19070, B 0.439216 -> 28784
//   Cr = 128 + 224/255 (0.5 R - 0.418688 G - 0.081312 B)
//        R 0.439216 -> 28784, G -0.367788 -> -24103, B -0.071427 -> -4681
// Each row of chroma coefficients sums to 0 (grey has no colour) and the luma
// row to 56284 = 219/255 x 65536, so white is 235 and black 16 exactly.
// Chroma is computed from the pair's sum (R0 + R1, ...), i.e. scaled by 2^17:
// |sum| <= 510 x 28784 + 128 x 2^17 < 2^25, plenty of room in int. The
// offsets (16, 128) are added before the shift, so the value shifted is never
// negative and >> rounds like floor; + half a step rounds to nearest.
// Results stay in 16..235 / 16..240 for any 8-bit input: no clamp.
constexpr int kYr = 16829, kYg = 33039, kYb = 6416;
constexpr int kUr = -9714, kUg = -19070, kUb = 28784;
constexpr int kVr = 28784, kVg = -24103, kVb = -4681;
constexpr int kLumaBias = (16 << 16) + (1 << 15);
constexpr int kChromaBias = (128 << 17) + (1 << 16);

} // namespace depthkey::yuyv
