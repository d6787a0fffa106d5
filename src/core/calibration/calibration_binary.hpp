/// The calibration table's binary format (CalibrationTable::load, fromBinary, writeBinary): what
/// the package ships (config/calibration.bin, compiled into the library) and what
/// identify_calibration writes. Every number is a little-endian 32-bit integer; a value v is held
/// as the integer v * 1e6 (6 decimals: the identifier's CSV held as many, and integer / 1e6 is the
/// double strtod gave for that text, both correctly rounded, so a table reads back bit for bit).
///
///   header   magic "WRCCALIB" (8 bytes), version, scale (1000000), the schema's length and text
///            (the kinds' and multipliers' codes in calibration_schema.hpp's order; a reader
///            refuses a file whose schema is not its own), the mesh count, then per mesh its nx,
///            its block's offset and size in bytes and the block's FNV-1a checksum
///   block    one per mesh, read only when a model needs that mesh:
///            a/b rows: count, values
///            per kind: knot count (0: not in the table), knots
///            combined correction: counts of spin shares, xi shares and knots (0 0 0: none), then
///            the spin shares, xi shares and knots
///            per a/b row: each kind's values at its knots, then the correction's multipliers in
///            the order (multiplier, sign, spin share, xi share, knot), the sign +1 first
///
/// What the numbers mean (axes, kinds, ranges): calibration_schema.hpp.
#pragma once

#include <cstdint>
#include <string_view>

namespace wheel_rail_contact {
namespace calibration {

inline constexpr std::string_view kBinaryMagic = "WRCCALIB";
inline constexpr std::uint32_t kBinaryVersion = 1;
/// Values are held as round(value * kBinaryScale) in an int32.
inline constexpr std::int32_t kBinaryScale = 1000000;

/// The shipped table's bytes (config/calibration.bin as it was at build time), in the library's
/// read-only data.
std::string_view shippedBinary();

}  // namespace calibration
}  // namespace wheel_rail_contact
