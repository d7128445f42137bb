// Explicit instances of the renderer templates, so that the strict flags of core/ (-Wconversion,
// -Werror, no exceptions, no RTTI) check the strip loop and every span routine.
#include "core/raster/renderer.hpp"

namespace lr {
template class Renderer<Rgb565Be, 1>;
template class Renderer<Rgb565Be, 8>;
template class Renderer<Rgb565Be, 32>;
template class Renderer<Rgb888, 1>;
template class Renderer<Rgb888, 8>;
template class Renderer<Rgb888, 32>;
}  // namespace lr
