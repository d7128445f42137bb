// The renderers for Rgb888 strips with every span routine (kAllSpans), one per strip height
// lineraster-sim offers: compiled here once, with the strict flags of core/ (-Wconversion,
// -Werror, no exceptions, no RTTI), and linked by hosted programs (renderer.hpp). One file per
// pixel format, so that the two compile in parallel.
#include "lineraster/core/raster/renderer.hpp"

namespace lr {
template class Renderer<Rgb888, 1>;
template class Renderer<Rgb888, 2>;
template class Renderer<Rgb888, 4>;
template class Renderer<Rgb888, 8>;
template class Renderer<Rgb888, 16>;
template class Renderer<Rgb888, 32>;
}  // namespace lr
