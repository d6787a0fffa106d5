// The shipped calibration table's bytes (config/calibration.bin) in the library's read-only data,
// put there by the assembler's .incbin: nothing is generated from the file and nothing compiled
// from it, and the installed library (or a copied binary) reads no file. The build passes the
// file's path as WRC_CALIBRATION_BIN and its SHA-256 as WRC_CALIBRATION_SHA256 (so that a changed
// table rebuilds this object, under ccache too: cmake/shipped_tables.cmake).
#include "core/calibration/calibration_binary.hpp"

#ifndef WRC_CALIBRATION_BIN
#error "WRC_CALIBRATION_BIN: config/calibration.bin's path (cmake/shipped_tables.cmake)"
#endif

__asm__(
    ".pushsection .rodata.wrc_calibration,\"a\"\n"
    ".balign 16\n"
    ".globl wrc_calibration_begin\n"
    ".hidden wrc_calibration_begin\n"
    "wrc_calibration_begin:\n"
    ".incbin \"" WRC_CALIBRATION_BIN
    "\"\n"
    ".globl wrc_calibration_end\n"
    ".hidden wrc_calibration_end\n"
    "wrc_calibration_end:\n"
    ".popsection\n");

extern "C" {
__attribute__((visibility("hidden"))) extern const char wrc_calibration_begin[];
__attribute__((visibility("hidden"))) extern const char wrc_calibration_end[];
}

namespace wheel_rail_contact {
namespace calibration {

std::string_view shippedBinary() {
  return std::string_view(wrc_calibration_begin,
                          static_cast<std::size_t>(wrc_calibration_end - wrc_calibration_begin));
}

}  // namespace calibration
}  // namespace wheel_rail_contact
