// The empty footprint image: the same startup, C library shims and semihosting as the footprint
// images, and no renderer. scripts/footprint.sh subtracts its flash (and each image's mesh and
// texture arrays) from every image's to give the renderer's own flash.
#include "firmware/common/semihost.hpp"

int main() {
  lr::fw::semihost::write("footprint: empty image\n");
  return 0;
}
