// Physical quantities as scene files write them: a number with an optional unit.
// Everything inside mpmshock is SI; units exist only at the edge (scene files, printing).
#pragma once

#include <string>
#include <string_view>

namespace mpmshock {

enum class Dimension {
  none,           // a pure number (porosity, Poisson ratio, coefficients)
  length,         // m
  time,           // s
  speed,          // m/s
  pressure,       // Pa
  density,        // kg/m3
  temperature,    // K
  specific_heat,  // J/(kg K)
  conductivity,   // W/(m K)
  specific_energy,  // J/kg
};

// The SI unit of a dimension, as the README and --check print it ("m/s"); "" for none.
std::string_view si_unit(Dimension dim);

// The units a scene may write for a dimension, for error messages ("m, mm, um, nm").
std::string accepted_units(Dimension dim);

// The text with every Unicode space (no-break, thin, narrow no-break, ...: category Zs) as an ASCII
// space and the Greek small letter mu (U+03BC) as the micro sign (U+00B5): they look the same as
// what a unit is spelled with, so a scene means them so.
std::string plain_spacing(std::string_view text);

// Parses "12.5", "12.5 mm" or "12.5mm" into SI (after plain_spacing: "12.5 μm" too). A bare number is already SI.
// Throws std::invalid_argument with a message that says what is wrong (no location:
// the caller knows the file, line and key and adds them).
double parse_quantity(std::string_view text, Dimension dim);

// Parses a plain finite number with no unit; throws std::invalid_argument.
double parse_number(std::string_view text);

// The shortest text that reads back as exactly v ("1.5e-05"), as messages and scene.txt print numbers.
std::string format_number(double v);

}  // namespace mpmshock
