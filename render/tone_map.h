#pragma once
// The film look's last step: linear radiance to display values. Exposure in stops, then
// a tone curve (none: clip at 1; aces: a filmic fit of the ACES reference rendering and
// output transforms), then the sRGB transfer function, at 8 or 16 bits.

#include <cstdint>
#include <string>

#include "linear_frame.h"
#include "png_image.h"

namespace globular {

struct ToneMapping {
    double exposure = 0;   ///< stops: radiance times 2^exposure
    bool aces = false;     ///< the ACES fit; false: clip at 1
    bool straightAlpha = true;  ///< divide colour by alpha (PNG), as LinearFrame is premultiplied

    /// From [render] exposure and tone_mapping ("none" or "aces").
    static ToneMapping from(double exposure, const std::string& toneMapping);

    /// Exposure and tone curve of one linear channel value; the result in [0, 1].
    float apply(float linear) const;
};

/// Krzysztof Narkowicz's fit of the ACES filmic curve (RRT + sRGB ODT):
/// x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]. 0 maps to 0; it
/// rises monotonically and reaches 1 near x = 7.2.
/// \see K. Narkowicz, "ACES Filmic Tone Mapping Curve", knarkowicz.wordpress.com, 2016.
float acesFilmic(float x);

/// The frame as 8-bit sRGB RGBA (alpha straight, 255 where covered).
Image encode8(const LinearFrame& frame, const ToneMapping& tone);
/// The frame as 16-bit sRGB RGBA.
Image16 encode16(const LinearFrame& frame, const ToneMapping& tone);

}  // namespace globular
